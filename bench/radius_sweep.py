"""The radius tools on the S-rail die (issue 16): max_radius of both die shoulders, a sweep of 15 radii
made with 1 and with 2 processes (the speed-up), and the README's plot rendered from the sweep's own table.

    /usr/bin/python3 bench/radius_sweep.py [OUT_DIR]     (default /tmp/meshround_radius_sweep)

Writes OUT_DIR/jobs1, OUT_DIR/jobs2 (15 STL variants + table.csv + table.json each) and
resources/images/radius_sweep.png; prints the numbers.
"""
import csv
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
for p in ("/usr/lib/freecad-python3/lib", os.path.join(ROOT, "resources", "srail")):
    if p not in sys.path:
        sys.path.append(p)
import FreeCAD  # noqa: E402,F401
sys.path.insert(0, os.path.join(ROOT, "Mod", "MeshRound"))
import MeshRound  # noqa: E402
import srail_die  # noqa: E402

ELEMENT_SIZE = 5.0  # mm, as the demo
RADII = [1.0 + 0.5 * i for i in range(15)]  # 1 .. 8 mm


def plot(table_csv, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    with open(table_csv, newline="") as stream:
        rows = [r for r in csv.DictReader(stream) if r["status"] == "ok"]
    r = [float(x["radius_0"]) for x in rows]
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.2))
    for ax, key, label in zip(axes, ("facets_added", "max_deviation", "min_new_angle_deg"),
                              ("facets added", "largest deviation (mm)", "smallest new angle (deg)")):
        ax.plot(r, [float(x[key]) for x in rows], "o-")
        ax.set_xlabel("radius (mm)")
        ax.set_title(label, fontsize=10)
        ax.grid(alpha=0.3)
    fig.suptitle("S-rail die, both shoulders: one variant per radius (meshround sweep's table.csv)", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main(out_dir="/tmp/meshround_radius_sweep"):
    t = time.perf_counter()
    mesh = srail_die.die_mesh(ELEMENT_SIZE)
    print(f"die mesh: {mesh.CountFacets} facets, {time.perf_counter() - t:.1f} s")
    seeds = list(srail_die.shoulder_seeds())
    best = []
    for _ in range(3):
        t = time.perf_counter()
        limits = MeshRound.max_radius(mesh, seeds)
        best.append(time.perf_counter() - t)
    for i, lim in enumerate(limits):
        print(f"shoulder {i}: max radius {lim.radius:.4f} mm ({lim.why}) {lim.reason}; {lim.stations} stations, "
              f"{lim.balls_solved} balls")
    print(f"max_radius, both shoulders: {min(best):.3f} s (best of 3: {', '.join(f'{b:.3f}' for b in best)})")
    seconds = {}
    for jobs in (1, 2):
        folder = os.path.join(out_dir, f"jobs{jobs}")
        result = MeshRound.sweep(mesh, seeds, RADII, out_dir=folder, jobs=jobs, thickness=1.0)
        seconds[jobs] = result.seconds
        made = sum(r["status"] == "ok" for r in result.rows)
        print(f"sweep of {len(RADII)} radii, {jobs} process(es): {result.seconds:.2f} s, {made} made; {result.stopped}")
    print(f"speed-up with 2 processes: {seconds[1] / seconds[2]:.2f}x")
    png = os.path.join(ROOT, "resources", "images", "radius_sweep.png")
    plot(os.path.join(out_dir, "jobs2", "table.csv"), png)
    print(f"plot: {png}")


if __name__ == "__main__":
    main(*sys.argv[1:])
