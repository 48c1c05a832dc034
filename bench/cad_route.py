"""Bench: one die shoulder of the S-rail die rounded at about 10k, 100k and 1M facets, MeshRound against
the CAD route on the same part.

    /usr/bin/python3 bench/cad_route.py [--sizes 10k,100k,1M] [--timeout 900]

MeshRound: round_edges on the die mesh, one chain (the shoulder through srail_die.shoulder_seeds()[0]),
r = 5 mm, the fastest of REPEAT runs.  Making the input mesh is not timed (the CAE mesh exists already).
Timed: the whole console call (Mesh.Mesh -> arrays -> engine -> Mesh.Mesh) and, inside it, the engine.
CAD route: OCCT fillet (Part makeFillet) of the same shoulder's CAD edges on the CAD solid, then the
whole filleted part meshed again the way the input mesh was made (MeshPart's Mefisto mesher, split in
four where the table says so).
Each measurement runs in its own process with a time limit, so one slow size cannot hang the bench.
Prints a markdown table.
"""
import argparse
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
RADIUS = 5.0
REPEAT = 3  # MeshRound runs per size; the table shows the fastest
# target -> (Mefisto element size on the die in mm, times every facet is then split in four).
# Facets scale as 1 / size^2 (5 mm gives ~31k).  Mefisto's time grows faster than its output (about 45 s
# at 100k), so the 1M mesh is a ~67k Mefisto mesh split twice (x16, exact on the planar faces).
SIZES = {"10k": (8.12, 0), "100k": (2.8, 0), "1M": (3.52, 2)}


def _setup():
    for p in ("/usr/lib/freecad-python3/lib", os.path.join(REPO, "resources", "srail")):
        if p not in sys.path:
            sys.path.append(p)
    import FreeCAD  # noqa: F401  (puts the user's Mod folders first: this tree's MeshRound must go before)
    sys.path.insert(0, os.path.join(REPO, "Mod", "MeshRound"))


def shoulder_edges(solid):
    """The CAD edges of the first shoulder: the tangent chain of shoulder edges through its seed."""
    import Part
    import srail_die
    seed = Part.Vertex(srail_die.shoulder_seeds()[0])
    chains = [Part.Wire(c) for c in Part.sortEdges(srail_die.shoulder_edges(solid))]
    return min(chains, key=lambda w: w.distToShape(seed)[0]).Edges


def cad_route(element_size, splits=0):
    """Seconds to fillet the shoulder on the CAD solid and to mesh the filleted part; its facet count."""
    import MeshPart
    import srail_die
    solid = srail_die.die_solid()
    edges = shoulder_edges(solid)
    t0 = time.perf_counter()
    filleted = solid.makeFillet(RADIUS, edges)
    t1 = time.perf_counter()
    mesh = MeshPart.meshFromShape(Shape=filleted, MaxLength=element_size)
    if splits:
        mesh = split_in_four(mesh, splits)
    t2 = time.perf_counter()
    if not filleted.isValid() or len(filleted.Faces) <= len(solid.Faces):
        raise RuntimeError("the OCCT fillet did not produce a valid filleted solid")
    return dict(fillet_s=t1 - t0, remesh_s=t2 - t1, seconds=t2 - t0, edges=len(edges),
                facets_out=mesh.CountFacets)


def split_in_four(mesh, times):
    """Each facet split into four at its edge midpoints, `times` times (shared midpoints: stays closed)."""
    from MeshRound.meshconv import arrays_to_mesh, mesh_to_arrays
    import numpy as np
    V, F = mesh_to_arrays(mesh)
    for _ in range(times):
        E = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
        edges, mid = np.unique(E, axis=0, return_inverse=True)
        m = len(V) + mid.reshape(3, -1).T  # midpoint ids of edges 01, 12, 20 of each facet
        V = np.concatenate([V, V[edges].mean(axis=1)])
        a, b, c = F.T
        F = np.concatenate([np.stack(t, 1) for t in ((a, m[:, 0], m[:, 2]), (m[:, 0], b, m[:, 1]),
                                                     (m[:, 2], m[:, 1], c), (m[:, 0], m[:, 1], m[:, 2]))])
    return arrays_to_mesh(V, F)


def meshround(element_size, splits=0):
    """Seconds of MeshRound.round_edges on the die mesh (one shoulder); facet counts."""
    import MeshRound
    import srail_die
    mesh = srail_die.die_mesh(element_size)
    if splits:
        mesh = split_in_four(mesh, splits)
    best = None
    for _ in range(REPEAT):  # the best of a few: one call is short enough to be disturbed
        t0 = time.perf_counter()
        res = MeshRound.round_edges(mesh, srail_die.shoulder_seeds()[:1], RADIUS)
        seconds = time.perf_counter() - t0
        if best is None or seconds < best[0]:
            best = (seconds, res)
    seconds, res = best
    return dict(seconds=seconds, engine_s=res.report.get("seconds_total"), chains=res.report.get("chains"),
                facets_in=mesh.CountFacets, facets_out=res.mesh.CountFacets,
                max_deviation=res.report.get("max_deviation"))


ROUTES = {"cad": cad_route, "meshround": meshround}


def measure(route, size, limit):
    """One route at one size in a fresh process: its numbers, or the reason it has none."""
    cmd = [sys.executable, os.path.abspath(__file__), "--one", route, *map(str, size)]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return dict(error=f"> {limit:.0f} s")
    lines = [line for line in p.stdout.splitlines() if line.startswith("{")]
    if p.returncode or not lines:
        last = (p.stderr.strip().splitlines() or ["no output"])[-1]
        print(f"{route} at {size}: FAILED: {last}", file=sys.stderr)
        return dict(error="failed")
    return json.loads(lines[-1])


def table(results):
    out = ["| target | input mesh | facets in | MeshRound s (engine s) | CAD route s = fillet + remesh "
           "| CAD route / MeshRound |",
           "| --- | --- | --- | --- | --- | --- |"]
    for name, (size, splits), cad, mr in results:
        mesh = f"Mefisto {size} mm" + (f", split x{4 ** splits}" if splits else "")
        facets = mr.get("facets_in", "?")
        mr_s = mr.get("error") or f"{mr['seconds']:.3f} ({mr['engine_s']:.3f})"
        cad_s = cad.get("error") or f"{cad['seconds']:.2f} = {cad['fillet_s']:.3f} + {cad['remesh_s']:.2f}"
        ratio = "?"
        if "error" not in mr and "error" not in cad and mr["seconds"] > 0:
            ratio = f"{cad['seconds'] / mr['seconds']:.0f}x"
        out.append(f"| {name} | {mesh} | {facets} | {mr_s} | {cad_s} | {ratio} |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", default=",".join(SIZES), help="comma-separated, of: " + ", ".join(SIZES))
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds allowed per route and size")
    ap.add_argument("--one", nargs=3, metavar=("ROUTE", "ELEMENT_SIZE", "SPLITS"), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.one:
        _setup()
        print(json.dumps(ROUTES[a.one[0]](float(a.one[1]), int(a.one[2]))))
        return 0
    unknown = [s for s in a.sizes.split(",") if s not in SIZES]
    if unknown:
        ap.error(f"unknown size(s) {', '.join(unknown)}; known: {', '.join(SIZES)}")
    results = []
    for name in a.sizes.split(","):
        size = SIZES[name]
        results.append((name, size, measure("cad", size, a.timeout), measure("meshround", size, a.timeout)))
        print(f"{name}: done", file=sys.stderr, flush=True)
    print(f"One die shoulder of the S-rail die (one chain, 5 CAD edges), r = {RADIUS:g} mm, "
          f"{os.cpu_count()} cores:\n")
    print(table(results))
    failed = any("error" in row for r in results for row in r[2:])
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
