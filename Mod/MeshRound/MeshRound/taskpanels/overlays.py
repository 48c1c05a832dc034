"""Temporary Coin3D drawings in the 3D view: chain highlight, seed markers, preview mesh.

They live in their own SoSeparator under the view's scene graph, are unpickable (clicks go through to
the real mesh underneath), never touch the document, and disappear with remove().  Arrays go to Coin
in one call each (pivy takes numpy arrays), so a big preview mesh costs no Python loop.
"""
import numpy as np
from pivy import coin

CHAIN_COLOR = (1.0, 0.45, 0.0)     # orange: the selected sharp-edge chains
SEED_COLOR = (0.85, 0.0, 0.0)      # red: the picked seeds
LAW_COLOR = (0.0, 0.6, 0.0)        # green: variable-radius control points
CONTACT_COLOR = (0.1, 0.2, 0.8)    # blue: where the ball touches the two sides
PREVIEW_COLOR = (0.55, 0.78, 0.95)  # light blue: the rounded mesh preview
STRIP_COLOR = (0.95, 0.0, 0.75)     # magenta: the facets of an existing round that was picked
CORNER_COLORS = {                   # where picked chains meet, by the corner's blend (api.NetworkPlan)
    "mitre": (0.6, 0.0, 0.8),       # purple
    "sphere": (0.0, 0.55, 0.55),    # teal
    "rolled": (0.1, 0.2, 0.8),      # blue
}


class Overlay:
    """One named layer of temporary drawings in a 3D view."""

    def __init__(self, view, on_top=False):
        self._graph = view.getSceneGraph()
        # SoAnnotation draws after everything else without depth test: lines stay visible inside the
        # rounded preview, which cuts the sharp edge away.
        self._root = coin.SoAnnotation() if on_top else coin.SoSeparator()
        pick_style = coin.SoPickStyle()
        pick_style.style = coin.SoPickStyle.UNPICKABLE
        self._root.addChild(pick_style)
        self._content = coin.SoSeparator()
        self._root.addChild(self._content)
        self._graph.addChild(self._root)

    def show(self, *nodes):
        """Replace what the layer draws by nodes."""
        self._content.removeAllChildren()
        for node in nodes:
            self._content.addChild(node)

    def clear(self):
        self._content.removeAllChildren()

    def in_scene(self):
        return self._graph.findChild(self._root) >= 0

    def remove(self):
        self.clear()
        if self.in_scene():
            self._graph.removeChild(self._root)


def polylines_node(polylines, color, width=4.0):
    """Thick lines through each (s, 3) array of polylines."""
    polylines = [np.asarray(p, dtype=np.float32).reshape(-1, 3) for p in polylines]
    polylines = [p for p in polylines if len(p) >= 2]
    separator = _styled_separator(color, line_width=width)
    if polylines:
        coords = coin.SoCoordinate3()
        points = np.concatenate(polylines)
        coords.point.setValues(0, len(points), points)
        lines = coin.SoLineSet()
        counts = np.array([len(p) for p in polylines], dtype=np.int32)
        lines.numVertices.setValues(0, len(counts), counts)
        separator.addChild(coords)
        separator.addChild(lines)
    return separator


def facet_edges_node(vertices, triangles, color, width=1.5):
    """The edges of facets (vertices (n, 3), triangles (m, 3)) as lines: a highlight that leaves what is
    under it (the preview) visible."""
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    loops = np.asarray(vertices, dtype=np.float32)[triangles[:, [0, 1, 2, 0]]]  # (m, 4, 3): closed
    return polylines_node(list(loops), color, width=width)


def markers_node(points, color):
    """Filled circle markers at points (k, 3), drawn at the same size whatever the zoom."""
    points = np.asarray(points, dtype=np.float32).reshape(-1, 3)
    separator = _styled_separator(color)
    if len(points):
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, len(points), points)
        markers = coin.SoMarkerSet()
        markers.markerIndex = coin.SoMarkerSet.CIRCLE_FILLED_9_9
        separator.addChild(coords)
        separator.addChild(markers)
    return separator


def mesh_node(vertices, triangles, color=PREVIEW_COLOR):
    """A shaded triangle mesh, pulled slightly towards the viewer so it wins over the base mesh where
    both coincide (everywhere but the rounded band)."""
    vertices = np.ascontiguousarray(vertices, dtype=np.float32).reshape(-1, 3)
    triangles = np.asarray(triangles, dtype=np.int32).reshape(-1, 3)
    separator = _styled_separator(color)
    hints = coin.SoShapeHints()
    hints.vertexOrdering = coin.SoShapeHints.COUNTERCLOCKWISE
    hints.creaseAngle = 0.5  # radians: smooth shading across the fine facets of the round
    offset = coin.SoPolygonOffset()
    offset.factor = -1.0
    offset.units = -1.0
    coords = coin.SoCoordinate3()
    coords.point.setValues(0, len(vertices), vertices)
    faces = coin.SoIndexedFaceSet()
    index = np.hstack([triangles, np.full((len(triangles), 1), -1, dtype=np.int32)]).ravel()
    faces.coordIndex.setValues(0, len(index), index)
    for node in (hints, offset, coords, faces):
        separator.addChild(node)
    return separator


def _styled_separator(color, line_width=None):
    separator = coin.SoSeparator()
    material = coin.SoMaterial()
    material.diffuseColor = color
    material.emissiveColor = tuple(0.3 * c for c in color)  # readable even when lit from behind
    separator.addChild(material)
    if line_width is not None:
        style = coin.SoDrawStyle()
        style.lineWidth = line_width
        separator.addChild(style)
    return separator
