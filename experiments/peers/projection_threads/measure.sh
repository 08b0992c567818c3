#!/bin/bash
# Alternating one- and two-thread runs of `plmap project` built with phase_trace.patch, for
# critical_path.py. Inputs: `bench_projection_peers --tool plmap --write-inputs NAME` with
#   --case plane --size 200000 (plane200k), --case sphere --size 7 (sphere7),
#   --case femur --femur /tmp/sp/data/meshes/armadillo.off (arm), in INPUTS.
# Usage: measure.sh TAG ROUNDS INPUTS NAME=PLMAP_BINARY...   (traces: TAG-NAME-CASE-T-ROUND.txt)
# Each run's map is compared (cmp) across thread counts and builds; a difference is logged.
set -u
tag=$1; rounds=$2; inputs=$3; shift 3
for r in $(seq 1 "$rounds"); do
  for c in plane200k sphere7 arm; do
    for b in "$@"; do
      name=${b%%=*}; bin=${b#*=}
      for T in 1 2; do
        load=$(cut -d' ' -f1 /proc/loadavg)
        # the summary goes to a file and is read after the run: a python reading the pipe would
        # start beside the measured process and take a CPU from its first phases
        PLMAP_TRACE=1 /usr/bin/time -f "%U %S %M" -o time.txt "$bin" project "$inputs/${c}_s1.off" "$inputs/${c}_s2.off" \
          -o "out-$name-$c-$T.plmapb" --threads "$T" --json --no-progress > summary.json 2> "$tag-$name-$c-$T-$r.txt"
        s=$(python3 -c "import json; print(json.load(open('summary.json'))['seconds'])")
        echo "$r $c $name T$T load $load seconds $s user,sys,maxrss_kB $(cat time.txt)" | tee -a "$tag-log.txt"
      done
    done
    first=${1%%=*}
    for b in "$@"; do
      name=${b%%=*}
      cmp -s "out-$name-$c-1.plmapb" "out-$name-$c-2.plmapb" || echo "DIFF $name $c 1/2 threads" | tee -a "$tag-log.txt"
      cmp -s "out-$first-$c-1.plmapb" "out-$name-$c-1.plmapb" || echo "DIFF $first/$name $c" | tee -a "$tag-log.txt"
    done
  done
done
