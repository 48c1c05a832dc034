# MeshRound: rounds sharp edges of triangle meshes with a rolling ball.
#
# FreeCAD runs this file at start-up, GUI or not, with this folder on sys.path.  Nothing needs
# registering for console use: `import MeshRound` gives the API (MeshRound.round_edges, make_rounding).
# The workbench itself is registered in InitGui.py.
#
# Solver decks open as Deck features (File > Open / Import) and a Rounding built on one exports as the
# rounded deck (File > Export): an entry of its own beside Fem's .inp/.bdf/.dat importers.
import FreeCAD

_DECK_FILTER = "MeshRound solver deck (*.k *.key *.dyn *.bdf *.nas *.dat *.inp)"  # deck_import.FILTER
FreeCAD.addImportType(_DECK_FILTER, "MeshRound.deck_import")
FreeCAD.addExportType(_DECK_FILTER, "MeshRound.deck_import")
