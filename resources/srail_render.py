"""FreeCAD GUI macro: render the S-rail die before and after rounding into one PNG.

    SRAIL_OUT=out QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a freecad resources/srail_render.py

Opens $SRAIL_OUT/srail_rounding.FCStd (written by srail_demo.py), renders the sharp die mesh and the
constant- and variable-radius roundings, whole and close up on the S bend, and writes a labelled 2 x 3
grid to $SRAIL_OUT/srail_before_after.png.  FreeCAD quits when done (also on error).
"""
import os
import traceback

import FreeCAD
import FreeCADGui
from pivy import coin
from PySide import QtCore, QtGui

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.environ.get("SRAIL_OUT", os.path.join(os.getcwd(), "out"))
TILE = (800, 600)
CLOSE_UP = dict(focus=(150.0, 100.0, 52.0), height=70.0)  # the far shoulder in the first bend
COLUMNS = [("DieMesh", "sharp die mesh"), ("RoundingConstant", "rounded, r = 5 mm"),
           ("RoundingVariable", "rounded, r = 3 - 8 - 3 mm")]


def show_only(doc, name, facets):
    """Show one object (shaded; with its facet edges when `facets`), hide the rest."""
    for obj in doc.Objects:
        vo = obj.ViewObject
        if vo is None:
            continue
        vo.Visibility = obj.Name == name
        if obj.Name == name:
            vo.DisplayMode = "Flat Lines" if facets else "Shaded"
            vo.ShapeColor = (0.80, 0.83, 0.88)
            vo.LineColor = (0.35, 0.38, 0.45)


def set_close_up(view):
    """Keep the isometric direction; centre the orthographic camera on the bend and zoom in."""
    cam = view.getCameraNode()
    direction = cam.orientation.getValue().multVec(coin.SbVec3f(0, 0, -1))
    focus = coin.SbVec3f(*CLOSE_UP["focus"])
    cam.position.setValue(focus - direction * 500.0)
    cam.focalDistance.setValue(500.0)
    if hasattr(cam, "height"):
        cam.height.setValue(CLOSE_UP["height"])


def snapshot(view, path, close_up):
    view.viewIsometric()
    view.fitAll()
    if close_up:
        set_close_up(view)
    FreeCADGui.updateGui()
    view.saveImage(path, TILE[0], TILE[1], "White")
    return QtGui.QImage(path)


def compose(tiles, path):
    """tiles[row][column] QImages -> one PNG with a caption over each column."""
    caption = 40
    w, h = TILE
    out = QtGui.QImage(w * len(tiles[0]), caption + h * len(tiles), QtGui.QImage.Format_RGB32)
    out.fill(QtGui.QColor("white"))
    p = QtGui.QPainter(out)
    font = p.font()
    font.setPointSize(16)
    font.setBold(True)
    p.setFont(font)
    for c, (_, label) in enumerate(COLUMNS):
        p.drawText(QtCore.QRect(c * w, 0, w, caption), QtCore.Qt.AlignCenter, label)
    for r, row in enumerate(tiles):
        for c, img in enumerate(row):
            p.drawImage(c * w, caption + r * h, img)
    p.setPen(QtGui.QPen(QtGui.QColor(180, 180, 180), 2))
    for c in range(1, len(tiles[0])):
        p.drawLine(c * w, caption, c * w, caption + h * len(tiles))
    p.drawLine(0, caption + h, w * len(tiles[0]), caption + h)
    p.end()
    out.save(path)


def main():
    # The Rounding proxies need not load to draw the stored meshes (FreeCAD only loads proxies of
    # installed add-ons during a restore; without one it warns and the meshes still show).
    doc = FreeCAD.openDocument(os.path.join(OUT, "srail_rounding.FCStd"))
    FreeCADGui.activateWorkbench("MeshWorkbench")
    view = FreeCADGui.getDocument(doc.Name).ActiveView
    view.setAnimationEnabled(False)
    view.setCameraType("Orthographic")
    tiles = []
    for close_up in (False, True):
        row = []
        for name, _ in COLUMNS:
            show_only(doc, name, facets=close_up)  # whole die: facet lines would only darken it
            row.append(snapshot(view, os.path.join(OUT, f"_tile_{name}_{int(close_up)}.png"), close_up))
        tiles.append(row)
    compose(tiles, os.path.join(OUT, "srail_before_after.png"))
    for f in os.listdir(OUT):
        if f.startswith("_tile_"):
            os.remove(os.path.join(OUT, f))


try:
    main()
except Exception:  # noqa: BLE001  -- report, then quit anyway: this runs unattended
    traceback.print_exc()
finally:
    os._exit(0)
