"""The console call at scale: MeshRound.round_edges(mesh, seed, 5.0) on one box edge, Mesh.Mesh in and out,
against FreeCAD's own Mesh.copy() of the same mesh (the floor of any call that returns a new mesh).

The box is 100 x 60 x 40 mm as 12 right triangles, each split k x k in its plane (tests/python/die_meshes.py):
k = 43 / 171 / 342 gives 22,188 / 350,892 / 1,403,568 facets; the seed is on the top back edge
(37, 60, 40), r = 5 mm, default tolerance and reach. Each size runs in a fresh process (so that its peak
memory is its own); per size it prints the median of --runs calls (after one warm-up call) of:

  call      the whole console call (what a user waits for), and its CPU seconds (both cores)
  copy      Mesh.copy() of the input
  stages    mesh -> arrays, the engine (with its passes, from the report), the output Mesh.Mesh
  memory    the process's peak RSS during the calls over its RSS before them, beside the input's arrays
            (float64 points and int64 indices, as the engine is handed them)

    /usr/bin/python3 bench/console_speed.py                     # 22k / 350k / 1.4M, 5 calls each
    /usr/bin/python3 bench/console_speed.py --sizes 342 --runs 9 --json out.json

The machine's load average is printed with the table: on a shared machine the wall-clock seconds move
with it; the ratio call / copy moves less.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
SIZES = (43, 171, 342)
SEED = (37.0, 60.0, 40.0)
RADIUS = 5.0


def _status_mb(field):
    with open("/proc/self/status") as stream:
        for line in stream:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def _reset_peak_rss():
    """Linux: writing 5 to clear_refs resets the peak RSS (VmHWM) to the current RSS."""
    try:
        with open("/proc/self/clear_refs", "w") as stream:
            stream.write("5")
        return True
    except OSError:
        return False


def box_arrays(k):
    sys.path.insert(0, os.path.join(REPO, "tests", "python"))
    import numpy as np
    import die_meshes
    x, y, z = 100.0, 60.0, 40.0
    V = np.array([(0, 0, 0), (x, 0, 0), (x, y, 0), (0, y, 0), (0, 0, z), (x, 0, z), (x, y, z), (0, y, z)], float)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 4, 7, 3)]
    F = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.int64)
    return die_meshes.subdivide(V, F, k)


def measure(k, runs):
    """One size, in this process: a dict of medians."""
    sys.path.insert(0, os.path.join(REPO, "tests", "python"))
    import conftest  # noqa: F401  (FreeCAD on sys.path, MeshRound from this checkout)
    import MeshRound
    from MeshRound import meshconv

    vertices, triangles = box_arrays(k)
    mesh = meshconv.arrays_to_mesh(vertices, triangles)
    input_mb = (vertices.size * 8 + triangles.size * 8) / 2**20
    del vertices, triangles
    MeshRound.round_edges(mesh, SEED, RADIUS)  # warm-up: first-call costs (imports, page faults) left out
    rss_before = _status_mb("VmRSS")
    peak_known = _reset_peak_rss()
    calls, cpus, copies, stages, passes = [], [], [], [], []
    for _ in range(runs):
        wall, cpu = time.perf_counter(), time.process_time()
        res = MeshRound.round_edges(mesh, SEED, RADIUS)
        calls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
        stages.append(res.report.get("seconds_stages") or _stages_by_hand(mesh))
        passes.append(res.report["seconds_per_pass"])
        report = res.report
        started = time.perf_counter()
        mesh.copy()
        copies.append(time.perf_counter() - started)
        del res
    peak = _status_mb("VmHWM") if peak_known else float("nan")

    def medians(dicts):
        keys = sorted({key for d in dicts for key in d})
        return {key: statistics.median(d.get(key, 0.0) for d in dicts) for key in keys}

    return dict(k=k, facets=mesh.CountFacets, points=mesh.CountPoints, runs=runs,
                call_s=statistics.median(calls), call_min_s=min(calls), cpu_s=statistics.median(cpus),
                copy_s=statistics.median(copies), stages_s=medians(stages), passes_s=medians(passes),
                facets_removed=report["facets_removed"], facets_added=report["facets_added"],
                rss_before_mb=rss_before, peak_rss_mb=peak, call_peak_mb=peak - rss_before, input_arrays_mb=input_mb,
                load=os.getloadavg())


def _stages_by_hand(mesh):
    """The stages of a workbench whose report does not time them (an older checkout): run one by one."""
    from MeshRound import api, meshconv
    started = time.perf_counter()
    vertices, triangles = meshconv.mesh_to_arrays(mesh)
    read = time.perf_counter()
    res = api._round(vertices, triangles, api._engine_arguments(SEED, RADIUS, None, 30.0, 3.0))
    engine = time.perf_counter()
    meshconv.arrays_to_mesh(res.vertices, res.triangles)
    return dict(mesh_to_arrays=read - started, engine=engine - read, output_mesh=time.perf_counter() - engine)


def table(rows):
    lines = ["| facets | console call s (CPU s) | Mesh.copy() s | call / copy | mesh → arrays s | engine s | "
             "output mesh s | peak RSS over the call's start MB (input arrays MB) |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in rows:
        st = r["stages_s"]
        lines.append(f"| {r['facets']:,} | {r['call_s']:.3f} ({r['cpu_s']:.3f}) | {r['copy_s']:.3f} | "
                     f"{r['call_s'] / r['copy_s']:.1f} | {st.get('mesh_to_arrays', float('nan')):.3f} | "
                     f"{st.get('engine', float('nan')):.3f} | {st.get('output_mesh', float('nan')):.3f} | "
                     f"{r['call_peak_mb']:.1f} ({r['input_arrays_mb']:.1f}) |")
    lines.append("")
    lines.append("engine passes (s, median): " + "; ".join(
        f"{r['facets']:,}: " + ", ".join(f"{key} {value:.3f}" for key, value in r["passes_s"].items()) for r in rows))
    lines.append("band (facets removed / added): " + "; ".join(
        f"{r['facets']:,}: {r['facets_removed']:,} / {r['facets_added']:,}" for r in rows))
    if len(rows) > 1:
        lines.append(f"t({rows[-1]['facets']:,}) / t({rows[0]['facets']:,}) = {rows[-1]['call_s'] / rows[0]['call_s']:.1f}")
    lines.append("load average (1, 5, 15 min) at each size's end: " + "; ".join(
        f"{r['facets']:,}: " + ", ".join(f"{x:.1f}" for x in r["load"]) for r in rows))
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", type=int, nargs="*", default=list(SIZES), help="k per size (12 k^2 facets)")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--json", help="write the rows here too")
    parser.add_argument("--one", type=int, help=argparse.SUPPRESS)  # a child process: one size, JSON out
    args = parser.parse_args()
    if args.one:
        print(json.dumps(measure(args.one, args.runs)))
        return
    rows = []
    for k in args.sizes:
        out = subprocess.run([sys.executable, os.path.abspath(__file__), "--one", str(k), "--runs", str(args.runs)],
                             check=True, capture_output=True, text=True).stdout
        rows.append(json.loads(out.strip().splitlines()[-1]))
        print(f"k = {k}: {rows[-1]['facets']:,} facets, call {rows[-1]['call_s']:.3f} s", file=sys.stderr)
    print(table(rows))
    if args.json:
        with open(args.json, "w") as stream:
            json.dump(rows, stream, indent=1)


if __name__ == "__main__":
    main()
