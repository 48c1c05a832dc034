"""Several chains in one call: each chain gets the radius control points nearest to it; chains that meet at a
corner are blended there (two rounds: a mitre; three: the corner ball), and what is not blended yet is refused
naming the corner, with the input left as it was."""
import os

import numpy as np
import pytest

import FreeCAD

import MeshRound
import soundness
from MeshRound import meshconv
from conftest import BOX_OTHER_SEED, BOX_SEED, BOX_SIZE

V = FreeCAD.Vector
X, Y, Z = BOX_SIZE
# Back edge (y = Y): 2 -> 6 mm from x = 0 to x = X; front edge (y = 0): 5 -> 3 mm.
BACK_LAW = [(V(0, Y, Z), 2.0), (V(X, Y, Z), 6.0)]
FRONT_LAW = [(V(0, 0, Z), 5.0), (V(X, 0, Z), 3.0)]


def profile_radius(face, u):
    """Radius of the circle through three points of the surface's profile at u (v = 0, 1/2, 1)."""
    a, b, c = (np.array(tuple(face.Surface.value(u, v))) for v in (0.0, 0.5, 1.0))
    return (np.linalg.norm(b - a) * np.linalg.norm(c - a) * np.linalg.norm(c - b)
            / (2 * np.linalg.norm(np.cross(b - a, c - a))))


def surface_near(faces, y):
    """The rounding surface whose first profile lies at y (back or front edge)."""
    return min(faces, key=lambda f: abs(f.Surface.value(f.ParameterRange[0], 0.5).y - y))


@pytest.fixture(scope="module")
def two_laws(box):
    # The control points are given mixed up on purpose: each belongs to the chain nearest to it.
    law = [BACK_LAW[0], FRONT_LAW[1], BACK_LAW[1], FRONT_LAW[0]]
    return MeshRound.round_edges(box, [BOX_SEED, BOX_OTHER_SEED], law)


def test_each_chain_follows_its_own_control_points(two_laws):
    assert two_laws.report["chains"] == 2
    for y, law in ((Y, BACK_LAW), (0.0, FRONT_LAW)):
        face = surface_near(two_laws.surfaces, y)
        u0, u1, _, _ = face.ParameterRange
        ends = sorted([(face.Surface.value(u, 0.5).x, profile_radius(face, u)) for u in (u0, u1)])
        assert ends[0][1] == pytest.approx(law[0][1], rel=1e-6)   # at x = 0
        assert ends[1][1] == pytest.approx(law[1][1], rel=1e-6)   # at x = X


def test_two_rounded_chains_leave_a_closed_clean_mesh(two_laws):
    out = two_laws.mesh
    assert out.isSolid() and not out.hasNonManifolds() and not out.hasSelfIntersections()
    assert two_laws.report["max_deviation"] <= 6.0 / 100


def test_two_convex_rounds_meet_at_their_mitre_and_the_input_is_kept(box):
    # The back and the end face's top edges meet at (X, Y, Z), the vertical edge there stays sharp, r = 3:
    # as OCCT's fillet, each round is its cylinder up to the plane x - X = y - Y bisecting the two edges, so
    # every vertex of the corner's cell (x > X - r, y > Y - r, z > Z - r) lies on the cylinder of its side.
    r = 3.0
    before = meshconv.mesh_to_arrays(box)
    out = MeshRound.round_edges(box, [BOX_SEED, V(X, Y / 2, Z)], r).mesh
    after = meshconv.mesh_to_arrays(box)
    assert np.array_equal(before[0], after[0]) and np.array_equal(before[1], after[1])
    assert out.isSolid() and not out.hasNonManifolds() and not out.hasSelfIntersections()
    pts = np.array([[p.x, p.y, p.z] for p in out.Points])
    f32 = 2e-5
    cell = np.all(pts > np.array([X - r, Y - r, Z - r]) + f32, axis=1)
    assert cell.sum() > 10
    back = pts[:, 0] - X <= pts[:, 1] - Y  # the back edge's side of the mitre plane
    to_back_axis = np.hypot(pts[:, 1] - (Y - r), pts[:, 2] - (Z - r))
    to_end_axis = np.hypot(pts[:, 0] - (X - r), pts[:, 2] - (Z - r))
    on_own = np.where(back, to_back_axis, to_end_axis)
    assert np.abs(on_own[cell] - r).max() < 1e-4
    assert np.any(cell & (np.abs(pts[:, 0] - X - (pts[:, 1] - Y)) < f32) & (pts[:, 2] < Z - 0.5 * r))  # the mitre's curve


def corner_of_box_mesh(element, square=True):
    """The part of MeshPart's `element` mm mesh of the box within 15 mm of the corner (X, Y, Z) (all three faces
    there; float32 points as meshed), kept in tests/python/data: the whole mesh takes the mesher a minute.
    The crop's edge is ragged (whole facets); `square`: cut square to the three chains, 13.5 mm from the corner,
    so that each chain runs off the mesh's edge across a plane square to it (a round ends only on such an edge)."""
    data = np.load(os.path.join(os.path.dirname(__file__), "data", f"box_corner_mesh{element}.npz"))
    V, F = data["V"], data["F"]
    if square:
        for axis, at in ((0, X - 13.5), (1, Y - 13.5), (2, Z - 13.5)):
            V, F = clipped(V, F, axis, at)
    return meshconv.arrays_to_mesh(V, F)


def clipped(V, F, axis, at):
    """The part of (V, F) where coordinate `axis` >= at: facets across that plane cut along it (a point on each
    cut edge, made once), the unused points dropped."""
    points, out, cut = [tuple(p) for p in V], [], {}

    def on_plane(a, b):
        if (min(a, b), max(a, b)) not in cut:
            pa, pb = np.array(points[a]), np.array(points[b])
            q = pa + (at - pa[axis]) / (pb[axis] - pa[axis]) * (pb - pa)
            q[axis] = at
            points.append(tuple(q))
            cut[min(a, b), max(a, b)] = len(points) - 1
        return cut[min(a, b), max(a, b)]

    for f in F:
        inside = [points[v][axis] >= at for v in f]
        if all(inside):
            out.append(list(f))
        elif any(inside):
            ring = []
            for k in range(3):
                if inside[k]:
                    ring.append(f[k])
                if inside[k] != inside[(k + 1) % 3]:
                    ring.append(on_plane(f[k], f[(k + 1) % 3]))
            out += [[ring[0], ring[k], ring[k + 1]] for k in range(1, len(ring) - 1)]
    points, out = np.array(points), np.array(out)
    used = np.unique(out)
    index = np.full(len(points), -1)
    index[used] = np.arange(len(used))
    return points[used], index[out]


@pytest.mark.parametrize("element", [1.0, 0.7])
def test_chains_running_off_a_ragged_crop_edge_are_refused_naming_the_end(element):
    """The crop's own edge (whole facets, up to 0.9 mm off the plane across each chain's end): the round's end
    cannot lie on it; refused naming the end, the input intact (it used to slide boundary vertices off the edge)."""
    mesh = corner_of_box_mesh(element, square=False)
    before = mesh.Topology
    seeds = [V(X - 7, Y, Z), V(X, Y - 7, Z), V(X, Y, Z - 7)]
    with pytest.raises(MeshRound.RoundingError, match=r"runs off the mesh's edge at \(.*\), but that edge is not one plane there") as err:
        MeshRound.round_edges(mesh, seeds, 5.0)
    assert err.value.code == "corner_not_blendable"
    assert mesh.Topology == before


@pytest.mark.parametrize("element, r", [(2.0, 3.0), (1.0, 5.0), (0.7, 5.0), (2.0, 5.999), (2.0, 9.999), (2.0, 13.999), (2.0, 17.999)])
def test_three_rounds_at_a_corner_meet_in_the_corner_ball(box, element, r):
    # The three edges at the box corner (X, Y, Z): the corner is the ball touching the three faces, centred r
    # inside each of them; every vertex near the corner lies on that ball or on the rounds' cylinders.
    # On the 1.0 and 0.7 mm meshes face vertices lie within a quarter edge of the rounds' corners on the
    # end planes: they are moved onto them, or the corner splits the face's edge beside it (both were
    # refused: the move was dropped where the end plane needed no facet split; a sliver beside the corner).
    # At r = 6 - 0.001 ... 18 - 0.001 on the 2 mm mesh the end planes cross the chains 0.001 mm from a vertex:
    # the vertex slides onto the plane (a split there left a sliver the output check refused).
    mesh = box if element == 2.0 else corner_of_box_mesh(element)
    seeds = [BOX_SEED, V(X, Y / 2, Z), V(X, Y, Z / 2)] if element == 2.0 else [V(X - 7, Y, Z), V(X, Y - 7, Z), V(X, Y, Z - 7)]
    before = mesh.Topology
    res = MeshRound.round_edges(mesh, seeds, r)
    assert mesh.Topology == before
    out = res.mesh
    V0, F0 = meshconv.mesh_to_arrays(mesh)
    V1, F1 = meshconv.mesh_to_arrays(out)
    ends = [((X - 13.5, Y, Z), 1.01 * r), ((X, Y - 13.5, Z), 1.01 * r), ((X, Y, Z - 13.5), 1.01 * r)]
    assert soundness.problems(V0, F0, V1, F1, open_ends=ends) == []  # the crop's edge kept but for the end profiles
    centre = np.array([X - r, Y - r, Z - r])
    pts = np.array([[p.x, p.y, p.z] for p in out.Points])
    f32 = 2e-5  # a Mesh.Mesh keeps float32 coordinates: ~1e-5 mm at 100 mm
    in_cell = np.all(pts >= centre - f32, axis=1)  # beyond all three rounds' end planes
    assert in_cell.sum() > 10
    assert np.abs(np.linalg.norm(pts[in_cell] - centre, axis=1) - r).max() < f32
    assert not np.any(np.all(pts > centre + f32, axis=1) & (np.linalg.norm(pts - centre, axis=1) > r + f32))


def test_a_radius_law_still_changing_into_a_three_round_corner_is_refused_naming_it(box):
    """(A law that agrees at the corner and holds its value there rounds: test_mixed_radii.py.)"""
    seeds = [BOX_SEED, V(X, Y / 2, Z), V(X, Y, Z / 2)]
    law = [(V(0, Y, Z), 3.0), (V(X, Y, Z), 4.0), (V(X, 0, Z), 3.0), (V(X, Y, 0), 3.0)]
    with pytest.raises(MeshRound.RoundingError, match=r"still changes within 2 r of the corner at \(100, 60, 40\)") as refused:
        MeshRound.round_edges(box, seeds, law)
    assert refused.value.code == "corner_not_blendable"


def test_a_chain_without_control_points_is_refused(box):
    with pytest.raises(MeshRound.RoundingError, match="no radius control point lies on the chain picked at"):
        MeshRound.round_edges(box, [BOX_SEED, BOX_OTHER_SEED], BACK_LAW)


def test_a_law_the_ball_cannot_follow_names_the_control_point(box):
    law = [(V(0, Y, Z), 3.0), (V(X, Y, Z), 45.0)]  # 45 mm: wider than the 40 mm side face
    with pytest.raises(MeshRound.RoundingError, match=r"too large.*control point at \(100, 60, 40\) \(r = 45"):
        MeshRound.round_edges(box, [BOX_SEED], law)


def test_both_top_edges_with_one_radius(box):
    """The front edge runs against x in the mesh's chain order: its profiles must loft as well."""
    res = MeshRound.round_edges(box, [BOX_SEED, BOX_OTHER_SEED], 5.0)
    assert res.report["chains"] == 2 and len(res.surfaces) == 2
    assert res.mesh.isSolid() and not res.mesh.hasSelfIntersections()
