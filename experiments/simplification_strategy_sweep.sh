#!/usr/bin/env bash
# Every map that `plmap simplify` writes must pass `plmap check`: run it on CGAL's meshes
# (libcgal-demo) with at most 60,000 triangles, to 10 % of their triangles (at least 4), each
# mesh with another combination of flattening, hole triangulation, ranking, cut, feature angle
# and oracles, and check every map. Prints one line per mesh: its exit code, check's exit code
# (0 valid, 1 invalid, - not run) and the options; an exit code 2 is a refused input, whose
# message is in OUT_DIR/MESH.err.
#
# Usage: experiments/simplification_strategy_sweep.sh OUT_DIR PLMAP [OFFSET]
#   OFFSET (default 0) shifts which mesh gets which combination.
# Needs libcgal-demo (the meshes are unpacked from its data.tar.gz).
set -euo pipefail
out=$1
plmap=$2
offset=${3:-0}
# shellcheck source=experiments/cgal_meshes.sh
source "$(dirname "$0")/cgal_meshes.sh"
oracles=("--oracle hausdorff:1" "--oracle normal-deviation:1 --oracle self-intersection"
         "--oracle aspect-ratio:1 --oracle long-edge:0.5")
i=0
while read -r f triangles <&3; do
  m=$(basename "$f" .off)
  i=$((i + 1)); j=$((i + offset))
  flattening=$([[ $((j % 3)) == 0 ]] && echo plane-projection || echo polar-map)
  holes=$([[ $((j % 2)) == 0 ]] && echo min-max-aspect || echo constrained-delaunay)
  ranking=$([[ $((j % 4)) -lt 2 ]] && echo estimate || echo exact)
  cut=$([[ $((j % 5)) == 0 ]] && echo deferred || echo per-step)
  target=$((triangles / 10)); ((target < 4)) && target=4
  # shellcheck disable=SC2206  # the oracle options are words
  args=(--target-elements "$target" --flattening "$flattening" --hole-triangulation "$holes" --ranking "$ranking"
        --cut "$cut" --feature-angle $(((j * 37) % 181)) ${oracles[$((j % 3))]} --threads 1)
  rc=0; timeout 300 "$plmap" simplify "$f" -o "$out/$m.plmapb" "${args[@]}" --json > "$out/$m.json" 2> "$out/$m.err" || rc=$?
  check=-
  if ((rc == 0)); then check=0; timeout 300 "$plmap" check "$out/$m.plmapb" > "$out/$m.check" 2>&1 || check=$?; fi
  echo "$m triangles=$triangles simplify=$rc check=$check ${args[*]}"
done 3< <(cgal_meshes "$out/meshes")
