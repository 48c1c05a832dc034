"""FreeCAD GUI macro: the radius of an existing round changed, as a PNG (README, "Changing the radius of an
existing round").  A 60 x 40 x 30 box whose top front edge OCCT filleted at 3 mm, meshed (elements 1.5 mm),
is the Base of a Rounding feature in its "Change radius of existing round" operation, one seed on the
round, Radius 8 mm.  Left: the input, the facets of the round the seed picks (reround.strip_facet_indices)
in orange; right: the feature's mesh, the new round's facets in orange.  Each is labelled with what the
feature reports (FoundRadius).  Writes resources/images/reround_before_after.png (or $REROUND_PNG); FreeCAD
quits when done (also on error).

    QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a -s "-screen 0 1600x1200x24" freecad resources/reround_render.py
"""
import math
import os
import sys

import FreeCAD
import FreeCADGui
import Mesh
import MeshPart
import Part
from PySide import QtCore, QtGui

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "Mod", "MeshRound"))
import MeshRound  # noqa: E402
from MeshRound import meshconv, reround  # noqa: E402
from MeshRound.objects.rounding import CHANGE_RADIUS  # noqa: E402
from render_support import rest_and_band, run_unattended, set_camera  # noqa: E402

V = FreeCAD.Vector
SIZE, R0, R1 = (60.0, 40.0, 30.0), 3.0, 8.0
SEED = V(30, R0 - R0 * math.cos(math.pi / 4), SIZE[2] - R0 + R0 * math.sin(math.pi / 4))  # on the round
TILE = (800, 600)
DIRECTION = (0.8, 1.0, -1.0)  # from the front left, above: the round's profile shows on the end face
GREY, ORANGE, LINES = (0.80, 0.83, 0.88), (1.00, 0.55, 0.15), (0.35, 0.38, 0.45)
OUT = os.environ.get("REROUND_PNG", os.path.join(HERE, "images", "reround_before_after.png"))


def filleted_box():
    """The box with its top front edge (y = 0, z = 30) filleted by OCCT at R0."""
    solid = Part.makeBox(*SIZE)
    edge = next(e for e in solid.Edges if all(abs(v.Point.y) < 1e-7 and abs(v.Point.z - SIZE[2]) < 1e-7
                                              for v in e.Vertexes))
    return solid.makeFillet(R0, [edge])


def split(mesh, facets):
    """Two Mesh.Mesh: mesh without `facets`, and those facets alone."""
    keep, only = Mesh.Mesh(mesh), Mesh.Mesh(mesh)
    chosen = set(int(i) for i in facets)
    keep.removeFacets(sorted(chosen))
    only.removeFacets([i for i in range(mesh.CountFacets) if i not in chosen])
    return keep, only


def main():
    doc = FreeCAD.newDocument("Reround")
    base = doc.addObject("Mesh::Feature", "FilletedBox")
    base.Mesh = MeshPart.meshFromShape(Shape=filleted_box(), MaxLength=1.5)
    rounding = MeshRound.make_rounding(base, SEED, R1, operation=CHANGE_RADIUS)
    doc.recompute()
    (found,) = rounding.FoundRadius
    vertices, triangles = meshconv.mesh_to_arrays(base.Mesh)
    strip = MeshRound.change_radius(base.Mesh, [SEED], 0).report["strips"][0]
    before = split(base.Mesh, reround.strip_facet_indices(vertices, triangles, strip))
    after = rest_and_band(base.Mesh, rounding.Mesh)
    shown = doc.addObject("Mesh::Feature", "Rest"), doc.addObject("Mesh::Feature", "Round")
    for obj in (base, rounding, rounding.Surfaces):
        obj.ViewObject.Visibility = False
    labels = [f"before: the round the seed picks, found r = {found:.2f} mm",
              f"after: Rounding \"Change radius of existing round\", r = {R1:g} mm"]
    tiles = [render(doc, shown, parts) for parts in (before, after)]
    save_side_by_side(tiles, labels)
    print("wrote", OUT, "found", found)


def render(doc, shown, parts):
    """One tile: the two parts (rest grey, round orange) with their facet edges."""
    for feature, part, color in zip(shown, parts, (GREY, ORANGE)):
        feature.Mesh = part
        feature.ViewObject.DisplayMode = "Flat Lines"
        feature.ViewObject.ShapeColor = color
        feature.ViewObject.LineColor = LINES
    doc.recompute()
    view = FreeCADGui.ActiveDocument.ActiveView
    set_camera(view, DIRECTION, (9.0, 6.0, 22.0), 42.0)
    FreeCADGui.updateGui()
    path = f"{OUT}.tile.png"
    view.saveImage(path, TILE[0], TILE[1], "White")
    tile = QtGui.QImage(path)
    os.remove(path)
    return tile


def save_side_by_side(tiles, labels, band=48):
    """The tiles side by side under a white band with their labels."""
    out = QtGui.QImage(TILE[0] * len(tiles), TILE[1] + band, QtGui.QImage.Format_RGB32)
    out.fill(QtGui.QColor(255, 255, 255))
    painter = QtGui.QPainter(out)
    font = painter.font()
    font.setPixelSize(22)
    painter.setFont(font)
    painter.setPen(QtGui.QColor(30, 30, 30))
    for k, (tile, label) in enumerate(zip(tiles, labels)):
        painter.drawImage(k * TILE[0], band, tile)
        painter.drawText(QtCore.QRect(k * TILE[0] + 20, 12, TILE[0] - 40, band - 12), QtCore.Qt.AlignLeft, label)
    painter.fillRect(TILE[0] - 1, 0, 2, TILE[1] + band, QtGui.QColor(160, 160, 160))
    painter.end()
    out.save(OUT)


run_unattended(main)
