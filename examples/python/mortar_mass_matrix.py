#!/usr/bin/env python3
# %% [markdown]
# # The mortar mass matrix from plmap's regions, with numpy and scipy.sparse
#
# Mortar and contact methods couple two non-matching P1 discretizations of one interface through
#
#     M_ij = ∫_D φ_i(x) ψ_j(Ξ(x)) dx,
#
# φ_i the hat functions of S1, ψ_j those of S2. On each region of a plmap map (a piece
# T1 ∩ Ξ⁻¹(T2)) both factors are affine, so φ_i ψ_j is quadratic there and a degree-2 rule on
# the region integrates it exactly. `Map.regions()` hands over all regions as flat arrays, so
# the assembly below is a few vectorised lines with no loop over regions.
#
# Run it as a script (`python3 mortar_mass_matrix.py [MAP.plmap]`) or cell by cell (`# %%`) in an
# editor that understands them. Without an argument it builds its own map: two triangulations of
# the unit square, one structured and one jittered, related by normal projection (the identity of
# the plane). The C++ twin is examples/mortar_mass_matrix; the test
# bindings/python/tests/test_mortar_example.py checks that both give the same matrix.

# %%
import sys

import numpy as np
import scipy.sparse

import plmap


# %% [markdown]
# ## Quadrature: degree-2 rules in barycentric coordinates of a region
# Triangles: the three edge midpoints, weight 1/3 each. Segments: Simpson's rule.

# %%
def degree_two_rule(d):
    """(corner weights (q, d+1), weights (q,)) of a rule exact for quadratics on a d-simplex."""
    if d == 2:
        return np.array([[0.5, 0.5, 0.0], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5]]), np.full(3, 1 / 3)
    return np.array([[1.0, 0.0], [0.5, 0.5], [0.0, 1.0]]), np.array([1 / 6, 4 / 6, 1 / 6])


def barycentric(local):
    """Local coordinates (..., d) -> barycentric (..., d+1): the P1 basis functions' values."""
    return np.concatenate([1 - local.sum(axis=-1, keepdims=True), local], axis=-1)


# %% [markdown]
# ## Assembly
# For every region r and quadrature point q: the point in local coordinates of the S1 element
# and of the S2 element (the same barycentric combination of the region's corners on both sides,
# since Ξ is affine on r), the hat functions there, and their products, times the weight and the
# region's measure. One COO triplet per (region, q, a, b); scipy sums the duplicates.

# %%
def mortar_mass_matrix(m):
    """M (S1 vertices x S2 vertices) as a scipy.sparse CSR matrix."""
    r = m.regions()
    d = m.dimension
    rows = m.domain.elements[r["domain_element"]]  # (R, d+1) S1 vertices of each region's element
    cols = m.target.elements[r["target_element"]]  # (R, d+1) S2 vertices
    corner_weights, weights = degree_two_rule(d)
    values = np.zeros((len(rows), d + 1, d + 1))
    for w_corner, w in zip(corner_weights, weights):
        on_s1 = np.einsum("c,rck->rk", w_corner, r["domain_local"])
        on_s2 = np.einsum("c,rck->rk", w_corner, r["target_local"])
        phi, psi = barycentric(on_s1), barycentric(on_s2)
        values += (w * r["domain_measure"])[:, None, None] * phi[:, :, None] * psi[:, None, :]
    i = np.broadcast_to(rows[:, :, None], values.shape)
    j = np.broadcast_to(cols[:, None, :], values.shape)
    shape = (m.domain.vertex_count, m.target.vertex_count)
    return scipy.sparse.coo_matrix((values.ravel(), (i.ravel(), j.ravel())), shape=shape).tocsr()


def lumped_mass(surface):
    """∫ of each hat function: |T| / (d+1) from every element at the vertex."""
    x = surface.vertices[surface.elements]
    if surface.dimension == 2:
        measure = 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1)
    else:
        measure = np.linalg.norm(x[:, 1] - x[:, 0], axis=1)
    return np.bincount(surface.elements.ravel(), np.repeat(measure / (surface.dimension + 1),
                                                           surface.dimension + 1),
                       minlength=surface.vertex_count)


# %% [markdown]
# ## A map to try it on
# Two triangulations of the unit square in the plane z = 0: a 6 x 6 grid, and a 9 x 9 grid whose
# interior vertices are jittered. Normal projection between coplanar surfaces is the identity of
# the plane, so D = S1 and Ξ(D) = S2.

# %%
def square_grid(cells, jitter=0.0, seed=0):
    t = np.linspace(0.0, 1.0, cells + 1)
    x, y = (a.ravel() for a in np.meshgrid(t, t))
    interior = (x > 0) & (x < 1) & (y > 0) & (y < 1)
    rng = np.random.default_rng(seed)
    x[interior] += jitter / cells * (rng.random(interior.sum()) - 0.5)
    y[interior] += jitter / cells * (rng.random(interior.sum()) - 0.5)
    i, j = (a.ravel() for a in np.meshgrid(np.arange(cells), np.arange(cells)))
    v = j * (cells + 1) + i
    triangles = np.concatenate([np.column_stack([v, v + 1, v + cells + 2]),
                                np.column_stack([v, v + cells + 2, v + cells + 1])])
    return plmap.Surface(np.column_stack([x, y, np.zeros_like(x)]), triangles)


def example_map():
    return plmap.project(square_grid(6), square_grid(9, jitter=0.5, seed=1))


# %% [markdown]
# ## Assemble and check
# Where D = S1 and Ξ(D) = S2 with Ξ measure-preserving, the entries sum to |S1|, the row sums are
# the lumped masses of S1 and the column sums those of S2.

# %%
def main(argv):
    m = plmap.load(argv[1]) if len(argv) > 1 else example_map()
    M = mortar_mass_matrix(m)
    print(f"{m}: M is {M.shape[0]} x {M.shape[1]} with {M.nnz} nonzeros")
    if len(argv) > 1:
        return 0
    errors = {
        "sum of all entries - |S1|": abs(M.sum() - m.domain.measure),
        "row sums - lumped mass of S1": np.abs(M.sum(axis=1).A1 - lumped_mass(m.domain)).max(),
        "column sums - lumped mass of S2": np.abs(M.sum(axis=0).A1 - lumped_mass(m.target)).max(),
    }
    for what, error in errors.items():
        print(f"  {what:<34} {error:.2e}")
    return 0 if max(errors.values()) <= 1e-12 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
