#!/bin/sh
# Regenerates the pictures of docs/drawing.md into this folder.
#   docs/pictures/make_pictures.sh BUILD_DIR
# BUILD_DIR is a configured and built plmap build tree (the `plmap` tool and the static
# libraries). Needs rsvg-convert (librsvg2-bin) for the PNGs and libcgal-demo for the meshes.
set -eu
build=$(cd "${1:?usage: make_pictures.sh BUILD_DIR}" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
src=$(cd "$here/../.." && pwd)
plmap="$build/apps/plmap"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

tar xzf /usr/share/doc/libcgal-dev/data.tar.gz data/meshes/sphere.off data/meshes/sphere966.off \
  data/meshes/pig.off data/meshes/elephant.off

# Both formats of one picture: the SVG, and the PNG converted from it by `plmap draw`.
draw() { name=$1; shift; "$plmap" draw "$@" -o "$here/$name.svg"; "$plmap" draw "$@" -o "$here/$name.png"; }

# Overlay of two triangulations of the unit square: every node type occurs.
"$plmap" generate grid --cells 2 --seed 3 -o s1_grid.off
"$plmap" generate delaunay --points 14 --boundary-points 4 --grid-points 12 --seed 5 -o s2_delaunay.off
"$plmap" build overlay s1_grid.off s2_delaunay.off -o overlay.plmap
draw element_overlay overlay.plmap --element 3
draw element_overlay_busy overlay.plmap --element 4
draw view_overlay_top overlay.plmap --view3d --elevation 90 --azimuth -90 --width 700 --height 760 \
  --element-labels

# Refinements of real meshes (S2 finer than S1).
"$plmap" build refine data/meshes/pig.off --random-points 2 --seed 1 -o pig.plmap
draw view_pig_refinement pig.plmap --view3d --up=-y --azimuth 60
"$plmap" build refine data/meshes/elephant.off --levels 1 -o elephant.plmap
# The elephant's SVG is ~3 MB: only the PNG is kept.
"$plmap" draw elephant.plmap --view3d --up y --azimuth 20 --width 1000 --height 800 \
  -o "$here/view_elephant_refinement.png"

# Normal projection (paper Figs. 1 and 2).
B="$build"
g++ -std=c++20 -O1 "$here/projection_examples.cpp" -I"$src/core/include" -I"$src/construct/include" \
  -I/usr/include/eigen3 "$B/construct/libplmap_construct.a" "$B/solvers/libplmap_solvers.a" \
  "$B/strategies/libplmap_strategies.a" "$B/core/libplmap_core.a" \
  -lfmt -lceres -lglog -lgflags -ltbb -lgmp -lmpfr -lpthread -o projection_examples
./projection_examples data/meshes
draw view_curves_projection curves_projection.plmap --view3d
draw element_curve_projection curves_projection.plmap --element 2
draw view_sphere_projection sphere_projection.plmap --view3d
