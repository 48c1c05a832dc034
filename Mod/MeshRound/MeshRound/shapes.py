"""Part objects from the engine's plain outputs: BRep texts -> faces, polylines -> wires."""
import numpy as np

import FreeCAD
import Part

from .errors import RoundingError


def faces_from_brep(texts):
    """The faces of each OCCT BRep text, in order (the engine gives one text per chain)."""
    faces = []
    for text in texts:
        shape = Part.Shape()
        try:
            shape.importBrepFromString(text)
        except Exception as exc:  # OCCT reports a bad text as a generic Part/Base error
            raise RoundingError(f"the engine returned an unreadable BRep surface: {exc}", "surface_failed") from exc
        faces.extend(shape.Faces)
    return faces


def polyline_wire(points, closed=False):
    """A Part.Wire through the rows of points (s, 3); closed loops get their first point repeated.

    Returns None for fewer than two distinct points, which Part.makePolygon cannot take.
    """
    rows = np.asarray(points, dtype=float).reshape(-1, 3).tolist()
    vectors = [FreeCAD.Vector(*row) for row in rows]  # one per polyline point (few), not per facet
    if closed and len(vectors) > 2:
        vectors.append(vectors[0])
    if len(vectors) < 2:
        return None
    try:
        return Part.makePolygon(vectors)
    except Part.OCCError:  # e.g. all points coincide
        return None


def polyline_wires(polylines, closed_flags=None):
    """Wires for a list of polylines; unusable (degenerate) polylines are left out."""
    closed_flags = closed_flags if closed_flags is not None else [False] * len(polylines)
    wires = (polyline_wire(p, c) for p, c in zip(polylines, closed_flags))
    return [w for w in wires if w is not None]


def compound(shapes):
    """A compound of shapes (an empty compound for none), e.g. for a Part::Feature's Shape."""
    return Part.makeCompound(list(shapes))


def wire_points(wire):
    """(s, 3) points of a polygon wire in order; a closed wire repeats its first point at the end."""
    points = [tuple(v.Point) for v in wire.OrderedVertexes]
    if wire.isClosed() and points:
        points.append(points[0])
    return np.array(points, dtype=np.float64).reshape(-1, 3)


def nearest_on_polylines(point, polylines):
    """The point (x, y, z) on any of the polylines (each (s, 3), s >= 1) nearest to `point`."""
    p = np.array([point[0], point[1], point[2]], dtype=np.float64)
    best, best_distance = None, np.inf
    for line in polylines:
        line = np.asarray(line, dtype=np.float64).reshape(-1, 3)
        if len(line) == 1:
            candidates = line
        else:
            a, b = line[:-1], line[1:]
            ab = b - a
            length2 = np.einsum("ij,ij->i", ab, ab)
            t = np.einsum("ij,ij->i", p - a, ab) / np.where(length2 > 0, length2, 1.0)
            candidates = a + np.clip(t, 0.0, 1.0)[:, None] * ab
        distances = np.linalg.norm(candidates - p, axis=1)
        i = int(np.argmin(distances))
        if distances[i] < best_distance:
            best, best_distance = candidates[i], distances[i]
    if best is None:
        raise ValueError("no polyline to project on")
    return tuple(float(c) for c in best)
