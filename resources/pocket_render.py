"""FreeCAD GUI macro: a rectangular pocket's rim rounded in one call, its corners mitred, as a PNG.

    QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a -s "-screen 0 1600x1200x24" freecad resources/pocket_render.py

Meshes an 80 x 60 x 30 block with a 40 x 30, 12 deep pocket (MeshPart, elements 0.8 mm), rounds the four
rim edges with r = 2 mm (one seed on each), and renders the result twice: the whole block, and a close-up
of one pocket corner with its facets, the new facets in orange.  Writes resources/images/pocket_rim.png
(or $POCKET_PNG).  FreeCAD quits when done (also on error).
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
OUT = os.environ.get("POCKET_PNG", os.path.join(HERE, "images", "pocket_rim.png"))
TILE = (800, 600)
GREY, ORANGE, LINES = (0.80, 0.83, 0.88), (1.00, 0.55, 0.15), (0.35, 0.38, 0.45)
VIEWS = [((-0.6, 1.0, -1.1), None, None, False), ((1.0, -1.0, -0.9), (60.0, 15.0, 28.5), 10.0, True)]


def main():
    block = Part.makeBox(80, 60, 30).cut(Part.makeBox(40, 30, 13, V(20, 15, 18))).removeSplitter()
    sharp = MeshPart.meshFromShape(Shape=block, MaxLength=0.8)
    rim = [V(40, 15, 30), V(60, 30, 30), V(40, 45, 30), V(20, 30, 30)]
    result = MeshRound.round_edges(sharp, rim, 2.0)
    doc = FreeCAD.newDocument("PocketRim")
    shown = []
    for part, color in zip(rest_and_band(sharp, result.mesh), (GREY, ORANGE)):
        feature = doc.addObject("Mesh::Feature", "Band" if color == ORANGE else "Rest")
        feature.Mesh = part
        shown.append((feature, color))
    doc.recompute()
    view = FreeCADGui.ActiveDocument.ActiveView
    tiles = []
    for k, (direction, focus, height, facets) in enumerate(VIEWS):
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
