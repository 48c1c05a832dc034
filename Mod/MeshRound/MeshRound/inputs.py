"""Checks and normalises what a caller hands to the rounding API.

Every problem becomes a RoundingError whose message says which argument is wrong and why, so that the
console, the feature's error state, the task panel and the CLI all show the same clear text.  Here only
the kinds of the arguments are checked (a number, a point); their ranges are the engine's one rule
(validate_options in cpp_core/src/options.cpp), asked through check_options.
"""
import numbers

import numpy as np

import FreeCAD
import Mesh

from .errors import RoundingError, require_core


def check_mesh(mesh):
    if not isinstance(mesh, Mesh.Mesh):
        raise RoundingError(f"mesh must be a Mesh.Mesh, not {type(mesh).__name__}")
    if mesh.CountFacets == 0:
        raise RoundingError("mesh is empty: it has no facets")


def seed_array(seeds):
    """(k, 3) float64 from a Vector, a 3-sequence, or a list of either."""
    if _is_point(seeds):
        seeds = [seeds]
    try:
        points = [_point(s) for s in seeds]
    except TypeError:
        raise RoundingError(
            "seeds must be a FreeCAD.Vector, an (x, y, z) triple, or a list of them; "
            f"got {type(seeds).__name__}") from None
    if not points:
        raise RoundingError("no seed given: pick at least one point near a sharp edge")
    array = np.array(points, dtype=np.float64).reshape(-1, 3)
    if not np.all(np.isfinite(array)):
        raise RoundingError("seed coordinates must be finite numbers")
    return array


def radius_and_law(radius):
    """(largest radius, law array (p, 4) or None) from a number or from [(point, r), ...] pairs."""
    if isinstance(radius, FreeCAD.Units.Quantity):
        radius = radius.Value  # mm
    if _is_number(radius):
        check_options(radius=_number("radius", radius))
        return float(radius), None
    try:
        pairs = [(_point(p), r) for p, r in radius]
    except (TypeError, ValueError):
        raise RoundingError(
            "radius must be a number (mm) or a list of (point, radius) control points; "
            f"got {type(radius).__name__}") from None
    if not pairs:
        raise RoundingError("variable radius needs at least one (point, radius) control point")
    law = np.array([(*p, _number("control point radius", r)) for p, r in pairs], dtype=np.float64)
    check_options(radius_law=law)
    return float(law[:, 3].max()), law


# The engine's rule for tolerance 0 ("automatic"): the largest radius times this (cpp_core; the panel's
# preview and its tolerance field say it with this number).
AUTO_TOLERANCE_FRACTION = 1.0 / 100.0


def automatic_tolerance(largest_radius):
    """The chordal tolerance the engine uses when none is given (0): largest radius / 100."""
    return float(largest_radius) * AUTO_TOLERANCE_FRACTION


def tolerance_value(tolerance):
    """The core's tolerance: 0 means 'largest radius / 100'."""
    if tolerance is None:
        return 0.0
    check_options(tolerance=_number("tolerance", tolerance))
    return float(tolerance)


def feature_angle_value(angle):
    check_options(feature_angle=_number("feature_angle", angle))
    return float(angle)


def reach_value(reach):
    check_options(reach=_number("reach", reach))
    return float(reach)


# The band element controls (RoundOptions in cpp_core/include/meshround/options.h, where their defaults and
# meanings are written): the keywords round_edges, round_deck and the CLI take, each 0 or None = off.
BAND_CONTROLS = ("max_element_angle", "element_length", "max_aspect_ratio")


def band_value(band):
    """The engine's band dict from None or a mapping of BAND_CONTROLS to numbers (None/0: off); checked
    by the engine's rule."""
    if band is None:
        return None
    if not hasattr(band, "items"):
        raise RoundingError(f"band must be a dict of element controls {BAND_CONTROLS}, got {type(band).__name__}")
    unknown = sorted(set(band) - set(BAND_CONTROLS))
    if unknown:
        raise RoundingError(f"unknown band element control(s) {unknown}; known: {list(BAND_CONTROLS)}")
    values = {k: _number(k, v) for k, v in band.items() if v is not None}
    check_options(band=values)
    return values or None


def check_options(radius=1.0, tolerance=0.0, feature_angle=30.0, reach=3.0, radius_law=None, band=None):
    """RoundingError (invalid_input) naming the option out of range, by the engine's own rule."""
    require_core().validate_options(radius=float(radius), tolerance=float(tolerance),
                                    feature_angle=float(feature_angle), reach=float(reach),
                                    radius_law=radius_law, band=band)


def _number(name, value):
    if not _is_number(value):
        raise RoundingError(f"{name} must be a number, got {value!r}")
    return float(value)


def _is_number(value):
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def _is_point(value):
    if isinstance(value, FreeCAD.Vector):
        return True
    return (isinstance(value, (tuple, list, np.ndarray)) and len(value) == 3
            and all(_is_number(c) for c in value))


def _point(value):
    """(x, y, z) floats of a Vector or 3-sequence of numbers; TypeError otherwise."""
    if not _is_point(value):
        raise TypeError(value)
    return float(value[0]), float(value[1]), float(value[2])
