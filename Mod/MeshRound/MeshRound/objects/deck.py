"""The "Deck" feature: a solver deck (LS-DYNA, Nastran, Abaqus) as a document object.

    deck = MeshRound.open_deck("die.k")            # a new document (or doc=...): the Deck and its parts
    rounding = MeshRound.make_rounding(deck, seeds, 5.0)
    MeshRound.export_deck(rounding, "die_r5.k")    # the rounded deck, in the deck's own format

The Deck is a Mesh::FeaturePython whose Mesh holds the deck's shells as triangles (decks.deck_triangles:
a quad as two, split on its shorter diagonal; the first len(shells) facets are one per element, in the
deck's element order), so that a Rounding takes it as its Base like any mesh.  Its recompute reads the
file again.  Each part of the deck with shells is a child "DeckPart" (App::FeaturePython, no geometry of
its own): the Deck's view provider draws every part with its own colour, as quads, and a part's child
hides or shows it (Space in the tree).  Properties (group "Deck"):
  File        App::PropertyFile      the deck (.k .key .dyn, .bdf .nas .dat, .inp); includes followed
  Format      App::PropertyString    (read-only) lsdyna / nastran / abaqus
  Nodes       App::PropertyInteger   (read-only) nodes the shells use
  Elements, Quads, Triangles         (read-only) shell elements: all, 4-node, 3-node
  Parts       App::PropertyStringList (read-only) one line per part with shells: "id name: counts"
  PartObjects App::PropertyLinkList  (read-only) the DeckPart children, in part order
The class paths MeshRound.objects.deck.Deck / DeckPart are stored in .FCStd files: keep them stable.
"""
import os

import numpy as np

import FreeCAD

from .. import decks, meshconv
from ..errors import RoundingError

TYPE = "Mesh::FeaturePython"
PART_TYPE = "App::FeaturePython"
GROUP = "Deck"

PROPERTIES = [
    ("App::PropertyFile", "File", "The solver deck: LS-DYNA .k .key .dyn, Nastran .bdf .nas .dat, Abaqus .inp"),
    ("App::PropertyString", "Format", "The deck's format family (by the file's extension)"),
    ("App::PropertyInteger", "Nodes", "Nodes the shell elements use"),
    ("App::PropertyInteger", "Elements", "Shell elements (3- and 4-node)"),
    ("App::PropertyInteger", "Quads", "4-node shell elements"),
    ("App::PropertyInteger", "Triangles", "3-node shell elements"),
    ("App::PropertyStringList", "Parts", "The deck's parts with shell elements"),
    ("App::PropertyLinkList", "PartObjects", "One child per part: hide or show a part with it"),
]
PART_PROPERTIES = [
    ("App::PropertyInteger", "PartId", "The part's ID in the deck (Abaqus: the index of its ELSET)"),
    ("App::PropertyString", "PartName", "The part's name in the deck (may be empty)"),
    ("App::PropertyInteger", "Elements", "Shell elements of the part"),
    ("App::PropertyInteger", "Quads", "4-node shell elements of the part"),
    ("App::PropertyInteger", "Triangles", "3-node shell elements of the part"),
]
INFO = ["Format", "Nodes", "Elements", "Quads", "Triangles", "Parts", "PartObjects"]


def _add_properties(obj, table, info):
    for type_name, name, tooltip in table:
        if name not in obj.PropertiesList:
            obj.addProperty(type_name, name, GROUP, tooltip)
            if name in info:
                obj.setPropertyStatus(name, ["ReadOnly"])


class DrawData:
    """What the view provider draws, without the deck's texts: node coordinates (float32), each shell's
    node indices (m, 4), node counts (3 or 4) and part IDs, and the parts in order [(id, name)]."""

    def __init__(self, arrays):
        self.xyz = np.ascontiguousarray(arrays["node_xyz"], np.float32)
        self.nodes = np.asarray(arrays["shell_nodes"], np.int32)
        self.counts = np.asarray(arrays["shell_counts"], np.int8)
        self.parts = np.asarray(arrays["shell_parts"], np.int64)
        names = {int(i): name for i, name in arrays["parts"]}
        self.part_list = [(int(p), names.get(int(p), "")) for p in np.unique(self.parts)]


class Deck:
    """Proxy of the Deck feature.  It caches what the view provider draws (not stored in the file: read
    again from the deck when a reopened document is first drawn)."""

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        _add_properties(obj, PROPERTIES, INFO)

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)

    def execute(self, obj):
        path = obj.File
        if not path:
            raise RoundingError(f"Deck '{obj.Label}' has no File: set it to a solver deck")
        arrays = decks.read_deck(path)  # RoundingError naming file:line for a malformed deck
        vertices, triangles, _, _ = decks.deck_triangles(arrays)
        data = DrawData(arrays)
        self._cache = (_file_key(path), data)
        quads = int(np.sum(data.counts == 4))
        obj.Format = arrays["format"]
        obj.Nodes, obj.Elements = len(vertices), len(data.counts)
        obj.Quads, obj.Triangles = quads, len(data.counts) - quads
        obj.Parts = [_part_line(data, pid, name) for pid, name in data.part_list]
        _sync_parts(obj, data)
        obj.Mesh = meshconv.arrays_to_mesh(vertices, triangles)  # last: the view provider redraws on it

    def draw_data(self, obj):
        """The DrawData of obj's deck (cached by path, size and time; read again when the file changed),
        or None when the file cannot be read."""
        key = _file_key(obj.File)
        cache = getattr(self, "_cache", None)
        if cache is not None and cache[0] == key:
            return cache[1]
        try:
            data = DrawData(decks.read_deck(obj.File))
        except (RoundingError, OSError) as exc:
            FreeCAD.Console.PrintWarning(f"{obj.Label}: cannot draw the deck's elements: {exc}\n")
            return None
        self._cache = (key, data)
        return data

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__  # the names FreeCAD >= 0.21 looks for


class DeckPart:
    """Proxy of a part child of a Deck: what the part holds (counts), and a visibility of its own."""

    def __init__(self, obj):
        obj.Proxy = self
        _add_properties(obj, PART_PROPERTIES, [name for _, name, _ in PART_PROPERTIES])

    def execute(self, obj):
        pass

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__


def _file_key(path):
    try:
        stat = os.stat(path)
    except OSError:
        return (path, None, None)
    return (os.path.abspath(path), stat.st_size, stat.st_mtime_ns)


def _part_line(data, pid, name):
    mask = data.parts == pid
    quads = int(np.sum(data.counts[mask] == 4))
    label = f"{pid} {name}".rstrip()
    return f"{label}: {int(mask.sum())} elements ({quads} quads, {int(mask.sum()) - quads} triangles)"


def _sync_parts(obj, data):
    """One DeckPart child per part with shells, in part order: existing children are updated, missing
    ones added, those of parts the deck no longer has removed."""
    doc = obj.Document
    existing = {child.PartId: child for child in obj.PartObjects if child is not None}
    children = []
    for index, (pid, name) in enumerate(data.part_list):
        child = existing.pop(pid, None)
        if child is None:
            child = doc.addObject(PART_TYPE, f"{obj.Name}Part")
            DeckPart(child)
            child.PartId = pid
            if FreeCAD.GuiUp:
                from ..viewproviders.deck import ViewProviderDeckPart
                ViewProviderDeckPart(child.ViewObject, index)
        mask = data.parts == pid
        quads = int(np.sum(data.counts[mask] == 4))
        child.PartName = name
        child.Elements, child.Quads, child.Triangles = int(mask.sum()), quads, int(mask.sum()) - quads
        child.Label = f"{obj.Label} part {pid}" + (f" {name}" if name else "")
        child.purgeTouched()  # nothing to compute in it
        children.append(child)
    obj.PartObjects = children
    for child in existing.values():
        doc.removeObject(child.Name)


def make_deck(path, doc=None, name=None):
    """Add a Deck feature reading the solver deck at `path` to doc (default: the active document, or a
    new one) and recompute it: its Mesh, counts and part children are there on return.  Raises
    RoundingError (invalid_input) for a file that is not a deck by its extension or does not read."""
    path = os.path.abspath(os.fspath(path))
    if not decks.is_deck_path(path):
        raise RoundingError(f"'{path}' is not a solver deck by its extension (.k .key .dyn: LS-DYNA, "
                            ".bdf .nas .dat: Nastran, .inp: Abaqus)", code="invalid_input")
    if not os.path.isfile(path):
        raise RoundingError(f"cannot read '{path}': no such file", code="invalid_input")
    doc = doc or FreeCAD.ActiveDocument or FreeCAD.newDocument(_document_name(path))
    obj = doc.addObject(TYPE, name or "Deck")
    obj.Label = os.path.basename(path)
    Deck(obj)
    obj.File = path
    obj.recompute()
    if "Invalid" in obj.State:
        message = obj.getStatusString()
        doc.removeObject(obj.Name)
        raise RoundingError(f"cannot open '{path}': {message}", code="invalid_input")
    obj.purgeTouched()  # read: the document's next recompute must not read it again
    if FreeCAD.GuiUp:  # after the recompute: the view provider draws from what it read
        from ..viewproviders.deck import ViewProviderDeck
        ViewProviderDeck(obj.ViewObject)
    return obj


def open_deck(path, doc=None):
    """Open the solver deck at `path` as a Deck (with its parts) in doc, or in a new document named
    after the file; returns the Deck."""
    if doc is None:
        doc = FreeCAD.newDocument(_document_name(path))
    deck = make_deck(path, doc)
    doc.recompute()
    return deck


def _document_name(path):
    stem = os.path.splitext(os.path.basename(str(path)))[0]
    return "".join(c if c.isalnum() else "_" for c in stem) or "Deck"
