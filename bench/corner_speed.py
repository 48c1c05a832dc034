"""Console-call times of a pocket rim rounded as one network (four chains, four mitred corners) against
one of its edges alone, on two mesh sizes of the 80 x 60 x 30 block with a 40 x 30, 12 deep pocket, r = 2;
of all twelve edges of that pocket (four rolled corners at the rim, four sphere corners at the floor) at
about 100k and 400k facets; and of a box corner's three edges (one sphere corner) against one of them,
100 x 60 x 40 box, r = 5.

    /usr/bin/python3 bench/corner_speed.py      (prints the best of three calls per row)
"""
import os
import sys
import time

sys.path.append("/usr/lib/freecad-python3/lib")
import FreeCAD  # noqa: E402
import MeshPart  # noqa: E402
import Part  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Mod", "MeshRound"))
import MeshRound  # noqa: E402

V = FreeCAD.Vector
RIM = [V(40, 15, 30), V(60, 30, 30), V(40, 45, 30), V(20, 30, 30)]
WALL_CORNERS = [V(20, 15, 24), V(60, 15, 24), V(60, 45, 24), V(20, 45, 24)]
FLOOR = [V(40, 15, 18), V(60, 30, 18), V(40, 45, 18), V(20, 30, 18)]


BOX_CORNER = [V(50, 60, 40), V(100, 30, 40), V(100, 60, 20)]


def best_of_three(mesh, seeds, radius=2.0):
    times = []
    for _ in range(3):
        start = time.perf_counter()
        MeshRound.round_edges(mesh, seeds, radius)
        times.append(time.perf_counter() - start)
    return min(times)


def main():
    block = Part.makeBox(80, 60, 30).cut(Part.makeBox(40, 30, 13, V(20, 15, 18))).removeSplitter()
    for max_length in (1.0, 0.45):
        mesh = MeshPart.meshFromShape(Shape=block, MaxLength=max_length)
        print(f"{mesh.CountFacets} facets: whole rim (4 chains, 4 mitres) {best_of_three(mesh, RIM):.3f} s, "
              f"one rim edge {best_of_three(mesh, RIM[:1]):.3f} s")
    for max_length in (0.8, 0.4):
        mesh = MeshPart.meshFromShape(Shape=block, MaxLength=max_length)
        print(f"{mesh.CountFacets} facets: the whole pocket (12 chains: 4 rolled, 4 sphere corners) "
              f"{best_of_three(mesh, RIM + WALL_CORNERS + FLOOR):.3f} s, rim and wall corners (8 chains, 4 rolled) "
              f"{best_of_three(mesh, RIM + WALL_CORNERS):.3f} s")
    for max_length in (2.0, 1.0):
        mesh = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=max_length)
        try:
            corner = f"{best_of_three(mesh, BOX_CORNER, 5.0):.3f} s"
        except MeshRound.RoundingError as e:
            corner = f"refused ({e.code})"
        print(f"{mesh.CountFacets} facets: box corner (3 chains, 1 sphere corner) {corner}, "
              f"one of its edges {best_of_three(mesh, BOX_CORNER[:1], 5.0):.3f} s")


if __name__ == "__main__":
    main()
