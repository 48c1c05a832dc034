"""Broken facets near the chain are refused with a RoundingError that names the place, and the input
arrays are left as they were: a non-manifold edge, a facet without area, a facet with a repeated vertex."""
import numpy as np
import pytest

import MeshRound
from MeshRound import api, meshconv
from conftest import BOX_RADIUS, BOX_SEED


@pytest.fixture(scope="module")
def arrays(box):
    return meshconv.mesh_to_arrays(box)


def band_facet(V, F):
    """A facet of the top face about 2 mm from the picked edge (y = 60, z = 40), near x = 50."""
    c = V[F].mean(axis=1)
    near = np.flatnonzero((np.abs(c[:, 1] - 58) < 1.5) & (np.abs(c[:, 2] - 40) < 1e-6) & (np.abs(c[:, 0] - 50) < 2))
    assert near.size, "the test mesh has no facet there"
    return int(near[0])


def broken(kind, V, F):
    V, F = V.copy(), F.copy()
    f = band_facet(V, F)
    a, b, c = F[f]
    if kind == "non-manifold":
        F = np.vstack([F, F[f:f + 1]])          # the same facet twice: its edges have three facets
    elif kind == "no area":
        V[a] = 0.5 * (V[b] + V[c])              # a corner moved onto the opposite side
    else:
        F[f] = [a, a, b]
    return V, F


@pytest.mark.parametrize("kind, message", [
    ("non-manifold", r"edge at \(.*\) near the chain is non-manifold"),
    ("no area", r"facet \d+ at \(.*\) near the chain is degenerate"),
    ("repeated vertex", r"facet \d+ at \(.*\) near the chain is degenerate"),
])
def test_broken_facets_near_the_chain_are_refused(arrays, kind, message):
    # As arrays: Mesh.Mesh itself drops some of these facets when it is built.
    V, F = broken(kind, *arrays)
    V_before, F_before = V.copy(), F.copy()
    with pytest.raises(MeshRound.RoundingError, match=message):
        api.round_arrays(V, F, BOX_SEED, BOX_RADIUS)
    assert np.array_equal(V, V_before) and np.array_equal(F, F_before)
