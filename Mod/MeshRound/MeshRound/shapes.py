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
            raise RoundingError(f"the engine returned an unreadable BRep surface: {exc}") from exc
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
