"""Is a rounded mesh sound against its input?  The checks an engineer makes before sending a tool mesh
to a solver, measured independently of the engine (numpy edge tables, FreeCAD's self-intersection test confirmed exactly).

    problems = soundness.problems(V0, F0, V1, F1)    # [] when sound, else one line per failed check
    problems = soundness.problems(V0, F0, V1, F1, open_ends=[(point, distance)])  # a round off the mesh's edge
"""
from fractions import Fraction

import numpy as np
from scipy.spatial import cKDTree

from MeshRound import meshconv
from reference import boundary_loops, edge_table, min_angles_deg, segment_distance, signed_volume

DEGENERATE_DEG = 0.01  # a facet with a smaller angle is degenerate (as the yardstick counts them)


def problems(V0, F0, V1, F1, open_ends=()):
    """Failed checks of the result (V1, F1) against the input (V0, F0): a new boundary (a hole or a crack),
    non-manifold or mis-oriented edges, degenerate facets, a flipped volume, self-intersecting facets.
    `open_ends`: (point, distance) pairs where a round runs off the mesh's edge -- its end profile, within
    that distance of the point, may become part of the boundary. Every other boundary edge of the result
    must lie on one of the input's, and the boundary keeps its loops."""
    t0, t1 = edge_table(np.asarray(F0)), edge_table(np.asarray(F1))
    found = []
    # A hole whose whole rim the rounding replaced was rounded over (the band's new surface covers it): only the
    # input's loops with a vertex left in the result must stay.
    loops_in = boundary_loops(t0, keep=_vertices_left(np.asarray(V0, float), np.asarray(V1, float)))
    if boundary_loops(t1) != loops_in:
        found.append(f"boundary loops {loops_in} -> {boundary_loops(t1)}")
    off = _new_boundary_points(np.asarray(V0, float), t0, np.asarray(V1, float), t1, open_ends)
    if len(off):
        found.append(f"{len(off)} new boundary edge point(s), e.g. at {np.round(off[0], 4).tolist()}")
    if (t1["count"] > 2).sum() > (t0["count"] > 2).sum():
        found.append(f"{int((t1['count'] > 2).sum())} non-manifold edge(s)")
    if t1["misoriented"] > t0["misoriented"]:
        found.append(f"{t1['misoriented']} mis-oriented edge(s)")
    degenerate = int((min_angles_deg(V1, F1) < DEGENERATE_DEG).sum())
    if degenerate > int((min_angles_deg(V0, F0) < DEGENERATE_DEG).sum()):
        found.append(f"{degenerate} degenerate facet(s)")
    if np.sign(signed_volume(V0, F0)) != np.sign(signed_volume(V1, F1)):
        found.append("orientation flipped")
    if not found and _self_intersects(V1, F1) and not _self_intersects(V0, F0):
        found.append("self-intersecting facets")
    return found


def _vertices_left(V0, V1):
    """Per input vertex: whether the result has a vertex at exactly its place."""
    return cKDTree(V1).query(V0)[0] == 0


def _new_boundary_points(V0, t0, V1, t1, open_ends):
    """Ends and middles of the result's boundary edges that lie neither on an input boundary edge nor near an
    open end."""
    edges0, edges1 = t0["edges"][t0["count"] == 1], t1["edges"][t1["count"] == 1]
    P = np.concatenate([V1[edges1[:, 0]], V1[edges1[:, 1]], 0.5 * (V1[edges1[:, 0]] + V1[edges1[:, 1]])])
    if not len(P):
        return P
    scale = max(np.abs(V0).max(), 1.0)
    ok = np.zeros(len(P), bool)
    for point, distance in open_ends:
        ok |= np.linalg.norm(P - np.asarray(point, float), axis=1) <= distance
    if len(edges0) and not ok.all():
        A, B = V0[edges0[:, 0]], V0[edges0[:, 1]]
        half = 0.5 * np.linalg.norm(B - A, axis=1).max() + 1e-6 * scale
        near = cKDTree(0.5 * (A + B)).query_ball_point(P[~ok], half)
        for i, candidates in zip(np.where(~ok)[0], near):
            c = np.asarray(candidates, int)
            ok[i] = len(c) > 0 and segment_distance(np.broadcast_to(P[i], (len(c), 3)), A[c], B[c]).min() <= 1e-6 * scale
    return P[~ok]


def _self_intersects(V, F):
    """Whether two facets of the mesh, stored as FreeCAD stores it (float32), share a point without sharing a
    vertex. FreeCAD's test (Moller's, in float32, with a fixed 1e-6 on unnormalised plane distances) finds the
    candidate pairs; each is confirmed in exact arithmetic, since below a facet size of ~0.05 mm that fixed
    epsilon takes facets apart by up to their own size as coplanar and reports them crossing."""
    mesh = meshconv.arrays_to_mesh(np.asarray(V, dtype=float), np.asarray(F))
    if not mesh.hasSelfIntersections():
        return False
    facets = mesh.Facets

    def meet(pair):
        s, t = facets[pair[0]], facets[pair[1]]
        if set(s.PointIndices) & set(t.PointIndices):
            return True  # (FreeCAD skips neighbours; counted as crossing, should one come)
        return _triangles_meet(*[[tuple(Fraction(float(c)) for c in p) for p in f.Points] for f in (s, t)])
    return any(meet(pair) for pair in mesh.getSelfIntersections())


def _triangles_meet(T, U):
    """Exact separating-axis test of two triangles (rational coordinates): no axis among the normals, the
    edge-edge crosses and the in-plane edge normals separates them (touching counts as meeting)."""
    def sub(a, b):
        return (a[0] - b[0], a[1] - b[1], a[2] - b[2])

    def cross(a, b):
        return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])

    def dot(a, b):
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]

    edges_t = [sub(T[(i + 1) % 3], T[i]) for i in range(3)]
    edges_u = [sub(U[(i + 1) % 3], U[i]) for i in range(3)]
    normals = [cross(edges_t[0], edges_t[1]), cross(edges_u[0], edges_u[1])]
    axes = normals + [cross(e, f) for e in edges_t for f in edges_u]
    axes += [cross(normals[0], e) for e in edges_t] + [cross(normals[1], f) for f in edges_u]
    for axis in axes:
        if axis == (0, 0, 0):
            continue
        t, u = [dot(axis, p) for p in T], [dot(axis, p) for p in U]
        if max(t) < min(u) or max(u) < min(t):
            return False
    return True
