"""Corners of four rounds: a square pyramid with every edge rounded, where four rounds meet at the apex and
three at each base corner. OCCT's fillet makes no valid solid of it (it does not blend four rounds at a
vertex); the rolling ball's answer -- and the reference here -- is the solid offset inwards by r and back
out with round joins (cases.pyramid): at the apex one ball touches the four faces, and the corner is a
patch of it bounded by the four rounds' end arcs.

Where the four faces' offsets do not meet in one point (the apex off the base's centre) no ball touches
all four: that corner needs an n-sided patch, which is refused by name, the input intact."""
import math

import numpy as np
import pytest

import cases
import FreeCAD
import Part
import reference
import soundness

import MeshRound
from MeshRound import meshconv

R = 4.0
TOL = R / 100
V = FreeCAD.Vector


def edge_middles(edges):
    return [e.valueAt(0.5 * (e.FirstParameter + e.LastParameter)) for e in edges]


def apex_ball(apex_height=30.0, half_base=30.0):
    """The ball of radius R touching the four faces of the regular pyramid: on its axis, R from each face."""
    slope = math.atan2(apex_height, half_base)  # the faces' angle to the base
    return np.array([30.0, 30.0, apex_height - R / math.cos(slope)])


@pytest.mark.parametrize("variant", ["fine", "coarse", "cad"])
def test_four_rounds_meet_in_the_ball_at_a_pyramids_apex(variant):
    case = cases.case("pyramid")
    mesh = case.mesh(variant)
    before = mesh.Topology
    res = MeshRound.round_edges(mesh, case.seeds, R, tolerance=TOL)
    assert mesh.Topology == before
    V0, F0 = meshconv.mesh_to_arrays(mesh)
    V1, F1 = meshconv.mesh_to_arrays(res.mesh)
    assert soundness.problems(V0, F0, V1, F1) == []
    # Against the offset solid, both ways (the report's corners come from the engine; the bar does not).
    row = reference.score(case, mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= 0.01 * R and row["dev_ref_to_out"] <= 0.01 * R, row
    corners = {tuple(np.round(c["vertex"], 6)): c for c in res.report["corners"]}
    assert sorted(corners) == sorted([(0, 0, 0), (60, 0, 0), (60, 60, 0), (0, 60, 0), (30, 30, 30)])
    apex = corners[(30, 30, 30)]
    assert apex["kind"] == "sphere" and len(apex["chains"]) == 4
    assert apex["deviation"] <= TOL and apex["normal_jump_deg"] <= 0.5
    # The patch's vertices lie on the ball touching the four faces, computed from the solid alone.
    centre = apex_ball()
    d = np.linalg.norm(V1 - centre, axis=1)
    near_apex = (V1[:, 2] > centre[2]) & (np.linalg.norm(V1[:, :2] - 30.0, axis=1) < 0.5 * R)
    assert near_apex.sum() >= 3
    assert np.abs(d[near_apex] - R).max() <= TOL
    for c in corners.values():
        if c["vertex"][2] == 0:
            assert c["kind"] == "sphere" and len(c["chains"]) == 3


def skewed_pyramid():
    """The apex at (24, 30, 30), off the base's centre: the four faces' offsets by R miss one point."""
    pts = [V(0, 0, 0), V(60, 0, 0), V(60, 60, 0), V(0, 60, 0)]
    apex = V(24, 30, 30)
    faces = [Part.Face(Part.makePolygon(pts + pts[:1]))]
    faces += [Part.Face(Part.makePolygon([pts[i], pts[(i + 1) % 4], apex, pts[i]])) for i in range(4)]
    s = Part.Solid(Part.Shell(faces))
    return s, [e for e in s.Edges if any((v.Point - apex).Length < 1e-9 for v in e.Vertexes)]


def test_four_rounds_whose_faces_have_no_common_ball_are_refused_by_name():
    solid, edges = skewed_pyramid()
    assert len(edges) == 4
    mesh = cases.mesh_of(solid, MaxLength=1.6)
    before = (mesh.Topology, mesh.CountFacets)
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_edges(mesh, edge_middles(edges), R, tolerance=TOL)
    assert err.value.code == "corner_not_blendable"
    assert "(24, 30, 30)" in str(err.value) and "n-sided patch" in str(err.value)
    assert (mesh.Topology, mesh.CountFacets) == before


@pytest.mark.parametrize("element, radius", [(0.0, 1.0), (0.0, 3.0), (1.0, 3.0), (3.0, 1.0)])
def test_a_clean_input_is_never_blamed(element, radius):
    """Every edge of the pyramid at other radii and meshes (element 0: the CAD mesh, one facet per face):
    a sound result, or a refusal that does not send the user to repair a mesh that is clean -- a pass
    that finds the mesh an earlier pass of the call made unfit reports result_invalid."""
    solid, edges = cases.pyramid()
    if element:
        mesh = cases.mesh_of(solid, MaxLength=element)
    else:
        mesh = cases.mesh_of(solid, **cases.MESH_VARIANTS["cad"])
    V0, F0 = meshconv.mesh_to_arrays(mesh)
    try:
        res = MeshRound.round_edges(mesh, edge_middles(edges), radius)
    except MeshRound.RoundingError as err:
        assert err.code not in ("non_manifold_input", "no_sharp_edge", "invalid_input"), str(err)
        return
    V1, F1 = meshconv.mesh_to_arrays(res.mesh)
    assert soundness.problems(V0, F0, V1, F1) == []


def test_a_flipped_facet_near_the_apex_is_named_as_the_inputs():
    """A flipped facet beside the apex that the first chains' passes do not reach: a later pass meets it,
    and the refusal still names the input's fault (non_manifold_input), not the call's own mesh."""
    solid, edges = cases.pyramid()
    V0, F0 = meshconv.mesh_to_arrays(cases.mesh_of(solid, MaxLength=1.6))
    near = int(np.linalg.norm(V0[F0].mean(axis=1) - [28, 28, 26], axis=1).argmin())
    F1 = F0.copy()
    F1[near] = F1[near][[0, 2, 1]]
    mesh = meshconv.arrays_to_mesh(V0, F1)
    before = mesh.Topology
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_edges(mesh, edge_middles(edges), R)
    assert err.value.code == "non_manifold_input" and "flipped" in str(err.value)
    assert mesh.Topology == before
