"""The picture of a rounded deck's band (README, "Solver decks"): the 60 x 40 x 30 box as a structured quad
deck (h = 2.5 mm, tests/python/deck_files.py), its top back edge rounded with r = 5 mm by
MeshRound.round_deck; kept elements grey, new quads blue, new triangles orange.

    /usr/bin/python3 resources/deck_band_render.py [OUT.png]
"""
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "python"))
import conftest  # noqa: E402,F401
import deck_files  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import MeshRound  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def main(out):
    xyz, quads, faces = deck_files.box_quads((60, 40, 30), 2.5)
    folder = tempfile.mkdtemp(prefix="meshround-render-")
    path = deck_files.write_deck(folder, "lsdyna_fixed", xyz, quads, faces, np.arange(1), np.arange(1), np.arange(1))
    res = MeshRound.round_deck(path, os.path.join(folder, "r5.k"), [(37, 40, 30)], 5.0)
    before, after = MeshRound.read_deck(path), res.paths[0]
    after = MeshRound.read_deck(after)
    new = ~np.isin(after["shell_ids"], before["shell_ids"])
    P = after["node_xyz"]
    polys, colours = [], []
    for nodes, is_new, count in zip(after["shell_nodes"], new, after["shell_counts"]):
        pts = P[nodes[:count]]
        c = pts.mean(axis=0)
        if not (20 < c[0] < 40 and c[1] > 24 and c[2] > 14):
            continue
        polys.append(pts)
        colours.append("#f0a040" if is_new and count == 3 else "#6fa8dc" if is_new else "#d9d9d9")
    fig = plt.figure(figsize=(8, 6), dpi=110)
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors="#303030", linewidths=0.4))
    ax.set_xlim(20, 40), ax.set_ylim(22, 42), ax.set_zlim(12, 32)
    ax.set_box_aspect((20, 20, 20))
    ax.view_init(elev=24, azim=58)
    ax.set_axis_off()
    d = res.report["deck"]
    ax.set_title(f"LS-DYNA deck, r = 5 mm: {d['elements_removed']} quads replaced by {d['new_quads']} quads (blue) "
                 f"and {d['new_triangles']} triangles (orange)", fontsize=9)
    fig.savefig(out, bbox_inches="tight")
    print(out, d)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "images", "deck_quad_band.png"))
