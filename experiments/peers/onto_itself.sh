#!/usr/bin/env bash
# Every CGAL mesh (libcgal-demo) of at most MAX_TRIANGLES triangles projected onto a copy of
# itself, read twice from its file, as `plmap project MESH MESH` does: the answer is known, the
# identity, so D must be all of S1. Matching meshes are what a mortar method with a conforming
# interface projects, and a copy is the most degenerate input the walks meet (every S2 edge lies
# on an S1 edge, every hit at distance 0). Prints one row per mesh that does not cover S1 (with
# the S1 measure left out and the edges not inserted), the meshes the reader refuses (with the
# reason), and a count.
#
# Usage: experiments/peers/onto_itself.sh BUILD_DIR OUT_DIR [MAX_TRIANGLES] (default 20000).
# Needs libcgal-demo.
set -euo pipefail
build=$1 out=$2 max=${3:-20000}
plmap=$build/apps/plmap
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=../cgal_meshes.sh
source "$here/../cgal_meshes.sh"
mkdir -p "$out"
echo "| mesh | triangles | covered / S1 | edges not inserted | coincident vertices |"
echo "|---|---|---|---|---|"
total=0 complete=0 refused=0
while read -r mesh triangles; do
  [[ $triangles -le $max ]] || continue
  name=$(basename "$mesh" .off)
  total=$((total + 1))
  if ! "$plmap" project "$mesh" "$mesh" -o "$out/$name.plmapb" --no-progress --json > "$out/$name.json" 2> "$out/$name.err"; then
    refused=$((refused + 1))
    echo "| $name | $triangles | refused: $(head -c 120 "$out/$name.err" | tr '\n|' ' /') | | |"
    continue
  fi
  row=$(python3 - "$out/$name.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
covered = j["covered_measure"] / j["domain_measure"]
print(f"{covered:.6f} {j['edges_not_inserted']}" if covered < 1 - 1e-9 else "ok")
PY
)
  if [[ $row == ok ]]; then
    complete=$((complete + 1))
  else
    coincident=$("$plmap" info "$mesh" --json | python3 -c 'import json, sys; print(json.load(sys.stdin)["coincident_vertices"])')
    read -r covered edges <<< "$row"
    echo "| $name | $triangles | $covered | $edges | $coincident |"
  fi
done < <(cgal_meshes "$out/meshes")
echo
echo "$complete of $total meshes project onto themselves as the identity; $refused refused by the reader."
