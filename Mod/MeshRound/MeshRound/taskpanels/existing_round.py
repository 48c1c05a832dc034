"""The Round edges task panel's "Existing round" pick mode (issue 15): a click on an existing round.

The engine recognises the round each seed is on (reround.change_radius_arrays at radius 0: the strip is
found and measured and its sharp edge rebuilt, nothing new is rounded), the panel highlights the strip's
facets, names the radius found and previews the round at the panel's radius (change_radius).  The rebuilt
sharp edges stand in for the chains: radius points land on them.
"""
from .. import reround, shapes
from ..errors import RoundingError
from . import overlays


def recognise(vertices, triangles, seeds, feature_angle, reach):
    """(strips, wires): the report row of the round each seed is on (with "facets": the input's facets that
    make it, reround.strip_facet_indices), and its rebuilt sharp edge as a wire.  RoundingError (the code
    first, e.g. "not_a_round: ...") when a seed is not on a round."""
    try:
        result = reround.change_radius_arrays(vertices, triangles, seeds, 0, feature_angle=feature_angle,
                                              reach=reach)
    except RoundingError as exc:
        raise reround.named(exc) from None
    strips = result.report["strips"]
    for strip in strips:
        strip["facets"] = reround.strip_facet_indices(vertices, triangles, strip)
    return strips, shapes.polyline_wires([strip["corner"] for strip in strips])


def found_text(strips):
    """"Found radius: 5 mm" (a constant round), "... 2 to 8 mm (variable)", one entry per round; "" without."""
    if not strips:
        return ""
    return "Found radius: " + ", ".join(_radius_text(strip) for strip in strips)


def _radius_text(strip):
    if strip["constant"]:
        return f"{strip['found_radius']:.4g} mm"
    return f"{strip['radius_min']:.4g} to {strip['radius_max']:.4g} mm (variable)"


def strip_facets(strips):
    """The input's facets (indices) that make the rounds `strips` (recognise's rows), all of them."""
    return sorted({int(i) for strip in strips for i in strip["facets"]})


def strips_node(vertices, triangles, strips):
    """The highlight of the rounds' facets (their edges, in overlays.STRIP_COLOR)."""
    return overlays.facet_edges_node(vertices, triangles[strip_facets(strips)], overlays.STRIP_COLOR)
