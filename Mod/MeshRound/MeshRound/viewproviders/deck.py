"""View providers of the Deck feature and its parts (GUI only): the deck's shells drawn as they are, a quad
as one quad, with its element edges (no quad diagonals), each part in its own colour and hidden or shown by
its DeckPart child.

The Deck is a Mesh::FeaturePython, so its C++ view provider (MeshGui::ViewProviderPython) also has the
mesh's own display modes (Shaded, Wireframe, Flat Lines, Points: the triangles a Rounding sees); this proxy
adds the display mode "Quads", the default:

    Quads (SoSeparator)
      SoShapeHints          two-sided lighting (decks' shells face either way), convex faces
      SoCoordinate3         every node of the deck (float32, filled from numpy in one call)
      SoPolygonOffset       faces pushed back: the edges drawn over them stay visible
      per part, in part order: SoSwitch (hidden: -1) > SoSeparator
        SoMaterial          the part's colour (DeckPart's ShapeColor), the Deck's Transparency
        SoIndexedFaceSet    one polygon per element: [a, b, c, d, -1] (quad), [a, b, c, -1] (triangle)
        SoSeparator > SoPickStyle(UNPICKABLE), SoLightModel(BASE_COLOR), SoMaterial (LineColor),
                      SoDrawStyle (LineWidth), SoIndexedLineSet (each element edge once: [a, b, -1])

A click on the faces selects the Deck at the clicked point (what the Round edges command and task panel
take as a seed); the sub-element named is "Facet<k>" with k the element's index in the deck, which is also
the index of its first triangle in the Deck's Mesh.  The class paths are stored in .FCStd files.
"""
from pivy import coin

import numpy as np

from .. import deck_drawing
from ..resources import icon_path

MODE = "Quads"
PALETTE = [(0.45, 0.62, 0.85), (0.93, 0.62, 0.35), (0.55, 0.78, 0.45), (0.85, 0.45, 0.50),
           (0.65, 0.55, 0.85), (0.45, 0.80, 0.80), (0.90, 0.80, 0.40), (0.70, 0.70, 0.70)]


class _PartNodes:
    """The Coin nodes of one part and the deck elements it draws (polygon k = element shells[k])."""

    def __init__(self, pid, shells, faces, lines, line_style):
        self.pid, self.shells = pid, shells
        self.switch = coin.SoSwitch()
        self.material = coin.SoMaterial()
        self.faces = coin.SoIndexedFaceSet()
        self.faces.coordIndex.setValues(0, len(faces), faces)
        self.lines = coin.SoIndexedLineSet()
        self.lines.coordIndex.setValues(0, len(lines), lines)
        body = coin.SoSeparator()
        body.addChild(self.material)
        body.addChild(self.faces)
        edges = coin.SoSeparator()
        for node in (*line_style, self.lines):
            edges.addChild(node)
        body.addChild(edges)
        self.switch.addChild(body)
        self.switch.whichChild = 0


class ViewProviderDeck:
    def __init__(self, vobj):
        vobj.Proxy = self
        vobj.DisplayMode = MODE

    def attach(self, vobj):
        self.ViewObject, self.Object = vobj, vobj.Object
        self.parts = {}  # part ID -> _PartNodes
        self.root = coin.SoSeparator()
        hints = coin.SoShapeHints()
        hints.vertexOrdering = coin.SoShapeHints.UNKNOWN_ORDERING  # two-sided lighting
        hints.shapeType = coin.SoShapeHints.UNKNOWN_SHAPE_TYPE
        hints.faceType = coin.SoShapeHints.CONVEX
        self.coords = coin.SoCoordinate3()
        offset = coin.SoPolygonOffset()
        offset.factor, offset.units = 1.0, 1.0
        self.part_group = coin.SoGroup()
        for node in (hints, self.coords, offset, self.part_group):
            self.root.addChild(node)
        pick = coin.SoPickStyle()
        pick.style = coin.SoPickStyle.UNPICKABLE  # a click goes through the edges to the faces
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        self.line_material, self.line_style = coin.SoMaterial(), coin.SoDrawStyle()
        self._line_nodes = (pick, light, self.line_material, self.line_style)
        vobj.addDisplayMode(self.root, MODE)
        self._apply_line_style()
        if vobj.Object.File:  # a reopened document, or attached after the first recompute
            self.redraw()

    def getDisplayModes(self, vobj):
        return [MODE]

    def getDefaultDisplayMode(self):
        return MODE

    def setDisplayMode(self, mode):
        return mode

    def getIcon(self):
        return icon_path("MeshRound_Deck.svg")

    def claimChildren(self):
        return [child for child in getattr(self.Object, "PartObjects", []) if child]

    def updateData(self, obj, prop):
        if prop == "Mesh" and hasattr(self, "root") and obj.File:  # set last by the Deck's recompute
            self.redraw()

    def onChanged(self, vobj, prop):
        if not hasattr(self, "root"):
            return
        if prop == "Transparency":
            for part in self.parts.values():
                part.material.transparency = vobj.Transparency / 100.0
        elif prop in ("LineColor", "LineWidth"):
            self._apply_line_style()

    def onDelete(self, vobj, subelements):
        """Deleting a Deck deletes its part children too."""
        obj = vobj.Object
        children = [child for child in obj.PartObjects if child]
        obj.PartObjects = []
        for child in children:
            obj.Document.removeObject(child.Name)
        return True

    def getElementPicked(self, picked_point):
        """The picked element as "Facet<k>": k the element's index in the deck (= its first triangle)."""
        path = picked_point.getPath()
        detail = picked_point.getDetail()
        if path is None or detail is None or not detail.isOfType(coin.SoFaceDetail.getClassTypeId()):
            raise ValueError("no element picked")
        tail = path.getTail()
        face = coin.cast(detail, "SoFaceDetail").getFaceIndex()
        for part in self.parts.values():
            if part.faces == tail and 0 <= face < len(part.shells):
                return f"Facet{int(part.shells[face])}"
        raise ValueError("no element picked")

    # ------------------------------------------------------------------ drawing
    def redraw(self):
        """Rebuild the nodes from the deck (the Deck proxy's cached DrawData)."""
        obj = self.Object
        data = obj.Proxy.draw_data(obj) if obj.Proxy is not None else None
        self.part_group.removeAllChildren()
        self.parts = {}
        if data is None:
            self.coords.point.setNum(0)
            return
        self.coords.point.setValues(0, len(data.xyz), data.xyz)
        order = np.argsort(data.parts, kind="stable")  # the elements part by part, in deck order within
        starts = np.searchsorted(data.parts[order], [pid for pid, _ in data.part_list] + [np.inf])
        for (pid, _), start, end in zip(data.part_list, starts, starts[1:]):
            shells = order[start:end]
            nodes, counts = data.nodes[shells], data.counts[shells]
            part = _PartNodes(pid, shells, deck_drawing.polygon_index(nodes, counts),
                              deck_drawing.edge_index(nodes, counts), self._line_nodes)
            self.parts[pid] = part
            self.part_group.addChild(part.switch)
        for index, pid in enumerate(self.parts):
            self.show_part(pid, *_part_view(obj, pid, index))
        self.onChanged(self.ViewObject, "Transparency")

    def show_part(self, pid, visible, color):
        """Show or hide part `pid` and give it `color` (r, g, b in 0..1)."""
        part = self.parts.get(pid)
        if part is None:
            return
        part.switch.whichChild = 0 if visible else -1
        part.material.diffuseColor = tuple(color[:3])
        part.material.transparency = self.ViewObject.Transparency / 100.0

    def _apply_line_style(self):
        vobj = self.ViewObject
        color = getattr(vobj, "LineColor", (0.0, 0.0, 0.0))
        self.line_material.diffuseColor = tuple(color[:3])
        self.line_style.lineWidth = float(getattr(vobj, "LineWidth", 1.0))

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__  # the names FreeCAD >= 0.21 looks for


def _part_view(deck, pid, index):
    """(visible, colour) of part pid as its DeckPart child says (shown, palette colour without one)."""
    for child in deck.PartObjects:
        if child is not None and child.PartId == pid and child.ViewObject is not None:
            vobj = child.ViewObject
            return vobj.Visibility, tuple(getattr(vobj, "ShapeColor", PALETTE[index % len(PALETTE)]))
    return True, PALETTE[index % len(PALETTE)]


class ViewProviderDeckPart:
    """A part of a Deck in the tree: its visibility (Space) and ShapeColor drive the Deck's drawing."""

    def __init__(self, vobj, index=0):
        vobj.addProperty("App::PropertyColor", "ShapeColor", "Display", "Colour of the part's elements")
        vobj.ShapeColor = PALETTE[index % len(PALETTE)]
        vobj.Proxy = self

    def attach(self, vobj):
        self.ViewObject, self.Object = vobj, vobj.Object
        vobj.addDisplayMode(coin.SoGroup(), "Default")  # nothing of its own: the Deck draws the part

    def getDisplayModes(self, vobj):
        return ["Default"]

    def getDefaultDisplayMode(self):
        return "Default"

    def setDisplayMode(self, mode):
        return mode

    def getIcon(self):
        return icon_path("MeshRound_DeckPart.svg")

    def onChanged(self, vobj, prop):
        if prop not in ("Visibility", "ShapeColor") or not hasattr(self, "Object"):
            return
        obj = self.Object
        for deck in obj.InList:
            proxy = getattr(deck.ViewObject, "Proxy", None) if deck.ViewObject else None
            if isinstance(proxy, ViewProviderDeck) and hasattr(proxy, "root"):
                proxy.show_part(obj.PartId, vobj.Visibility, tuple(vobj.ShapeColor))

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__
