#!/bin/sh
# Regenerates the pictures of docs/algorithms/simplification.md into this folder: CGAL's femur
# (7,798 triangles) simplified to 500 by `plmap simplify`, smoothed by `plmap smooth` and refined
# two levels through the map by `plmap refine`, each drawn by `plmap draw --view3d`.
#   docs/pictures/make_simplification_pictures.sh BUILD_DIR
# BUILD_DIR is a built plmap build tree. Needs rsvg-convert (librsvg2-bin) for the PNGs and
# libcgal-demo for the femur.
set -eu
build=$(cd "${1:?usage: make_simplification_pictures.sh BUILD_DIR}" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
plmap="$build/apps/plmap"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

tar xzf /usr/share/doc/libcgal-demo/data.tar.gz data/meshes/femur.off

# The settings of experiments/configs/simplification_peers.toml.
"$plmap" simplify data/meshes/femur.off -o femur.plmap --coarse femur_coarse.off --target-elements 500 \
  --oracle hausdorff:1 --oracle aspect-ratio:1 --feature-angle 180 --threads 1 --no-progress
"$plmap" smooth femur.plmap -o femur_smooth.plmap
"$plmap" refine femur_smooth.plmap --levels 2 -o femur_refined.off
# The coarse and refined surfaces alone, as identity maps (their own edges only).
"$plmap" build identity femur_coarse.off -o coarse.plmap
"$plmap" build identity femur_refined.off -o refined.plmap

view="--view3d --width 760 --height 1000"
# shellcheck disable=SC2086
"$plmap" draw coarse.plmap $view --no-legend -o "$here/simplification_femur_coarse.png"
# shellcheck disable=SC2086
"$plmap" draw femur_smooth.plmap $view -o "$here/simplification_femur_map.png"
# shellcheck disable=SC2086
"$plmap" draw refined.plmap $view --no-legend --no-domain-edges -o "$here/simplification_femur_refined.png"
