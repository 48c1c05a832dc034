"""FreeCAD GUI macro: the picture of the method for the README (resources/images/method.png).

    QTWEBENGINE_CHROMIUM_FLAGS=--no-sandbox xvfb-run -a -s "-screen 0 1600x1200x24" \\
        freecad resources/method_render.py

Rounds the top back edge of a coarse 100 x 60 x 40 box mesh (r = 8 mm) with MeshRound and draws what
each pass makes, from the engine's own outputs, in three panels: the sharp-edge chain and balls at
stations along the solved spine; the exact rolling-ball surface and its two contact lines; the
rounded mesh with the new band.  Writes $METHOD_PNG (default resources/images/method.png).  FreeCAD
quits when done (also on error).
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "Mod", "MeshRound"))

import FreeCAD  # noqa: E402
import FreeCADGui  # noqa: E402
import MeshPart  # noqa: E402
import Part  # noqa: E402
from PySide import QtCore, QtGui  # noqa: E402

sys.path.insert(0, HERE)
import render_support  # noqa: E402

OUT = os.environ.get("METHOD_PNG", os.path.join(HERE, "images", "method.png"))
TILE = (640, 520)
RADIUS = 8.0
SEED = (37.0, 60.0, 40.0)
GREY, ORANGE, LINES = (0.80, 0.83, 0.88), (1.00, 0.55, 0.15), (0.35, 0.38, 0.45)
RED, BLUE, GREEN = (0.85, 0.10, 0.10), (0.10, 0.25, 0.90), (0.05, 0.60, 0.15)
PANELS = ["1  sharp chain (red) traced from one pick;\n    ball centres solved on the mesh (blue spine)",
          "2  exact rolling-ball surface (B-spline)\n    and its two contact lines (green)",
          "3  mesh cut along the contact lines,\n    the band between them re-meshed (orange)"]


def add(doc, name, shape_or_mesh, color, line_width=None, transparency=0, flat_lines=False):
    kind = "Mesh::Feature" if hasattr(shape_or_mesh, "CountFacets") else "Part::Feature"
    obj = doc.addObject(kind, name)
    if kind == "Mesh::Feature":
        obj.Mesh = shape_or_mesh
    else:
        obj.Shape = shape_or_mesh
    vo = obj.ViewObject
    vo.ShapeColor = color
    vo.Transparency = transparency
    if line_width:
        vo.LineColor = color
        vo.LineWidth = line_width
        if hasattr(vo, "PointSize"):
            vo.PointSize = 1
    if flat_lines:
        vo.DisplayMode = "Flat Lines"
        vo.LineColor = LINES
    return obj


def new_facets(before, after):
    """The facets of `after` whose three vertices are all new (the engine keeps input vertices exactly)."""
    import numpy as np
    old = {tuple(p) for p in before.Topology[0]}
    points, facets = after.Topology
    is_new = np.array([tuple(p) not in old for p in points])
    return np.asarray(facets), is_new[np.asarray(facets)].all(axis=1)


def split(mesh, keep):
    part = mesh.copy()
    part.removeFacets([int(i) for i, k in enumerate(keep) if not k])
    return part


def build(doc):
    import MeshRound
    box = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=7.0)
    res = MeshRound.round_edges(box, FreeCAD.Vector(*SEED), RADIUS)
    spine = res.spines[0]
    along = spine.discretize(Number=101)
    balls = [Part.makeSphere(RADIUS, along[i]) for i in (8, 25, 42)]
    _, band = new_facets(box, res.mesh)
    panels = [
        [add(doc, "Sharp1", box, GREY, transparency=60),
         add(doc, "Chain", res.chains[0], RED, line_width=5),
         add(doc, "Spine", spine, BLUE, line_width=4),
         add(doc, "Balls", Part.makeCompound(balls), (0.55, 0.65, 1.0), transparency=40)],
        [add(doc, "Sharp2", box, GREY, transparency=70, flat_lines=True),
         add(doc, "Surface", res.surfaces[0], ORANGE, transparency=15),
         add(doc, "Contacts", Part.makeCompound(res.contacts[:2]), GREEN, line_width=5)],
        [add(doc, "Rest", split(res.mesh, ~band), GREY, flat_lines=True),
         add(doc, "Band", split(res.mesh, band), ORANGE, flat_lines=True)],
    ]
    doc.recompute()
    return panels


def set_camera(view):
    """Looking at the edge's end x = 0 obliquely, so the round's profile shows."""
    render_support.set_camera(view, (1.0, -0.75, -0.55), (26.0, 55.0, 33.0), 58.0)


def main():
    os.makedirs(os.path.dirname(os.path.abspath(OUT)), exist_ok=True)
    doc = FreeCAD.newDocument("Method")
    FreeCADGui.activateWorkbench("MeshWorkbench")
    panels = build(doc)
    view = FreeCADGui.getDocument(doc.Name).ActiveView
    view.setAnimationEnabled(False)
    view.setCameraType("Orthographic")
    caption = 64
    out = QtGui.QImage(TILE[0] * len(panels), TILE[1] + caption, QtGui.QImage.Format_RGB32)
    out.fill(QtGui.QColor("white"))
    painter = QtGui.QPainter(out)
    font = painter.font()
    font.setPointSize(13)
    painter.setFont(font)
    for i, shown in enumerate(panels):
        names = {o.Name for o in shown}
        for obj in doc.Objects:
            obj.ViewObject.Visibility = obj.Name in names
        set_camera(view)
        FreeCADGui.updateGui()
        tile = OUT + f".tile{i}.png"
        view.saveImage(tile, TILE[0], TILE[1], "White")
        painter.drawImage(i * TILE[0], caption, QtGui.QImage(tile))
        os.remove(tile)
        painter.drawText(QtCore.QRect(i * TILE[0] + 16, 4, TILE[0] - 16, caption - 4),
                         QtCore.Qt.AlignLeft | QtCore.Qt.AlignVCenter, PANELS[i])
    painter.setPen(QtGui.QPen(QtGui.QColor(170, 170, 170), 2))
    for i in range(1, len(panels)):
        painter.drawLine(i * TILE[0], 0, i * TILE[0], TILE[1] + caption)
    painter.end()
    out.save(OUT)


render_support.run_unattended(main)
