#!/usr/bin/env bash
# Every map that `plmap smooth` writes must pass `plmap check`, and `plmap refine` must take every
# smoothed parametrization: run both on the maps that simplification_strategy_sweep.sh wrote
# (simplifications of CGAL's meshes with varied strategies), each map with other smoothing
# weights, sweeps and passes, and refinement levels 1-2. Prints one line per map: smooth's exit
# code, check's (0 valid, 1 invalid, - not run), refine's, and the options; an exit code 2 is
# a refused input, whose message is in OUT_DIR/MAP.smooth.err or .refine.err.
#
# Usage: experiments/smoothing_refinement_sweep.sh MAP_DIR OUT_DIR PLMAP
#   MAP_DIR holds the *.plmapb of simplification_strategy_sweep.sh.
set -euo pipefail
maps=$1
out=$2
plmap=$3
mkdir -p "$out"
weights=(floater mean-value uniform)
passes=("" "--no-quadrilaterals" "--no-element-pass")
i=0
for f in "$maps"/*.plmapb; do
  m=$(basename "$f" .plmapb)
  i=$((i + 1))
  # shellcheck disable=SC2206  # the pass option is one word or none
  args=(--weights "${weights[$((i % 3))]}" --sweeps $((1 + i % 3)) ${passes[$(((i / 3) % 3))]})
  rc=0; timeout 600 "$plmap" smooth "$f" -o "$out/$m.plmapb" "${args[@]}" --json > "$out/$m.smooth.json" 2> "$out/$m.smooth.err" || rc=$?
  check=- refine=-
  if ((rc == 0)); then
    check=0; timeout 600 "$plmap" check "$out/$m.plmapb" > "$out/$m.check" 2>&1 || check=$?
    refine=0; timeout 600 "$plmap" refine "$out/$m.plmapb" --levels $((1 + i % 2)) -o "$out/$m.refined.off" --json \
      > "$out/$m.refine.json" 2> "$out/$m.refine.err" || refine=$?
  fi
  echo "$m smooth=$rc check=$check refine=$refine ${args[*]} --levels $((1 + i % 2))"
done
