"""Independent yardstick: how far a rounded mesh is from OCCT's exact fillet, and whether it is a sound mesh.

Everything here is numpy + scipy (cKDTree), vectorised; nothing calls MeshRound.  Distances are exact
point-to-triangle distances to a triangle set; the exact solids are tessellated 2,000 times finer than r
(LinearDeflection 5e-4 r), so "exact" means to 5e-4 r, 1/20 of the tolerance r/100.
`score(case, inp, out, report)` returns every figure of one rounding; see test_accuracy.py for the bounds.
"""
import numpy as np
from scipy.spatial import cKDTree

import cases

CHUNK = 200_000  # point/triangle pairs evaluated at once
SHARP_DEG = 20.0  # an edge of an exact solid is "its own sharp edge" when its faces turn by more


# ---------------------------------------------------------------------------------------------- arrays
def mesh_arrays(mesh):
    """(V float64 (n,3), F int64 (m,3)) of a Mesh.Mesh."""
    pts, facets = mesh.Topology
    return (np.array([tuple(p) for p in pts], dtype=float).reshape(-1, 3),
            np.array(facets, dtype=np.int64).reshape(-1, 3))


def shape_arrays(shape, deflection):
    """(V, F) of a Part shape (or face) tessellated with the given chordal deflection."""
    pts, tris = shape.tessellate(deflection)
    return np.array([tuple(p) for p in pts], dtype=float).reshape(-1, 3), np.array(tris, dtype=np.int64).reshape(-1, 3)


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


def refine(V, F, max_edge):
    """Triangle soup (V, F) of the same surface, split at longest-edge midpoints until no edge exceeds
    max_edge: the splits are exact, they only keep triangles small for the tree queries below."""
    T, done = V[F], []
    while len(T):
        L = np.stack([norm(T[:, (i + 1) % 3] - T[:, (i + 2) % 3]) for i in range(3)], axis=1)
        small = L.max(axis=1) <= max_edge
        done.append(T[small])
        T, L = T[~small], L[~small]
        k = L.argmax(axis=1)  # the vertex opposite the longest edge
        rows = np.arange(len(T))
        apex, p, q = T[rows, k], T[rows, (k + 1) % 3], T[rows, (k + 2) % 3]
        m = 0.5 * (p + q)
        T = np.concatenate([np.stack((apex, p, m), 1), np.stack((apex, m, q), 1)])
    T = np.concatenate(done) if done else np.zeros((0, 3, 3))
    return T.reshape(-1, 3), np.arange(3 * len(T)).reshape(-1, 3)


def pairs_within(tree, P, radius):
    """(point index, tree index) for every tree point within radius[i] of P[i] (flattened ball queries)."""
    lists = tree.query_ball_point(P, radius)
    counts = np.fromiter((len(x) for x in lists), dtype=np.int64, count=len(P))
    rows = np.repeat(np.arange(len(P)), counts)
    cols = np.fromiter((j for x in lists for j in x), dtype=np.int64, count=int(counts.sum()))
    return rows, cols


class TriangleSet:
    """Exact distance queries to a triangle set: for a point at distance d0 from the nearest vertex, the
    nearest triangle has its centroid within d0 + (largest centroid-to-corner radius)."""

    def __init__(self, V, F, max_edge):
        V, F = refine(V, F, max_edge)
        self.A, self.B, self.C = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
        cen = (self.A + self.B + self.C) / 3
        self.rad = max(norm(X - cen).max() for X in (self.A, self.B, self.C)) if len(F) else 0.0
        self.centroids = cKDTree(cen)
        self.vertices = cKDTree(V)

    def distance(self, P):
        out = np.full(len(P), np.inf)
        if len(P) == 0 or self.centroids.n == 0:
            return out
        d0, _ = self.vertices.query(P)
        step = max(1, CHUNK // 64)
        for s in range(0, len(P), step):
            rows, cols = pairs_within(self.centroids, P[s:s + step], d0[s:s + step] + self.rad + 1e-9)
            d = point_triangle_distance(P[s + rows], self.A[cols], self.B[cols], self.C[cols])
            np.minimum.at(out, s + rows, d)
        return out


# -------------------------------------------------------------------------------------- the chain
class Chain:
    """Distances to a case's CAD chain (sampled every 0.02 r: exact to 0.01 r)."""

    def __init__(self, case):
        self.points = case.points
        self.tree = cKDTree(self.points)

    def distance(self, P):
        return self.tree.query(P)[0]

    def facet_distance(self, V, F, beyond):
        """Distance from each facet to the chain, exact only where it decides `> beyond` (else a bound)."""
        A, B, C = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
        cen = (A + B + C) / 3
        rad = np.max([norm(X - cen) for X in (A, B, C)], axis=0)
        dv = np.min([self.distance(X) for X in (A, B, C)], axis=0)  # upper bound
        lo = np.maximum(self.distance(cen) - rad, 0)  # lower bound
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
    return F[chain.distance(cen) <= within + rad]


def exact_skin(shape, case, chain, within):
    """TriangleSet of an exact solid's skin near the chain."""
    r = case.r_max
    V, F = shape_arrays(shape, 5e-4 * r)
    return TriangleSet(V, near_triangles(V, F, chain, within), 0.2 * r)


def round_samples(case):
    """Points on the exact rounds (OCCT's fillet faces), about r/20 apart."""
    pts = []
    for f in case.rounds:
        V, F = refine(*shape_arrays(f, 5e-4 * case.r_max), 0.05 * case.r_max)
        pts.append(V)
    return np.unique(np.concatenate(pts), axis=0)


def surface_samples(V, F):
    """Vertices, edge midpoints and centroids of a triangle mesh: where a chordal error shows."""
    T = V[F]
    mids = [(T[:, i] + T[:, (i + 1) % 3]) / 2 for i in range(3)]
    return np.concatenate([V, T.mean(axis=1)] + mids)


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
def edge_table(F):
    """Undirected edges (sorted vertex pairs) with their facet count and up to two facets;
    also how many directed edges occur twice (neighbours whose orientations disagree)."""
    directed = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    facet = np.tile(np.arange(len(F)), 3)
    key = np.sort(directed, axis=1)
    edges, inv, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    inv = inv.ravel()
    order = np.argsort(inv, kind="stable")
    start = np.searchsorted(inv[order], np.arange(len(edges)))
    first = facet[order][start]
    second = np.where(count == 2, facet[order][np.minimum(start + 1, len(order) - 1)], -1)
    twice = len(directed) - len(np.unique(directed, axis=0))
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


def max_dihedral_near(V, F, table, chain, reach, own_sharp, r, only=None):
    """Largest turn across manifold edges near the chain (midpoint within reach), except along the exact
    solid's own sharp edges; `only`: a facet mask, edges must touch one of those facets."""
    E = table["edges"]
    ok = table["count"] == 2
    if only is not None:
        ok &= only[table["first"]] | only[np.maximum(table["second"], 0)]
    mid = V[E].mean(axis=1)
    ok &= chain.distance(mid) <= reach
    if len(own_sharp):
        ok &= cKDTree(own_sharp).query(mid)[0] > 0.05 * r
    idx = np.where(ok)[0]
    return float(dihedrals_deg(V, F, table, idx).max()) if len(idx) else 0.0


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


def exact_geometry(case, reach):
    """Per case (cached): the chain, the exact filleted and sharp skins near it, samples on the rounds,
    and the filleted / sharp solids' own sharp edges."""
    key = (case.name, reach)
    if key not in _CACHE:
        chain, r = Chain(case), case.r_max
        _CACHE[key] = dict(
            chain=chain,
            filleted=exact_skin(case.reference, case, chain, (reach + 3) * r),
            sharp=exact_skin(case.solid, case, chain, 4 * r),
            rounds=round_samples(case),
            own_sharp_filleted=sharp_edge_points(case.reference, 0.01 * r),
            own_sharp_input=sharp_edge_points(case.solid, 0.01 * r))
    return _CACHE[key]


def input_tessellation_error(case, V0, F0, geo):
    """Hausdorff distance, within 2 r of the chain, between the input mesh and the sharp CAD solid: the
    chordal error of the input on curved faces, which no rounding of that mesh can undo."""
    chain, r = geo["chain"], case.r_max
    near = near_triangles(V0, F0, chain, 2 * r)
    P = surface_samples(V0, near)
    there = geo["sharp"].distance(P[chain.distance(P) <= 2 * r]).max(initial=0)
    Vs, Fs = shape_arrays(case.solid, 5e-4 * r)
    S = refine(Vs, near_triangles(Vs, Fs, chain, 2 * r), 0.1 * r)[0]
    S = S[chain.distance(S) <= 2 * r]
    back = TriangleSet(V0, near, 0.2 * r).distance(S).max(initial=0)
    return float(max(there, back))


def score(case, inp, out, report=None, reach=3.0):
    """Every figure of one rounding of `case`: inp, out are Mesh.Mesh; report the engine's report dict."""
    r = case.r_max
    geo = exact_geometry(case, reach)
    chain = geo["chain"]
    V0, F0 = mesh_arrays(inp)
    V1, F1 = mesh_arrays(out)
    res = dict(case=case.name, r=r, tolerance=case.tolerance, facets_in=len(F0), facets_out=len(F1))

    # accuracy, both ways, relative to r
    P = surface_samples(V1, near_triangles(V1, F1, chain, (reach + 1) * r))
    P = P[chain.distance(P) <= (reach + 1) * r]
    res["dev_out_to_ref"] = float(geo["filleted"].distance(P).max(initial=0) / r)
    band = F1[chain.facet_distance(V1, F1, (reach + 1) * r) <= (reach + 1) * r]
    res["dev_ref_to_out"] = float(TriangleSet(V1, band, 0.2 * r).distance(geo["rounds"]).max() / r)
    res["input_error"] = input_tessellation_error(case, V0, F0, geo) / r

    # topology
    t0, t1 = edge_table(F0), edge_table(F1)
    res["boundary_edges_in"] = int((t0["count"] == 1).sum())
    res["boundary_edges_out"] = int((t1["count"] == 1).sum())
    res["nonmanifold_edges"] = int((t1["count"] > 2).sum())
    res["misoriented_edges"] = t1["misoriented"]
    angles1 = min_angles_deg(V1, F1)
    res["degenerate_facets"] = int((angles1 < 0.01).sum())
    res["orientation_kept"] = bool(np.sign(signed_volume(V0, F0)) == np.sign(signed_volume(V1, F1)))
    res["self_intersections"] = bool(out.hasSelfIntersections())
    exact_change = case.reference.Volume - case.solid.Volume
    change = abs(signed_volume(V1, F1)) - abs(signed_volume(V0, F0))
    res["volume_change_error"] = float(abs(change - exact_change) / abs(exact_change))

    # locality: far input vertices and facets are in the result, bit for bit
    id0, id1 = common_vertex_ids(V0, V1)
    longest = np.zeros(len(V0))
    for i in range(3):
        np.maximum.at(longest, F0[:, i], np.max([norm(V0[F0[:, i]] - V0[F0[:, j]]) for j in range(3)], axis=0))
    far_v = chain.distance(V0) > reach * r + longest
    res["far_vertices"] = int(far_v.sum())
    res["far_vertices_lost"] = int((~np.isin(id0[far_v], id1)).sum())
    far_f = chain.facet_distance(V0, F0, reach * r) > reach * r
    keys0, keys1 = as_rows(cyclic_keys(id0[F0])), as_rows(cyclic_keys(id1[F1]))
    res["far_facets"] = int(far_f.sum())
    res["far_facets_lost"] = int((~np.isin(keys0[far_f], keys1)).sum())

    # smoothness: turns across edges of made facets near the chain, vs the input's own near it
    made = ~np.isin(keys1, keys0)
    res["new_facets"] = int(made.sum())
    res["max_dihedral_new_deg"] = max_dihedral_near(V1, F1, t1, chain, reach * r, geo["own_sharp_filleted"], r, made)
    res["max_dihedral_input_deg"] = max_dihedral_near(V0, F0, t0, chain, reach * r, geo["own_sharp_input"], r)

    # element quality: made facets vs the input's own near the chain
    near0 = chain.facet_distance(V0, F0, 1.5 * r) <= 1.5 * r
    res["min_angle_new_deg"] = float(angles1[made].min()) if made.any() else float("nan")
    res["slivers_new"] = int((angles1[made] < 10.0).sum())
    res["min_angle_input_near_deg"] = float(min_angles_deg(V0, F0[near0]).min())
    if report is not None:
        res["input_forces_small_angles"] = bool(report.get("input_forces_small_angles", False))
        res["engine_max_deviation"] = report.get("max_deviation")
    return res
