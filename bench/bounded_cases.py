"""Times of the cases that must finish (round or refuse) in bounded time: the 100 x 60 x 40 box meshed
with MaxLength=2, its top back edge picked at (37, 60, 40).

    /usr/bin/python3 bench/bounded_cases.py [case ...]      (one process per case; prints seconds, code)
"""
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = {
    "r=1e-4": dict(radius=1e-4),
    "r=5,tol=1e-7": dict(radius=5.0, tolerance=1e-7),
    "r=0.05": dict(radius=0.05),
    "r=5": dict(radius=5.0),
    "control 3 m away": dict(radius=[((0, 60, 40), 4.0), ((37, 60, 3040), 6.0)]),
}


def run(name):
    sys.path.append("/usr/lib/freecad-python3/lib")
    import FreeCAD  # noqa: F401
    # after FreeCAD, which puts the user's Mod folders first: this tree's engine, not an installed one
    sys.path.insert(0, os.path.join(os.path.dirname(HERE), "Mod", "MeshRound"))
    import MeshPart
    import Part
    import MeshRound
    assert MeshRound.__file__.startswith(os.path.dirname(HERE)), MeshRound.__file__
    mesh = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=2)
    kw = dict(CASES[name])
    if isinstance(kw["radius"], list):
        kw["radius"] = [(FreeCAD.Vector(*p), r) for p, r in kw["radius"]]
    t = time.perf_counter()
    try:
        res = MeshRound.round_edges(mesh, FreeCAD.Vector(37, 60, 40), **kw)
        outcome = f"rounded: {res.report.get('facets_in')} -> {res.report.get('facets_out')} facets"
    except Exception as e:  # noqa: BLE001
        outcome = f"{getattr(e, 'code', type(e).__name__)}: {e}"
    print(f"{name:18s} {time.perf_counter() - t:8.2f} s  {outcome[:300]}", flush=True)


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--one":
        run(sys.argv[2])
    else:
        for name in sys.argv[1:] or CASES:
            try:
                subprocess.run([sys.executable, __file__, "--one", name], timeout=float(os.environ.get("CASE_TIMEOUT", 120)))
            except subprocess.TimeoutExpired:
                print(f"{name:18s} > {os.environ.get('CASE_TIMEOUT', 120)} s (killed)", flush=True)
