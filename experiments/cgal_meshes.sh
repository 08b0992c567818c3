# shellcheck shell=bash
# Sourced by the sweeps over CGAL's meshes: `cgal_meshes DIR` unpacks every .off of libcgal-demo's
# data.tar.gz into DIR and prints, one line each, "PATH TRIANGLES" for the meshes with at most
# 60,000 faces (the count of an OFF header; empty or unreadable headers are skipped), in the
# shell's glob order. The sweeps read the list on file descriptor 3, so that the commands they
# run cannot swallow it from standard input.
cgal_meshes() {
  local dir=$1
  mkdir -p "$dir"
  tar -xzf /usr/share/doc/libcgal-demo/data.tar.gz -C "$dir" --strip-components=2 --wildcards 'data/meshes/*.off'
  local f triangles
  for f in "$dir"/*.off; do
    triangles=$(awk 'NR > 1 && $0 !~ /^#/ && NF >= 2 { print $2; exit }' "$f")
    [[ -z "$triangles" || "$triangles" -gt 60000 ]] && continue
    echo "$f $triangles"
  done
}
