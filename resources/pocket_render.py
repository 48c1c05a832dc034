"""FreeCAD GUI macro: corners of rounds made in one call, as a PNG: a rectangular pocket's rim with its
corners mitred (scene pocket_rim, the default); every edge of that pocket, the rim rolling on around the
rounded wall corners and the floor's corners spheres (scene pocket_all); a box corner with its three
edges rounded, meeting in the corner ball (scene box_corner), or two of them (the top edges) mitred, the
third edge left sharp (scene box_top_corner); a square pyramid with every edge rounded, four rounds
meeting in the ball at its apex (scene pyramid); every edge of the pocket with radii of their own, wall
corners 5 under a rim and floor of 3, the rim and the floor rolling on around the wall corners (tori at the
floor's corners, scene pocket_mixed).

    QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a -s "-screen 0 1600x1200x24" freecad resources/pocket_render.py
    MESHROUND_SCENE=box_corner QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a -s "-screen 0 1600x1200x24" freecad resources/pocket_render.py

pocket_rim: an 80 x 60 x 30 block with a 40 x 30, 12 deep pocket (MeshPart, elements 0.8 mm), its four rim
edges rounded with r = 2 mm (one seed on each); pocket_all: all twelve of its edges. box_corner: a 100 x 60 x 40 box (elements 2 mm), the three
edges at (100, 60, 40) rounded with r = 5 mm (box_top_corner: its two top edges there). Each is rendered twice: the whole part, and a close-up of a
corner with its facets, the new facets in orange. Writes resources/images/<scene>.png (or $POCKET_PNG).
FreeCAD quits when done (also on error).
"""
import os
import sys

import FreeCAD
import FreeCADGui
import Mesh
import MeshPart
import Part
from PySide import QtGui

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "Mod", "MeshRound"))
import MeshRound  # noqa: E402
from render_support import rest_and_band, run_unattended, set_camera  # noqa: E402

V = FreeCAD.Vector
TILE = (800, 600)
GREY, ORANGE, LINES = (0.80, 0.83, 0.88), (1.00, 0.55, 0.15), (0.35, 0.38, 0.45)
def _pyramid():
    """A square pyramid (base 60 x 60, height 30): four rounds meet at its apex, three at each base corner."""
    pts = [V(0, 0, 0), V(60, 0, 0), V(60, 60, 0), V(0, 60, 0)]
    faces = [Part.Face(Part.makePolygon(pts + pts[:1]))]
    faces += [Part.Face(Part.makePolygon([pts[i], pts[(i + 1) % 4], V(30, 30, 30), pts[i]])) for i in range(4)]
    return Part.Solid(Part.Shell(faces))


# scene -> (solid, element size, seeds, radius, views: (view direction, focus, height, facets shown))
SCENES = {
    "pocket_rim": (lambda: Part.makeBox(80, 60, 30).cut(Part.makeBox(40, 30, 13, V(20, 15, 18))).removeSplitter(), 0.8,
                   [V(40, 15, 30), V(60, 30, 30), V(40, 45, 30), V(20, 30, 30)], 2.0,
                   [((-0.6, 1.0, -1.1), None, None, False), ((1.0, -1.0, -0.9), (60.0, 15.0, 28.5), 10.0, True)]),
    "pocket_all": (lambda: Part.makeBox(80, 60, 30).cut(Part.makeBox(40, 30, 13, V(20, 15, 18))).removeSplitter(), 0.8,
                   [V(40, 15, 30), V(60, 30, 30), V(40, 45, 30), V(20, 30, 30), V(20, 15, 24), V(60, 15, 24), V(60, 45, 24),
                    V(20, 45, 24), V(40, 15, 18), V(60, 30, 18), V(40, 45, 18), V(20, 30, 18)], 2.0,
                   [((-0.6, 1.0, -1.1), None, None, False), ((1.0, -0.8, -0.7), (59.0, 16.0, 24.0), 16.0, True)]),
    "pocket_mixed": (lambda: Part.makeBox(80, 60, 30).cut(Part.makeBox(40, 30, 13, V(20, 15, 18))).removeSplitter(), 0.8,
                     [V(40, 15, 30), V(60, 30, 30), V(40, 45, 30), V(20, 30, 30), V(20, 15, 24), V(60, 15, 24), V(60, 45, 24),
                      V(20, 45, 24), V(40, 15, 18), V(60, 30, 18), V(40, 45, 18), V(20, 30, 18)],
                     [(p, 5.0 if 19 < p.z < 29 else 3.0) for p in (V(40, 15, 30), V(60, 30, 30), V(40, 45, 30), V(20, 30, 30),
                                                                   V(20, 15, 24), V(60, 15, 24), V(60, 45, 24), V(20, 45, 24),
                                                                   V(40, 15, 18), V(60, 30, 18), V(40, 45, 18), V(20, 30, 18))],
                     [((-0.6, 1.0, -1.1), None, None, False), ((0.9, -0.9, -0.8), (58.0, 17.0, 20.0), 14.0, True)]),
    "box_corner": (lambda: Part.makeBox(100, 60, 40), 2.0, [V(50, 60, 40), V(100, 30, 40), V(100, 60, 20)], 5.0,
                   [((-1.0, -1.1, -0.8), None, None, False), ((-1.0, -1.0, -1.0), (97.0, 57.0, 37.0), 16.0, True)]),
    "box_top_corner": (lambda: Part.makeBox(100, 60, 40), 2.0, [V(50, 60, 40), V(100, 30, 40)], 5.0,
                       [((-1.0, -1.1, -0.8), None, None, False), ((-1.0, -1.0, -1.0), (97.0, 57.0, 37.0), 16.0, True)]),
    "pyramid": (lambda: _pyramid(), 1.6, [V(30, 0, 0), V(60, 30, 0), V(30, 60, 0), V(0, 30, 0), V(15, 15, 15), V(45, 15, 15),
                                          V(45, 45, 15), V(15, 45, 15)], 4.0,
                [((-1.0, 0.6, -0.7), None, None, False), ((-0.45, 0.35, -1.0), (30.0, 30.0, 25.0), 16.0, True)]),
}
SCENE = os.environ.get("MESHROUND_SCENE", "pocket_rim")
OUT = os.environ.get("POCKET_PNG", os.path.join(HERE, "images", SCENE + ".png"))


def main():
    build, element, seeds, radius, views = SCENES[SCENE]
    sharp = MeshPart.meshFromShape(Shape=build(), MaxLength=element)
    result = MeshRound.round_edges(sharp, seeds, radius)
    doc = FreeCAD.newDocument("Corners")
    shown = []
    for part, color in zip(rest_and_band(sharp, result.mesh), (GREY, ORANGE)):
        feature = doc.addObject("Mesh::Feature", "Band" if color == ORANGE else "Rest")
        feature.Mesh = part
        shown.append((feature, color))
    doc.recompute()
    view = FreeCADGui.ActiveDocument.ActiveView
    tiles = []
    for k, (direction, focus, height, facets) in enumerate(views):
        for feature, color in shown:
            feature.ViewObject.DisplayMode = "Flat Lines" if facets else "Shaded"
            feature.ViewObject.ShapeColor = color
            feature.ViewObject.LineColor = LINES
        set_camera(view, direction, focus, height)
        FreeCADGui.updateGui()
        path = f"{OUT}.{k}.png"
        view.saveImage(path, TILE[0], TILE[1], "White")
        tiles.append(QtGui.QImage(path))
        os.remove(path)
    out = QtGui.QImage(TILE[0] * len(tiles), TILE[1], QtGui.QImage.Format_RGB32)
    painter = QtGui.QPainter(out)
    for k, tile in enumerate(tiles):
        painter.drawImage(k * TILE[0], 0, tile)
    painter.end()
    out.save(OUT)
    print("wrote", OUT, result.report["chains"], "chains")


run_unattended(main)
