#!/bin/sh
# Projection benchmark against the peers (README.md here): runs plmap (1 thread and all cores),
# dune-grid-glue's ContactMerge and PSurface's ContactMapping on the same generated inputs, each
# tool and input in its own process, REPS times, and writes
#   OUT/raw.jsonl      one JSON line per run (bench_projection_peers output)
#   OUT/summary.jsonl  medians per case and tool
#   OUT/table.md       the Markdown tables (times, memory, covered-measure errors, ratios)
#
# Usage: experiments/peers/run.sh [--build DIR] [--out DIR] [--reps N] [--large] [--psurface-long]
#   --build DIR        build tree holding experiments/peers/bench_projection_peers (default build-rel)
#   --large            add the 1M-triangle plane pair and the 1M-segment circles
#   --psurface-long    let PSurface (all-pairs, O(n m)) also run the femur pairs and sphere L5,
#                      once each (minutes per run); by default it runs the inputs <= 2k elements
# Default matrix: about 10-15 minutes on a 2-core machine.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$root/build-rel
out=$root/experiments/peers/results
reps=3
large=0
psurface_long=0
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --reps) reps=$2; shift 2 ;;
    --large) large=1; shift ;;
    --psurface-long) psurface_long=1; shift ;;
    *) echo "run.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
bench=$build/experiments/peers/bench_projection_peers
[ -x "$bench" ] || { echo "run.sh: $bench not built (cmake --build $build --target bench_projection_peers)" >&2; exit 2; }
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tar -xzf /usr/share/doc/libcgal-demo/data.tar.gz -C "$work" data/meshes/femur.off
femur=$work/data/meshes/femur.off
tools=$("$bench" --list-tools | tr '\n' ' ')
has() { case " $tools " in *" $1 "*) return 0 ;; *) return 1 ;; esac; }

raw=$out/raw.jsonl
: > "$raw"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB"
  echo "command: $0 --build $build --reps $reps$( [ $large = 1 ] && echo ' --large')$( [ $psurface_long = 1 ] && echo ' --psurface-long')"
  echo "tools: $tools"
} > "$out/run_info.txt"
cat "$out/run_info.txt"

# run TOOL THREADS CASE SIZE REPS: REPS runs, each in a new process, appended to raw.jsonl.
run() {
  i=1
  while [ "$i" -le "$5" ]; do
    status=0
    timeout 1200 "$bench" --tool "$1" --threads "$2" --case "$3" --size "$4" --seed 1 --femur "$femur" \
      >> "$raw" 2> "$work/err" || status=$?
    if [ "$status" -ne 0 ]; then
      why="process failed (exit $status)"
      [ "$status" -eq 124 ] && why="timed out after 1200 s"
      printf '{"tool":"%s","threads":%s,"family":"%s","size":%s,"ok":false,"error":"%s: %s"}\n' \
        "$1" "$2" "$3" "$4" "$why" "$(tr '"\n' "' " < "$work/err" | cut -c1-200)" >> "$raw"
    fi
    printf '%s threads=%s %s %s run %s: %s\n' "$1" "$2" "$3" "$4" "$i" \
      "$(tail -n 1 "$raw" | sed -E 's/.*"ok":(true|false).*"seconds":([-0-9.e+]+).*/ok=\1 seconds=\2/')"
    i=$((i + 1))
  done
}

# all_tools CASE SIZE PSURFACE_REPS (0: PSurface skipped)
all_tools() {
  run plmap 1 "$1" "$2" "$reps"
  run plmap 0 "$1" "$2" "$reps"
  if has contactmerge; then run contactmerge 1 "$1" "$2" "$reps"; fi
  if has psurface && [ "$3" -gt 0 ]; then run psurface 1 "$1" "$2" "$3"; fi
}

long=$([ $psurface_long = 1 ] && echo 1 || echo 0)
all_tools plane 2000 "$reps"
all_tools plane 20000 0
all_tools plane 200000 0
[ $large = 1 ] && all_tools plane 1000000 0
all_tools sphere 3 "$reps"
all_tools sphere 5 "$long"
all_tools sphere 7 0
all_tools femur 0 "$long"
all_tools femur-offset 0 "$long"
for n in 100 1000; do all_tools circle $n "$reps"; done
for n in 10000 100000; do all_tools circle $n 0; done
[ $large = 1 ] && all_tools circle 1000000 0

python3 "$here/summarize.py" "$raw" "$out/summary.jsonl" "$out/table.md" "$out/run_info.txt"
cat "$out/table.md"
