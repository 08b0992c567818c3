#!/usr/bin/env bash
# Projection of a coarse surface onto the fine one it was made from, as a user who wants a coarse
# model with its fine surface as the map's target would run it: each CGAL mesh (libcgal-demo) is
# simplified by `plmap simplify --coarse` to about TARGET triangles (the coarse S1; its vertices
# lie on the fine S2, which is then on both sides of S1), projected back onto the fine mesh with
# `plmap project --allow-negative`, and the map checked with `plmap check --against-rays`
# under the rules the map records. Prints one table row per mesh: the ray check's missed and
# extra fractions by reason, and the image error.
#
# Usage: experiments/peers/coarse_over_fine.sh BUILD_DIR OUT_DIR [SAMPLES] [TARGET] [MESH...]
# (default meshes: bull camel homer cow lion). Needs libcgal-demo.
set -euo pipefail
build=$1 out=$2 samples=${3:-100000} target=${4:-1500}
shift $(($# < 4 ? $# : 4))
meshes=("$@")
[[ ${#meshes[@]} -gt 0 ]] || meshes=(bull camel homer cow lion)
plmap=$build/apps/plmap
mkdir -p "$out/meshes"
for m in "${meshes[@]}"; do
  tar -xzf /usr/share/doc/libcgal-demo/data.tar.gz -C "$out/meshes" --strip-components=2 "data/meshes/$m.off"
done

echo "| mesh | S1 / S2 triangles | missed | nearer sheet | S1 in between | S2 seen twice | S2 crosses itself | missed defects | farther sheet | in a folding element | next to a fold | not covered | extra | extra defects | image error median | p99 | max |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for m in "${meshes[@]}"; do
  fine=$out/meshes/$m.off coarse=$out/$m.coarse.off
  "$plmap" simplify "$fine" -o "$out/$m.param.plmapb" --coarse "$coarse" --target-elements "$target" \
    --no-progress --json > "$out/$m.simplify.json"
  "$plmap" project "$coarse" "$fine" -o "$out/$m.plmapb" --allow-negative --no-progress --json > "$out/$m.project.json"
  "$plmap" check "$out/$m.plmapb" --against-rays "$samples" --no-progress --json > "$out/$m.check.json" || true
  python3 - "$m" "$out/$m.project.json" "$out/$m.check.json" "$coarse" "$fine" <<'PY'
import json, sys
name, c = sys.argv[1], json.load(open(sys.argv[3]))
def triangles(path):
    with open(path) as f:
        words = [w for line in f if not line.startswith("#") for w in line.split()]
    return int(words[2])  # OFF, vertex count, face count
r = c["against_rays"]; m = r["missed"]; x = r["extra"]; e = r["image_error_relative_to_edge"]
by = {k: v["fraction"] for k, v in m["by_reason"].items()}
print(f"| {name} | {triangles(sys.argv[4])} / {triangles(sys.argv[5])} | {m['fraction']:.2e} | {by['nearer_sheet']:.2e} | "
      f"{by['domain_in_between']:.2e} | {by['target_seen_twice']:.2e} | {by['target_crosses_itself']:.2e} | "
      f"{m['defect_fraction']:.2e} | {by['farther_sheet']:.2e} | {by['in_folding_element']:.2e} | {by['next_to_fold']:.2e} | {by['not_covered']:.2e} | "
      f"{x['fraction']:.2e} | {x['defect_fraction']:.2e} | {e['median']:.1e} | {e['p99']:.1e} | {e['max']:.1e} |")
PY
done
