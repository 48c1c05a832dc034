"""A sharp edge that runs off the mesh's edge: die meshes are open shells (the working surface only), and a
shoulder often runs to the mesh's boundary. The round runs to the chain's end and its end profile, in the plane
across the chain there, becomes part of the mesh's edge -- as OCCT's fillet of the open shell does (the
open_sheet and lchannel_open cases of test_accuracy.py compare both ways against it on fine, coarse and CAD
meshes). Here: radii from r/100 of the face to just under it on structured and coarse grids, the boundary
checked point by point, and the ends that cannot be made refused with the input intact."""
import math

import numpy as np
import pytest

import cases
import soundness
from MeshRound import api
import MeshRound

SEED = (50.0, 60.0, 40.0)
ENDS = [np.array([0.0, 60.0, 40.0]), np.array([100.0, 60.0, 40.0])]


def sheet_arrays(max_length, crop_deg=None):
    """The top and back faces of a 100 x 60 x 40 box, meshed (the chain: their shared edge, y = 60, z = 40). With
    crop_deg = (top, back), its end at x = 100 is cut slanted across the chain (cases.cropped)."""
    box = cases.Part.makeBox(100 if crop_deg is None else 160, 60, 40)
    shell = cases.Part.makeShell([f for f in box.Faces if abs(f.CenterOfMass.z - 40) < 1e-9 or abs(f.CenterOfMass.y - 60) < 1e-9])
    if crop_deg is not None:
        shell = cases.cropped(shell, cases.V(100, 60, 40), crop_deg)
    mesh = cases.mesh_of(shell, MaxLength=max_length)
    V = np.array([[p.x, p.y, p.z] for p in mesh.Topology[0]])
    return V, np.array(mesh.Topology[1])


@pytest.mark.parametrize("max_length", [2.0, 5.0])
@pytest.mark.parametrize("radius", [0.5, 2.0, 5.0, 20.0, 39.2])
def test_a_shoulder_running_off_the_mesh_edge_rounds_to_its_end_profile(max_length, radius):
    V, F = sheet_arrays(max_length)
    res = api.round_arrays(V, F, SEED, radius)
    V1, F1 = np.asarray(res.vertices), np.asarray(res.triangles)
    # Sound, with the end profiles (and nothing else new) on the boundary; without them the check bites.
    ends = [(e, 1.01 * radius) for e in ENDS]
    assert soundness.problems(V, F, V1, F1, open_ends=ends) == []
    assert any("new boundary edge" in p for p in soundness.problems(V, F, V1, F1))
    # The new boundary points at each end lie on the exact end profile: the circle of radius r about
    # (y, z) = (60 - r, 40 - r) in the end plane, within the tolerance r / 100.
    table = soundness.edge_table(F1)
    on_boundary = np.unique(table["edges"][table["count"] == 1])
    P = V1[on_boundary]
    for x in (0.0, 100.0):
        arc = P[(np.abs(P[:, 0] - x) < 1e-9) & (P[:, 1] > 60 - radius + 1e-6) & (P[:, 2] > 40 - radius + 1e-6)]
        assert len(arc) >= 3
        r_at = np.hypot(arc[:, 1] - (60 - radius), arc[:, 2] - (40 - radius))
        assert np.abs(r_at - radius).max() <= radius / 100 + 1e-6 * 100


def test_a_radius_over_the_back_face_is_refused_at_the_mesh_boundary():
    V, F = sheet_arrays(2.0)
    V0, F0 = V.copy(), F.copy()
    with pytest.raises(MeshRound.RoundingError, match=r"mesh boundary at \(") as err:
        api.round_arrays(V, F, SEED, 40.8)
    assert err.value.code == "radius_too_large"
    assert np.array_equal(V, V0) and np.array_equal(F, F0)


def end_profile_points(V1, F1, radius, plane_normal):
    """The result's boundary points on the round's end profile at x ~ 100, in the quarter between the two contact
    lines (y >= 60 - r, z >= 40 - r), and their distance to the crop plane through the chain's end (100, 60, 40)."""
    table = soundness.edge_table(F1)
    P = V1[np.unique(table["edges"][table["count"] == 1])]
    P = P[(np.abs(P[:, 0] - 100) < 3 * radius) & (P[:, 1] > 60 - radius - 1e-6) & (P[:, 2] > 40 - radius - 1e-6)]
    return P, (P - np.array([100.0, 60.0, 40.0])) @ plane_normal


@pytest.mark.parametrize("max_length", [2.0, 5.0])
@pytest.mark.parametrize("crop_deg,radius", [((30.0, 0.0), 5.0), ((60.0, 0.0), 5.0), ((0.0, 40.0), 20.0),
                                             ((30.0, 20.0), 5.0), ((30.0, 20.0), 20.0), ((60.0, 0.0), 0.5)])
def test_an_end_slanted_across_the_chain_rounds_to_the_plane_of_the_mesh_edge(crop_deg, radius, max_length):
    """The mesh's edge at the chain's end is cut slanted (the top face acute, the back face obtuse, or both): as
    OCCT's fillet of the open shell, the round runs on to that plane and its end profile is the round's section by
    it (an ellipse), which becomes the mesh's edge (test_accuracy's open_sheet_slanted compares with OCCT)."""
    V, F = sheet_arrays(max_length, crop_deg)
    res = api.round_arrays(V, F, SEED, radius)
    V1, F1 = np.asarray(res.vertices), np.asarray(res.triangles)
    assert soundness.problems(V, F, V1, F1, open_ends=[(e, 3 * radius) for e in ENDS]) == []
    top, back = (math.tan(math.radians(a)) for a in crop_deg)
    normal = np.array([1.0, -top, back]) / math.sqrt(1 + top * top + back * back)
    P, off = end_profile_points(V1, F1, radius, normal)
    assert len(P) >= 3
    assert np.abs(off).max() <= 1e-6 * 100  # on the crop plane
    on_round = np.hypot(P[:, 1] - (60 - radius), P[:, 2] - (40 - radius))  # on the round's cylinder
    assert np.abs(on_round - radius).max() <= radius / 100 + 1e-6 * 100
    # reaching its contacts on both faces: the ellipse's ends, where the plane meets the two contact lines
    assert P[:, 1].min() < 60 - radius + 1e-6 * 100 and P[:, 2].min() < 40 - radius + 1e-6 * 100


def test_an_end_cut_nearly_along_the_chain_is_refused_naming_it():
    """A crop 75 degrees from square: the plane would cut the round over a length of 4 r; refused, input intact."""
    V, F = sheet_arrays(2.0, (75.0, 0.0))
    V0, F0 = V.copy(), F.copy()
    with pytest.raises(MeshRound.RoundingError, match=r"runs off the mesh's edge at \(100, 60, 40\) along that edge") as err:
        api.round_arrays(V, F, SEED, 5.0)
    assert err.value.code == "corner_not_blendable"
    assert np.array_equal(V, V0) and np.array_equal(F, F0)


def test_an_end_whose_cut_bends_within_the_round_is_refused_naming_where():
    """The top face's end cut at 30 degrees from the chain's end for 3 mm across, then square: the mesh's edge is
    not one plane out to the end profile's contacts (5 mm across at r 5); refused corner_not_blendable naming
    the place, input intact. (At r 2 its contacts lie on the first plane: it rounds.)"""
    V_ = cases.V
    bend = V_(100 - 3 * math.tan(math.radians(30)), 57, 40)
    top = cases.Part.Face(cases.Part.makePolygon([V_(0, 0, 40), V_(bend.x, 0, 40), bend, V_(100, 60, 40), V_(0, 60, 40), V_(0, 0, 40)]))
    back = cases.Part.Face(cases.Part.makePolygon([V_(0, 60, 0), V_(100, 60, 0), V_(100, 60, 40), V_(0, 60, 40), V_(0, 60, 0)]))
    shell = cases.Part.makeShell([top, back])
    shell.sewShape(1e-6)
    mesh = cases.mesh_of(shell, MaxLength=1.0)
    V = np.array([[p.x, p.y, p.z] for p in mesh.Topology[0]])
    F = np.array(mesh.Topology[1])
    V0, F0 = V.copy(), F.copy()
    with pytest.raises(MeshRound.RoundingError, match=r"is not one plane there: at \(") as err:
        api.round_arrays(V, F, SEED, 5.0)
    assert err.value.code == "corner_not_blendable"
    assert np.array_equal(V, V0) and np.array_equal(F, F0)
    res = api.round_arrays(V, F, SEED, 2.0)
    V1, F1 = np.asarray(res.vertices), np.asarray(res.triangles)
    assert soundness.problems(V, F, V1, F1, open_ends=[(e, 3 * 2.0) for e in ENDS]) == []


# ------------------------------------------------------------------ a die's working surface, open at its edge
def open_die():
    """The S-rail die's working surface only (binder flat, channel walls and floor: an open shell, as a tool mesh
    comes to CAE), both shoulders running off its edge at x = 0 and x = 360; and its mesh (MeshPart, 8 mm)."""
    import srail_die  # (on the path through die_meshes)
    d = srail_die.DEFAULT
    solid = srail_die.die_solid()
    def on_side(f):
        bb = f.BoundBox
        return (bb.XMax < 1e-6 or bb.XMin > d.length - 1e-6 or bb.YMax < 1e-6 or bb.YMin > d.width - 1e-6 or bb.ZMax < 1e-6)
    shell = cases.Part.makeShell([f for f in solid.Faces if not on_side(f)])
    edges = srail_die.shoulder_edges(shell)
    mesh = cases.mesh_of(shell, MaxLength=8.0)
    return shell, edges, mesh


def test_the_shoulders_of_an_open_die_round_like_occt_both_ways():
    import die_meshes  # noqa: F401  (puts resources/srail on the path)
    import reference
    from MeshRound import meshconv
    import srail_die
    shell, edges, mesh = open_die()
    r = 5.0
    case = cases.Case("open_die_r5", lambda: (shell, edges), r)
    V0, F0 = meshconv.mesh_to_arrays(mesh)
    assert soundness.boundary_loops(soundness.edge_table(F0)) == 1
    res = MeshRound.round_edges(mesh, srail_die.shoulder_seeds(), r, tolerance=r / 100)
    V1, F1 = meshconv.mesh_to_arrays(res.mesh)
    chain_ends = [np.array(tuple(v.Point)) for e in edges for v in e.Vertexes
                  if v.Point.x < 1e-6 or v.Point.x > srail_die.DEFAULT.length - 1e-6]
    assert len(chain_ends) == 4  # each shoulder runs off the edge at both ends
    assert soundness.problems(V0, F0, V1, F1, open_ends=[(p, 1.01 * r) for p in chain_ends]) == []
    row = reference.score(case, mesh, res.mesh, res.report)
    bound = reference.allowed_deviation(row)
    assert row["dev_out_to_ref"] <= bound and row["dev_ref_to_out"] <= bound, row
    assert row["boundary_loops_out"] == 1 and row["boundary_off_reference"] <= bound, row
    assert row["far_facets_lost"] == 0 and row["far_facets_added"] == 0
