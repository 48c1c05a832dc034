"""The `meshround` command line: round sharp edges of a mesh file, headless.

    meshround round IN OUT --seed X,Y,Z [--seed ...] (--radius R | --radius-at X,Y,Z:R ...)
                    [--tolerance T] [--feature-angle A] [--reach K] [--report FILE] [--part PID]
    (IN and OUT both solver decks -- .k .key .dyn / .bdf .nas .dat / .inp, one family -- round the deck
    and write it back with its IDs, parts, sets and other cards kept: MeshRound.decks)
    meshround reround IN OUT --seed X,Y,Z [--seed ...] --radius R [--tolerance T] [--report FILE] [--part PID]
    (IN and OUT both solver decks: the deck's existing round changed, written back: MeshRound.change_radius_deck)
    meshround demo [--out DIR]
    meshround max-radius IN --seed X,Y,Z [...]          (cli_radius.py)
    meshround sweep IN OUTDIR --seed X,Y,Z [...] --radius 3:10:0.5   (IN a mesh, or a solver deck swept as one)

Run as `/usr/bin/python3 -m MeshRound.cli ...` with Mod/MeshRound on sys.path (the `meshround` wrapper
next to this package does that).  Exit status: 0 done, 1 the work failed (unreadable input, no sharp
edge found, rounding or writing failed), 2 the command line is wrong (argparse's convention).
OUT is written to a temporary file in its folder and renamed on success, so a failed run leaves no file.
"""
import argparse
import importlib.util
import json
import math
import os
import sys
import tempfile

try:
    from .deck_formats import deck_family
except ImportError:  # run as a script: python3 -m MeshRound.cli puts the package on the path
    from MeshRound.deck_formats import deck_family

FREECAD_LIB = "/usr/lib/freecad-python3/lib"
MOD_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # .../Mod/MeshRound
REPO_ROOT = os.path.dirname(os.path.dirname(MOD_ROOT))
# The demo script: in the source tree (<repo>/resources), or in the installed workbench, where
# tools/setup.sh copies the demo's files (~/.local/share/FreeCAD/Mod/MeshRound/resources).
DEMO_SCRIPTS = (os.path.join(REPO_ROOT, "resources", "srail_demo.py"),
                os.path.join(MOD_ROOT, "resources", "srail_demo.py"))

# What FreeCAD 0.20's Mesh module reads, and writes, chosen by file extension.
READ_EXTENSIONS = ("stl", "ast", "obj", "ply", "off", "bms", "smf", "nas", "bdf")
WRITE_EXTENSIONS = READ_EXTENSIONS + ("3mf", "iv", "x3d", "x3dz", "xhtml", "wrl", "vrml", "wrz", "idtf",
                                      "mgl", "py", "asy")

EXIT_FAILED, EXIT_USAGE = 1, 2


class Failure(Exception):
    """The work could not be done; the message is printed and the exit status is 1."""


# ------------------------------------------------------------------------------ argument types
def _finite(text):
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"not a finite number: {text!r}")
    return value


def point(text):
    """'X,Y,Z' -> (x, y, z)."""
    parts = text.split(",")
    if len(parts) != 3:
        raise argparse.ArgumentTypeError(f"expected X,Y,Z (three comma-separated numbers), got {text!r}")
    return tuple(_finite(p) for p in parts)


def control_point(text):
    """'X,Y,Z:R' -> ((x, y, z), r)."""
    where, colon, radius = text.rpartition(":")
    if not colon:
        raise argparse.ArgumentTypeError(f"expected X,Y,Z:R, got {text!r}")
    return point(where), _finite(radius)


# ------------------------------------------------------------------------------ the parser
def build_parser():
    parser = argparse.ArgumentParser(
        prog="meshround", description="Round sharp edges of triangle meshes with a rolling ball.",
        epilog="Exit status: 0 done, 1 the rounding (or reading/writing) failed, 2 bad command line.")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    rnd = commands.add_parser(
        "round", help="round the sharp-edge chains nearest to the seeds",
        description="Round the sharp-edge chains of IN nearest to the seeds and write OUT. "
                    f"Formats by extension: reads {', '.join(READ_EXTENSIONS)}; "
                    f"writes those and {', '.join(WRITE_EXTENSIONS[len(READ_EXTENSIONS):])}.")
    rnd.add_argument("input", metavar="IN", help="mesh file to read")
    rnd.add_argument("output", metavar="OUT", help="mesh file to write (format from its extension)")
    rnd.add_argument("--seed", metavar="X,Y,Z", type=point, action="append", required=True,
                     help="a point near a sharp edge; its whole chain is rounded (repeatable)")
    radius = rnd.add_mutually_exclusive_group(required=True)
    radius.add_argument("--radius", metavar="R", type=_finite, help="constant radius (mm)")
    radius.add_argument("--radius-at", metavar="X,Y,Z:R", type=control_point, action="append",
                        help="variable radius: radius R at the chain point nearest X,Y,Z (repeatable; with "
                             "several chains each point belongs to the chain nearest to it)")
    rnd.add_argument("--tolerance", metavar="T", type=_finite, default=None,
                     help="chordal tolerance (mm); default: largest radius / 100")
    rnd.add_argument("--feature-angle", metavar="A", type=_finite, default=30.0,
                     help="an edge is sharp when its facets turn by at least A degrees (default 30)")
    rnd.add_argument("--reach", metavar="K", type=_finite, default=3.0,
                     help="re-mesh facets within K x radius of a chain (default 3)")
    rnd.add_argument("--report", metavar="FILE", help="write the rounding report as JSON")
    add_band_and_deck_arguments(rnd)

    add_reround_parser(commands)

    demo = commands.add_parser(
        "demo", help="round the S-rail die's shoulders (constant and variable radius) into DIR",
        description="Round both die shoulders of the S-rail die mesh, once with r = 5 mm and once with "
                    "r = 3 -> 8 -> 3 mm, and write the meshes (STL, OBJ), an FCStd with the Rounding "
                    "features, a JSON report and a before/after PNG into DIR (resources/srail_demo.py).")
    demo.add_argument("--out", metavar="DIR", default="out", help="output folder (default: out)")
    from . import cli_radius
    cli_radius.add_parsers(commands, point, _finite)
    return parser


def add_band_and_deck_arguments(command):
    """The band element controls and the solver deck options (round and reround take the same)."""
    band = command.add_argument_group("band elements (each off by default; the finer rule wins)")
    band.add_argument("--element-angle", metavar="DEG", type=_finite, default=None,
                      help="at most DEG degrees of the round's profile per element across it (e.g. 10)")
    band.add_argument("--element-length", metavar="L", type=_finite, default=None,
                      help="element length along the round in mm (default: the input's own next to the edge)")
    band.add_argument("--max-aspect", metavar="X", type=_finite, default=None,
                      help="largest aspect ratio (longest / shortest side) of the round's elements, >= 1")
    band.add_argument("--triangles", action="store_true",
                      help="solver decks: write the band as triangles only (default: quads where they pair)")
    command.add_argument("--node-id-start", metavar="N", type=int, default=None,
                         help="solver decks: number new nodes from N (default: above the deck's largest node ID)")
    command.add_argument("--element-id-start", metavar="N", type=int, default=None,
                         help="solver decks: number new elements from N (default: above the deck's largest element ID)")
    command.add_argument("--part", metavar="PID", type=int, default=None,
                         help="solver decks: work on this part's shells only (LS-DYNA/Nastran PID; Abaqus: the "
                              "ELSET's number in order of appearance); other parts are kept as they are")


def add_reround_parser(commands):
    """`meshround reround`: change the radius of existing rounds (reround.py)."""
    rr = commands.add_parser(
        "reround", help="change the radius of the existing rounds at the seeds (radius 0: sharpen them)",
        description="Find the existing round (a strip of facets turning between two flat sides) at each seed, "
                    "measure its radius, rebuild the sharp edge it replaced and round that edge again with "
                    "radius R (0: leave it sharp); write OUT. The found radius is printed per strip. IN and OUT "
                    "both solver decks (.k .key .dyn / .bdf .nas .dat / .inp, one family): the deck is written "
                    "back with only the band's elements and nodes changed (MeshRound.change_radius_deck).")
    rr.add_argument("input", metavar="IN", help="mesh file or solver deck to read")
    rr.add_argument("output", metavar="OUT", help="mesh file or solver deck to write (format from its extension)")
    rr.add_argument("--seed", metavar="X,Y,Z", type=point, action="append", required=True,
                    help="a point on an existing round (repeatable)")
    rr.add_argument("--radius", metavar="R", type=_finite, required=True, help="the new radius (mm); 0: sharp")
    rr.add_argument("--tolerance", metavar="T", type=_finite, default=None,
                    help="chordal tolerance (mm); default: radius / 100")
    rr.add_argument("--report", metavar="FILE", help="write the report (with found_radius per strip) as JSON")
    add_band_and_deck_arguments(rr)


def check_extensions(parser, args, decks=True):
    """IN and OUT formats known (`decks`: a solver deck pair is known too, written back in its format)."""
    decks_in, decks_out = deck_family(args.input), deck_family(args.output)
    if decks and decks_in and decks_out:
        if decks_in != decks_out:
            parser.error(f"'{args.input}' is a {decks_in} deck and '{args.output}' a {decks_out} deck: "
                         "a deck is written back in its own format")
        return
    if getattr(args, "part", None) is not None:
        parser.error("--part needs a solver deck as IN and OUT (.k .key .dyn, .bdf .nas .dat, .inp)")
    for path, allowed, role in ((args.input, READ_EXTENSIONS, "read"),
                                (args.output, WRITE_EXTENSIONS, "write")):
        ext = os.path.splitext(path)[1].lstrip(".").lower()
        if not ext:
            parser.error(f"cannot {role} '{path}': no file extension to tell the mesh format "
                         f"(known: {', '.join(allowed)})")
        if ext not in allowed:
            parser.error(f"cannot {role} '{path}': unknown mesh format '.{ext}' "
                         f"(known: {', '.join(allowed)})")


def check_options(parser, args):
    """Options out of range are a wrong command line (exit 2), by the engine's own rule."""
    _, MeshRound = _import_freecad()
    from MeshRound import inputs
    law = None
    if args.radius_at:
        law = [(*p, r) for p, r in args.radius_at]
    try:
        inputs.check_options(radius=args.radius if args.radius is not None else 1.0,
                             tolerance=args.tolerance or 0.0, feature_angle=args.feature_angle,
                             reach=args.reach, radius_law=law)
        if hasattr(args, "element_angle"):
            inputs.band_value(band_controls(args))
    except MeshRound.RoundingError as exc:
        parser.error(str(exc))


def band_controls(args):
    """The band element controls of the command line, as round_edges' band argument."""
    return dict(max_element_angle=args.element_angle, element_length=args.element_length,
                max_aspect_ratio=args.max_aspect)


def quality_line(q):
    """One line on the band's elements as CAE checks them (report["band_quality"] or a deck's quality)."""
    warp = f", warpage <= {q['max_warpage_deg']:.1f} deg" if q.get("quads") else ""
    return (f"band elements: {q['elements']} ({q.get('quads', 0)} quads), angles {q['min_angle_deg']:.1f}-"
            f"{q['max_angle_deg']:.1f} deg, aspect ratio <= {q['max_aspect_ratio']:.2f}{warp}, "
            f"shortest side {q['min_side']:.3f} mm")


# ------------------------------------------------------------------------------ the commands
def run_round(args):
    if deck_family(args.input) and deck_family(args.output):
        return run_round_deck(args)
    Mesh, MeshRound = _import_freecad()
    mesh = _read_mesh(Mesh, args.input)
    radius = args.radius if args.radius is not None else args.radius_at
    try:
        result = MeshRound.round_edges(mesh, args.seed, radius, tolerance=args.tolerance,
                                       feature_angle=args.feature_angle, reach=args.reach, band=band_controls(args))
    except MeshRound.RoundingError as exc:
        raise Failure(f"rounding failed [{getattr(exc, 'code', 'invalid_input')}]: {exc}") from exc
    _write_result(args, result)
    r = result.report
    deviation = r.get("max_deviation")
    deviation = f"{deviation:.4f} mm" if isinstance(deviation, (int, float)) else "unknown"
    print(f"meshround: {r.get('chains')} chain(s) rounded, {r.get('facets_in')} -> {r.get('facets_out')} "
          f"facets, max deviation {deviation}, {r.get('seconds', 0.0):.2f} s -> {args.output}")
    print(f"meshround: {quality_line(r['band_quality'])}")
    note = MeshRound.quality_note(r)
    if note:
        print(f"meshround: {note}", file=sys.stderr)


def _rounds_found(report):
    """'N round(s) found (r = ...)' of change_radius' report: a strip of rounds mitred into each other counts
    each of its rounds (a loop has as many as mitres, an open strip one more)."""
    rounds = 0
    for s in report["strips"]:
        mitres = s.get("mitres", 0)
        rounds += 1 if mitres == 0 else mitres if len(s["corner_line"]) == mitres else mitres + 1
    found = ", ".join(f"{x:.4g}" for x in report["found_radius"])
    mitred = sum(s.get("mitres", 0) for s in report["strips"])
    return f"{rounds} round(s) found (r = {found} mm" + (f"; {mitred} mitre(s))" if mitred else ")")


def run_round_deck(args):
    """IN and OUT solver decks: MeshRound.round_deck or, for reround, change_radius_deck (each writes OUT
    itself, all or nothing)."""
    _, MeshRound = _import_freecad()
    from MeshRound.decks import QuadOptions
    reround = args.command == "reround"
    radius = args.radius if reround or args.radius is not None else args.radius_at
    edit = MeshRound.change_radius_deck if reround else MeshRound.round_deck
    try:
        res = edit(args.input, args.output, args.seed, radius, part=args.part, tolerance=args.tolerance,
                   band=band_controls(args), node_id_start=args.node_id_start, element_id_start=args.element_id_start,
                   quad_options=QuadOptions(quads=False) if args.triangles else None,
                   **({} if reround else dict(feature_angle=args.feature_angle, reach=args.reach)))
    except MeshRound.RoundingError as exc:
        what = "changing the radius" if reround else "rounding"
        raise Failure(f"{what} failed [{getattr(exc, 'code', 'invalid_input')}]: {exc}") from exc
    except OSError as exc:
        raise Failure(f"cannot write '{args.output}': {exc}") from exc
    if args.report:
        _write_all_or_nothing([(args.report, lambda path: _dump_json(dict(res.report, input=args.input,
                                                                             output=args.output), path))])
    d = res.report["deck"]
    if reround:
        done = f"{_rounds_found(res.report)} -> r = {args.radius:g} mm"
    else:
        done = f"{res.report.get('chains')} chain(s) rounded"
    print(f"meshround: {done}; {d['elements_removed']} of "
          f"{d['elements_in']} elements replaced by {d['new_quads']} quads and {d['new_triangles']} triangles, "
          f"{d['nodes_new']} new nodes, {len(d['sets_updated'])} set(s) updated, "
          f"{res.report.get('seconds', 0.0):.2f} s -> {', '.join(res.paths)}")
    print(f"meshround: {quality_line(d['quality'])}")


def run_radius_tool(args):
    """max-radius and sweep (cli_radius.py)."""
    from . import cli_radius
    Mesh, MeshRound = _import_freecad()
    if args.command == "sweep" and cli_radius.sweeps_deck(args, deck_family):
        if not os.path.isfile(args.input):
            raise Failure(f"cannot read '{args.input}': no such file")
        return cli_radius.run_sweep(args, MeshRound, args.input, Failure)
    if args.command == "sweep" and deck_family(args.input):  # a deck's shells, swept as a triangle mesh
        mesh = _deck_mesh(MeshRound, args.input, args.part)
    elif getattr(args, "part", None) is not None:
        raise Failure("--part needs a solver deck as IN")
    else:
        mesh = _read_mesh(Mesh, args.input)
    if args.command == "max-radius":
        cli_radius.run_max_radius(args, MeshRound, mesh, Failure, _dump_json)
    else:
        cli_radius.run_sweep(args, MeshRound, mesh, Failure)
def _deck_mesh(MeshRound, path, part):
    """The shells of a solver deck (of one part) as a Mesh.Mesh of triangles (a quad split in two)."""
    from MeshRound import decks, meshconv
    try:
        vertices, triangles, _, _ = decks.deck_triangles(MeshRound.read_deck(path), part)
    except MeshRound.RoundingError as exc:
        raise Failure(f"cannot read '{path}': {exc}") from exc
    return meshconv.arrays_to_mesh(vertices, triangles)


def run_reround(args):
    if deck_family(args.input) and deck_family(args.output):
        return run_round_deck(args)
    Mesh, MeshRound = _import_freecad()
    mesh = _read_mesh(Mesh, args.input)
    try:
        result = MeshRound.change_radius(mesh, args.seed, args.radius, tolerance=args.tolerance,
                                         band=band_controls(args))
    except MeshRound.RoundingError as exc:
        raise Failure(f"changing the radius failed [{getattr(exc, 'code', 'invalid_input')}]: {exc}") from exc
    _write_result(args, result)
    r = result.report
    print(f"meshround: {_rounds_found(r)} -> r = {args.radius:g} mm, "
          f"{r.get('facets_in')} -> {r.get('facets_out')} facets, {r.get('seconds', 0.0):.2f} s -> {args.output}")


def _write_result(args, result):
    """OUT, and the report if asked for, all or nothing."""
    report = dict(result.report, input=args.input, output=args.output)
    writes = [(args.output, result.mesh.write)]
    if args.report:
        writes.append((args.report, lambda path: _dump_json(report, path)))
    _write_all_or_nothing(writes)


def demo_script():
    """The first of DEMO_SCRIPTS that exists, or None."""
    return next((path for path in DEMO_SCRIPTS if os.path.isfile(path)), None)


def run_demo(out_dir):
    """Run the S-rail demo (resources/srail_demo.py: main(out_dir))."""
    script = demo_script()
    if script is None:
        raise Failure("the demo script srail_demo.py is missing (looked for "
                      f"{' and '.join(DEMO_SCRIPTS)}); run tools/setup.sh from the MeshRound source tree")
    _import_freecad()
    spec = importlib.util.spec_from_file_location("srail_demo", script)
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
        module.main(out_dir=out_dir)
    except Failure:
        raise
    except Exception as exc:  # RoundingError naming the shoulder, a failed render, a write error, ...
        raise Failure(f"the demo failed: {exc}") from exc


def _import_freecad():
    if FREECAD_LIB not in sys.path:
        sys.path.append(FREECAD_LIB)
    try:
        import FreeCAD  # noqa: F401  (must come before Mesh)
        import Mesh
        import MeshRound
    except ImportError as exc:
        raise Failure(f"cannot import FreeCAD ({exc}); run with Debian's /usr/bin/python3 and "
                      f"FreeCAD 0.20 installed in {FREECAD_LIB}") from exc
    return Mesh, MeshRound


def _read_mesh(Mesh, path):
    if not os.path.isfile(path):
        raise Failure(f"cannot read '{path}': no such file")
    try:
        mesh = Mesh.Mesh(path)
    except Exception as exc:  # FreeCAD raises OSError or its own Base exceptions for bad files
        raise Failure(f"cannot read '{path}': {exc}") from exc
    if mesh.CountFacets == 0:
        raise Failure(f"cannot read '{path}': no facets (empty, or not a valid mesh file)")
    return mesh


def _write_all_or_nothing(writes):
    """For each (path, write): write(temp) into a temporary file beside path; only when every write has
    succeeded are the temporary files renamed to their paths, so a failure leaves none of them."""
    staged = []  # (temporary file, final path)
    current = None
    try:
        for current, write in writes:
            temp = _temporary_beside(current)
            staged.append((temp, current))
            write(temp)
        for temp, current in staged:
            os.replace(temp, current)
    except Exception as exc:  # OSError, or FreeCAD's own exception types from the mesh writer
        raise Failure(f"cannot write '{current}': {exc}") from exc
    finally:
        for temp, _ in staged:
            if os.path.exists(temp):
                os.remove(temp)


def _temporary_beside(path):
    """A new empty file next to `path`, keeping its extension (FreeCAD picks the format from it)."""
    stem, ext = os.path.splitext(os.path.basename(path))
    folder = os.path.dirname(os.path.abspath(path))
    handle, temp = tempfile.mkstemp(prefix=f".{stem}.", suffix=ext, dir=folder)
    os.close(handle)
    return temp


def _dump_json(data, path):
    with open(path, "w", encoding="utf-8") as stream:
        json.dump(data, stream, indent=2, sort_keys=True)
        stream.write("\n")


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "round":
            check_extensions(parser, args)
            check_options(parser, args)
            run_round(args)
        elif args.command in ("max-radius", "sweep"):
            run_radius_tool(args)
        elif args.command == "reround":
            check_extensions(parser, args)
            if args.radius < 0 or (args.tolerance is not None and args.tolerance <= 0):
                parser.error("--radius must be >= 0 and --tolerance > 0")
            run_reround(args)
        else:
            run_demo(args.out)
    except Failure as exc:
        print(f"meshround: error: {exc}", file=sys.stderr)
        return EXIT_FAILED
    return 0


if __name__ == "__main__":
    sys.exit(main())
