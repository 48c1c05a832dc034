"""Change the radius of an existing round (issue 15).

    import MeshRound
    res = MeshRound.change_radius(mesh, seeds, radius, tolerance=None)
    res.mesh                                   # the mesh with the round at the new radius (radius 0: sharp)
    res.report["found_radius"]                 # per strip: the radius the round had (mm)
    res.report["strips"][0]["law"]             # per strip: [(x, y, z, r)] along the rebuilt edge
    res.report["strips"][0]["recognised"]      # how the strip was told from its sides

Each seed picks a point on an existing round: a strip of facets turning between two flat sides (or a flat
side and one curved along the round, as a wall curved in plan: report["strips"][i]["corner_line"] is then
the rebuilt edge as a polyline).  The
engine (cpp_core sharpen.h) finds the strip, measures its radius at every vertex (the ball tangent to
both sides through it), rebuilds the sharp edge the round replaced by extending the two sides to their
corner line, then rounds that edge with round_edges' passes at `radius` (a number, or [(point, r)]
control points; 0: the sharp edge only).  A strip that is not a round between two flat sides is refused
with RoundingError code "not_a_round", naming the place and the reason; the input mesh is never changed.
"""
import math
import time

import FreeCAD
import numpy as np

from . import api, inputs, meshconv
from .errors import RoundingError, check_cancelled

__all__ = ["change_radius", "change_radius_arrays", "named", "strip_facet_indices"]


def change_radius(mesh, seeds, radius, tolerance=None, feature_angle=30.0, reach=3.0, max_new_facets=None,
                  cancel=None, fit_tolerance=0.01, band=None):
    """Round the existing rounds that `seeds` pick again at `radius` (0: sharpen them).

    mesh: Mesh.Mesh (not modified).  seeds: a point, or a list of points, each on an existing round.
    radius: mm (>= 0), or [(point, r)] control points.  fit_tolerance: share of the found radius its
    vertices may stray from the measured law before the strip is refused as not a round.  The other
    arguments are round_edges' (band: the new round's element controls).  Returns a RoundingResult whose
    report adds "strips" (per strip: found_radius, radius_min, radius_max, constant, law, fit_residual,
    opening_deg, convex, corner, strip_facets, recognised, ...) and "found_radius" (the list of the
    strips' found radii).
    """
    started = time.perf_counter()
    check_cancelled(cancel)
    inputs.check_mesh(mesh)
    vertices, triangles = meshconv.mesh_to_arrays(mesh)
    result = change_radius_arrays(vertices, triangles, seeds, radius, tolerance, feature_angle, reach, max_new_facets,
                                  cancel, fit_tolerance, band)
    result.mesh  # noqa: B018  (built now: part of this call's cost)
    check_cancelled(cancel)
    result.report["seconds"] = time.perf_counter() - started
    return result


def change_radius_arrays(vertices, triangles, seeds, radius, tolerance=None, feature_angle=30.0, reach=3.0,
                         max_new_facets=None, cancel=None, fit_tolerance=0.01, band=None, arrays=True):
    """change_radius for a mesh given as vertices (n, 3) and triangles (m, 3) (the task panel's preview, a
    solver deck's shells).  result.delta is the change as an edit of the input (mesh_delta.h); arrays=False:
    result.vertices / triangles are made from it on first use (a deck's edit needs the delta only)."""
    started = time.perf_counter()
    check_cancelled(cancel)
    if len(triangles) == 0:
        raise RoundingError("mesh is empty: it has no facets")
    arguments = _arguments(seeds, radius, tolerance, feature_angle, reach, max_new_facets, cancel, fit_tolerance, band)
    result = api._round(vertices, triangles, arguments, engine="change_radius", arrays=arrays)
    result.report["found_radius"] = [s["found_radius"] for s in result.report["strips"]]
    result.report["seconds"] = time.perf_counter() - started
    return result


def strip_facet_indices(vertices, triangles, strip, slack=1e-3, flat_angle=0.5):
    """The facets of the input (vertices (n, 3), triangles (m, 3)) that make the round `strip` (a row of
    report["strips"]): every vertex within the round's width of its corner line (r tan(opening / 2) at the
    local found radius) and between the line's ends, turning about the line: not facing along it (an end
    face) nor across it (a side's facet there, which faces away from the line by 90 deg within flat_angle).
    Their count is a constant round's "strip_facets" (a variable one's within some 10 %); the task panel
    highlights them."""
    vertices, triangles = np.asarray(vertices, dtype=np.float64), np.asarray(triangles, dtype=np.int64)
    line = np.asarray(strip.get("corner_line") or strip["corner"], dtype=np.float64).reshape(-1, 3)
    if len(line) > 2:
        return _curved_strip_facets(vertices, triangles, strip, line, slack, flat_angle)
    start, end = np.asarray(strip["corner"], dtype=np.float64)
    length = float(np.linalg.norm(end - start))
    axis = (end - start) / length
    corners = vertices[triangles]                                  # (m, 3, 3)
    along = (corners - start) @ axis                               # (m, 3)
    radial = corners - start - along[..., None] * axis             # from the corner line, across it
    width = _found_radius_along(strip, start, axis, along) * math.tan(math.radians(strip["opening_deg"]) / 2)
    near = (np.linalg.norm(radial, axis=2) <= width * (1 + slack) + slack * strip["found_radius"]).all(axis=1)
    inside = (along > -slack).all(axis=1) & (along < length + slack).all(axis=1)
    normals = _unit(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]))
    turning = (np.abs(normals @ axis) < 0.5) & (np.abs(np.sum(normals * _unit(radial.mean(axis=1)), axis=1))
                                                 > math.sin(math.radians(flat_angle)))
    return np.flatnonzero(near & inside & turning)


def _curved_strip_facets(vertices, triangles, strip, line, slack, flat_angle):
    """strip_facet_indices for a strip whose corner line is a polyline (a side curved along the round): the
    same tests, each vertex against its nearest segment (the largest radius of the law for the width)."""
    width = max(row[3] for row in strip["law"]) * math.tan(math.radians(strip["opening_deg"]) / 2)
    box_lo, box_hi = line.min(axis=0) - 2 * width, line.max(axis=0) + 2 * width
    candidates = np.flatnonzero(((vertices[triangles] >= box_lo) & (vertices[triangles] <= box_hi)).all(axis=(1, 2)))
    corners = vertices[triangles[candidates]].reshape(-1, 3)        # (3c, 3)
    a, d = line[:-1], line[1:] - line[:-1]                          # segments
    w = np.clip(np.einsum("pkj,kj->pk", corners[:, None, :] - a[None], d) / np.sum(d * d, axis=1), 0.0, 1.0)
    foot = a[None] + w[..., None] * d[None]                         # (3c, k, 3)
    dist = np.linalg.norm(corners[:, None, :] - foot, axis=2)
    k = np.argmin(dist, axis=1)
    radial = (corners - foot[np.arange(len(corners)), k]).reshape(-1, 3, 3)
    axis = _unit(d[k]).reshape(-1, 3, 3)
    inside = (((w[np.arange(len(corners)), k] > 0) | (k > 0)) & ((w[np.arange(len(corners)), k] < 1) | (k < len(d) - 1)))
    near = (np.linalg.norm(radial, axis=2) <= width * (1 + slack) + slack * strip["found_radius"]).all(axis=1)
    tri = corners.reshape(-1, 3, 3)
    normals = _unit(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]))
    turning = (np.abs(np.sum(normals * axis.mean(axis=1), axis=1)) < 0.5) & \
        (np.abs(np.sum(normals * _unit(radial.mean(axis=1)), axis=1)) > math.sin(math.radians(flat_angle)))
    return candidates[near & inside.reshape(-1, 3).all(axis=1) & turning]


def _found_radius_along(strip, start, axis, along):
    """The strip's found radius (its law, linear between stations) at the positions `along` its corner line."""
    law = np.asarray(strip["law"], dtype=np.float64).reshape(-1, 4)
    stations = (law[:, :3] - start) @ axis
    order = np.argsort(stations)
    return np.interp(along, stations[order], law[order, 3])


def _unit(rows):
    return rows / np.maximum(np.linalg.norm(rows, axis=-1, keepdims=True), 1e-300)


def named(exc):
    """A change of radius's refusal as the feature and the task panel show it: its code first (e.g.
    "not_a_round: ..."), as the README's table of refusals lists it; a cancellation as it is."""
    if exc.code == "cancelled":
        return exc
    return RoundingError(f"{exc.code}: {exc}", exc.code)


def sharpen_only(radius):
    """True for radius 0 (mm, or a Quantity of 0): sharpen the rounds, make no new one."""
    if isinstance(radius, FreeCAD.Units.Quantity):
        radius = radius.Value
    return inputs._is_number(radius) and float(radius) == 0.0


def _arguments(seeds, radius, tolerance, feature_angle, reach, max_new_facets, cancel, fit_tolerance, band=None):
    """round_edges' checked arguments; radius 0 (sharpen only) passes through as 0."""
    sharpen = sharpen_only(radius)
    arguments = api._engine_arguments(seeds, 1.0 if sharpen else radius, tolerance, feature_angle, reach,
                                      max_new_facets, cancel, band)
    if sharpen:
        arguments["radius"] = 0.0
    if isinstance(fit_tolerance, bool) or not inputs._is_number(fit_tolerance) or not 0 < float(fit_tolerance) < 1:
        raise RoundingError(f"fit_tolerance must be a share of the radius in (0, 1), got {fit_tolerance!r}")
    arguments["fit_tolerance"] = float(fit_tolerance)
    return arguments
