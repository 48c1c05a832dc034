"""Accuracy of MeshRound.round_edges against OCCT's exact fillet of the CAD solid that was meshed.

Every case of cases.py x every mesh variant (fine, coarse, cad) is rounded once with tolerance r/100; the
figures (reference.score) are printed (pytest -s) and written to tests/artifacts/accuracy.json.
Bounds, all relative to the exact answer, none hard-coded per case:
  * deviation both ways <= tolerance + the input's own tessellation error near the chain (+ the
    yardstick's own precision, reference.MEASURE);
  * topology as the input's: boundary loops (on the reference's free edges), no non-manifold / mis-oriented / degenerate facets, no
    self-intersection, orientation kept;
  * locality: input vertices and facets beyond reach * r are in the result bit for bit, and no facet is
    made entirely beyond the reach;
  * smoothness: made facets turn by at most max(20 deg, the input's own faceting near the chain + 1 deg);
  * quality: no made facet under 10 deg unless the input has such facets near the chain and the report
    says so (input_forces_small_angles), or it is at a concave end's cusp, where the round's end leaves a
    face tangentially and no facet within the tolerance has an angle over acos(1 - t / r) (reference.CUSP_NEAR,
    CUSP_FLOOR; the report's cusp_facets); the report counts the facets under 10 deg exactly. (Thin
    facets that the reach forces on large CAD facets: test_room.py.)
"""
import json
import os
import sys
import time

import numpy as np
import pytest

import cases
import reference

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.append(os.path.join(HERE, "..", "..", "Mod", "MeshRound"))
ARTIFACT = os.path.join(HERE, "..", "artifacts", "accuracy.json")

MAX_TURN_DEG = 20.0  # a round at t = r/100 turns ~16 deg between facets
MIN_ANGLE_DEG = 10.0
RUNS = [(c, v) for c in cases.CONSTANT + cases.VARIABLE for v in cases.MESH_VARIANTS]
ROWS = {}

# Known engine faults, one line per (property, case, mesh): expected to fail, and strict, so that a fix
# turns the line into a failure until it is struck from this list.
# Rounds ending at corners on CAD meshes (a rim edge into the pocket's next wall, the whole rim, the rim with its
# wall corners, the L bracket's shoulder into its 135 degree wall): deviation, topology, locality and smoothness
# hold, but the CAD facets that span the whole face beside the band's corner leave new facets under 10 degrees
# there. (A box corner's three rounds and its two top edges, and the pyramid, left such facets too where each
# round's trim cut the facets the one before had made: a network's flat patches are now meshed again whole,
# improve.h remesh_flat_patches. The whole rim's top face is an annulus whose out-of-reach strip along the
# block's edge leaves no room for 10 degrees at reach 3.)
# (The drafted rim edge's CAD mesh passes since a single chain's flat patches with facets under 10 degrees are
# meshed again whole, as a network's, and its new facets then counted again: its report said 31 under 10 degrees
# where the yardstick found 26; now both 24, where its input's own go down to 0.76 degrees.)
_CAD_CORNER_THIN = {("pocket_edge", "cad"), ("pocket_rim_square", "cad"), ("pocket_rim_walls", "cad"), ("l_bracket_135", "cad")}
_REFUSED = set()  # (none now: the drafted rim with its wall corners on the CAD mesh rounds since the trim
                  # line stopped taking points a hair outside their facet)
KNOWN_FAULTS = {
    "deviation": set(_REFUSED),
    "topology": set(_REFUSED),
    "locality": set(_REFUSED),
    "smoothness": set(_REFUSED),
    # (A concave end's cusp -- the round's end leaves the top face's trace tangentially -- forces facets
    # under 10 degrees there: allowed as reference.CUSP_NEAR / CUSP_FLOOR say, and named by the report. The
    # fine and the drafted coarse rim edge were faults until a point was put on the cap's edge along the
    # top face one step from the cusp: 1.4 and 1.8 deg, now 5.6 and 5.5.)
    "quality": _CAD_CORNER_THIN | _REFUSED,
}


def runs(prop):
    """RUNS for one property, the known faults marked as strict expected failures."""
    faults = KNOWN_FAULTS[prop]
    return [pytest.param(c, v, marks=pytest.mark.xfail(strict=True, reason="known engine fault"))
            if (c, v) in faults else (c, v) for c, v in RUNS]


def round_case(name, variant):
    """Round one case (once per session) and score it against the exact fillet."""
    if (name, variant) not in ROWS:
        import MeshRound
        case = cases.case(name)
        mesh = case.mesh(variant)
        started = time.perf_counter()
        try:
            res = MeshRound.round_edges(mesh, case.seeds, case.radius, tolerance=case.tolerance)
        except MeshRound.RoundingError as exc:
            ROWS[name, variant] = dict(case=name, mesh=variant, error=str(exc))
        else:
            row = dict(case=name, mesh=variant, seconds=time.perf_counter() - started)
            row.update(reference.score(case, mesh, res.mesh, res.report))
            ROWS[name, variant] = row
        figures = {k: round(v, 4) if isinstance(v, float) else v for k, v in ROWS[name, variant].items()}
        print("\n" + json.dumps(figures))
    row = ROWS[name, variant]
    if "error" in row:
        pytest.fail(f"round_edges refused {name}/{variant}: {row['error']}")
    return row



@pytest.fixture(scope="module", autouse=True)
def write_artifact():
    """Rows of this run replace the same (case, mesh) rows of the file: a -k run keeps the others."""
    yield
    if not ROWS:
        return
    try:
        with open(ARTIFACT) as f:
            rows = {(r["case"], r["mesh"]): r for r in json.load(f)}
    except (OSError, ValueError, KeyError, TypeError):
        rows = {}
    rows.update(ROWS)
    os.makedirs(os.path.dirname(ARTIFACT), exist_ok=True)
    with open(ARTIFACT, "w") as f:
        json.dump(list(rows.values()), f, indent=1)


# ----------------------------------------------------------------------------------- the yardstick itself
def test_meshes_are_float32_already():
    """Mesh.Mesh holds float32 points: no STL round trip is needed to give MeshRound what a file would."""
    V, _ = reference.mesh_arrays(cases.case("pocket_rim").mesh("coarse"))
    assert np.array_equal(V.astype(np.float32).astype(float), V)


@pytest.mark.parametrize("name", ["box", "pocket_rim"])
def test_yardstick_scores_the_cad_route_near_zero(name):
    """OCCT's fillet re-meshed finely is within the yardstick's precision of itself."""
    case = cases.case(name)
    out = cases.mesh_of(case.reference, LinearDeflection=case.r_max / 1000,
                                       AngularDeflection=0.1, Relative=False)
    row = reference.score(case, case.mesh("cad"), out)
    assert row["dev_out_to_ref"] < reference.MEASURE and row["dev_ref_to_out"] < reference.MEASURE


def test_yardstick_sees_a_dent():
    """A vertex of the exact round pushed r/20 into the solid shows as a deviation of about r/20.  (This
    tessellation has round vertices only on the end faces: the push is inward from both.)"""
    case = cases.case("box")
    V, F = reference.mesh_arrays(cases.mesh_of(
        case.reference, LinearDeflection=case.r_max / 1000, AngularDeflection=0.1, Relative=False))
    axis = np.array([35.0, 25.0])  # the round's axis in (y, z); x runs along the edge, end faces x = 0, 60
    on_round = np.where(np.abs(np.linalg.norm(V[:, 1:] - axis, axis=1) - 5) < 1e-3)[0]
    i = on_round[np.argmax(np.minimum(V[on_round, 1] - 35, V[on_round, 2] - 25) - V[on_round, 0])]
    push = 0.05 * case.r_max
    V[i, 1:] -= push * (V[i, 1:] - axis) / 5
    V[i, 0] += push
    row = reference.score(case, case.mesh("cad"), cases.Mesh.Mesh([list(map(tuple, V[f])) for f in F]))
    assert 0.9 * push / case.r_max < row["dev_out_to_ref"] < 1.1 * push / case.r_max


@pytest.mark.parametrize("name", cases.VARIABLE)
def test_reference_law_ends_as_specified(name):
    """The variable references (per-edge Part::Fillet stations) start and end at the radii asked for."""
    case = cases.case(name)
    (_, r_first), (_, r_last) = case.radius[0], case.radius[-1]
    assert r_first == pytest.approx(case.law[0][1], rel=0.02)
    assert r_last == pytest.approx(case.law[-1][1], rel=0.02)


# ---------------------------------------------------------------------------------------- the rounding
@pytest.mark.parametrize("name,variant", runs("deviation"))
def test_deviation_both_ways(name, variant):
    row = round_case(name, variant)
    assert row["dev_out_to_ref"] <= reference.allowed_deviation(row)
    assert row["dev_ref_to_out"] <= reference.allowed_deviation(row)


@pytest.mark.parametrize("name,variant", runs("topology"))
def test_topology_is_kept(name, variant):
    row = round_case(name, variant)
    # The boundary (an open shell's edge) keeps its loops and lies on the reference's own free edges: where a
    # round runs off the mesh's edge, its end profile becomes part of that edge, as in OCCT's fillet.
    assert row["boundary_loops_out"] == row["boundary_loops_in"]
    assert row["boundary_off_reference"] <= reference.allowed_deviation(row)
    assert (row["nonmanifold_edges"], row["misoriented_edges"], row["degenerate_facets"]) == (0, 0, 0)
    assert row["orientation_kept"] and not row["self_intersections"]


@pytest.mark.parametrize("name,variant", runs("locality"))
def test_far_mesh_is_untouched(name, variant):
    row = round_case(name, variant)
    assert row["far_vertices_lost"] == 0
    assert row["far_facets_lost"] == 0
    assert row["far_facets_added"] == 0


@pytest.mark.parametrize("name,variant", runs("smoothness"))
def test_round_is_smooth(name, variant):
    row = round_case(name, variant)
    assert row["max_dihedral_new_deg"] <= max(MAX_TURN_DEG, row["max_dihedral_input_deg"] + 1.0)


@pytest.mark.parametrize("name,variant", runs("quality"))
def test_no_slivers_made(name, variant):
    row = round_case(name, variant)
    assert row["thin_facets"] == row["slivers_new"], "the report miscounts the facets under 10 degrees"
    if row["min_angle_new_deg"] >= MIN_ANGLE_DEG:
        return
    if row["slivers_new_off_round_ends"] == 0 and row["min_angle_input_near_deg"] >= MIN_ANGLE_DEG:
        # every one at a cusp of the exact round (reference.CUSP_NEAR, CUSP_FLOOR), and the report says so
        assert row["cusp_facets"] == row["slivers_new"], "the report does not name the cusps' facets"
        return
    assert row["min_angle_input_near_deg"] < MIN_ANGLE_DEG, "slivers made where the input has none"
    assert row["input_forces_small_angles"], "the report does not say the input forced small angles"


def test_no_sliver_beside_a_sphere_corner_on_a_cad_mesh():
    """The box corner's three rounds on its CAD mesh (each face two facets): the new facets within 1.5 r of the
    corner vertex are 10 deg or more. A cut facet's extra trim points were spaced in the surface's parameter,
    which at a sphere corner's plane runs 5 mm over the last 0.25 mm of the line: a point landed 0.05 mm from
    the band's corner and left facets of 3.0 deg there. (Farther out, on the 100 x 40 faces, the three trims
    left 8 thin facets: test_no_slivers_made[box_corner-cad] checks them all.)"""
    import MeshRound
    case = cases.case("box_corner")
    mesh = case.mesh("cad")
    res = MeshRound.round_edges(mesh, case.seeds, case.radius, tolerance=case.tolerance)
    V0, F0 = reference.mesh_arrays(mesh)
    V1, F1 = reference.mesh_arrays(res.mesh)
    old = {tuple(sorted(map(tuple, V0[f]))) for f in F0}
    corner = np.array([100.0, 60.0, 40.0])
    near = [f for f in F1 if tuple(sorted(map(tuple, V1[f]))) not in old
            and np.linalg.norm(V1[f].mean(axis=0) - corner) <= 1.5 * case.radius]
    assert len(near) > 100  # the corner's patch and the rounds' ends
    smallest = min(min_angle_deg(V1[f]) for f in near)
    assert smallest >= 10.0, smallest


def min_angle_deg(P):
    """The smallest angle of triangle P (3 x 3), degrees."""
    out = []
    for i in range(3):
        u, w = P[(i + 1) % 3] - P[i], P[(i + 2) % 3] - P[i]
        out.append(np.degrees(np.arccos(np.clip(u @ w / np.linalg.norm(u) / np.linalg.norm(w), -1, 1))))
    return min(out)
