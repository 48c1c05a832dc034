"""S-rail die meshes of any size for the speed tests, in about a second.

Meshing the die finely with Mefisto takes minutes (about a minute for 120k facets).  Instead its coarse
mesh (elements of about 8 mm, 9198 facets) is refined: every facet is split into k x k facets in its own
plane, which keeps the die's surfaces, its sharp shoulders and a closed, consistently oriented mesh, with
k^2 times the facets (k = 4: 147k, k = 11: 1.1M).

    vertices, triangles, seeds = die_meshes.die_arrays(4)     # float64 (n, 3), int64 (m, 3), [Vector] x 2
"""
import functools
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SRAIL = os.path.join(os.path.dirname(os.path.dirname(HERE)), "resources", "srail")
if SRAIL not in sys.path:
    sys.path.append(SRAIL)

BASE_ELEMENT = 8.0  # mm


def subdivide(vertices, triangles, k):
    """Every triangle split into k x k triangles in its plane, with its orientation.  A new point is
    identified by its integer barycentric weights on the input vertex ids, so points on shared edges are
    made once (computed once, from the same sorted weights) and the result stays conforming."""
    vertices = np.asarray(vertices, dtype=np.float64)
    triangles = np.asarray(triangles, dtype=np.int64)
    i, j = (a.ravel() for a in np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij"))
    keep = i + j <= k
    i, j = i[keep], j[keep]
    lattice = {(a, b): n for n, (a, b) in enumerate(zip(i.tolist(), j.tolist()))}
    weights = np.stack([k - i - j, i, j], axis=1)                 # (p, 3) on the corners a, b, c
    m, p = len(triangles), len(weights)
    ids = np.broadcast_to(triangles[:, None, :], (m, p, 3))
    w = np.broadcast_to(weights[None, :, :], (m, p, 3))
    ids = np.where(w > 0, ids, -1)                                # corners with weight 0 do not count
    order = np.argsort(ids, axis=2, kind="stable")
    ids = np.take_along_axis(ids, order, axis=2).reshape(-1, 3)
    w = np.take_along_axis(w, order, axis=2).reshape(-1, 3)
    keys, inverse = np.unique(np.concatenate([ids, w], axis=1), axis=0, return_inverse=True)
    points = np.einsum("nk,nkd->nd", keys[:, 3:].astype(np.float64), vertices[np.maximum(keys[:, :3], 0)]) / k
    local = []  # the k^2 small triangles of one input triangle, as lattice point numbers
    for a in range(k):
        for b in range(k - a):
            local.append((lattice[a, b], lattice[a + 1, b], lattice[a, b + 1]))
            if a + b < k - 1:
                local.append((lattice[a + 1, b], lattice[a + 1, b + 1], lattice[a, b + 1]))
    faces = inverse.reshape(m, p)[:, np.array(local, dtype=np.int64)].reshape(-1, 3)
    return points, faces


@functools.lru_cache(maxsize=1)
def _base_die():
    import srail_die
    points, facets = srail_die.die_mesh(BASE_ELEMENT).Topology  # 9198 facets: small enough for Topology
    return (np.array([tuple(p) for p in points], dtype=np.float64),
            np.array(facets, dtype=np.int64), srail_die.shoulder_seeds())


def die_arrays(k):
    """(vertices, triangles, seeds) of the die with 9198 * k^2 facets; seeds: one point on each shoulder."""
    vertices, triangles, seeds = _base_die()
    return (*subdivide(vertices, triangles, k), list(seeds))
