"""Large radii at a mitre: two top edges of a 100 x 60 x 40 box rounded into their corner at (100, 60, 40),
the vertical edge there left sharp. OCCT's fillet fits any radius up to the box's height (40 mm); so must
MeshRound. The balls stop r before the corner (their setback) and are measured on a ball clear of the
mitre: for a radius over a quarter of the 60 mm edge, that ball is found further along the chain (before,
r = 15.5 to 39.9 was refused as too large). On a box only 30 mm deep the two ends' setbacks may take 0.9 of
that edge: 26.4 rounds, 26.6 is refused naming the chain. Reference: OCCT's fillet of the CAD box, both ways."""
import pytest

import cases
import Part
import reference

import MeshRound

LIMIT = 0.01 + reference.MEASURE  # / r: the tolerance r/100 plus the yardstick's own precision


def shallow_top_corner():
    """The two top edges at (100, 30, 40) of a 100 x 30 x 40 box: the mitred edge is 30 mm long."""
    s = Part.makeBox(100, 30, 40)
    at = cases.V(100, 30, 40)
    return s, [e for e in s.Edges if any((v.Point - at).Length < cases.TOL for v in e.Vertexes)
               and abs(e.Vertexes[0].Point.z - e.Vertexes[1].Point.z) < cases.TOL]


@pytest.mark.parametrize("builder, radius, variant", [(cases.box_top_corner, 20.0, "fine"), (cases.box_top_corner, 35.0, "coarse"),
                                                      (cases.box_top_corner, 35.0, "fine"), (shallow_top_corner, 26.4, "fine")])
def test_a_radius_past_a_quarter_of_the_edge_rounds_like_occt(builder, radius, variant):
    case = cases.Case(f"{builder.__name__}_r{radius:g}", builder, radius)
    assert_rounds_like_occt(case, case.mesh(variant))


@pytest.mark.parametrize("radius", [3.0, 5.0, 20.0, 39.9])
def test_a_sliver_left_at_the_mitre_is_not_taken_for_the_fold(radius):
    """A 2.5 mm mesh of the box: the first round's trim leaves a thin top facet on the second chain's last
    edge, beside the first round's end cap (upright in the mitre plane). The sliver is flat with the top,
    so the cap beside it is a wall, not the rest of a fold: before, the cap was taken into the top's base
    mesh and the chain through the corner as turning onto it, and every radius was refused."""
    case = cases.Case(f"box_top_corner_r{radius:g}_mesh2.5", cases.box_top_corner, radius)
    assert_rounds_like_occt(case, cases.mesh_of(case.solid, MaxLength=2.5))


def assert_rounds_like_occt(case, mesh):
    before = mesh.Topology
    res = MeshRound.round_edges(mesh, case.seeds, case.radius, tolerance=case.tolerance)
    assert mesh.Topology == before
    row = reference.score(case, mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= LIMIT and row["dev_ref_to_out"] <= LIMIT, row
    assert row["boundary_edges_out"] == row["boundary_edges_in"] == 0
    assert row["nonmanifold_edges"] == 0 and row["misoriented_edges"] == 0 and row["degenerate_facets"] == 0
    assert row["orientation_kept"] and not row["self_intersections"]
    assert row["far_vertices_lost"] == 0


def test_a_radius_past_the_face_is_refused_naming_it():
    """40.1 mm does not fit on the 40 mm high side faces: refused, the input intact."""
    solid, edges = cases.box_top_corner()  # (OCCT's fillet itself fails at this radius)
    mesh = cases.mesh_of(solid, MaxLength=2.5 * 40.1)
    seeds = [e.valueAt(0.5 * (e.FirstParameter + e.LastParameter)) for e in edges]
    before = mesh.Topology
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_edges(mesh, seeds, 40.1)
    assert err.value.code == "radius_too_large"
    assert mesh.Topology == before


def test_setbacks_past_most_of_the_edge_are_refused_naming_the_chain():
    """26.6 mm on the 30 mm edge: the two ends' setbacks would take more than 0.9 of it."""
    solid, edges = shallow_top_corner()
    mesh = cases.mesh_of(solid, MaxLength=2.0)
    seeds = [e.valueAt(0.5 * (e.FirstParameter + e.LastParameter)) for e in edges]
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_edges(mesh, seeds, 26.6)
    assert err.value.code == "radius_too_large" and "too short" in str(err.value)
