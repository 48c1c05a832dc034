"""Broken facets near the chain are refused with a RoundingError that names the place, and the input
arrays are left as they were: a non-manifold edge, a facet without area, a facet with a repeated vertex;
and a ball whose contacts lie beyond the reach, on any kind of mesh."""
import numpy as np
import pytest

import cases  # first: it puts FreeCAD's modules on the path
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


# A slot whose walls open by 30 degrees: a ball of r = 4 touches them 3.73 r from the edge, beyond the
# default reach of 3 r. On fine meshes that shows at the base meshes' edge; on coarse and CAD meshes the
# contact lies inside a facet that runs past the reach, and must be refused just the same (it used to
# make a broken mesh).
SLOT_PROFILE = [(0, 0), (70, 0), (70, 10), (30, 10), (82, 40), (0, 40)]  # (y, z), floor z = 10 from y = 30


@pytest.fixture(scope="module")
def narrow_slot():
    return cases.extruded_profile(SLOT_PROFILE, 60)


@pytest.mark.parametrize("variant", ["fine", "coarse", "cad"])
def test_a_ball_touching_beyond_the_reach_is_refused_on_any_mesh(narrow_slot, variant):
    options = dict(cases.MESH_VARIANTS[variant])
    if "MaxLength" in options:
        options["MaxLength"] *= 4.0
    V, F = meshconv.mesh_to_arrays(cases.mesh_of(narrow_slot, **options))
    V_before, F_before = V.copy(), F.copy()
    seed = (20.0, 30.0, 10.0)
    with pytest.raises(MeshRound.RoundingError, match=r"touches the base mesh beyond the reach; increase the reach factor"):
        api.round_arrays(V, F, seed, 4.0)
    assert np.array_equal(V, V_before) and np.array_equal(F, F_before)
    result = api.round_arrays(V, F, seed, 4.0, reach=4.5)  # as the message says: room for the contacts
    assert result.report["facets_added"] > 0 and result.report["max_deviation"] <= 0.04
