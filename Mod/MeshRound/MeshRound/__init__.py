"""MeshRound: round sharp edges of triangle meshes with a rolling ball.

    import MeshRound
    res = MeshRound.round_edges(mesh, seeds, radius)              # console API -> RoundingResult
    obj = MeshRound.make_rounding(base_feature, seeds, radius)    # parametric Mesh feature "Rounding"
    wires = MeshRound.trace_chains(mesh, seeds)                   # the chains seeds select
    plan = MeshRound.plan_network(mesh, seeds, radius)            # their corners' blends (or the refused one)
    res = MeshRound.change_radius(mesh, seeds, radius)            # an existing round to a new radius (0: sharp)
    MeshRound.quality_note(res.report)                            # why new facets are under 10 deg, if any
    deck = MeshRound.read_deck("die.k")                           # solver deck (LS-DYNA/Nastran/Abaqus) as arrays
    res = MeshRound.round_deck("die.k", "die_r5.k", seeds, 5)     # round a deck, write it back (decks.py)
    res = MeshRound.change_radius_deck("die.k", "die_r8.k", seeds, 8)  # a deck's existing round to a new radius
    deck = MeshRound.open_deck("die.k")                           # in FreeCAD: a Deck feature (parts, quads)
    MeshRound.export_deck(rounding, "die_r5.k")                   # a Rounding on a Deck, as the rounded deck
    MeshRound.max_radius(mesh, seeds)                             # largest radius per chain, what stops it
    MeshRound.sweep(mesh, seeds, radii, out_dir)                  # one rounded variant per radius + table
    MeshRound.sweep("die.k", seeds, radii, out_dir)               # ... of a solver deck, each variant a deck
    MeshRound.sweep_sheet(rounding, sheet, "B", out_dir)          # a Rounding over a spreadsheet column
    token = MeshRound.CancelToken()                               # round_edges(..., cancel=token); from
    token.cancel()                                                # another thread: stops the run

Outside FreeCAD, put /usr/lib/freecad-python3/lib and <repo>/Mod/MeshRound on sys.path first.

The names are loaded on first use (PEP 562), so importing the package costs nothing and needs no
FreeCAD: the workbench registration and `python3 -m MeshRound.cli` (which finds FreeCAD itself) rely on it.
"""
import importlib

__version__ = "0.1.0"

# public name -> submodule defining it
_EXPORTS = {
    "round_edges": "api",
    "trace_chains": "api",
    "plan_network": "api",
    "RoundingResult": "api",
    "quality_note": "api",
    "RoundingError": "errors",
    "CancelToken": "errors",
    "make_rounding": "objects.rounding",
    "read_deck": "decks",
    "round_deck": "decks",
    "open_deck": "objects.deck",      # a deck as a Deck feature in FreeCAD (issue 14)
    "make_deck": "objects.deck",
    "export_deck": "deck_export",
    # radius tools (issue 16)
    "max_radius": "radius_limits",
    "check_rules": "radius_limits",
    "sweep": "sweep",
    "optimise_radius": "sweep",
    "sweep_features": "sweep",
    "sweep_sheet": "sweep",
    "change_radius": "reround",
    "change_radius_deck": "decks",
}
__all__ = list(_EXPORTS)


def __getattr__(name):
    if name not in _EXPORTS:
        raise AttributeError(f"module 'MeshRound' has no attribute {name!r}")
    module = importlib.import_module(f".{_EXPORTS[name]}", __name__)
    # Every name of that module at once (later look-ups skip this function): importing submodule `sweep`
    # sets the package's attribute `sweep` to the module, which must not hide the function sweep.
    for other, where in _EXPORTS.items():
        if where == _EXPORTS[name]:
            globals()[other] = getattr(module, other)
    return globals()[name]


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))
