"""Solver deck file extensions -> format family (no FreeCAD needed: the command line checks with it).
The engine's reader chooses by the same table (cpp_core deck_format_for)."""
import os

DECK_EXTENSIONS = {".k": "lsdyna", ".key": "lsdyna", ".dyn": "lsdyna", ".bdf": "nastran", ".nas": "nastran",
                   ".dat": "nastran", ".inp": "abaqus"}


def deck_family(path):
    """'lsdyna', 'nastran' or 'abaqus' for a solver deck's extension, else None."""
    return DECK_EXTENSIONS.get(os.path.splitext(str(path))[1].lower())
