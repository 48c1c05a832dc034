"""Radius sweeps and the optimiser hook (issue 16): many rounded variants of one mesh, one per radius.

    s = MeshRound.sweep(mesh, seeds, [3, 4, 5, 6], out_dir="variants")   # files + table.csv + table.json
    s = MeshRound.sweep("die.k", seeds, [3, 4, 5])                       # a solver deck: variants are decks
    s.rows                 # one dict per variant: radii, file, status, facets_added, max_deviation, ...
    s = MeshRound.sweep_sheet(rounding, sheet, "B", "variants")         # in FreeCAD: radii from a column
    best = MeshRound.optimise_radius(mesh, seeds, objective)             # objective(path) -> float

Variants are made on parallel threads (the engine lets go of Python's lock while it rounds, so they
run on as many cores; the mesh's arrays are shared, not copied; jobs=None means one per core). Not
processes: forking a process that runs threads of its own (FreeCAD's, a test runner's) can leave a worker
waiting forever on a lock another thread held; a radius above a chain's largest feasible radius (max_radius) is not tried: the
table says so in one line per such variant (status "above_limit") and the sweep goes on with the rest.
Every sweep (of a mesh, of a deck, of a Rounding feature from a spreadsheet) writes the same table.
"""
import concurrent.futures
import csv
import dataclasses
import json
import math
import os
import tempfile
import time

import numpy as np

import FreeCAD

from . import api, decks, inputs, meshconv, radius_limits
from .deck_formats import deck_family
from .errors import RoundingError

# What FreeCAD's Mesh module writes, by extension (as the command line).
WRITE_FORMATS = ("stl", "ast", "obj", "ply", "off", "bms", "smf", "nas", "bdf", "3mf", "iv", "x3d", "x3dz", "xhtml",
                 "wrl", "vrml", "wrz", "idtf", "mgl", "py", "asy")
# The report numbers the table's CSV carries (the JSON has the whole report).
TABLE_COLUMNS = ("facets_removed", "facets_added", "max_deviation", "min_new_angle_deg", "thin_facets", "seconds")


@dataclasses.dataclass
class SweepResult:
    rows: list          # one dict per variant, in the order of `radii`
    limits: list        # max_radius's ChainLimit per chain (empty when not measured)
    out_dir: str        # where the files and the tables are
    table_csv: str      # path of the CSV table
    table_json: str     # path of the JSON table
    jobs: int           # worker threads used
    seconds: float      # wall-clock time of the whole sweep
    stopped: str        # "" or the line that says which radii were above the feasible limit


# The work shared with the worker threads (set before the pool starts; read only while it runs).
_WORK = {}


def _variant(task):
    """Make one variant in a worker: round, write the file; returns the table row."""
    index, radii = task
    w = _WORK
    row = dict(index=index, radii=list(radii), file=None, status="ok", message="")
    radius = radii[0] if len(set(radii)) == 1 else [(p, r) for p, r in zip(w["control_points"], radii)]
    name = f"{w['stem']}_{index:03d}_r{'_'.join(f'{r:g}' for r in radii)}.{w['fmt']}"
    try:
        if w["deck"]:
            if w["deck_includes"]:  # the variant's includes beside it: a folder of its own
                name = os.path.join(os.path.splitext(name)[0], os.path.basename(w["deck"]))
                os.makedirs(os.path.join(w["out_dir"], os.path.dirname(name)), exist_ok=True)
            res = decks.round_deck(w["deck"], os.path.join(w["out_dir"], name), w["seeds"], radius, part=w["part"],
                                   **w["options"])
        else:
            res = api.round_arrays(w["vertices"], w["triangles"], w["seeds"], radius, **w["options"])
            meshconv.arrays_to_mesh(res.vertices, res.triangles).write(os.path.join(w["out_dir"], name))
        row.update(file=name, report=res.report)
        row.update({k: res.report.get(k) for k in TABLE_COLUMNS})
    except RoundingError as exc:
        row.update(status=getattr(exc, "code", "invalid_input"), message=str(exc))
    return row


def radius_rows(radii, chains):
    """Each variant's radii, one per chain: from numbers (every chain the same) or per-chain lists."""
    rows = []
    for r in radii:
        if isinstance(r, (list, tuple, np.ndarray)):
            row = [float(x) for x in r]
            if len(row) != chains:
                raise RoundingError(f"a variant gives {len(row)} radii for {chains} chain(s)")
        else:
            row = [float(r)] * chains
        if not all(math.isfinite(x) and x > 0 for x in row):
            raise RoundingError(f"radii must be positive numbers, got {row}")
        rows.append(row)
    if not rows:
        raise RoundingError("a sweep needs at least one radius")
    return rows


def sweep(mesh, seeds, radii, out_dir=None, fmt=None, jobs=None, tolerance=None, feature_angle=30.0, reach=3.0,
          thickness=None, tool="die", k=None, check_limits=True, stem="variant", part=None):
    """One rounded variant of `mesh` per entry of `radii`, written to out_dir (None: a new temporary folder),
    with table.csv and table.json (each variant's report, file name and rule flags).

    mesh: a Mesh.Mesh, or the path of a solver deck (LS-DYNA .k/.key/.dyn, Nastran .bdf/.nas/.dat, Abaqus
    .inp): each variant is then that deck rounded by round_deck (IDs, parts, sets and every other line kept
    outside the band) and written in its own format (a deck with includes: each variant in a folder of its
    own, its includes beside it); part: round_deck's part, for a deck only.
    radii: numbers (every picked chain gets that radius), or lists of one radius per distinct chain in seed
    order (each seed then carries its chain's radius).  fmt: a Mesh write format (WRITE_FORMATS; None: stl),
    for a deck None or its own extension.  jobs: worker threads (None: one per core; 1: in the calling thread).
    thickness, tool, k: check_rules' stamping rule (radius >= k.t), flagged in the table.  check_limits:
    measure max_radius first and skip the variants above it (status "above_limit").  Returns a SweepResult."""
    started = time.perf_counter()
    deck = _deck_path(mesh, fmt, part)
    if deck:
        arrays = decks.read_deck(deck)
        vertices, triangles, _, _ = decks.deck_triangles(arrays, part)
        fmt, includes = os.path.splitext(deck)[1].lstrip("."), len(arrays["files"]) > 1
    else:
        inputs.check_mesh(mesh)
        fmt, includes = fmt or "stl", False
        if fmt not in WRITE_FORMATS:
            raise RoundingError(f"unknown mesh format {fmt!r}: one of {', '.join(WRITE_FORMATS)}")
        vertices, triangles = meshconv.mesh_to_arrays(mesh)
    seed_points = inputs.seed_array(seeds)
    limits = radius_limits.max_radius_arrays(vertices, triangles, seed_points, feature_angle, reach) if check_limits else []
    chains = len(limits) if limits else len(seed_points)
    rows = radius_rows(radii, chains)
    if len(set(tuple(r) for r in rows)) < len(rows):
        raise RoundingError("a sweep's variants must differ: a radius is repeated")
    if any(len(set(r)) > 1 for r in rows) and chains != len(seed_points):
        raise RoundingError("per-chain radii need exactly one seed per chain")
    out_dir = _out_dir(out_dir)
    table, todo = _within_limits(rows, limits)
    _WORK.clear()
    _WORK.update(vertices=vertices, triangles=triangles, seeds=seed_points, control_points=[tuple(p) for p in seed_points],
                 options=dict(tolerance=tolerance, feature_angle=feature_angle, reach=reach), out_dir=out_dir,
                 fmt=fmt, stem=stem, deck=deck, deck_includes=includes, part=part)
    jobs = _jobs(jobs, len(todo))
    if jobs == 1:
        done = [_variant(t) for t in todo]
    else:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            done = list(pool.map(_variant, todo))
    for row in done:
        table[row["index"]] = row
    return _finish(table, limits, out_dir, jobs, started, thickness, tool, k)


def _deck_path(mesh, fmt, part):
    """mesh's path when it is a solver deck (fmt None or the deck's own family), else None."""
    family = deck_family(mesh) if isinstance(mesh, (str, os.PathLike)) else None
    if family is None:
        if isinstance(mesh, (str, os.PathLike)):
            raise RoundingError(f"'{mesh}' is not a solver deck by its extension: give a Mesh.Mesh or a deck "
                                f"({', '.join(sorted(decks.DECK_EXTENSIONS))})", code="invalid_input")
        if part is not None:
            raise RoundingError("part is for a solver deck only", code="invalid_input")
        return None
    if fmt is not None and deck_family("x." + str(fmt)) != family:
        raise RoundingError(f"a {family} deck's variants are written as {family} decks, not {fmt!r} "
                            "(no conversion between formats)", code="invalid_input")
    return os.fspath(mesh)


def _out_dir(out_dir):
    out_dir = out_dir or tempfile.mkdtemp(prefix="meshround_sweep_")
    os.makedirs(out_dir, exist_ok=True)
    return out_dir


def _within_limits(rows, limits):
    """(table, todo): the table with an "above_limit" row for each variant past a chain's largest feasible
    radius (None elsewhere), and the (index, radii) of the others, to be made."""
    table, todo = [None] * len(rows), []
    for i, row in enumerate(rows):
        over = [c for c, r in enumerate(row) if limits and r > limits[c].radius]
        if over:
            c = over[0]
            table[i] = dict(index=i, radii=row, file=None, status="above_limit",
                            message=f"chain {c}: r = {row[c]:g} mm is above its largest feasible radius "
                                    f"{limits[c].radius:.6g} mm: {limits[c].reason}")
        else:
            todo.append((i, row))
    return table, todo


def _finish(table, limits, out_dir, jobs, started, thickness, tool, k):
    """The rule flags of every row, the "stopped at the feasible limit" line, the tables written."""
    if limits:
        for row in table:
            row["rules"] = radius_limits.check_rules(limits, row["radii"], thickness, tool, k)
    stopped = ""
    skipped = [row for row in table if row["status"] == "above_limit"]
    if skipped:
        over = [next(r for r, lim in zip(row["radii"], limits) if r > lim.radius) for row in skipped]
        smallest = min(limit.radius for limit in limits)
        stopped = (f"{len(skipped)} of {len(table)} variant(s) not made: r = {', '.join(f'{r:g}' for r in over)} mm above "
                   f"the feasible limit ({smallest:.6g} mm for the tightest chain)")
    result = SweepResult(rows=table, limits=limits, out_dir=out_dir, table_csv=os.path.join(out_dir, "table.csv"),
                         table_json=os.path.join(out_dir, "table.json"), jobs=jobs,
                         seconds=time.perf_counter() - started, stopped=stopped)
    _write_tables(result)
    return result


def _jobs(jobs, tasks):
    if jobs is None:
        jobs = os.cpu_count() or 1
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise RoundingError(f"jobs must be a positive whole number or None, got {jobs!r}")
    if getattr(FreeCAD, "GuiUp", False):
        return 1  # one at a time under FreeCAD's GUI (a call there keeps its window live from the main thread)
    return max(1, min(jobs, tasks))


def _write_tables(result):
    chains = max(len(row["radii"]) for row in result.rows)
    with open(result.table_csv, "w", newline="", encoding="utf-8") as stream:
        out = csv.writer(stream)
        out.writerow(["variant"] + [f"radius_{c}" for c in range(chains)] + ["file", "status"] + list(TABLE_COLUMNS) +
                     ["rule_flags", "message"])
        for row in result.rows:
            flags = sorted({f for rule in row.get("rules", []) for f in rule["flags"]})
            out.writerow([row["index"]] + row["radii"] + [row["file"] or "", row["status"]] +
                         [row.get(c, "") if row.get(c) is not None else "" for c in TABLE_COLUMNS] +
                         [" ".join(flags), row["message"]])
    with open(result.table_json, "w", encoding="utf-8") as stream:
        json.dump(dict(rows=result.rows, limits=[lim.as_dict() for lim in result.limits], jobs=result.jobs,
                       seconds=result.seconds, stopped=result.stopped), stream, indent=1, default=_plain)
        stream.write("\n")


def _plain(value):
    if isinstance(value, FreeCAD.Vector):
        return list(value)
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"not JSON: {type(value).__name__}")


@dataclasses.dataclass
class OptimiseResult:
    radius: float        # the radius the minimiser settled on
    value: float         # the objective there
    path: str            # that variant's file
    evaluations: list    # (radius, value, path) for every variant made, in order
    bounds: tuple        # the radius range searched
    scipy_result: object  # scipy.optimize.OptimizeResult


def optimise_radius(mesh, seeds, objective, bounds=None, out_dir=None, fmt="stl", xatol=None, maxiter=25,
                    tolerance=None, feature_angle=30.0, reach=3.0):
    """Minimise objective(path) over one radius for every picked chain: the place where a stamping
    simulation plugs in.  Each trial radius is rounded (round_edges), written to out_dir (None: a new
    temporary folder) as `opt_NNN_r<radius>.<fmt>`, and objective is called with that file's path; it
    returns a number (smaller is better).  A radius the engine refuses scores +inf.

    bounds: (low, high) in mm; None: (the largest feasible radius / 100, the largest feasible radius)
    (max_radius, the tightest chain).  xatol: the radius tolerance (None: 1e-3 of the range).  The search
    is scipy.optimize.minimize_scalar(method="bounded") (Brent's method on the interval, Debian's
    python3-scipy).  Returns an OptimiseResult."""
    from scipy.optimize import minimize_scalar
    if not callable(objective):
        raise RoundingError("objective must be a function of a file path returning a number")
    inputs.check_mesh(mesh)
    if bounds is None:
        largest = min(limit.radius for limit in radius_limits.max_radius(mesh, seeds, feature_angle, reach))
        bounds = (largest / 100, largest)
    low, high = (float(b) for b in bounds)
    if not (0 < low < high):
        raise RoundingError(f"bounds must be 0 < low < high, got {bounds!r}")
    out_dir = out_dir or tempfile.mkdtemp(prefix="meshround_optimise_")
    os.makedirs(out_dir, exist_ok=True)
    evaluations = []

    def score(radius):
        path = os.path.join(out_dir, f"opt_{len(evaluations):03d}_r{radius:.6g}.{fmt}")
        try:
            res = api.round_edges(mesh, seeds, float(radius), tolerance=tolerance, feature_angle=feature_angle, reach=reach)
        except RoundingError:
            evaluations.append((float(radius), math.inf, None))
            return math.inf
        res.mesh.write(path)
        value = float(objective(path))
        evaluations.append((float(radius), value, path))
        return value

    found = minimize_scalar(score, bounds=(low, high), method="bounded",
                            options=dict(xatol=xatol or 1e-3 * (high - low), maxiter=maxiter))
    best = min((e for e in evaluations if e[2]), key=lambda e: e[1], default=(float(found.x), math.inf, None))
    return OptimiseResult(radius=best[0], value=best[1], path=best[2], evaluations=evaluations, bounds=(low, high),
                          scipy_result=found)


def sweep_features(base, seeds, radii, tolerance=0, feature_angle=30, reach=3, doc=None):
    """In FreeCAD: one parametric Rounding of mesh feature `base` per radius (named Rounding_r<radius>),
    each recomputing on its own like any Rounding; no recompute here.  Returns the features."""
    from .objects.rounding import make_rounding
    features = []
    for r in radii:
        name = f"Rounding_r{float(r):g}".replace(".", "_")
        features.append(make_rounding(base, seeds, float(r), tolerance=tolerance, feature_angle=feature_angle,
                                      reach=reach, name=name, doc=doc))
    return features


def sweep_sheet(rounding, sheet, column, out_dir=None, fmt="stl", thickness=None, tool="die", k=None,
                check_limits=True, stem=None):
    """In FreeCAD: sweep one parametric Rounding over the radii in a column of a Spreadsheet.

    For each cell of `column` (e.g. "B"; a first cell that is not a number is a header) the Rounding's
    Radius is bound to that cell by an expression (`Sheet.B2`, ...), the document is recomputed and the
    Rounding's mesh is written to out_dir (None: a new temporary folder) as <stem>_NNN_r<radius>.<fmt>
    (stem: the Rounding's name).  A radius above a chain's largest feasible radius (max_radius of the
    Rounding's base and seeds; check_limits=False skips it) is not recomputed: its row says so (status
    "above_limit") and SweepResult.stopped has the line, as for sweep.  A recompute that fails gives a row
    with status "failed" and the feature's error.  The table (table.csv, table.json) is sweep's, each row
    with the cell it came from.  Afterwards the Rounding's Radius (its value or expression) is as before,
    recomputed.  thickness, tool, k: check_rules' stamping rule.  Returns a SweepResult (jobs 1)."""
    from .objects.rounding import check_base
    started = time.perf_counter()
    if not hasattr(rounding, "Seeds") or not hasattr(rounding, "Radius") or not hasattr(rounding, "Base"):
        raise RoundingError(f"{getattr(rounding, 'Label', rounding)!r} is not a Rounding feature")
    if len(rounding.RadiusLaw):
        raise RoundingError(f"{rounding.Label} has a variable radius law: the sheet sweep sets its constant Radius; "
                            "empty the law first")
    if getattr(sheet, "TypeId", "") != "Spreadsheet::Sheet" or sheet.Document != rounding.Document:
        raise RoundingError("sheet must be a Spreadsheet in the Rounding's document")
    if fmt not in WRITE_FORMATS:
        raise RoundingError(f"unknown mesh format {fmt!r}: one of {', '.join(WRITE_FORMATS)}")
    check_base(rounding.Base)
    cells, radii = sheet_column(sheet, column)
    seeds = list(rounding.Seeds)
    limits = (radius_limits.max_radius(rounding.Base.Mesh, seeds, rounding.FeatureAngle.Value, rounding.Reach)
              if check_limits else [])
    rows = radius_rows(radii, len(limits) if limits else len(seeds))
    out_dir = _out_dir(out_dir)
    stem = stem or rounding.Name
    table, todo = _within_limits(rows, limits)
    doc = rounding.Document
    saved_expression = dict((p.lstrip("."), e) for p, e in rounding.ExpressionEngine).get("Radius")
    saved_value = rounding.Radius.Value
    try:
        for i, row in todo:
            rounding.setExpression("Radius", f"{sheet.Name}.{cells[i]}")
            doc.recompute()
            entry = dict(index=i, radii=row, file=None, status="ok", message="")
            if "Invalid" in rounding.State or abs(rounding.Radius.Value - row[0]) > 1e-9 * max(1.0, row[0]):
                entry.update(status="failed", message=rounding.getStatusString() or "recompute failed")
            else:
                name = f"{stem}_{i:03d}_r{row[0]:g}.{fmt}"
                rounding.Mesh.write(os.path.join(out_dir, name))
                report = {key: _number(value) for key, value in rounding.Statistics.items()}
                entry.update(file=name, report=report)
                entry.update({key: report.get(key) for key in TABLE_COLUMNS})
            table[i] = entry
    finally:
        rounding.setExpression("Radius", saved_expression)
        if saved_expression is None:
            rounding.Radius = saved_value
        doc.recompute()
    for entry, cell in zip(table, cells):
        entry["cell"] = cell
    return _finish(table, limits, out_dir, 1, started, thickness, tool, k)


def sheet_column(sheet, column):
    """(cells, radii) of a Spreadsheet column, top to bottom: the used cells' addresses and numbers (mm);
    a first cell that is not a number is a header and left out; an empty sheet column is refused."""
    import re
    column = str(column).upper()
    if not re.fullmatch(r"[A-Z]{1,2}", column):
        raise RoundingError(f"column must be a spreadsheet column's letters (A ... ZZ), got {column!r}")
    used = sorted({int(row) for row in re.findall(rf'address="{column}(\d+)"', sheet.cells.Content)})
    cells, radii = [], []
    for n, row in enumerate(used):
        address = f"{column}{row}"
        value = sheet.get(address)
        value = getattr(value, "Value", value)  # a quantity (e.g. "5 mm"): its value in mm
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            if n == 0:
                continue  # a header
            raise RoundingError(f"{sheet.Label}.{address} is not a radius: {value!r}")
        cells.append(address)
        radii.append(float(value))
    if not cells:
        raise RoundingError(f"{sheet.Label} has no radii in column {column}")
    return cells, radii


def _number(text):
    """A Statistics value (a string) as the number it was, when it was one."""
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text
