#!/usr/bin/env bash
# The --against-rays baseline of docs/benchmarks.md: makes the real-mesh contact pairs (CGAL's
# femur, bones and armadillo from libcgal-demo, each against an isotropically remeshed copy moved
# out along its normals by 0.2-0.3 mean edge lengths and flipped; inputs.cpp, femur_pair) and the
# synthetic pairs, projects each with `plmap project` (default rules: averaged normals, no
# distance limit, no normal check) and checks the map with `plmap check --against-rays`.
# Prints two tables: the ray check's, and (d = 2) the measure of S1 that the projection left out
# of D by why (`left_out_measure` of `plmap project --json`), as fractions of S1's measure.
#
# Usage: experiments/peers/against_rays.sh BUILD_DIR OUT_DIR [SAMPLES]
# Needs libcgal-demo (the meshes are unpacked from its data.tar.gz).
set -euo pipefail
build=$1 out=$2 samples=${3:-200000}
plmap=$build/apps/plmap
bench=$build/experiments/peers/bench_projection_peers
mkdir -p "$out/meshes"
tar -xzf /usr/share/doc/libcgal-demo/data.tar.gz -C "$out/meshes" --strip-components=2 \
  data/meshes/femur.off data/meshes/bones.off data/meshes/armadillo.off

run_pair() {  # NAME BENCH-ARGS...
  local name=$1; shift
  "$bench" --tool plmap "$@" --write-inputs "$out/$name" > "$out/$name.bench.json"
  local ext=off; [[ -f $out/${name}_s1.curve ]] && ext=curve
  "$plmap" project "$out/${name}_s1.$ext" "$out/${name}_s2.$ext" -o "$out/$name.plmapb" --json > "$out/$name.project.json"
  "$plmap" check "$out/$name.plmapb" --against-rays "$samples" --json > "$out/$name.check.json" || true
  python3 - "$name" "$out/$name.project.json" "$out/$name.check.json" "$out/left_out.md" <<'PY'
import json, sys
name, p, c = sys.argv[1], json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
r = c["against_rays"]; m = r["missed"]; e = r["image_error_relative_to_edge"]
by = {k: v["fraction"] for k, v in m["by_reason"].items()}
print(f"| {name} | {p['covered_measure'] / p['domain_measure']:.4f} | {p['edges_not_inserted']} | "
      f"{m['fraction']:.2e} | {by['nearer_sheet']:.2e} | {by['domain_in_between']:.2e} | {by['target_seen_twice']:.2e} | {by['target_crosses_itself']:.2e} | "
      f"{m['defect_fraction']:.2e} | {by['farther_sheet']:.2e} | {by['in_folding_element']:.2e} | {by['next_to_fold']:.2e} | "
      f"{by['not_covered']:.2e} | {r['extra']['fraction']:.2e} | {r['extra']['defect_fraction']:.2e} | {e['median']:.1e} | {e['p99']:.1e} | {e['max']:.1e} | "
      f"{c['violation_count']} |")
lo = p.get("left_out_measure")
if lo:
    s1 = p["domain_measure"]
    with open(sys.argv[4], "a") as f:
        f.write(f"| {name} | {1 - p['covered_measure'] / s1:.2e} | " +
                " | ".join(f"{lo[k] / s1:.2e}" for k in ("outside", "unmapped", "reversed", "enclosed", "folded", "unbacked", "occluded")) +
                " |\n")
PY
}

rm -f "$out/left_out.md"
echo "| pair | covered / S1 | edges not inserted | missed | nearer sheet | S1 in between | S2 seen twice | S2 crosses itself | defects | farther sheet | in folding element | next to fold | not covered | extra | extra defects | error median | p99 | max | violations |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
run_pair femur --case femur --femur "$out/meshes/femur.off"
run_pair bones --case femur --femur "$out/meshes/bones.off"
run_pair armadillo --case femur --femur "$out/meshes/armadillo.off"
run_pair plane-200k --case plane --size 200000
run_pair sphere-L7 --case sphere --size 7
run_pair circle-1M --case circle --size 1000000

echo
echo "| pair | S1 outside D | outside | unmapped | reversed | enclosed | folded | unbacked | occluded |"
echo "|---|---|---|---|---|---|---|---|---|"
cat "$out/left_out.md"
