"""Change the radius of an existing round (issue 15).

    import MeshRound
    res = MeshRound.change_radius(mesh, seeds, radius, tolerance=None)
    res.mesh                                   # the mesh with the round at the new radius (radius 0: sharp)
    res.report["found_radius"]                 # per strip: the radius the round had (mm)
    res.report["strips"][0]["law"]             # per strip: [(x, y, z, r)] along the rebuilt edge
    res.report["strips"][0]["recognised"]      # how the strip was told from its sides

Each seed picks a point on an existing round: a strip of facets turning between two flat sides.  The
engine (cpp_core sharpen.h) finds the strip, measures its radius at every vertex (the ball tangent to
both sides through it), rebuilds the sharp edge the round replaced by extending the two sides to their
corner line, then rounds that edge with round_edges' passes at `radius` (a number, or [(point, r)]
control points; 0: the sharp edge only).  A strip that is not a round between two flat sides is refused
with RoundingError code "not_a_round", naming the place and the reason; the input mesh is never changed.
"""
import time

from . import api, inputs, meshconv
from .errors import RoundingError, check_cancelled

__all__ = ["change_radius"]


def change_radius(mesh, seeds, radius, tolerance=None, feature_angle=30.0, reach=3.0, max_new_facets=None,
                  cancel=None, fit_tolerance=0.01):
    """Round the existing rounds that `seeds` pick again at `radius` (0: sharpen them).

    mesh: Mesh.Mesh (not modified).  seeds: a point, or a list of points, each on an existing round.
    radius: mm (>= 0), or [(point, r)] control points.  fit_tolerance: share of the found radius its
    vertices may stray from the measured law before the strip is refused as not a round.  The other
    arguments are round_edges'.  Returns a RoundingResult whose report adds "strips" (per strip:
    found_radius, radius_min, radius_max, constant, law, fit_residual, opening_deg, convex, corner,
    strip_facets, recognised, ...) and "found_radius" (the list of the strips' found radii).
    """
    started = time.perf_counter()
    check_cancelled(cancel)
    inputs.check_mesh(mesh)
    arguments = _arguments(seeds, radius, tolerance, feature_angle, reach, max_new_facets, cancel, fit_tolerance)
    vertices, triangles = meshconv.mesh_to_arrays(mesh)
    result = api._round(vertices, triangles, arguments, engine="change_radius")
    result.report["found_radius"] = [s["found_radius"] for s in result.report["strips"]]
    result.mesh  # noqa: B018  (built now: part of this call's cost)
    check_cancelled(cancel)
    result.report["seconds"] = time.perf_counter() - started
    return result


def _arguments(seeds, radius, tolerance, feature_angle, reach, max_new_facets, cancel, fit_tolerance):
    """round_edges' checked arguments; radius 0 (sharpen only) passes through as 0."""
    sharpen_only = inputs._is_number(radius) and float(radius) == 0.0
    arguments = api._engine_arguments(seeds, 1.0 if sharpen_only else radius, tolerance, feature_angle, reach,
                                      max_new_facets, cancel)
    if sharpen_only:
        arguments["radius"] = 0.0
    if isinstance(fit_tolerance, bool) or not inputs._is_number(fit_tolerance) or not 0 < float(fit_tolerance) < 1:
        raise RoundingError(f"fit_tolerance must be a share of the radius in (0, 1), got {fit_tolerance!r}")
    arguments["fit_tolerance"] = float(fit_tolerance)
    return arguments
