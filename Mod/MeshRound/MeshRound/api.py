"""The console API: round sharp edge chains of a Mesh.Mesh with a rolling ball.

    import MeshRound
    res = MeshRound.round_edges(mesh, seeds, radius, tolerance=None, feature_angle=30.0, reach=3.0,
                                cancel=None)
    res.mesh, res.surfaces, res.spines, res.chains, res.contacts, res.report

Only this module calls the compiled engine (errors.py imports it for its exception class).  It validates
in Python first (so every bad input is a RoundingError with a clear message), converts the mesh to arrays
once, calls the engine, and turns its plain outputs into FreeCAD objects.  The *_arrays variants skip the
mesh conversion for callers that keep the arrays (the task panel traces a chain on every pick).
"""
import dataclasses
import functools
import math
import time

import FreeCAD
import numpy as np

from . import inputs, meshconv, meshedit, progress, radius_limits, shapes
from .errors import CancelToken, RoundingError, check_cancelled, require_core

__all__ = ["RoundingError", "CancelToken", "RoundingResult", "round_edges", "round_arrays", "trace_chains",
           "trace_arrays", "NetworkPlan", "plan_network", "plan_arrays", "quality_note"]


@dataclasses.dataclass
class RoundingResult:
    """What one rounding produced; `mesh` is new, the input mesh is never modified."""
    surfaces: list      # Part.Face: the exact rolling-ball surface per chain (on a Part.BSplineSurface), then
                        # each sphere corner's patch of the ball (on a Part.Sphere), bounded by the rounds' end arcs
    spines: list        # Part.Wire: the ball-centre path, per chain
    chains: list        # Part.Wire: the sharp-edge chains that were rounded
    contacts: list      # Part.Wire: the ball's contact lines, two per chain (side A, side B)
    report: dict        # JSON-ready numbers: chains, facets_removed, facets_added, max_deviation, ...
    delta: dict = dataclasses.field(default=None, repr=False)  # the result as an edit of the input (meshedit.py)
    _input: tuple = dataclasses.field(default=None, repr=False)  # the input's (vertices, triangles): what delta edits

    @property
    def vertices(self):
        """float64 (n, 3): the rounded mesh as arrays ..."""
        return self._arrays[0]

    @property
    def triangles(self):
        """... int64 (m, 3); made on first use from the input and the delta (the engine's apply_delta)."""
        return self._arrays[1]

    @functools.cached_property
    def _arrays(self):
        vertices, triangles = _call_engine("apply_delta", *self._input, self.delta)
        return _checked_mesh_arrays(vertices, triangles)

    @functools.cached_property
    def mesh(self):
        """... and as a Mesh.Mesh, built on first use (a preview that only draws arrays skips it); the
        same mesh vertex for vertex and facet for facet."""
        return meshconv.arrays_to_mesh(self.vertices, self.triangles)

    def __repr__(self):
        r = self.report
        return (f"<RoundingResult: {r.get('chains')} chain(s), {r.get('facets_in')} -> "
                f"{r.get('facets_out')} facets, {r.get('seconds', 0.0):.3f} s>")


def round_edges(mesh, seeds, radius, tolerance=None, feature_angle=30.0, reach=3.0, max_new_facets=None,
                cancel=None, thickness=None, tool="die", k=None, band=None):
    """Round the sharp-edge chains of `mesh` that pass nearest to `seeds`.

    mesh: Mesh.Mesh (not modified).  seeds: a Vector, an (x, y, z) triple, or a list of them; each picks
    the sharp edge nearest to it and its whole chain.  radius: mm, or a list of (point, radius) control
    points for a variable radius.  tolerance: chordal tolerance, None or 0 means largest radius / 100.
    feature_angle: degrees between facets from which an edge is sharp.  reach: facets within reach * r
    of a chain are re-meshed.  max_new_facets: the work budget (None: the engine's default, 2,000,000);
    a rounding that would make more new facets is refused (code work_limit).  cancel: a
    MeshRound.CancelToken, or None; token.cancel() from another thread stops the run within about 0.1 s with RoundingError(code "cancelled"), the input untouched
    (a token cancelled before the call is refused at once).  thickness: the sheet thickness t in mm, for
    the stamping rule radius >= k.t (radius_limits.check_rules, tool "die" or "punch", k overriding its
    factors); given, the report gets "rules": one check_rules row per chain (flags "below_k_t"; a variable
    radius is checked by its smallest); None: no such entry.  band: the band's element controls, a dict
    of any of max_element_angle (degrees of the profile per element across the round, e.g. 10),
    element_length (mm along the round; default the input's own) and max_aspect_ratio (longest / shortest
    side, >= 1), each None or 0 = off; the report's "band_quality" gives what was made (smallest and
    largest angle, aspect ratio, shortest side).  Returns a RoundingResult; raises RoundingError.
    """
    started = time.perf_counter()
    check_cancelled(cancel)
    inputs.check_mesh(mesh)
    arguments = _engine_arguments(seeds, radius, tolerance, feature_angle, reach, max_new_facets, cancel, band)
    rule_radius = _rule_radius(radius, thickness, tool, k)  # bad rule arguments are refused before the work
    vertices, triangles = meshconv.mesh_to_arrays(mesh)
    read = time.perf_counter()
    # The output is the input's copy with the band edited (meshedit.py); the copy is made on the other
    # core while the engine runs.
    copy = meshedit.start_copy(mesh) if _editable_shape(mesh) else None
    try:
        result = _round(vertices, triangles, arguments, arrays=False)
    finally:
        copy = copy() if copy is not None else None  # the worker is always joined
    engine = time.perf_counter()
    if copy is not None and meshedit.editable(mesh, result.delta):
        edited = meshedit.edited_copy(copy, result.delta, vertices)
        if edited is not None:
            result.mesh = edited
    result.mesh  # noqa: B018  (build it now if it was not edited: part of this call's cost)
    check_cancelled(cancel)  # a request while the result was built: nothing is returned
    done = time.perf_counter()
    result.report["seconds"] = done - started
    result.report["seconds_stages"] = dict(mesh_to_arrays=read - started, engine=engine - read, output_mesh=done - engine)
    if thickness is not None:
        result.report["rules"] = radius_limits.check_rules(None, [rule_radius] * int(result.report.get("chains") or 1),
                                                           thickness, tool, k)
    return result


def _rule_radius(radius, thickness, tool, k):
    """The radius the k.t rule checks (a law's smallest), after checking the rule's arguments; None
    without a thickness."""
    if thickness is None:
        return None
    largest, law = inputs.radius_and_law(radius)
    smallest = float(law[:, 3].min()) if law is not None else largest
    radius_limits.check_rules(None, smallest, thickness, tool, k)
    return smallest


def round_arrays(vertices, triangles, seeds, radius, tolerance=None, feature_angle=30.0, reach=3.0,
                 max_new_facets=None, cancel=None, band=None, arrays=True):
    """round_edges for a mesh given as vertices (n, 3) and triangles (m, 3); result.mesh is built lazily
    (arrays=False: result.vertices / triangles too, from result.delta, for a caller that uses the delta)."""
    started = time.perf_counter()
    check_cancelled(cancel)
    if len(triangles) == 0:
        raise RoundingError("mesh is empty: it has no facets")
    arguments = _engine_arguments(seeds, radius, tolerance, feature_angle, reach, max_new_facets, cancel, band)
    result = _round(vertices, triangles, arguments, arrays=arrays)
    result.report["seconds"] = time.perf_counter() - started
    return result


def quality_note(report):
    """One sentence on the new facets under 10 degrees and why they are there, or "" when there are none.

    Three causes are told apart: the input's own facets there are that thin (input_forces_small_angles);
    the round ends at a cusp (cusp_facets: a round running into a face its side goes on past, as a pocket's
    rim edge into the next wall, leaves that side tangentially, and the chordal tolerance allows no larger
    angle at that point than half the profile's step, cusp_angle_deg); or the input facets the round cuts are
    too large for the reach, which leaves too narrow a strip to grade from the round's spacing to their far
    corners; then the engine has rounded the chain again at wider reaches, and reach_for_room is the first
    that made none (0: none of those did).
    """
    thin = report.get("thin_facets", 0)
    if not thin:
        return ""
    text = f"{thin} new facet(s) under 10 deg (smallest {report.get('min_new_angle_deg', 0.0):.1f} deg)"
    cusp = report.get("cusp_facets", 0)
    if cusp == thin:
        return text + (f": at the round's end cusps, where its end leaves a face tangentially, a facet's angle is "
                       f"half the profile's step, {report.get('cusp_angle_deg', 0.0):.1f} deg (the tolerance t "
                       f"allows no more than acos(1 - t / r) there).")
    if cusp:
        text += f" ({cusp} at the round's end cusps, {report.get('cusp_angle_deg', 0.0):.1f} deg)"
    if report.get("input_forces_small_angles"):
        return text + (f": the input's own facets there have angles down to "
                       f"{report.get('min_input_angle_deg', 0.0):.1f} deg.")
    if report.get("reach_for_room"):
        return text + (f": the input facets the round cuts are too large for the reach; "
                       f"at reach {report['reach_for_room']:g} none is.")
    return text + "."


def trace_chains(mesh, seeds, feature_angle=30.0):
    """The sharp-edge chains the seeds select, as Part.Wire (closed loops are closed wires)."""
    inputs.check_mesh(mesh)
    vertices, triangles = meshconv.mesh_to_arrays(mesh)
    return trace_arrays(vertices, triangles, seeds, feature_angle)


def trace_arrays(vertices, triangles, seeds, feature_angle=30.0):
    """trace_chains for a mesh given as arrays."""
    seed_points = inputs.seed_array(seeds)
    angle = inputs.feature_angle_value(feature_angle)
    found = _call_engine("trace_chains", vertices, triangles, seed_points, feature_angle=angle)
    return shapes.polyline_wires([c["points"] for c in found], [c["closed"] for c in found])


@dataclasses.dataclass
class NetworkPlan:
    """What round_edges will make of the chains the seeds select, before it makes anything (plan_network)."""
    chains: list   # Part.Wire per chain, in the order round_edges rounds them
    corners: list  # one dict per corner: 'vertex' (FreeCAD.Vector), 'kind' ('mitre', 'sphere', 'rolled' as in
                   # the report), 'chains' (indices into `chains`)
    refusal: str   # None, or why round_edges would refuse a corner (its message, naming the vertex)

    def summary(self):
        """One line for a user: the corners by kind, or the refusal."""
        if self.refusal:
            return f"Corner not blended: {self.refusal}"
        if not self.corners:
            return ""
        kinds = [k["kind"] for k in self.corners]
        counts = ", ".join(f"{kinds.count(k)} {k}" for k in ("mitre", "sphere", "rolled") if k in kinds)
        return f"{len(self.corners)} corner(s): {counts}"


def plan_network(mesh, seeds, radius, tolerance=None, feature_angle=30.0, reach=3.0):
    """The chains the seeds select and, where they meet, how each corner will be blended -- or the corner
    round_edges would refuse, with its reason -- without rounding anything (a fraction of a second)."""
    inputs.check_mesh(mesh)
    vertices, triangles = meshconv.mesh_to_arrays(mesh)
    return plan_arrays(vertices, triangles, seeds, radius, tolerance, feature_angle, reach)


def plan_arrays(vertices, triangles, seeds, radius, tolerance=None, feature_angle=30.0, reach=3.0):
    """plan_network for a mesh given as arrays."""
    arguments = _engine_arguments(seeds, radius, tolerance, feature_angle, reach)
    for unused in ("max_new_facets", "cancel"):
        arguments.pop(unused)
    found = _call_engine("plan_network", vertices, triangles, **arguments)
    chains = found["chains"]
    wires = shapes.polyline_wires([c["points"] for c in chains], [c["closed"] for c in chains])
    corners = [dict(vertex=FreeCAD.Vector(*c["vertex"]), kind=c["kind"], chains=list(c["chains"])) for c in found["corners"]]
    return NetworkPlan(wires, corners, found["refusal"])


def _engine_arguments(seeds, radius, tolerance, feature_angle, reach, max_new_facets=None, cancel=None, band=None):
    """Keyword arguments for core.round_edges, every one checked."""
    largest_radius, law = inputs.radius_and_law(radius)
    if max_new_facets is not None and (isinstance(max_new_facets, bool) or not isinstance(max_new_facets, int) or max_new_facets < 1):
        raise RoundingError(f"max_new_facets must be a positive whole number (or None: the default), got {max_new_facets!r}",
                            code="invalid_input")
    return dict(
        seeds=inputs.seed_array(seeds),
        radius=largest_radius,
        tolerance=inputs.tolerance_value(tolerance),
        feature_angle=inputs.feature_angle_value(feature_angle),
        reach=inputs.reach_value(reach),
        radius_law=law,
        max_new_facets=int(max_new_facets or 0),  # 0: the engine's default
        cancel=cancel,
        band=inputs.band_value(band),
    )


def _round(vertices, triangles, arguments, engine="round_edges", arrays=True):
    """core.<engine> (round_edges, or change_radius: the same result dict) turned into a RoundingResult;
    `arrays`: make result.vertices / triangles now (else on first use, from the input and the delta;
    change_radius' delta is its two steps, sharpening and rounding, as one edit of the input)."""
    vertices = np.ascontiguousarray(vertices, dtype=np.float64)
    triangles = np.ascontiguousarray(triangles, dtype=np.int64)
    seeds = arguments.pop("seeds")
    radius = arguments.pop("radius")
    raw = _call_engine(engine, vertices, triangles, seeds, radius, arrays=arrays, **arguments)
    check_cancelled(arguments["cancel"])  # asked for after the engine's last poll
    delta = None if raw["delta"] is None else _checked_delta(raw["delta"])
    contacts = [side for pair in raw["contacts"] for side in pair]
    closed = list(raw["closed"])
    result = RoundingResult(
        surfaces=shapes.faces_from_brep(list(raw["faces"]) + list(raw.get("corner_faces", []))),
        spines=shapes.polyline_wires(raw["spines"], closed),
        chains=shapes.polyline_wires(raw["chains"], closed),
        contacts=shapes.polyline_wires(contacts, [c for c in closed for _ in (0, 1)]),
        report=_json_ready(raw["report"]),
        delta=delta, _input=None if delta is None else (vertices, triangles),
    )
    if "strips" in raw:  # change_radius: what was found on each existing round (reround.py)
        result.report["strips"] = _json_ready(raw["strips"])
    if raw["vertices"] is not None:
        result._arrays = _checked_mesh_arrays(raw["vertices"], raw["triangles"])
    facets_out = len(result.triangles) if delta is None else len(triangles) - len(delta["removed"]) + len(delta["added"])
    result.report.update(facets_in=len(triangles), facets_out=facets_out)
    return result


def _editable_shape(mesh):
    """A mesh whose copy can take the engine's edit (meshedit.py): no Placement."""
    return mesh.Placement.isIdentity()


def _call_engine(name, *args, **kwargs):
    """Call core.<name>; anything the engine raises reaches the caller as a RoundingError.

    Inside progress.busy() in the GUI the call runs on a worker thread while the window stays alive."""
    function = getattr(require_core(), name)
    try:
        return progress.wait_for(function, *args, **kwargs)
    except RoundingError:
        raise
    except (MemoryError, KeyboardInterrupt):
        raise
    except Exception as exc:  # a binding or engine bug must still surface as the documented error type
        raise RoundingError(f"the rounding engine failed in {name}: {type(exc).__name__}: {exc}",
                            "result_invalid") from exc


def _checked_mesh_arrays(vertices, triangles):
    """The engine's mesh as arrays, refused if it could not be turned into a valid Mesh.Mesh."""
    vertices = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    if len(triangles) == 0:
        raise RoundingError("the engine returned an empty mesh", "result_invalid")
    if triangles.min() < 0 or triangles.max() >= len(vertices) or not np.all(np.isfinite(vertices)):
        raise RoundingError("the engine returned an invalid mesh (index out of range or non-finite point)",
                            "result_invalid")
    return vertices, triangles


def _checked_delta(delta):
    """The engine's result as an edit of its input, refused if it could not make a valid mesh (checked at
    the band's cost: the new facets' vertex ids and the new and moved points)."""
    n = int(delta["input_vertices"])
    added = np.asarray(delta["added"]).reshape(-1, 3)
    points = np.concatenate([np.asarray(delta["new_points"]).reshape(-1, 3), np.asarray(delta["moved_to"]).reshape(-1, 3)])
    if int(delta["input_facets"]) - len(delta["removed"]) + len(added) <= 0:
        raise RoundingError("the engine returned an empty mesh", "result_invalid")
    if (len(added) and (added.min() < 0 or added.max() >= n + len(delta["new_points"]))) or not np.all(np.isfinite(points)):
        raise RoundingError("the engine returned an invalid mesh (index out of range or non-finite point)",
                            "result_invalid")
    return delta


def _json_ready(value):
    """The engine's report with numpy scalars/arrays turned into plain Python (for json.dump)."""
    if isinstance(value, dict):
        return {str(k): _json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_ready(v) for v in value]
    if isinstance(value, np.ndarray):
        return _json_ready(value.tolist())
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None  # JSON has no NaN/inf
    return value
