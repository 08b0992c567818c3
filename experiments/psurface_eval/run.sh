#!/bin/sh
# plmap against PSurface 2.0 on the same maps (experiments/psurface_eval/README.md).
# Usage: experiments/psurface_eval/run.sh [build-dir] [extra psurface_eval args]
# Needs a Release build of the target psurface_eval (built only when libpsurface-dev is
# installed), the Debian package libcgal-demo (CGAL's femur.off), and the plmap tool for the
# plane-pair map ($PLMAP, default build-dir/apps/plmap; the case is skipped without it).
set -eu
build=${1:-build-release}
[ $# -gt 0 ] && shift
bench="$build/experiments/psurface_eval/psurface_eval"
if [ ! -x "$bench" ]; then
  echo "run.sh: $bench not built (is libpsurface-dev installed?)" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tar -xzf /usr/share/doc/libcgal-demo/data.tar.gz -C "$work" data/meshes/femur.off
set -- --femur "$work/data/meshes/femur.off" "$@"
plmap=${PLMAP:-$build/apps/plmap}
if [ -x "$plmap" ]; then
  # A projection-built map between two unit squares with different meshes (ghost nodes,
  # intersection nodes, boundary): 2048 -> 4102 triangles.
  "$plmap" generate grid --cells 32 --jitter 0.2 --seed 3 -o "$work/plane1.off" >/dev/null
  "$plmap" generate delaunay --points 2000 --boundary-points 100 --seed 4 -o "$work/plane2.off" >/dev/null
  "$plmap" project "$work/plane1.off" "$work/plane2.off" -o "$work/planes-2048-4102.plmap" >/dev/null
  set -- --map "$work/planes-2048-4102.plmap" "$@"
else
  echo "run.sh: $plmap not found, skipping the plane-pair map" >&2
fi
lscpu | grep 'Model name' || true
date -u +%Y-%m-%dT%H:%MZ
"$bench" --json "${PLMAP_PSURFACE_JSON:-psurface_eval.json}" "$@"
