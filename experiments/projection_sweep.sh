#!/usr/bin/env bash
# Every map that `plmap project` writes must pass `plmap check`, and the ray check must find no
# area in D whose ray misses S2 (extra): run it on contact pairs made from CGAL's meshes
# (libcgal-demo) with at most 60,000 triangles — each mesh against an isotropically remeshed copy
# moved out along its normals and flipped (bench_projection_peers --write-inputs, the pairs of
# against_rays.sh) — each pair with another combination of distance rule, normal check, rim,
# renumbering and thread count, and check the map against 20,000 rays with the same rules.
# Prints one line per mesh: project's exit code, check's (0 valid, 1 a violation or a ray-check
# defect above --ray-tolerance, - not run), the extra fraction, the defect fraction and the
# options. An exit code 2 is a refused input, whose message is in OUT_DIR/MESH.err.
#
# Usage: experiments/projection_sweep.sh BUILD_DIR OUT_DIR [OFFSET]
#   OFFSET (default 0) shifts which mesh gets which combination.
# Needs libcgal-demo (the meshes are unpacked from its data.tar.gz).
set -euo pipefail
build=$1
out=$2
offset=${3:-0}
plmap=$build/apps/plmap
bench=$build/experiments/peers/bench_projection_peers
# shellcheck source=experiments/cgal_meshes.sh
source "$(dirname "$0")/cgal_meshes.sh"
normal_checks=(none facing none)
i=0
while read -r f triangles <&3; do
  m=$(basename "$f" .off)
  i=$((i + 1)); j=$((i + offset))
  # The remeshing to 0.8 of the mean edge length can explode on meshes of very uneven edges (a
  # few long polygons): bounded in time and memory, such a mesh gives no pair.
  if ! (ulimit -v 6000000; timeout 120 "$bench" --tool plmap --case femur --femur "$f" --write-inputs "$out/$m" \
          > "$out/$m.bench.json" 2> "$out/$m.bench.err"); then
    echo "$m triangles=$triangles pair=not-made ($(head -c 200 "$out/$m.bench.err" | tr '\n' ' '))"
    continue
  fi
  rules=(--normal-check "${normal_checks[$((j % 3))]}")
  ((j % 4 == 3)) && rules+=(--max-distance 0.05 --relative-distance)
  args=("${rules[@]}" --threads $((1 + j % 2)) --renumber "$([[ $((j % 5)) == 0 ]] && echo always || echo auto)")
  ((j % 7 == 0)) && args+=(--no-rim)
  rc=0; timeout 600 "$plmap" project "$out/${m}_s1.off" "$out/${m}_s2.off" -o "$out/$m.plmapb" "${args[@]}" --json \
    > "$out/$m.json" 2> "$out/$m.err" || rc=$?
  check=- extra=- defects=-
  if ((rc == 0)); then
    check=0
    timeout 600 "$plmap" check "$out/$m.plmapb" --against-rays 20000 --ray-tolerance 1 "${rules[@]}" --json \
      > "$out/$m.check.json" 2> "$out/$m.check.err" || check=$?
    read -r extra defects < <(python3 -c 'import json, sys
r = json.load(open(sys.argv[1]))["against_rays"]
print(r["extra"]["defect_fraction"], r["missed"]["defect_fraction"])' "$out/$m.check.json" 2> /dev/null || echo "- -")
  fi
  echo "$m triangles=$triangles project=$rc check=$check extra=$extra defects=$defects ${args[*]}"
done 3< <(cgal_meshes "$out/meshes")
