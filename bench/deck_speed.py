"""Read + round + write of a large LS-DYNA deck, each part timed (MeshRound.round_deck's report).

The deck: a structured quad mesh of a W x D x H box (tests/python/deck_files.py, standard fixed fields,
two parts, sets along the rounded edge); its top back edge rounded with r = 5.  Default size: h = 1 mm on a
600 x 400 x 300 box, 1,080,000 quads.

    /usr/bin/python3 bench/deck_speed.py [--h 1.0] [--size 600,400,300] [--folder /tmp/meshround-deck-bench]

Prints the deck's size and the wall and processor seconds of: read (engine's reader, includes the file read), split (shells to
triangles), round (the engine), elements (triangles back to elements, quad pairing, parts, sets), write
(engine's writer, in memory), save_and_check (files written, read back, checked watertight, moved).
"""
import argparse
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "python"))
import conftest  # noqa: E402,F401  (FreeCAD, MeshRound from this tree)
import deck_files  # noqa: E402
import MeshRound  # noqa: E402
import numpy as np  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--h", type=float, default=1.0)
    parser.add_argument("--size", default="600,400,300")
    parser.add_argument("--folder", default="/tmp/meshround-deck-bench")
    parser.add_argument("--radius", type=float, default=5.0)
    parser.add_argument("--reuse", action="store_true", help="round the deck a previous run wrote (same --h, --size)")
    args = parser.parse_args()
    size = tuple(float(x) for x in args.size.split(","))
    os.makedirs(args.folder, exist_ok=True)
    start = time.perf_counter()
    path = os.path.join(args.folder, "big.k")
    if not (args.reuse and os.path.exists(path)):
        xyz, quads, faces = deck_files.box_quads(size, args.h)
        centroid = xyz[quads].mean(axis=1)
        on_edge = lambda p: np.hypot(p[:, 1] - size[1], p[:, 2] - size[2])  # noqa: E731
        near = np.flatnonzero(on_edge(centroid) < 2 * args.h)
        far = np.flatnonzero(faces == 4)[:1000]
        edge = np.flatnonzero(on_edge(xyz) < 1e-9)
        path = deck_files.write_deck(args.folder, "lsdyna_fixed", xyz, quads, faces, near, far, edge, name="big")
    made = time.perf_counter() - start
    out = os.path.join(args.folder, "big_r5.k")
    seed = (size[0] * 0.37, size[1], size[2])
    res = MeshRound.round_deck(path, out, [seed], args.radius)
    s, c = res.report["seconds_deck"], res.report["cpu_seconds_deck"]
    total, cpu = sum(s.values()), sum(c.values())
    d = res.report["deck"]
    print(f"deck: {d['elements_in']:,} shells ({d['quads_in']:,} quads), {os.path.getsize(path) / 1e6:.1f} MB "
          f"(made in {made:.1f} s, not timed below)")
    print(f"  {'step':15s} {'wall':>9s} {'cpu':>9s} {'cpu share':>9s}")
    for k in s:
        print(f"  {k:15s} {s[k]:7.2f} s {c[k]:7.2f} s {100 * c[k] / cpu:7.1f} %")
    print(f"  {'total':15s} {total:7.2f} s {cpu:7.2f} s")
    print(json.dumps({k: res.report["deck"][k] for k in ("elements_removed", "new_quads", "new_triangles",
                                                          "nodes_new", "sets_updated", "check")}))


if __name__ == "__main__":
    main()
