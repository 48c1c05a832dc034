"""File > Open / Import / Export of solver decks in FreeCAD (registered in Init.py as "MeshRound solver
deck"): open() makes a new document with the deck as a Deck feature, insert() adds it to a document,
export() writes a selected Rounding built on a Deck as the rounded deck (deck_export.export_deck).
FreeCAD records `import MeshRound.deck_import` and these calls in macros: keep the names."""
import os

import FreeCAD

from .deck_formats import DECK_EXTENSIONS

FILTER = "MeshRound solver deck (" + " ".join("*" + ext for ext in DECK_EXTENSIONS) + ")"


def open(filename):  # noqa: A001  (the name FreeCAD calls)
    """File > Open: a new document named after the file, holding the Deck."""
    from .objects.deck import open_deck
    return open_deck(filename).Document


def insert(filename, docname):
    """File > Import: the Deck added to document `docname` (made if missing)."""
    from .objects.deck import open_deck
    try:
        doc = FreeCAD.getDocument(docname)
    except NameError:
        doc = FreeCAD.newDocument(docname)
    FreeCAD.setActiveDocument(doc.Name)
    return open_deck(filename, doc)


def export(objects, filename):
    """File > Export: the one Rounding (built on a Deck) among `objects` as the rounded deck."""
    from .deck_export import _is_rounding, export_deck
    from .errors import RoundingError
    roundings = [obj for obj in objects if _is_rounding(obj)]
    if len(roundings) != 1:
        raise RoundingError(f"select one Rounding built on a solver deck to export as '{os.path.basename(filename)}'"
                            f" ({len(roundings)} selected)", code="invalid_input")
    return export_deck(roundings[0], filename)
