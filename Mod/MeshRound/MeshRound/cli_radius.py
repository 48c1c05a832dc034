"""The radius tools' commands (issue 16), added to `meshround` by cli.py:

    meshround max-radius IN --seed X,Y,Z [--seed ...] [--feature-angle A] [--reach K]
                         [--radius R --thickness T [--tool die|punch] [--k F]] [--json FILE]
    meshround sweep IN OUTDIR --seed X,Y,Z [--seed ...] (--radius SPEC | --radius-csv FILE)
                    [--format stl] [--jobs N] [--tolerance T] [--feature-angle A] [--reach K]
                    [--thickness T [--tool die|punch] [--k F]] [--part PID]

A solver deck as IN (.k .key .dyn / .bdf .nas .dat / .inp) is swept as a deck: each variant is the deck
rounded and written back in its own format (MeshRound.round_deck); with --format stl (or another mesh
format) the deck's shells are swept as a triangle mesh (a quad split in two) and written in that format.

SPEC is START:STOP:STEP (STOP included when the steps reach it) or a comma-separated list.  The CSV has
one row per variant and one radius per chain (in seed order); a first row that is not numbers is a header.
"""
import argparse
import csv
import json
import math
import sys


def radius_spec(text):
    """'3:10:0.5' -> [3, 3.5, ..., 10]; '3,5,8' -> [3, 5, 8]."""
    try:
        if ":" in text:
            start, stop, step = (float(x) for x in text.split(":"))
            if not (step > 0 and stop >= start and all(math.isfinite(x) for x in (start, stop, step))):
                raise ValueError
            count = int(math.floor((stop - start) / step + 1e-9)) + 1
            values = [round(start + i * step, 10) for i in range(count)]
        else:
            values = [float(x) for x in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected START:STOP:STEP or R1,R2,... (mm), got {text!r}") from None
    if not values or not all(math.isfinite(v) and v > 0 for v in values):
        raise argparse.ArgumentTypeError(f"radii must be positive numbers, got {text!r}")
    return values


def read_radius_csv(path):
    """One list of per-chain radii per row."""
    rows = []
    with open(path, newline="", encoding="utf-8") as stream:
        for n, row in enumerate(csv.reader(stream)):
            cells = [c.strip() for c in row if c.strip()]
            if not cells:
                continue
            try:
                rows.append([float(c) for c in cells])
            except ValueError:
                if n == 0:
                    continue  # a header
                raise
    return rows


def add_parsers(commands, point, finite):
    """The two sub-commands, on cli.py's subparsers; `point` and `finite` are its argument types."""
    def common(p):
        p.add_argument("--seed", metavar="X,Y,Z", type=point, action="append", required=True,
                       help="a point near a sharp edge; its whole chain is measured / rounded (repeatable)")
        p.add_argument("--feature-angle", metavar="A", type=finite, default=30.0, help="sharp from A degrees (default 30)")
        p.add_argument("--reach", metavar="K", type=finite, default=3.0, help="reach factor the rounding uses (default 3)")
        p.add_argument("--thickness", metavar="T", type=finite, help="sheet thickness (mm) for the radius >= k.t rule")
        p.add_argument("--tool", choices=("die", "punch"), default="die", help="tool type for the rule (default die)")
        p.add_argument("--k", metavar="F", type=finite, help="the rule's factor (default: die 5, punch 4)")

    mx = commands.add_parser("max-radius", help="the largest radius each picked chain rounds with, and what stops it",
                             description="Measure, for each chain the seeds pick, the largest radius that rounds "
                                         "(from the ball's room along the chain; no rounding is made), where and why.")
    mx.add_argument("input", metavar="IN", help="mesh file to read")
    common(mx)
    mx.add_argument("--radius", metavar="R", type=finite, help="also check radius R against the limit and the k.t rule")
    mx.add_argument("--json", metavar="FILE", help="write the limits as JSON")

    sw = commands.add_parser("sweep", help="one rounded variant per radius, with a table (CSV, JSON)",
                             description="Round the picked chains once per radius, on parallel threads; write "
                                         "each variant into OUTDIR and table.csv / table.json with each one's report. "
                                         "Radii above the feasible limit are skipped with a line saying so.")
    sw.add_argument("input", metavar="IN", help="mesh file or solver deck to read")
    sw.add_argument("out_dir", metavar="OUTDIR", help="folder for the variants and the tables")
    common(sw)
    radii = sw.add_mutually_exclusive_group(required=True)
    radii.add_argument("--radius", metavar="SPEC", type=radius_spec, help="START:STOP:STEP or R1,R2,... (mm)")
    radii.add_argument("--radius-csv", metavar="FILE", help="CSV: one row per variant, one radius per chain")
    sw.add_argument("--format", default=None,
                    help="output mesh format (extension; default stl, for a solver deck its own format)")
    sw.add_argument("--part", metavar="PID", type=int, default=None,
                    help="solver decks: round only this part's shells (as meshround round --part)")
    sw.add_argument("--jobs", metavar="N", type=int, default=None, help="threads (default: one per core)")
    sw.add_argument("--tolerance", metavar="T", type=finite, default=None, help="chordal tolerance (default r/100)")


def _rule_options(args):
    return dict(thickness=args.thickness, tool=args.tool, k={args.tool: args.k} if args.k else None)


def run_max_radius(args, MeshRound, mesh, failure, dump_json):
    try:
        limits = MeshRound.max_radius(mesh, args.seed, feature_angle=args.feature_angle, reach=args.reach)
    except MeshRound.RoundingError as exc:
        raise failure(f"measuring failed [{getattr(exc, 'code', 'invalid_input')}]: {exc}") from exc
    rules = None
    if args.radius is not None or args.thickness is not None:
        radius = args.radius if args.radius is not None else 0.0
        rules = MeshRound.check_rules(limits, radius, **_rule_options(args)) if args.radius is not None else None
    for i, limit in enumerate(limits):
        p = limit.chain_point
        print(f"chain {i}: max radius {limit.radius:.4f} mm ({limit.why}): {limit.reason}; "
              f"smallest room near ({p.x:.4g}, {p.y:.4g}, {p.z:.4g})")
        if rules and rules[i]["message"]:
            print(f"chain {i}: rule: {rules[i]['message']}")
    if args.json:
        dump_json(dict(chains=[lim.as_dict() for lim in limits], rules=rules), args.json)


def sweeps_deck(args, deck_family):
    """True when sweep's IN is a solver deck written back as one (no --format, or its own family's)."""
    family = deck_family(args.input)
    fmt = (args.format or "").lower().lstrip(".")
    return bool(family) and (not fmt or deck_family("x." + fmt) == family)


def run_sweep(args, MeshRound, mesh, failure):
    """mesh: a Mesh.Mesh, or the solver deck's path (sweeps_deck)."""
    radii = args.radius
    if args.radius_csv:
        try:
            radii = read_radius_csv(args.radius_csv)
        except (OSError, ValueError) as exc:
            raise failure(f"cannot read radii from '{args.radius_csv}': {exc}") from exc
    try:
        fmt = args.format.lower().lstrip(".") if args.format and not isinstance(mesh, str) else None
        result = MeshRound.sweep(mesh, args.seed, radii, out_dir=args.out_dir, fmt=fmt, part=args.part,
                                 jobs=args.jobs, tolerance=args.tolerance, feature_angle=args.feature_angle,
                                 reach=args.reach, **_rule_options(args))
    except MeshRound.RoundingError as exc:
        raise failure(f"sweep failed [{getattr(exc, 'code', 'invalid_input')}]: {exc}") from exc
    made = sum(row["status"] == "ok" for row in result.rows)
    for row in result.rows:
        radii_text = "/".join(f"{r:g}" for r in row["radii"])
        if row["status"] == "ok":
            print(f"r = {radii_text}: {row['file']} (+{row['facets_added']} facets, deviation {row['max_deviation']:.4f} mm)")
        else:
            print(f"r = {radii_text}: not made [{row['status']}]: {row['message']}")
        flags = sorted({f for rule in row.get("rules", []) for f in rule["flags"]} - {"above_limit"})
        if flags:
            print(f"r = {radii_text}: rule: {'; '.join(r['message'] for r in row['rules'] if r['message'])}")
    if result.stopped:
        print(f"meshround: sweep stopped at the feasible limit: {result.stopped}")
    print(f"meshround: {made} of {len(result.rows)} variant(s) made in {result.seconds:.2f} s with {result.jobs} "
          f"process(es) -> {result.table_csv}")
    if made == 0:
        raise failure("no variant could be made")
    sys.stdout.flush()
