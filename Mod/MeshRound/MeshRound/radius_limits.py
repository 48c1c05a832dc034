"""How large each chain's radius may be, and the stamping rules a radius is checked against (issue 16).

    limits = MeshRound.max_radius(mesh, seeds)          # one ChainLimit per chain: radius, where, why
    flags = MeshRound.check_rules(limits, 5.0, thickness=1.2, tool="die")

max_radius is measured from the geometry by the engine (cpp_core/include/meshround/max_radius.h): at
stations along the chain the rolling ball is solved between the chain's two faces exactly as the rounding
solves it, and the largest radius whose ball fits everywhere is bracketed to `precision` (relative;
default 1e-4, so the answer is good to 0.01%) -- no rounding is made.  What it does not measure: the ends'
setbacks at mitred corners and leaning end faces (round_edges refuses those as corner_not_blendable,
"too short"), and the rounding's own output check (result_invalid).
"""
import dataclasses

import numpy as np

import FreeCAD

from . import inputs, meshconv, shapes
from .errors import RoundingError

DEFAULT_REACH = 3.0  # round_edges' default reach factor

# What stops a larger ball (ChainLimit.why), in words.
WHY_TEXT = {
    "none": "every ball up to the mesh's size fits",
    "face_end": "the ball's contact runs off the end of its face (the surface turns away from the ball there)",
    "opposite_wall": "the ball reaches a face across from the chain (the surface turns towards the ball there)",
    "curvature": "the chain bends tighter than the ball on the ball's side: the round's edge would fold back",
    "neighbouring_chain": "the ball's contact reaches another picked chain",
    "boundary": "the ball's contact reaches the mesh boundary",
    "reach": "the ball's contact lies beyond reach x r (a larger reach factor lets it go on)",
    "no_ball": "no ball touches both faces there",
    "end_setback": "the round cannot run on to the face or corner where its chain ends (the chain is too short, or the ball does not fit there)",
}

# Rule of thumb for the smallest tool radius, as a multiple k of the sheet thickness t (check_rules).
# Source, stated honestly: the lower ends of the ranges that common deep-drawing / stamping design rules of
# thumb give (die entry radius about 5-10 t, punch nose radius about 4-10 t); not taken from a standard
# and not checked against one cited document here: set k from your own or your material supplier's rules.
DEFAULT_K = {"die": 5.0, "punch": 4.0}
# check_rules' flags, in words (the task panel's rule line).
FLAG_TEXT = {"below_k_t": "below k·t", "above_limit": "above the feasible limit"}


@dataclasses.dataclass
class ChainLimit:
    """The largest radius one chain rounds with, and what stops a larger one."""
    radius: float                # mm: the largest radius whose ball fits at every station (to `precision`)
    radius_refused: float        # mm: the smallest radius found not to fit (0 when none did)
    why: str                     # one of WHY_TEXT's keys
    where: FreeCAD.Vector        # the limiting feature: where the ball's contact meets it
    chain_point: FreeCAD.Vector  # the point of the chain where the room is smallest
    curvature_radius: float      # mm, for why == "curvature": the chain's radius of curvature there
    chain: object                # Part.Wire: the chain
    stations: int                # how many places along the chain were measured
    balls_solved: int            # the work: single balls solved

    @property
    def reason(self):
        """why, in words, with the place."""
        text = WHY_TEXT.get(self.why, self.why)
        if self.why == "curvature":
            text += f" (radius of curvature {self.curvature_radius:.4g} mm)"
        if self.why == "none":
            return text
        return f"{text}, at ({self.where.x:.4g}, {self.where.y:.4g}, {self.where.z:.4g})"

    def as_dict(self):
        """JSON-ready."""
        return dict(radius=self.radius, radius_refused=self.radius_refused, why=self.why, reason=self.reason,
                    where=list(self.where), chain_point=list(self.chain_point), curvature_radius=self.curvature_radius,
                    stations=self.stations, balls_solved=self.balls_solved)


def max_radius(mesh, seeds, feature_angle=30.0, reach=None, precision=1e-4):
    """The largest radius each chain the seeds select can be rounded with: one ChainLimit per distinct
    chain, in seed order.  reach: the reach factor the rounding will use (None: round_edges' default, 3):
    a contact beyond reach x r stops the ball there (why "reach").  precision: relative bracket width.
    Raises RoundingError for bad input (as round_edges)."""
    inputs.check_mesh(mesh)
    vertices, triangles = meshconv.mesh_to_arrays(mesh)
    return max_radius_arrays(vertices, triangles, seeds, feature_angle, reach, precision)


def max_radius_arrays(vertices, triangles, seeds, feature_angle=30.0, reach=None, precision=1e-4):
    """max_radius for a mesh given as arrays."""
    from .api import _call_engine  # the one caller of the engine's functions
    seed_points = inputs.seed_array(seeds)
    angle = inputs.feature_angle_value(feature_angle)
    reach = inputs.reach_value(DEFAULT_REACH if reach is None else reach)
    if not (isinstance(precision, (int, float)) and 0 < precision < 0.1):
        raise RoundingError(f"precision must be a number in (0, 0.1), got {precision!r}")
    raw = _call_engine("max_radius", np.ascontiguousarray(vertices, dtype=np.float64),
                       np.ascontiguousarray(triangles, dtype=np.int64), seed_points, feature_angle=angle,
                       reach=reach, precision=float(precision))
    wires = shapes.polyline_wires([c["points"] for c in raw], [c["closed"] for c in raw])
    return [ChainLimit(radius=c["radius"], radius_refused=c["radius_refused"], why=c["why"],
                       where=FreeCAD.Vector(*c["where"]), chain_point=FreeCAD.Vector(*c["chain_point"]),
                       curvature_radius=c["curvature_radius"], chain=wire, stations=c["stations"],
                       balls_solved=c["balls_solved"]) for c, wire in zip(raw, wires)]


def check_rules(limits, radius, thickness=None, tool="die", k=None):
    """Flag chains whose radius breaks a rule.  limits: max_radius's list (None: no feasibility check);
    radius: one number for every chain or one per chain; thickness: sheet thickness t in mm (None: no k.t
    rule); tool: "die" or "punch", or one per chain; k: {tool: factor} overriding DEFAULT_K.
    Returns one dict per chain: radius, min_radius (k.t or None), max_radius (or None), flags (a list of
    "below_k_t", "above_limit") and message ("" when none)."""
    factors = dict(DEFAULT_K, **(k or {}))
    count = len(limits) if limits is not None else (len(radius) if isinstance(radius, (list, tuple)) else 1)
    radii = list(radius) if isinstance(radius, (list, tuple)) else [radius] * count
    tools = list(tool) if isinstance(tool, (list, tuple)) else [tool] * count
    if len(radii) != count or len(tools) != count:
        raise RoundingError(f"check_rules: {count} chain(s) but {len(radii)} radii and {len(tools)} tool types")
    if thickness is not None and not (isinstance(thickness, (int, float)) and thickness > 0):
        raise RoundingError(f"thickness must be a positive number (mm), got {thickness!r}")
    rows = []
    for i in range(count):
        if tools[i] not in factors:
            raise RoundingError(f"unknown tool type {tools[i]!r}: one of {', '.join(sorted(factors))}")
        r = float(radii[i])
        smallest = factors[tools[i]] * thickness if thickness is not None else None
        largest = limits[i].radius if limits is not None else None
        flags, words = [], []
        if smallest is not None and r < smallest:
            flags.append("below_k_t")
            words.append(f"r = {r:g} mm is below {factors[tools[i]]:g} t = {smallest:g} mm ({tools[i]} radius rule)")
        if largest is not None and r > largest:
            flags.append("above_limit")
            words.append(f"r = {r:g} mm is above the largest that fits, {largest:.6g} mm: {limits[i].reason}")
        rows.append(dict(chain=i, radius=r, tool=tools[i], min_radius=smallest, max_radius=largest, flags=flags,
                         message="; ".join(words)))
    return rows


def rule_line(rows, tool):
    """(text, flagged): one line for the task panel from check_rules' rows -- the flags and why, or that the
    k.t rule is met; ("", False) when there is nothing to say."""
    flagged = [row for row in rows if row["flags"]]
    if flagged:
        flags = sorted({flag for row in flagged for flag in row["flags"]})
        messages = list(dict.fromkeys(row["message"] for row in flagged))
        return f"{', '.join(FLAG_TEXT[f] for f in flags)}: {'; '.join(messages)}", True
    if rows and rows[0]["min_radius"] is not None:
        return f"r >= {max(row['min_radius'] for row in rows):g} mm ({tool}, {DEFAULT_K[tool]:g} t): met", False
    return "", False

