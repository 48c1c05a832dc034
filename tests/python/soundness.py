"""Is a rounded mesh sound against its input?  The checks an engineer makes before sending a tool mesh
to a solver, measured independently of the engine (numpy edge tables, FreeCAD's self-intersection test).

    problems = soundness.problems(V0, F0, V1, F1)    # [] when sound, else one line per failed check
"""
import numpy as np

from MeshRound import meshconv
from reference import edge_table, min_angles_deg, signed_volume

DEGENERATE_DEG = 0.01  # a facet with a smaller angle is degenerate (as the yardstick counts them)


def problems(V0, F0, V1, F1):
    """Failed checks of the result (V1, F1) against the input (V0, F0): new boundary edges, non-manifold
    or mis-oriented edges, degenerate facets, a flipped volume, self-intersecting facets."""
    t0, t1 = edge_table(np.asarray(F0)), edge_table(np.asarray(F1))
    found = []
    boundary_in, boundary_out = int((t0["count"] == 1).sum()), int((t1["count"] == 1).sum())
    if boundary_out > boundary_in:
        found.append(f"boundary edges {boundary_in} -> {boundary_out}")
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


def _self_intersects(V, F):
    return bool(meshconv.arrays_to_mesh(np.asarray(V, dtype=float), np.asarray(F)).hasSelfIntersections())
