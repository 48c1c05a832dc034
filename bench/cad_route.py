"""Bench: the CAD route vs MeshRound on the S-rail die, at about 10k, 100k and 1M facets.

    /usr/bin/python3 bench/cad_route.py [--sizes 10k,100k,1M] [--timeout 900]

CAD route: OCCT fillet of both die shoulders on the CAD solid, then the whole part meshed again with
MeshPart at the same element size (what a tool designer does when the CAD model exists).
MeshRound: round_edges on the die mesh (the mesh exists already; making it is not timed).
Each measurement runs in its own process with a time limit, so one slow size cannot hang the bench;
a run past the limit shows as "> limit".  Prints a markdown table.
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
# target facet count -> (Mefisto element size on the die, times each facet is split in four afterwards).
# Facets scale as 1 / size^2 (5 mm gives ~31k).  Mefisto's time grows faster than its output (48 s at
# 124k), so the 1M input mesh is a ~62k Mefisto mesh split twice (x16, exact on the planar faces); the CAD
# route there remeshes at the equivalent size, 3.52 / 4 mm.
SIZES = {"10k": (8.12, 0), "100k": (2.8, 0), "1M": (3.52, 2)}  # Mefisto is not monotone: 3.1 gives 68k


def _setup():
    for p in ("/usr/lib/freecad-python3/lib", os.path.join(REPO, "resources", "srail")):
        if p not in sys.path:
            sys.path.append(p)
    import FreeCAD  # noqa: F401  (puts the user's Mod folders first: this tree's MeshRound must go before)
    sys.path.insert(0, os.path.join(REPO, "Mod", "MeshRound"))


def cad_route(element_size, splits=0):
    """Seconds to fillet the CAD solid and to mesh the filleted part; its facet count."""
    import MeshPart
    import srail_die
    solid = srail_die.die_solid()
    t0 = time.perf_counter()
    filleted = solid.makeFillet(RADIUS, srail_die.shoulder_edges(solid))
    t1 = time.perf_counter()
    mesh = MeshPart.meshFromShape(Shape=filleted, MaxLength=element_size / 2 ** splits)
    t2 = time.perf_counter()
    return dict(fillet_s=t1 - t0, remesh_s=t2 - t1, seconds=t2 - t0, facets_out=mesh.CountFacets)


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
    """Seconds of MeshRound.round_edges on the die mesh (both shoulders); facet counts."""
    import MeshRound
    import srail_die
    mesh = split_in_four(srail_die.die_mesh(element_size), splits) if splits else srail_die.die_mesh(element_size)
    t0 = time.perf_counter()
    res = MeshRound.round_edges(mesh, srail_die.shoulder_seeds(), RADIUS)
    return dict(seconds=time.perf_counter() - t0, facets_in=mesh.CountFacets, facets_out=res.mesh.CountFacets,
                engine_s=res.report.get("seconds_total"))


ROUTES = {"cad": cad_route, "meshround": meshround}


def measure(route, size, limit):
    """One route at one size in a fresh process; None when it ran past `limit` seconds or failed."""
    cmd = [sys.executable, os.path.abspath(__file__), "--one", route, *map(str, size)]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=limit)
    except subprocess.TimeoutExpired:
        return None
    lines = [l for l in p.stdout.splitlines() if l.startswith("{")]
    if p.returncode or not lines:
        print(f"{route} at {size} failed: {p.stderr[-300:]}", file=sys.stderr)
        return None
    return json.loads(lines[-1])


def seconds(row, limit):
    return f"> {limit:.0f}" if row is None else f"{row['seconds']:.2f}"


def table(results, limit):
    out = ["| target | element mm | facets in | CAD route s (fillet + remesh) | MeshRound s | speed-up |",
           "| --- | --- | --- | --- | --- | --- |"]
    for name, (size, splits), cad, mr in results:
        facets = mr["facets_in"] if mr else "?"
        size = f"{size / 2 ** splits:.2f}" + (f" ({size} split x{4 ** splits})" if splits else "")
        detail = f" ({cad['fillet_s']:.2f} + {cad['remesh_s']:.2f})" if cad else ""
        ratio = "?"
        if mr and mr["seconds"] > 0:
            ratio = f"{cad['seconds'] / mr['seconds']:.0f}x" if cad else f"> {limit / mr['seconds']:.0f}x"
        out.append(f"| {name} | {size} | {facets} | {seconds(cad, limit)}{detail} | {seconds(mr, limit)} | {ratio} |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default=",".join(SIZES))
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds allowed per route and size")
    ap.add_argument("--one", nargs=3, metavar=("ROUTE", "ELEMENT_SIZE", "SPLITS"), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.one:
        _setup()
        print(json.dumps(ROUTES[a.one[0]](float(a.one[1]), int(a.one[2]))))
        return
    results = []
    for name in a.sizes.split(","):
        size = SIZES[name]
        results.append((name, size, measure("cad", size, a.timeout), measure("meshround", size, a.timeout)))
        print(f"{name}: done", file=sys.stderr, flush=True)
    print(table(results, a.timeout))


if __name__ == "__main__":
    main()
