"""Never a broken mesh: inputs that used to give a broken result (open, non-manifold, mis-oriented,
degenerate or self-intersecting) are refused with the right code and the input untouched, or rounded to
a sound mesh. Behind them the engine's output guard refuses anything unsound with result_invalid.

  * a radius too large for the face beside the edge: on the grid mesh the ball touches the next sharp
    edge at a vertex, which the wall test used to miss;
  * a huge radius on the S-rail die;
  * a few facets missing beside the chain, or a couple of mm from it inside the band;
  * a flipped facet beside the chain.
"""
import re

import numpy as np
import pytest

import cases  # first: it puts FreeCAD's modules on the path
import MeshPart
import MeshRound
import Part
import die_meshes
import soundness
from MeshRound import api, meshconv
from conftest import BOX_SEED, BOX_SIZE, grid_box

RADIUS = 5.0


def cad_box():
    return meshconv.mesh_to_arrays(MeshPart.meshFromShape(Shape=Part.makeBox(*BOX_SIZE), MaxLength=2))


@pytest.fixture(scope="module", params=["grid", "cad"])
def box_arrays(request):
    return grid_box() if request.param == "grid" else cad_box()


def assert_sound(V0, F0, result):
    """The result's topology is the input's (tests/python/soundness.py)."""
    assert soundness.problems(V0, F0, result.vertices, result.triangles) == []


def assert_refused(V, F, seed, radius, code, message=None):
    V_before, F_before = V.copy(), F.copy()
    with pytest.raises(MeshRound.RoundingError, match=message) as error:
        api.round_arrays(V, F, seed, radius)
    assert error.value.code == code, str(error.value)
    assert np.array_equal(V, V_before) and np.array_equal(F, F_before)
    return str(error.value)


# ---------------------------------------------------------------- 1. a radius too large for the face
@pytest.mark.parametrize("radius", [41.0, 40.5])
def test_a_radius_larger_than_the_face_beside_the_edge_is_refused(box_arrays, radius):
    # The back face is 40 high: the ball touches its bottom edge (at a vertex, on the grid).
    V, F = box_arrays
    message = assert_refused(V, F, BOX_SEED, radius, "radius_too_large",
                             r"would reach past the next sharp edge or the mesh boundary at \(.*\)")
    assert "radius " + f"{radius:g}" in message


def test_a_radius_just_under_the_face_rounds_soundly(box_arrays):
    V, F = box_arrays
    result = api.round_arrays(V, F, BOX_SEED, 39.5)
    assert result.report["facets_added"] > 0
    assert_sound(V, F, result)


# ---------------------------------------------------------------------- 2. a huge radius on the die
def test_a_huge_radius_on_the_die_is_refused():
    V, F, seeds = die_meshes.die_arrays(1)
    for seed in (seeds[0], seeds):
        assert_refused(V, F, seed, 1e5, "radius_too_large", r"radius 100000 is too large at \(")


# ------------------------------------------------------------------- 3. facets missing near the chain
def without_facets_near(V, F, point, count):
    centroids = V[F].mean(axis=1)
    drop = np.argsort(np.linalg.norm(centroids - np.array(point), axis=1))[:count]
    return F[np.setdiff1d(np.arange(len(F)), drop)]


def round_with_hole(box_arrays, where, count):
    """The box with `count` facets nearest `where` taken out, and its rounding: (V, F, result, error)."""
    V, F = box_arrays
    F = without_facets_near(V, F, where, count)
    try:
        return V, F, api.round_arrays(V, F, BOX_SEED, RADIUS), None
    except MeshRound.RoundingError as error:
        return V, F, None, error


@pytest.mark.parametrize("count", [1, 2, 3])
@pytest.mark.parametrize("where", [(50.0, 59.5, 40.0), (50.0, 60.0, 39.5)], ids=["top", "back"])
def test_a_hole_beside_the_chain_is_refused_or_rounded_soundly(box_arrays, where, count):
    V, F, result, error = round_with_hole(box_arrays, where, count)
    if error is not None:
        assert error.code == "non_manifold_input", str(error)
        assert "open next to the chain at (50, 60, 40)" in str(error)
    else:
        assert_sound(V, F, result)  # the hole lay inside the round and went with it


@pytest.mark.parametrize("count", [1, 2, 3])
@pytest.mark.parametrize("where", [(50.0, 57.0, 40.0), (50.0, 60.0, 36.0), (50.0, 52.0, 40.0)],
                         ids=["top-3mm", "back-4mm", "top-8mm"])
def test_a_hole_inside_the_band_is_refused_or_rounded_soundly(box_arrays, where, count):
    V, F, result, error = round_with_hole(box_arrays, where, count)
    if error is not None:
        # The ball would touch the hole's edge: the room beside the chain ends there. Named as a hole, where it is
        # (it read "the next sharp edge or the mesh boundary"): a flaw to fill, or a pin hole that limits the radius.
        assert error.code == "radius_too_large" and "edge of a hole in the mesh at (" in str(error), str(error)
        assert named_point_near(error, where, 3.0), str(error)
    else:
        assert_sound(V, F, result)


def named_point_near(error, where, distance):
    """The last point the message names lies within `distance` of `where`."""
    x, y, z = map(float, re.findall(r"\(([-\d.e]+), ([-\d.e]+), ([-\d.e]+)\)", str(error))[-1])
    return np.linalg.norm(np.array([x, y, z]) - np.array(where)) <= distance


# ------------------------------------------------------------------------------- 5. a flipped facet
@pytest.mark.parametrize("where", [(50.0, 59.5, 40.0), (50.0, 60.0, 39.5), (50.0, 57.0, 40.0), (50.0, 55.2, 40.0),
                                   (50.0, 60.0, 35.1), (50.0, 52.0, 40.0)],
                         ids=["top-beside", "back-beside", "top-3mm", "top-cut", "back-cut", "top-8mm"])
def test_a_flipped_facet_near_the_chain_is_refused(box_arrays, where):
    V, F = box_arrays
    F = F.copy()
    f = int(np.argmin(np.linalg.norm(V[F].mean(axis=1) - np.array(where), axis=1)))
    F[f] = F[f][[0, 2, 1]]
    assert_refused(V, F, BOX_SEED, RADIUS, "non_manifold_input", r"near the chain are oriented against each other \(a flipped facet\)")


# ------------------------------------------------------- 6. a hole or a flipped facet at a corner
# Two rounds meeting in a mitre (the vertical edge left sharp) and three in a sphere corner, at the box's
# corner (100, 60, 40). The facets around a corner lie beyond the rounds' ends, where each chain's own
# checks do not look: a flaw there is named as the input's (non_manifold_input), not as a corner that
# cannot be made or a result that failed its check.
CORNER_SEEDS = {"mitre": [(50.0, 60.0, 40.0), (100.0, 30.0, 40.0)],
                "sphere": [(50.0, 60.0, 40.0), (100.0, 30.0, 40.0), (100.0, 60.0, 20.0)]}
NEAR_CORNER = [(100.0, 58.0, 39.5), (100.0, 56.5, 37.5), (99.0, 59.5, 38.5), (97.0, 57.0, 40.0), (100.0, 55.5, 35.5)]
NEAR_CORNER_IDS = ["at-vertex", "side-2mm", "back-1mm", "top-3mm", "side-contact"]


@pytest.mark.parametrize("blend", ["mitre", "sphere"])
@pytest.mark.parametrize("where", NEAR_CORNER, ids=NEAR_CORNER_IDS)
def test_a_hole_at_a_corner_is_named_as_the_inputs_or_rounded_soundly(box_arrays, blend, where):
    V, F = box_arrays
    F = without_facets_near(V, F, where, 1)
    F_before = F.copy()
    try:
        result = api.round_arrays(V, F, CORNER_SEEDS[blend], RADIUS)
    except MeshRound.RoundingError as error:
        assert np.array_equal(F, F_before)
        if error.code == "radius_too_large":  # the ball would touch the hole's edge, as beside one chain
            assert "edge of a hole in the mesh at (" in str(error), str(error)
        else:
            assert error.code == "non_manifold_input", str(error)
            assert "the mesh is open" in str(error), str(error)
    else:
        assert_sound(V, F, result)  # the hole lay inside the rounds and went with them


@pytest.mark.parametrize("blend", ["mitre", "sphere"])
@pytest.mark.parametrize("where", NEAR_CORNER, ids=NEAR_CORNER_IDS)
def test_a_flipped_facet_at_a_corner_is_named_as_the_inputs(box_arrays, blend, where):
    V, F = box_arrays
    F = F.copy()
    f = int(np.argmin(np.linalg.norm(V[F].mean(axis=1) - np.array(where), axis=1)))
    F[f] = F[f][[0, 2, 1]]
    assert_refused(V, F, CORNER_SEEDS[blend], RADIUS, "non_manifold_input", r"oriented against each other \(a flipped facet\)")


# ------------------------------------- 7. a hole or a flipped facet on the faces a round's end is cut from
# The L bracket's shoulder (cases.l_bracket(1), CAD mesh: each face a few large facets) ends on the block's end
# face (x = 80) and on the 135-degree wall; each end's cap is cut from the facets there. With one of those facets
# missing (a hole) or facing the other way, the gap between the round's end profile and the cut facets could not
# be closed and the refusal read "a new boundary edge, a hole in the mesh at (66.97, 0, 25)" (result_invalid), a
# place on the front face away from the flaw. Now it names the input's flaw (non_manifold_input) at a point of
# the facet's sides. ("front-beside-chain": the seed then picks the wall's foot, whose end meets the hole.)
L_BRACKET_FACETS = {"end-face-beyond-cap": (80.0, 14.3, 6.7), "wall-above-cap": (75.7, 8.7, 30.0),
                    "end-face-cap": (80.0, 4.3, 6.7), "front-beside-chain": (75.7, 0.0, 6.7)}


def l_bracket_arrays():
    case = cases.case("l_bracket_135")
    V, F = meshconv.mesh_to_arrays(case.mesh("cad"))
    return V, F, [tuple(s) for s in case.seeds], case.radius


@pytest.mark.parametrize("flaw", ["hole", "flip"])
@pytest.mark.parametrize("where", list(L_BRACKET_FACETS))
def test_a_hole_or_a_flipped_facet_where_a_round_s_end_cap_is_cut_is_named_as_the_inputs(where, flaw):
    V, F, seeds, radius = l_bracket_arrays()
    f = int(np.argmin(np.linalg.norm(V[F].mean(axis=1) - np.array(L_BRACKET_FACETS[where]), axis=1)))
    corners = V[F[f]]
    if flaw == "hole":
        F = np.delete(F, f, axis=0)
        says = r"the mesh is open \((a hole in it|a hole beside)"
    else:
        F = F.copy()
        F[f] = F[f][[0, 2, 1]]
        says = r"oriented against each other \(a flipped facet\)"
    error = assert_refused(V, F, seeds, radius, "non_manifold_input", says)
    assert any(on_a_side(p, corners) for p in points_named(error)), error


def on_a_side(p, corners, within=1e-3):
    """Point p lies on one of the triangle's sides."""
    p = np.array(p)
    for a, b in zip(corners, np.roll(corners, -1, axis=0)):
        t = np.clip(np.dot(p - a, b - a) / np.dot(b - a, b - a), 0.0, 1.0)
        if np.linalg.norm(a + t * (b - a) - p) <= within:
            return True
    return False


def points_named(message):
    return [tuple(map(float, m)) for m in re.findall(r"\(([-\d.e]+), ([-\d.e]+), ([-\d.e]+)\)", str(message))]
