"""Console-call times of MeshRound.change_radius (find the round, sharpen it, round it again) on meshes of
OCCT's fillets: a box edge (60 x 40 x 30, r0 = 5, made 8), the S-shaped plate's edge (r0 = 4, made 6) and a
circular pocket's rim (r0 = 3, made 4.5) and a rectangular pocket's rim rolling around its rounded wall corners
(R 6; r0 = 2, made 3), each on a MeshPart mesh (elements 0.4 r0), a CAD tessellation
(deflection 0.004 mm) and, for the box, a mesh of about 100k facets; beside each, round_edges of the same
edge on a mesh of the sharp solid alike, and the radius-0 call (sharpen only).

    /usr/bin/python3 bench/reround_speed.py      (prints the best of three calls per row)
"""
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "python"))
import conftest  # noqa: E402,F401  (FreeCAD's modules and the workbench from this tree)
import MeshPart  # noqa: E402
import MeshRound  # noqa: E402
import cases  # noqa: E402
import test_change_radius as reround  # noqa: E402


def best_of_three(call):
    times = []
    for _ in range(3):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return min(times)


def row(label, case, r0, r1, **mesher):
    rounded = MeshPart.meshFromShape(Shape=case(r0).reference, **mesher)
    sharp = MeshPart.meshFromShape(Shape=case(r0).solid, **mesher)
    seed = [reround.seed_on_round(case(r0))]
    change = best_of_three(lambda: MeshRound.change_radius(rounded, seed, r1))
    sharpen = best_of_three(lambda: MeshRound.change_radius(rounded, seed, 0))
    fresh = best_of_three(lambda: MeshRound.round_edges(sharp, seed, r1))
    print(f"{label:48s} {rounded.CountFacets:7d} facets: change_radius {change:6.3f} s (sharpen {sharpen:6.3f} s); "
          f"round_edges on the sharp solid's mesh ({sharp.CountFacets} facets) {fresh:6.3f} s", flush=True)


def main():
    cad = dict(reround.CAD_MESH)
    box = lambda r: reround.case_at("box", r)  # noqa: E731
    row("box edge 5 -> 8, MeshPart 2 mm", box, 5.0, 8.0, MaxLength=2.0)
    row("box edge 5 -> 8, CAD", box, 5.0, 8.0, **cad)
    row("box edge 5 -> 8, MeshPart 0.35 mm", box, 5.0, 8.0, MaxLength=0.35)
    row("S plate 4 -> 6, MeshPart 1.6 mm", reround.s_case, 4.0, 6.0, MaxLength=1.6)
    row("S plate 4 -> 6, CAD", reround.s_case, 4.0, 6.0, **cad)
    row("pocket rim 3 -> 4.5, MeshPart 1.2 mm", reround.loop_case, 3.0, 4.5, MaxLength=1.2)
    row("pocket rim 3 -> 4.5, CAD", reround.loop_case, 3.0, 4.5, **cad)
    row("rim around wall corners 2 -> 3, MeshPart 0.8 mm", reround.rim_case, 2.0, 3.0, MaxLength=0.8)
    row("rim around wall corners 2 -> 3, CAD", reround.rim_case, 2.0, 3.0, **cad)


if __name__ == "__main__":
    assert cases  # (the solids the rows are made of)
    main()
