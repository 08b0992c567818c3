# Usage: offset_along_normals.py S1.off GAP OUT.off
# Writes S1 moved by GAP along its area-weighted vertex normals (plmap's default directions),
# with the orientation reversed (a contact pair facing S1).
import math, sys
L = open(sys.argv[1]).read().split(); nv, nf = int(L[1]), int(L[2]); i = 4
V = [tuple(map(float, L[i + 3 * k:i + 3 * k + 3])) for k in range(nv)]; i += 3 * nv
F = [tuple(map(int, L[i + 4 * k + 1:i + 4 * k + 4])) for k in range(nf)]
N = [[0.0] * 3 for _ in V]
for a, b, c in F:
    u = [V[b][j] - V[a][j] for j in range(3)]; v = [V[c][j] - V[a][j] for j in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    for x in (a, b, c):
        for j in range(3): N[x][j] += n[j]
gap = float(sys.argv[2])
with open(sys.argv[3], 'w') as f:
    f.write(f'OFF\n{nv} {nf} 0\n')
    for p, n in zip(V, N):
        l = math.sqrt(sum(x * x for x in n))
        f.write(' '.join(repr(p[j] + gap * n[j] / l) for j in range(3)) + '\n')
    for a, b, c in F: f.write(f'3 {a} {c} {b}\n')
