"""Rounds that run past their chain's end -- to the face it ends at (issue 12, point 1), to a mitre's plane --
at radii up to what fits.

One rim edge of a pocket (cases.pocket_edge) runs at both ends into the next wall, while the block's top
face goes on around the pocket's corner. From r = 10 (reach 3 r = 30 mm) the top face's base mesh takes in
the far side of the pocket too, and its vertices on an end's plane beyond the chain's end (the next rim
edge, up to the pocket's far corner) measured as inside the band: holes and points that were not a number
(refused, but the radius fits: max_radius gives 12 and, drafted 10 degrees, 14.52). Now every radius up to
0.98 of the limit rounds, sound and within r / 100 of OCCT's fillet of that edge both ways.
"""
import pytest

import cases
import reference

import MeshRound


def assert_sound_and_like_occt(case, mesh, res):
    """Within r / 100 of OCCT's fillet both ways; watertight, oriented, local, no degenerate or crossing facets."""
    row = reference.score(case, mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= 0.01 and row["dev_ref_to_out"] <= 0.01, row
    reference.assert_sound_and_local(row)


@pytest.mark.parametrize("draft, radius", [(0.0, 10.0), (0.0, 11.76), (10.0, 11.5), (10.0, 14.2)])
def test_a_rim_edge_rounds_into_the_walls_at_its_ends_up_to_its_limit(draft, radius):
    case = cases.Case(f"pocket_edge_{draft:g}_r{radius:g}", cases.pocket_edge(draft), radius)
    mesh = cases.mesh_of(case.solid, MaxLength=2.0)
    before = mesh.Topology
    res = MeshRound.round_edges(mesh, case.seeds, radius)
    assert mesh.Topology == before
    assert_sound_and_like_occt(case, mesh, res)


# The whole rim, its four rounds mitred at the corners: where a round runs past its chain's end to the
# mitre's plane (r past the end at a square corner), the band's corner is farther from the chain than the
# contact line; mesh vertices there were taken as clearly outside without being measured, and one a hair
# inside the line was left beside it unsnapped: near-duplicate cut points and a degenerate gap at the
# mitre's top corner from r = 8 on a 1.5 mm mesh (max_radius: 12).
@pytest.mark.parametrize("radius", [8.0, 11.76])
def test_a_square_rim_mitres_at_large_radii(radius):
    case = cases.Case(f"pocket_rim_square_r{radius:g}", cases.pocket_rim_square(0.0), radius)
    mesh = cases.mesh_of(case.solid, MaxLength=1.5)
    res = MeshRound.round_edges(mesh, case.seeds, radius)
    assert [c["kind"] for c in res.report["corners"]] == ["mitre"] * 4
    assert_sound_and_like_occt(case, mesh, res)


# Where a mitre's foot on the pocket's wall corner falls a hair (5e-5 mm) from a mesh vertex there: the two
# rounds meeting at it judged "on the line" with slacks of their own (6e-5 and 4.5e-5 mm, from their
# chains' coordinates), so one took the vertex as its corner and the other cut beside it (a degenerate
# facet). The slack is now the mesh's (its float32 precision), the same for every round.
@pytest.mark.parametrize("element", [1.0, 3.0])
def test_a_mitres_foot_a_hair_from_a_mesh_vertex_is_that_vertex(element):
    radius = 9.0 - 5e-5  # the wall contact at z = 21 + 5e-5; both meshes have a vertex at z = 21 on the corner
    case = cases.Case(f"pocket_rim_square_foot_{element:g}", cases.pocket_rim_square(0.0), radius)
    mesh = cases.mesh_of(case.solid, MaxLength=element)
    res = MeshRound.round_edges(mesh, case.seeds, radius)
    assert [c["kind"] for c in res.report["corners"]] == ["mitre"] * 4
    assert_sound_and_like_occt(case, mesh, res)
