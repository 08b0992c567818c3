#!/usr/bin/env bash
# How far `plmap simplify` gets towards its target, with default options, on CGAL's meshes
# (libcgal-demo) and on generated regular grids (flat grids, a tent, a three-page book), and
# whether every map it writes passes `plmap check`. Each mesh goes to 5 % of its triangles (at
# least 12); the grids and the tent to 2, the book to 6. With two binaries (a base and a
# change), both run on every mesh and the table puts them side by side.
#
# Usage: experiments/simplification_reach.sh OUT_DIR PLMAP [PLMAP ...]
# Needs libcgal-demo (the meshes are unpacked from its data.tar.gz) and python3.
set -euo pipefail
out=$1; shift
binaries=("$@")
mkdir -p "$out/meshes"
meshes=(cube-meshed fandisk anchor couplingdown joint rotor elephant femur helmet pinion mushroom knot1 handle blade
        cylinder bunny00 cow dino hand head)
members=("${meshes[@]/#/data/meshes/}")
# members missing from an older libcgal-demo are skipped (tar reports them; the rest unpacks)
tar -xzf /usr/share/doc/libcgal-demo/data.tar.gz -C "$out/meshes" --strip-components=2 \
  "${members[@]/%/.off}" 2>/dev/null || true

python3 - "$out/meshes" <<'PY'
import math, sys
out = sys.argv[1]
def write(name, vertices, triangles):
    with open(f"{out}/{name}.off", "w") as f:
        f.write(f"OFF\n{len(vertices)} {len(triangles)} 0\n")
        f.writelines("%.17g %.17g %.17g\n" % v for v in vertices)
        f.writelines("3 %d %d %d\n" % t for t in triangles)
def grid(name, n, alternating=False, height=lambda x, y: 0.0):
    v = [(i / n, j / n, height(i / n, j / n)) for j in range(n + 1) for i in range(n + 1)]
    t = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i; b = a + 1; c = a + n + 2; d = a + n + 1
            t += [(a, b, d), (b, c, d)] if alternating and (i + j) % 2 else [(a, b, c), (a, c, d)]
    write(name, v, t)
grid("grid60", 60)
grid("grid60alt", 60, alternating=True)
grid("tent40", 40, height=lambda x, y: 0.3 * min(x, 1 - x))
# three 8 x 3 pages on a common spine along the x axis (a non-manifold feature line)
v = [(i / 8, 0.0, 0.0) for i in range(9)]; t = []
for p in range(3):
    angle = 2 * math.pi * (p + 0.1) / 3; first = len(v)
    for r in range(1, 4):
        v += [(i / 8, math.cos(angle) * r / 3, math.sin(angle) * r / 3) for i in range(9)]
    at = lambda i, r: i if r == 0 else first + (r - 1) * 9 + i
    for r in range(3):
        for i in range(8):
            t += [(at(i, r), at(i + 1, r), at(i + 1, r + 1)), (at(i, r), at(i + 1, r + 1), at(i, r + 1))]
write("book", v, t)
PY

header="| mesh | triangles → target |"
rule="|---|---|"
for i in "${!binaries[@]}"; do
  echo "binary $((i + 1)): ${binaries[$i]}"
  header+=" binary $((i + 1)): triangles, Hausdorff / size, κ max, s, check |"; rule+="---|"
done
echo "$header"; echo "$rule"
for f in "${meshes[@]/%/.off}" grid60.off grid60alt.off tent40.off book.off; do
  path=$out/meshes/$f
  [[ -f $path ]] || continue
  name=${f%.off}
  n=$(sed -n 2p "$path" | awk '{print $2}')
  target=$((n / 20)); ((target < 12)) && target=12
  case $name in grid60|grid60alt|tent40) target=2 ;; book) target=6 ;; esac
  row="| $name | $n → $target |"
  for b in "${binaries[@]}"; do
    map=$out/$name.plmapb
    cells=$("$b" simplify "$path" -o "$map" --target-elements "$target" --json --no-progress 2>/dev/null |
      python3 -c "import json, sys; d = json.load(sys.stdin); print('%d, %.3g, %.3g, %.2f' % (d['elements_after'], d['hausdorff_error_relative'], d['quality']['kappa_max'], d['seconds']))" ||
      echo "failed")
    verdict=$("$b" check "$map" > /dev/null 2>&1 && echo valid || echo INVALID)
    row+=" $cells, $verdict |"
  done
  echo "$row"
done
