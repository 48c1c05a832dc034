"""The rounded Mesh.Mesh made by editing a copy of the input, at the band's cost instead of the mesh's.

The engine gives its result as an edit of its input (the delta: cpp_core/include/meshround/mesh_delta.h):
the facets it removes, the input vertices it moves, the points and facets it adds.  FreeCAD 0.20's
Mesh.Mesh applies that to a copy of the input in C++ loops, never building the whole mesh anew (which
through a file costs ~0.8 s CPU at 1.4M facets, most of it FreeCAD checking the neighbours of every facet):

  copy()                            every point's float32 bits and every facet's order kept
  removeFacets(removed)             takes them out and drops the points no facet uses any more: the
                                    delta's `freed` vertices (~0.2 s CPU at 1.4M facets: FreeCAD compacts
                                    its arrays)
  setPoint(i, v)                    the kept vertices the round moved (snapped onto its trim lines)
  addFacets((points, facets), True) appends the points and the facets, each facet joined to its
                                    neighbours old and new (~0.15 s CPU at 1.4M facets); the check drops
                                    a facet that would make an edge non-manifold

The points added are the freed vertices the new facets use (ascending), then the delta's new points: the
result is the engine's apply_delta order vertex for vertex and facet for facet, so result.mesh and
result.vertices / result.triangles are one mesh.  edited_copy returns None when the copy cannot be made
that way -- a mesh with a Placement (its points are kept in local coordinates), or FreeCAD leaving out a
facet (the counts are checked) -- and the caller builds the mesh from the arrays instead.
"""
import numpy as np

import FreeCAD


def start_copy(mesh):
    """mesh.copy() on a worker thread, to overlap the engine's run (which holds no GIL): returns a callable
    that waits for the copy and returns it (None if copy() failed: the caller then builds from arrays)."""
    import threading
    box = {}

    def work():
        try:
            box["copy"] = mesh.copy()
        except Exception:  # noqa: BLE001  (no copy: the arrays path makes the mesh)
            box["copy"] = None

    thread = threading.Thread(target=work, name="MeshRound copy", daemon=True)
    thread.start()

    def result():
        thread.join()
        return box.get("copy")
    return result


def editable(mesh, delta):
    """Whether `mesh` is the delta's input in a form edited_copy can edit."""
    return (mesh.Placement.isIdentity() and mesh.CountPoints == delta["input_vertices"]
            and mesh.CountFacets == delta["input_facets"])


def edited_copy(copy, delta, vertices):
    """Apply the delta to `copy` (the input's Mesh.copy(), edited in place) and return it, or None when
    FreeCAD did not take the edit as given.  `vertices`: the input's (n, 3) points, for the freed vertices
    that new facets use again."""
    n = int(delta["input_vertices"])
    removed, freed = np.asarray(delta["removed"]), np.asarray(delta["freed"], dtype=np.int64)
    added = np.asarray(delta["added"], dtype=np.int64).reshape(-1, 3)
    if len(removed):
        copy.removeFacets(removed.tolist())
    kept = n - len(freed)
    if copy.CountPoints != kept:  # e.g. points no facet used, which FreeCAD keeps when nothing is removed
        return None
    used = np.unique(added[added < n])
    reused = used[np.isin(used, freed, assume_unique=True)]  # ascending
    index = np.empty(n, dtype=np.int64)  # only the entries looked up below are set
    index[used] = used - np.searchsorted(freed, used)
    index[reused] = kept + np.arange(len(reused))
    moved, moved_to = np.asarray(delta["moved"], dtype=np.int64), np.asarray(delta["moved_to"]).reshape(-1, 3)
    at = dict(zip(moved.tolist(), range(len(moved))))
    points = vertices[reused].copy()
    for i, v in enumerate(reused.tolist()):
        if v in at:
            points[i] = moved_to[at[v]]
    still = ~np.isin(moved, freed)
    for v, p in zip((moved[still] - np.searchsorted(freed, moved[still])).tolist(), moved_to[still].tolist()):
        copy.setPoint(v, FreeCAD.Vector(*p))
    points = np.concatenate([points, np.asarray(delta["new_points"]).reshape(-1, 3)])
    facets = np.where(added < n, index[np.minimum(added, n - 1)], added - n + kept + len(reused))
    vectors = [FreeCAD.Vector(*p) for p in points.tolist()]
    copy.addFacets((vectors, list(map(tuple, facets.tolist()))), True)
    expected = (kept + len(points), int(delta["input_facets"]) - len(removed) + len(added))
    if (copy.CountPoints, copy.CountFacets) != expected:
        return None
    return copy
