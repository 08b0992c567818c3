#!/bin/sh
# Evaluation throughput benchmark (docs/benchmarks.md, "Evaluation throughput").
# Usage: experiments/bench_point_location.sh [build-dir] [extra bench_point_location args]
# Needs a Release build of the target bench_point_location and the Debian package libcgal-demo
# (for CGAL's femur.off, simplified to about 500 triangles by the benchmark).
set -eu
build=${1:-build-release}
[ $# -gt 0 ] && shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tar -xzf /usr/share/doc/libcgal-demo/data.tar.gz -C "$work" data/meshes/femur.off
out=${PLMAP_BENCH_JSON:-bench_point_location.json}
lscpu | grep 'Model name' || true
date -u +%Y-%m-%dT%H:%MZ
"$build/experiments/bench_point_location" --femur "$work/data/meshes/femur.off" --json "$out" "$@"
