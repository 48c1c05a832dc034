"""FreeCAD GUI macro: render the S-rail die before and after rounding into one PNG.

    SRAIL_OUT=out QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a freecad resources/srail_render.py

Opens $SRAIL_OUT/srail_rounding.FCStd (written by srail_demo.py) and renders the sharp die mesh and the
constant- and variable-radius roundings in three rows: the whole die, a close-up of the S bend, and a
close-up of the channel's open end (where the shoulders' cross-section shows).  The facets the rounding
made (every vertex new) are drawn in orange.  Writes a labelled 3 x 3 grid to
$SRAIL_OUT/srail_before_after.png; with SRAIL_SMALL=path also a half-size copy there.  FreeCAD quits
when done (also on error).
"""
import os
import sys

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from render_support import rest_and_band, run_unattended, set_camera  # noqa: E402

OUT = os.environ.get("SRAIL_OUT", os.path.join(os.getcwd(), "out"))
SMALL = os.environ.get("SRAIL_SMALL")
TILE = (800, 600)
BASE = "DieMesh"
COLUMNS = [(BASE, "sharp die mesh"), ("RoundingConstant", "rounded, r = 5 mm"),
           ("RoundingVariable", "rounded, r = 3 - 8 - 3 mm")]
GREY, ORANGE, LINES = (0.80, 0.83, 0.88), (1.00, 0.55, 0.15), (0.35, 0.38, 0.45)
# Rows: (label, view direction, focus point, view height in mm or None for the whole die, facet lines).
ROWS = [
    ("whole die", (-1.0, 1.0, -1.0), None, None, False),
    ("S bend", (-1.0, 1.0, -1.0), (150.0, 100.0, 52.0), 70.0, True),   # the far shoulder, first bend
    ("open end", (1.0, 0.0, -0.4), (0.0, 70.0, 49.0), 52.0, True),  # both shoulders at x = 0
]


def split_new_facets(doc, name):
    """Two Mesh::Features for object `name`: the facets it shares vertices with the base mesh on, and
    the facets whose three vertices are all new (the round).  Input vertices keep their exact values."""
    if name == BASE:
        return [(doc.getObject(name), GREY)]
    out = []
    parts = rest_and_band(doc.getObject(BASE).Mesh, doc.getObject(name).Mesh)
    for suffix, part, color in zip(("Rest", "Band"), parts, (GREY, ORANGE)):
        feature = doc.addObject("Mesh::Feature", f"{name}{suffix}")
        feature.Mesh = part
        out.append((feature, color))
    return out


def show_only(doc, shown, facets):
    """Show the (feature, colour) pairs in `shown` (shaded; with facet edges when `facets`)."""
    names = {f.Name for f, _ in shown}
    for obj in doc.Objects:
        if obj.ViewObject is not None:
            obj.ViewObject.Visibility = obj.Name in names
    for feature, color in shown:
        vo = feature.ViewObject
        vo.DisplayMode = "Flat Lines" if facets else "Shaded"
        vo.ShapeColor = color
        vo.LineColor = LINES


def snapshot(view, path, row):
    _, direction, focus, height, _ = row
    set_camera(view, direction, focus, height)
    FreeCADGui.updateGui()
    view.saveImage(path, TILE[0], TILE[1], "White")
    return QtGui.QImage(path)


def compose(tiles, path):
    """tiles[row][column] QImages -> one PNG, a caption over each column and a label in each row."""
    caption = 44
    w, h = TILE
    out = QtGui.QImage(w * len(tiles[0]), caption + h * len(tiles), QtGui.QImage.Format_RGB32)
    out.fill(QtGui.QColor("white"))
    p = QtGui.QPainter(out)
    font = p.font()
    font.setPointSize(18)
    font.setBold(True)
    p.setFont(font)
    for c, (_, label) in enumerate(COLUMNS):
        p.drawText(QtCore.QRect(c * w, 0, w, caption), QtCore.Qt.AlignCenter, label)
    for r, row in enumerate(tiles):
        for c, img in enumerate(row):
            p.drawImage(c * w, caption + r * h, img)
    font.setPointSize(14)
    font.setBold(False)
    p.setFont(font)
    for r, (label, *_) in enumerate(ROWS):
        box = QtCore.QRect(0, caption + r * h, p.fontMetrics().horizontalAdvance(label) + 24, 34)
        p.fillRect(box, QtGui.QColor("white"))
        p.drawText(box, QtCore.Qt.AlignCenter, label)
    p.setPen(QtGui.QPen(QtGui.QColor(170, 170, 170), 2))
    for c in range(1, len(tiles[0])):
        p.drawLine(c * w, caption, c * w, caption + h * len(tiles))
    for r in range(1, len(tiles)):
        p.drawLine(0, caption + r * h, w * len(tiles[0]), caption + r * h)
    p.end()
    out.save(path)
    if SMALL:
        out.scaledToWidth(out.width() // 2, QtCore.Qt.SmoothTransformation).save(SMALL)


def main():
    # The Rounding proxies need not load to draw the stored meshes (FreeCAD only loads proxies of
    # installed add-ons during a restore; without one it warns and the meshes still show).
    doc = FreeCAD.openDocument(os.path.join(OUT, "srail_rounding.FCStd"))
    FreeCADGui.activateWorkbench("MeshWorkbench")
    parts = {name: split_new_facets(doc, name) for name, _ in COLUMNS}
    view = FreeCADGui.getDocument(doc.Name).ActiveView
    view.setAnimationEnabled(False)
    view.setCameraType("Orthographic")
    tiles = []
    for r, row in enumerate(ROWS):
        tiles.append([])
        for name, _ in COLUMNS:
            show_only(doc, parts[name], facets=row[4])
            tiles[-1].append(snapshot(view, os.path.join(OUT, f"_tile_{name}_{r}.png"), row))
    compose(tiles, os.path.join(OUT, "srail_before_after.png"))
    for f in os.listdir(OUT):
        if f.startswith("_tile_"):
            os.remove(os.path.join(OUT, f))


run_unattended(main)
