"""Independent yardstick: how far a rounded mesh is from OCCT's exact fillet, and whether it is a sound mesh.

Everything here is numpy + scipy (cKDTree), vectorised, and the tests' own module _yardstick (yardstick.cpp:
OCCT's BVH and 2D face classifier); nothing calls MeshRound.  Distances are exact point-to-triangle distances
to a triangle set; the exact solids are tessellated 2,000 times finer than r
(LinearDeflection 5e-4 r), so "exact" means to 5e-4 r, 1/20 of the tolerance r/100.
`score(case, inp, out, report)` returns every figure of one rounding; see test_accuracy.py for the bounds.
"""
import hashlib
import itertools

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

import cases
from _yardstick import Triangles, in_domain, surface_points  # built by tools/setup.sh (tests/python/CMakeLists.txt, yardstick.cpp)

SHARP_DEG = 20.0  # an edge of an exact solid is "its own sharp edge" when its faces turn by more


# ---------------------------------------------------------------------------------------------- arrays
def mesh_arrays(mesh):
    """(V float64 (n,3), F int64 (m,3)) of a Mesh.Mesh."""
    pts, facets = mesh.Topology
    return (np.array([tuple(p) for p in pts], dtype=float).reshape(-1, 3),
            np.array(facets, dtype=np.int64).reshape(-1, 3))


def shape_arrays(shape, deflection):
    """(V, F) of a Part shape tessellated with the given chordal deflection (MeshPart: Part's own
    Shape.tessellate takes minutes on a face with a hole at this deflection)."""
    return mesh_arrays(cases.mesh_of(shape, LinearDeflection=deflection,
                                                    AngularDeflection=0.1, Relative=False))


def dot(a, b):
    return np.einsum("ij,ij->i", a, b)


def norm(a):
    return np.sqrt(dot(a, a))


# ------------------------------------------------------------------------------------------- distances
def segment_distance(P, A, B):
    ab = B - A
    t = np.clip(dot(P - A, ab) / np.maximum(dot(ab, ab), 1e-300), 0.0, 1.0)
    return norm(P - A - ab * t[:, None])


def point_triangle_distance(P, A, B, C):
    """Row-wise exact distance from P[i] to triangle (A[i], B[i], C[i]): the plane distance when the
    projection falls inside the triangle, else the nearest of its three sides (also for zero-area ones)."""
    n = np.cross(B - A, C - A)
    nn = dot(n, n)
    inside = nn > 1e-30 * np.maximum(dot(B - A, B - A), 1e-300) ** 2
    for X, Y in ((A, B), (B, C), (C, A)):  # P projects to the inner side of every edge
        inside &= dot(np.cross(Y - X, P - X), n) >= 0
    out = np.minimum(np.minimum(segment_distance(P, A, B), segment_distance(P, B, C)), segment_distance(P, C, A))
    plane = np.abs(dot(P - A, n)) / np.sqrt(np.where(nn > 0, nn, 1.0))
    return np.where(inside, plane, out)


def pairs_within(tree, P, radius):
    """(point index, tree index) for every tree point within radius[i] of P[i] (flattened ball queries)."""
    lists = tree.query_ball_point(P, radius)
    counts = np.fromiter((len(x) for x in lists), dtype=np.int64, count=len(P))
    rows = np.repeat(np.arange(len(P)), counts)
    cols = np.fromiter(itertools.chain.from_iterable(lists), dtype=np.int64, count=int(counts.sum()))
    return rows, cols


class TriangleSet:
    """Exact distances to a triangle set: OCCT's BVH over the triangles, searched branch and bound, with the
    exact point-triangle distance of point_triangle_distance (yardstick.cpp, the tests' own module)."""

    def __init__(self, V, F):
        self._triangles = Triangles(V, np.asarray(F, dtype=np.int64).reshape(-1, 3))

    def distance(self, P):
        """Each point's distance to the nearest triangle (inf for an empty set)."""
        return self._triangles.distance(np.asarray(P, dtype=float).reshape(-1, 3))


# -------------------------------------------------------------------------------------- the chain
class Chain:
    """Distances to a case's CAD chain (sampled every 0.02 r: exact to 0.01 r)."""

    def __init__(self, case):
        self.points = case.points
        self.tree = cKDTree(self.points)

    def distance(self, P, within=np.inf):
        """Distance from each point to the chain, inf where it exceeds `within` (the search stops there: a
        large mesh sorted by a reach is sorted fast)."""
        return self.tree.query(P, distance_upper_bound=np.nextafter(within, np.inf))[0]

    def facet_distance(self, V, F, beyond):
        """For each facet, a figure on the same side of `beyond` as its distance to the chain (a bound of that
        distance; inf for a facet far beyond): what decides `> beyond`."""
        A, B, C = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
        cen = (A + B + C) / 3
        rad = np.max([norm(X - cen) for X in (A, B, C)], axis=0)
        dv = np.min([self.distance(X, beyond) for X in (A, B, C)], axis=0)  # upper bound (inf: > beyond)
        lo = np.maximum(self.distance(cen, beyond + rad.max(initial=0)) - rad, 0)  # lower bound
        out = np.where(lo > beyond, lo, dv)
        unsure = np.where((lo <= beyond) & (dv > beyond))[0]
        if len(unsure):
            rows, cols = pairs_within(self.tree, cen[unsure], rad[unsure] + beyond)
            d = point_triangle_distance(self.points[cols], A[unsure][rows], B[unsure][rows], C[unsure][rows])
            best = np.full(len(unsure), np.inf)
            np.minimum.at(best, rows, d)
            out[unsure] = np.minimum(dv[unsure], best)
        return out


# ---------------------------------------------------------------------------------- exact geometry
def near_triangles(V, F, chain, within):
    """The triangles of (V, F) whose centroid lies within `within` (+ their own size) of the chain."""
    cen = V[F].mean(axis=1)
    rad = np.max([norm(V[F[:, i]] - cen) for i in range(3)], axis=0)
    return F[chain.distance(cen, within + rad.max(initial=0)) <= within + rad]


def exact_skin(shape, case, chain, within):
    """TriangleSet of an exact solid's skin near the chain."""
    V, F = shape_arrays(shape, 5e-4 * case.r_max)
    return TriangleSet(V, near_triangles(V, F, chain, within))


def face_samples(face, step, keep=None):
    """Points on a CAD face on a (u, v) grid about `step` apart, inside its trimmed domain; `keep`: a test of
    the grid's points (array -> bool array) made before the (slower) domain test."""
    u0, u1, v0, v1 = face.ParameterRange
    length = lambda pts: sum((p - q).Length for p, q in zip(pts, pts[1:]))  # noqa: E731
    um, vm = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
    lu = length([face.valueAt(u, vm) for u in np.linspace(u0, u1, 33)])
    lv = length([face.valueAt(um, v) for v in np.linspace(v0, v1, 33)])
    us = np.linspace(u0, u1, int(np.ceil(lu / step)) + 1)
    vs = np.linspace(v0, v1, int(np.ceil(lv / step)) + 1)
    grid = np.stack(np.meshgrid(us, vs, indexing="ij"), axis=-1).reshape(-1, 2)
    brep = face.exportBrepToString()
    P = surface_points(brep, grid)  # as face.valueAt(u, v), for the whole grid at once
    wanted = keep(P) if keep is not None else np.ones(len(P), bool)
    if abs(face.Surface.toShape(u0, u1, v0, v1).Area - face.Area) <= 1e-7 * face.Area:
        return P[wanted]  # the face is its whole (u, v) rectangle: every grid point lies in it
    ids = np.flatnonzero(wanted)  # as face.isPartOfDomain(u, v), OCCT's classifier made once for them all
    return P[ids[in_domain(brep, grid[ids])]]


def round_samples(case):
    """Points on the exact rounds (OCCT's fillet faces), about r/20 apart."""
    return np.concatenate([face_samples(f, 0.05 * case.r_max) for f in case.rounds])


def surface_samples(V, F):
    """Vertices, edge midpoints and centroids of a triangle mesh (each once): where a chordal error shows."""
    E = unique_pairs(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1))
    return np.concatenate([V[np.unique(F)], V[E].mean(axis=1), V[F].mean(axis=1)])


def sharp_edge_points(shape, step):
    """Points along the edges of an exact solid whose two faces meet at more than SHARP_DEG."""
    pts = [np.zeros((0, 3))]
    for e in shape.Edges:
        faces = shape.ancestorsOfType(e, cases.Part.Face)
        if len(faces) != 2:
            continue
        p = e.valueAt(0.5 * (e.FirstParameter + e.LastParameter))
        n = [f.normalAt(*f.Surface.parameter(p)) for f in faces]
        if np.degrees(n[0].getAngle(n[1])) > SHARP_DEG:
            pts.append(cases.chain_points([e], step))
    return np.concatenate(pts)


# ------------------------------------------------------------------------------------ mesh topology
def unique_pairs(E, **options):
    """np.unique(E, axis=0, **options) for rows of two non-negative ids, sorted the same way (each row one
    int64 key: a sort of numbers, many times faster than numpy's sort of rows)."""
    n = int(E.max(initial=0)) + 1
    out = np.unique(E[:, 0].astype(np.int64) * n + E[:, 1], **options)
    keys = out[0] if options else out
    pairs = np.stack([keys // n, keys % n], axis=1)
    return (pairs,) + tuple(out[1:]) if options else pairs


def edge_table(F):
    """Undirected edges (sorted vertex pairs) with their facet count and up to two facets;
    also how many directed edges occur twice (neighbours whose orientations disagree)."""
    directed = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    facet = np.tile(np.arange(len(F)), 3)
    key = np.sort(directed, axis=1)
    edges, inv, count = unique_pairs(key, return_inverse=True, return_counts=True)
    inv = inv.ravel()
    order = np.argsort(inv, kind="stable")
    start = np.searchsorted(inv[order], np.arange(len(edges)))
    first = facet[order][start]
    second = np.where(count == 2, facet[order][np.minimum(start + 1, len(order) - 1)], -1)
    twice = len(directed) - len(unique_pairs(directed))
    return dict(edges=edges, count=count, first=first, second=second, misoriented=int(twice))


def facet_normals(V, F):
    n = np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    return n / np.maximum(norm(n), 1e-300)[:, None]


def min_angles_deg(V, F):
    T = V[F]
    ang = []
    for i in range(3):
        u, v = T[:, (i + 1) % 3] - T[:, i], T[:, (i + 2) % 3] - T[:, i]
        c = dot(u, v) / np.maximum(norm(u) * norm(v), 1e-300)
        ang.append(np.degrees(np.arccos(np.clip(c, -1, 1))))
    return np.min(ang, axis=0)


def signed_volume(V, F):
    return float(dot(V[F[:, 0]], np.cross(V[F[:, 1]], V[F[:, 2]])).sum() / 6)


def dihedrals_deg(V, F, table, edges):
    """Turn between the two facets of each given (manifold) edge."""
    n = facet_normals(V, F)
    c = dot(n[table["first"][edges]], n[table["second"][edges]])
    return np.degrees(np.arccos(np.clip(c, -1, 1)))


def max_dihedral_near(V, F, table, chain, reach, own_sharp, r, only=None, below=180.0):
    """Largest turn under `below` across manifold edges near the chain (midpoint within reach), except
    edges along the exact solid's own sharp edges (both ends within r/20 of one); `only`: a facet mask,
    edges must touch one of those facets."""
    E = table["edges"]
    ok = table["count"] == 2
    if only is not None:
        ok &= only[table["first"]] | only[np.maximum(table["second"], 0)]
    ok &= chain.distance(V[E].mean(axis=1), reach) <= reach
    if len(own_sharp):
        on = cKDTree(own_sharp).query(V, distance_upper_bound=0.06 * r)[0] <= 0.05 * r
        ok &= ~(on[E[:, 0]] & on[E[:, 1]])
    turn = dihedrals_deg(V, F, table, np.where(ok)[0])
    turn = turn[turn < below]
    return float(turn.max()) if len(turn) else 0.0


# -------------------------------------------------------------------------------------------- identity
def as_rows(X):
    X = np.ascontiguousarray(X)
    return X.view(np.dtype((np.void, X.dtype.itemsize * X.shape[1]))).ravel()


def common_vertex_ids(V0, V1):
    """Ids shared by bit-identical coordinates: (ids of V0, ids of V1)."""
    _, inv = np.unique(np.concatenate([V0, V1]), axis=0, return_inverse=True)
    inv = inv.ravel()
    return inv[:len(V0)], inv[len(V0):]


def cyclic_keys(F):
    """Facets as rows rotated to start at their smallest id: equal rows = same facet, same orientation."""
    k = F.argmin(axis=1)
    rows = np.arange(len(F))[:, None]
    return F[rows, (k[:, None] + np.arange(3)) % 3]


# ------------------------------------------------------------------------------------------------ score
_CACHE = {}
# The samples are remade when the code that makes them changes: this file, and cases.py (which faces are rounds).
_SOURCE = hashlib.sha1(b"".join(open(m.__file__ if m else __file__, "rb").read() for m in (None, cases))).hexdigest()


def exact_geometry(case, reach):
    """Per case (kept for the session): the chain, the exact filleted and sharp skins near it, samples on the
    rounds and on the sharp faces at the chain, and the filleted solid's own sharp edges.  The samples are also
    kept on disk (cases.kept_on_disk); the skins are cut anew from the solids' stored tessellations."""
    key = (case.name, reach)
    if key not in _CACHE:
        chain, r = Chain(case), case.r_max

        def make():
            return dict(sharp_samples=sharp_samples_near(case, chain, 2 * r), rounds=round_samples(case),
                        own_sharp_filleted=sharp_edge_points(case.reference, 0.01 * r))
        what = ("exact samples", _SOURCE, cases.shape_digest(case.reference), cases.shape_digest(case.solid),
                hashlib.sha1(np.ascontiguousarray(case.points).tobytes()).hexdigest(), r)
        _CACHE[key] = dict(cases.kept_on_disk(what, make), chain=chain,
                           filleted=exact_skin(case.reference, case, chain, (reach + 1.5) * r),
                           sharp=exact_skin(case.solid, case, chain, 4 * r))
    return _CACHE[key]


def sharp_samples_near(case, chain, within):
    """Points on the sharp solid's faces that touch the chain, within `within` of it, about r/10 apart."""
    faces = [f for f in case.solid.Faces if any(e.isSame(c) for e in f.Edges for c in case.chain)]
    return np.concatenate([face_samples(f, 0.1 * case.r_max, lambda P: chain.distance(P, within) <= within) for f in faces])


def input_tessellation_error(case, V0, F0, geo):
    """Hausdorff distance, within 2 r of the chain, between the input mesh and the sharp CAD solid: the
    chordal error of the input on curved faces, which no rounding of that mesh can undo."""
    chain, r = geo["chain"], case.r_max
    near = near_triangles(V0, F0, chain, 2 * r)
    P = surface_samples(V0, near)
    there = geo["sharp"].distance(P[chain.distance(P, 2 * r) <= 2 * r]).max(initial=0)
    S = geo["sharp_samples"]
    back = TriangleSet(V0, near).distance(S).max(initial=0)
    return float(max(there, back))


def deviation_samples(case, geo, V1, F1, made, reach):
    """Both ways, relative to r: (points on the made facets, their distance to the exact filleted solid),
    (points on the exact rounds, their distance to the result near the chain)."""
    r, chain = case.r_max, geo["chain"]
    P = surface_samples(V1, F1[made])
    P = P[chain.distance(P, (reach + 1) * r) <= (reach + 1) * r]  # made facets beyond: see far_facets_added
    band = F1[chain.facet_distance(V1, F1, (reach + 1) * r) <= (reach + 1) * r]
    return ((P, geo["filleted"].distance(P) / r), (geo["rounds"], TriangleSet(V1, band).distance(geo["rounds"]) / r))


def accuracy(case, geo, V0, F0, V1, F1, made, reach):
    """Deviations relative to r: made facets -> exact filleted solid (kept facets are the input's own, see
    input_error), points on the exact rounds -> the result near the chain, and the input's own error."""
    (_, out_to_ref), (_, ref_to_out) = deviation_samples(case, geo, V1, F1, made, reach)
    return dict(dev_out_to_ref=float(out_to_ref.max(initial=0)), dev_ref_to_out=float(ref_to_out.max(initial=0)),
                input_error=input_tessellation_error(case, V0, F0, geo) / case.r_max)


def corner_deviations(case, inp, out, reach=3.0):
    """The deviations both ways (relative to r), split at 1 r from the network's corner vertices (the ends
    of the picked edges): {"far": (out->ref, ref->out), "near": (...)}, where the issue's bounds differ
    (the tolerance beyond 1 r of every corner; 3 tolerances from OCCT's own corner construction within)."""
    geo = exact_geometry(case, reach)
    V0, F0 = mesh_arrays(inp)
    V1, F1 = mesh_arrays(out)
    id0, id1 = common_vertex_ids(V0, V1)
    made = ~np.isin(as_rows(cyclic_keys(id1[F1])), as_rows(cyclic_keys(id0[F0])))
    corners = np.array([[v.Point.x, v.Point.y, v.Point.z] for e in case.chain for v in e.Vertexes])
    res = {"far": [], "near": []}
    for P, d in deviation_samples(case, geo, V1, F1, made, reach):
        near = np.min(np.linalg.norm(P[:, None, :] - corners[None, :, :], axis=2), axis=1) <= case.r_max
        res["far"].append(float(d[~near].max(initial=0)))
        res["near"].append(float(d[near].max(initial=0)))
    return {k: tuple(v) for k, v in res.items()}


def boundary_loops(table, keep=None):
    """How many loops (connected pieces) the boundary edges of an edge table make; with `keep` (a bool per
    vertex), only those with a vertex it keeps."""
    edges = table["edges"][table["count"] == 1]
    if not len(edges):
        return 0
    ids, pairs = np.unique(edges, return_inverse=True)
    pairs = pairs.reshape(-1, 2)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(ids), len(ids)))
    count, label = connected_components(graph, directed=False)
    if keep is None:
        return int(count)
    return len(np.unique(label[np.asarray(keep)[ids]]))


def free_edge_points(shape, step):
    """Points every `step` along the edges of `shape` that bound one face only (an open shell's edge)."""
    faces_of = {}
    for i, face in enumerate(shape.Faces):
        for e in face.Edges:
            faces_of.setdefault(e.hashCode(), (e, set()))[1].add(i)
    pts = [np.array([tuple(p) for p in e.discretize(Distance=step)]) for e, faces in faces_of.values() if len(faces) == 1]
    return np.concatenate(pts) if pts else np.zeros((0, 3))


def boundary_off_reference(case, V1, t1):
    """The largest distance / r from the result's boundary edges (ends and middles) to the reference's own free
    edges: 0 without a boundary, inf for a boundary where the reference has none."""
    edges = t1["edges"][t1["count"] == 1]
    if not len(edges):
        return 0.0
    free = free_edge_points(case.reference, case.r_max / 500)
    if not len(free):
        return float("inf")
    P = np.concatenate([V1[edges[:, 0]], V1[edges[:, 1]], 0.5 * (V1[edges[:, 0]] + V1[edges[:, 1]])])
    return float(cKDTree(free).query(P)[0].max() / case.r_max)


def topology(case, out, V0, F0, V1, F1, t0, t1):
    change = abs(signed_volume(V1, F1)) - abs(signed_volume(V0, F0))
    exact_change = case.reference.Volume - case.solid.Volume
    return dict(
        boundary_edges_in=int((t0["count"] == 1).sum()),
        boundary_edges_out=int((t1["count"] == 1).sum()),
        boundary_loops_in=boundary_loops(t0),
        boundary_loops_out=boundary_loops(t1),
        boundary_off_reference=boundary_off_reference(case, V1, t1),
        nonmanifold_edges=int((t1["count"] > 2).sum()),
        misoriented_edges=t1["misoriented"],
        degenerate_facets=int((min_angles_deg(V1, F1) < 0.01).sum()),
        orientation_kept=bool(np.sign(signed_volume(V0, F0)) == np.sign(signed_volume(V1, F1))),
        self_intersections=bool(out.hasSelfIntersections()),
        volume_change_error=float(abs(change - exact_change) / abs(exact_change)))


def locality(case, chain, V0, F0, V1, F1, made, ids, keys, reach):
    """Input vertices beyond reach * r + their longest edge, and input facets entirely beyond reach * r,
    must be in the result bit for bit (facets with their orientation); no facet is made entirely beyond
    the reach (+5 %, for the chain's own tessellation)."""
    (id0, id1), (keys0, keys1) = ids, keys
    r = case.r_max
    longest = np.zeros(len(V0))
    for i in range(3):
        np.maximum.at(longest, F0[:, i], np.max([norm(V0[F0[:, i]] - V0[F0[:, j]]) for j in range(3)], axis=0))
    far_v = chain.distance(V0, reach * r + longest.max(initial=0)) > reach * r + longest
    far_f = chain.facet_distance(V0, F0, reach * r) > reach * r
    far_made = chain.facet_distance(V1, F1[made], 1.05 * reach * r) > 1.05 * reach * r
    return dict(far_vertices=int(far_v.sum()), far_vertices_lost=int((~np.isin(id0[far_v], id1)).sum()),
                far_facets=int(far_f.sum()), far_facets_lost=int((~np.isin(keys0[far_f], keys1)).sum()),
                far_facets_added=int(far_made.sum()))


def smoothness_and_quality(case, geo, V0, F0, V1, F1, t0, t1, made, reach, feature_angle):
    """Turns across edges of made facets near the chain vs the input's own there; smallest angles of the
    made facets vs the input's own within 1.5 r."""
    r, chain = case.r_max, geo["chain"]
    angles = min_angles_deg(V1, F1[made])
    near0 = chain.facet_distance(V0, F0, 1.5 * r) <= 1.5 * r
    # Thin made facets that a round's tangential end does not explain: not within CUSP_NEAR r of a corner of
    # OCCT's fillet faces, or thinner than CUSP_FLOOR of the most the tolerance allows at a cusp.
    corners = np.array([tuple(v.Point) for f in case.rounds for v in f.Vertexes]).reshape(-1, 3)
    thin = np.where(angles < 10.0)[0]
    floor = CUSP_FLOOR * np.degrees(np.arccos(1 - case.tolerance / r))
    off_ends = 0
    for i in thin:
        P = V1[F1[made][i]]
        near = len(corners) and np.linalg.norm(P[:, None, :] - corners[None, :, :], axis=2).min() <= CUSP_NEAR * r
        off_ends += int(not near or angles[i] < floor)
    return dict(
        slivers_new_off_round_ends=off_ends,
        new_facets=int(made.sum()),
        max_dihedral_new_deg=max_dihedral_near(V1, F1, t1, chain, reach * r, geo["own_sharp_filleted"], r, made),
        # the input's own faceting of its curved faces: turns below the feature angle (sharper ones are creases)
        max_dihedral_input_deg=max_dihedral_near(V0, F0, t0, chain, reach * r, [], r, below=feature_angle),
        min_angle_new_deg=float(angles.min()) if len(angles) else float("nan"),
        slivers_new=int((angles < 10.0).sum()),
        min_angle_input_near_deg=float(min_angles_deg(V0, F0[near0]).min()))


# At a concave end a round leaves its side tangentially (a cusp): no facet there within tolerance t has an angle
# over acos(1 - t / r) (8.1 deg at t = r / 100; OCCT's mesh of its own fillet at that deflection: 1.4 deg).
CUSP_NEAR = 0.5   # / r: a facet with a corner this near a corner of the exact round is at its end
CUSP_FLOOR = 0.6  # x acos(1 - t / r): the least angle allowed there

MEASURE = 0.002  # / r: the yardstick's own precision (exact solids tessellated to 5e-4 r, samples)


def assert_sound_and_local(row):
    """A scored rounding of a closed mesh (score's row): still closed, no non-manifold, mis-oriented or
    degenerate facet, its orientation kept, no self-intersection, nothing lost or added away from the band."""
    assert row["boundary_edges_out"] == row["boundary_edges_in"] == 0, row
    assert (row["nonmanifold_edges"], row["misoriented_edges"], row["degenerate_facets"]) == (0, 0, 0), row
    assert row["orientation_kept"] and not row["self_intersections"], row
    assert row["far_vertices_lost"] == row["far_facets_lost"] == row["far_facets_added"] == 0, row


def allowed_deviation(row):
    """The deviation bound of a scored row, / r: the tolerance, the input's own chordal error, MEASURE."""
    return row["tolerance"] / row["r"] + row["input_error"] + MEASURE


def score(case, inp, out, report=None, reach=3.0, feature_angle=30.0):
    """Every figure of one rounding of `case`: inp, out are Mesh.Mesh; report the engine's report dict."""
    geo = exact_geometry(case, reach)
    V0, F0 = mesh_arrays(inp)
    V1, F1 = mesh_arrays(out)
    id0, id1 = common_vertex_ids(V0, V1)
    keys0, keys1 = as_rows(cyclic_keys(id0[F0])), as_rows(cyclic_keys(id1[F1]))
    made = ~np.isin(keys1, keys0)  # facets that are not input facets
    t0, t1 = edge_table(F0), edge_table(F1)
    res = dict(case=case.name, r=case.r_max, tolerance=case.tolerance, facets_in=len(F0), facets_out=len(F1))
    res.update(accuracy(case, geo, V0, F0, V1, F1, made, reach))
    res.update(topology(case, out, V0, F0, V1, F1, t0, t1))
    res.update(locality(case, geo["chain"], V0, F0, V1, F1, made, (id0, id1), (keys0, keys1), reach))
    res.update(smoothness_and_quality(case, geo, V0, F0, V1, F1, t0, t1, made, reach, feature_angle))
    if report is not None:
        res["input_forces_small_angles"] = bool(report.get("input_forces_small_angles", False))
        res["thin_facets"] = report.get("thin_facets")
        res["cusp_facets"] = report.get("cusp_facets", 0)
        res["thin_facets_short_of_room"] = report.get("thin_facets_short_of_room")
        res["reach_for_room"] = report.get("reach_for_room")
        res["engine_max_deviation"] = report.get("max_deviation")
    return res
