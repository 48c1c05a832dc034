"""The solver deck part of the GUI macro (run by test_gui_deck.py): a quad deck opened through FreeCAD's
File > Open path (the module registered for .k), its Coin nodes (quads drawn as quads, edges without diagonals), a part hidden and
shown again, a click on the deck that the Round edges command takes as its seed, a Rounding on the deck
made through the task panel's OK and exported as the deck, screenshots, and the time to open and draw a
deck of about 100k quads."""
import os
import time

import numpy as np

import FreeCAD
import FreeCADGui
from pivy import coin

import deck_files
from gui_support import click, press_task_button, redraw_seconds, screenshot, step

SIZE, H = (60.0, 40.0, 30.0), 2.5    # the deck tests' box (tests/python/test_decks.py)
SEED = FreeCAD.Vector(37.0, 40.0, 30.0)  # on its top back edge
CLICK = FreeCAD.Vector(37.2, 38.8, 30.0)  # on the top face, 1.2 mm from that edge


def run(work_dir):
    from MeshRound.objects.deck import Deck
    FreeCADGui.activateWorkbench("MeshRoundWorkbench")
    step("commands", [c for c in ("MeshRound_RoundEdges", "MeshRound_ExportDeck") if c in FreeCADGui.listCommands()])
    xyz, quads, faces = deck_files.box_quads(SIZE, H)
    path = write_box_deck(work_dir, "lsdyna_fixed", xyz, quads, faces)

    # File > Open's path (Gui::Application::open): the module registered for the extension (Init.py) is
    # imported and its open() called, as these two commands
    (module,) = step("import_modules", FreeCAD.getImportType("k"))
    FreeCADGui.doCommand(f"import {module}")
    FreeCADGui.doCommand(f"{module}.open(u{path!r})")
    doc = FreeCAD.ActiveDocument
    deck = next(o for o in doc.Objects if isinstance(getattr(o, "Proxy", None), Deck))
    step("opened", {"document": doc.Name, "deck": deck.Name, "label": deck.Label, "state": deck.State,
                    "quads": deck.Quads, "triangles": deck.Triangles, "parts": list(deck.Parts),
                    "display_mode": deck.ViewObject.DisplayMode,
                    "children": [c.Name for c in deck.ViewObject.claimChildren()]})
    view = FreeCADGui.ActiveDocument.ActiveView
    show_deck(view)
    step("scene", scene_counts(deck, quads))
    step("deck_screenshot", screenshot("gui_deck.png"))

    top = next(c for c in deck.PartObjects if c.PartId == 2)
    top.ViewObject.Visibility = False  # as Space on the part in the tree
    FreeCADGui.updateGui()
    step("top_hidden", {"switches": part_switches(deck), "visible": top.ViewObject.Visibility})
    step("top_hidden_screenshot", screenshot("gui_deck_top_hidden.png"))
    top.ViewObject.Visibility = True
    top.ViewObject.ShapeColor = (0.9, 0.2, 0.2)
    FreeCADGui.updateGui()
    step("top_shown", {"switches": part_switches(deck),
                       "top_color": list(deck.ViewObject.Proxy.parts[2].material.diffuseColor[0])})

    click_and_round(doc, deck, view, work_dir, path)
    reopen(doc, work_dir)
    open_large_deck(work_dir)


def reopen(doc, work_dir):
    """Saved with a part hidden and recoloured, closed and opened again: the deck is drawn as before (read
    from its file again), the part still hidden, its colour kept."""
    deck = doc.getObject("Deck")
    top = next(c for c in deck.PartObjects if c.PartId == 2)
    top.ViewObject.Visibility = False
    top.ViewObject.ShapeColor = (0.2, 0.6, 0.3)
    path = os.path.join(work_dir, "deck.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    FreeCADGui.updateGui()
    deck = doc.getObject("Deck")
    proxy = deck.ViewObject.Proxy
    step("reopened", {"proxy": type(proxy).__module__ + "." + type(proxy).__name__,
                      "display_mode": deck.ViewObject.DisplayMode, "switches": part_switches(deck),
                      "polygons": sum(len(p.shells) for p in proxy.parts.values()),
                      "top_color": list(proxy.parts[2].material.diffuseColor[0])})
    FreeCAD.closeDocument(doc.Name)


def write_box_deck(folder, style, xyz, quads, faces, size=SIZE):
    """The deck file (two parts: 2 the top face; sets along the top back edge y = size[1], z = size[2])."""
    centroid = xyz[quads].mean(axis=1)
    near = np.flatnonzero(np.linalg.norm(centroid[:, 1:] - size[1:], axis=1) < 2 * H)
    edge = np.flatnonzero(np.linalg.norm(xyz[:, 1:] - size[1:], axis=1) < 1e-9)
    return deck_files.write_deck(folder, style, xyz, quads, faces, near, np.flatnonzero(faces == 4), edge)


def show_deck(view):
    view.setCameraOrientation(FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 30).multiply(
        FreeCAD.Rotation(FreeCAD.Vector(1, 0, 0), 55)))
    view.fitAll()
    FreeCADGui.updateGui()


def scene_counts(deck, quads):
    """What the Deck's view provider put in the scene, counted from the Coin nodes found under its root:
    polygons by corner count, and whether an edge line joins two opposite corners of a quad."""
    vobj = deck.ViewObject
    root = vobj.Proxy.root  # the display mode "Quads"
    search = coin.SoSearchAction()
    search.setNode(root)
    search.apply(vobj.RootNode)
    mode_path = search.getPath()  # ... > the view provider's display mode switch > root
    switch = mode_path.getNodeFromTail(1) if mode_path else None
    shown = (switch is not None and switch.isOfType(coin.SoSwitch.getClassTypeId())
             and coin.cast(switch, "SoSwitch").getChild(coin.cast(switch, "SoSwitch").whichChild.getValue()) == root)
    faces, lines = find(root, coin.SoIndexedFaceSet), find(root, coin.SoIndexedLineSet)
    sizes, segments = [], []
    for node in faces:
        index = np.array(node.coordIndex.getValues(), int)
        ends = np.flatnonzero(index == -1)
        sizes += np.diff(np.r_[-1, ends]).tolist()
    for node in lines:
        index = np.array(node.coordIndex.getValues(), int).reshape(-1, 3)
        segments.append(index[:, :2])
    segments = np.sort(np.concatenate(segments), axis=1)
    diagonals = np.sort(np.concatenate([quads[:, [0, 2]], quads[:, [1, 3]]]), axis=1)
    sides = np.sort(np.concatenate([quads[:, [k, (k + 1) % 4]] for k in range(4)]), axis=1)
    # the deck's node indices are read_deck's (its node order); the file writes node i as ID 1001 + i in
    # order, so they are the same here
    as_set = lambda a: set(map(tuple, a.tolist()))  # noqa: E731
    return {"in_scene_and_shown": bool(shown), "face_sets": len(faces), "line_sets": len(lines),
            "polygon_corners": {str(k): sizes.count(k + 1) for k in (3, 4)},
            "segments": len(segments), "unique_segments": len(as_set(segments)),
            "diagonal_segments": len(as_set(segments) & as_set(diagonals)),
            "segments_not_sides": len(as_set(segments) - as_set(sides)),
            "element_sides": len(as_set(sides)),
            "coordinates": sum(n.point.getNum() for n in find(root, coin.SoCoordinate3))}


def find(root, kind):
    search = coin.SoSearchAction()
    search.setType(kind.getClassTypeId())
    search.setInterest(coin.SoSearchAction.ALL)
    search.setSearchingAll(True)  # into switches that are off, too
    search.apply(root)
    return [path.getTail() for path in search.getPaths()]


def part_switches(deck):
    return {str(pid): part.switch.whichChild.getValue() for pid, part in deck.ViewObject.Proxy.parts.items()}


def click_and_round(doc, deck, view, work_dir, path):
    """A real click on the deck's top face selects the Deck at that point; the Round edges command takes
    it as the seed; OK makes a Rounding on the Deck, which exports as the rounded deck."""
    import MeshRound
    from MeshRound.taskpanels.round_edges import active_panel
    FreeCADGui.Selection.clearSelection()
    click(view, CLICK)
    selection = FreeCADGui.Selection.getSelectionEx()
    picked = [(s.ObjectName, list(s.SubElementNames), [list(p) for p in s.PickedPoints]) for s in selection]
    step("click_selection", picked)
    FreeCADGui.runCommand("MeshRound_RoundEdges")
    FreeCADGui.updateGui()
    panel = active_panel()
    step("panel", {"open": panel is not None, "base": panel.base.Name if panel else None,
                   "seeds": [list(s) for s in panel.seeds] if panel else [],
                   "chain_lengths": [w.Length for w in panel.chain_wires] if panel else [],
                   "ghost_transparency": [round(p.material.transparency[0], 2)
                                          for p in deck.ViewObject.Proxy.parts.values()]})
    if panel is None:
        return
    panel.form.radius.setProperty("rawValue", 5.0)
    press_task_button("ok")
    rounding = next((o for o in doc.Objects if o.Name.startswith("Rounding") and hasattr(o, "Seeds")), None)
    step("rounding", None if rounding is None else {
        "state": rounding.State, "base": rounding.Base.Name, "facets": rounding.Mesh.CountFacets,
        "solid": rounding.Mesh.isSolid(), "deck_visible": deck.ViewObject.Visibility,
        "transparency_after": [round(p.material.transparency[0], 2) for p in deck.ViewObject.Proxy.parts.values()]})
    if rounding is None:
        return
    step("rounded_screenshot", screenshot("gui_deck_rounded.png"))
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(doc.Name, rounding.Name)
    step("export_command_active", FreeCADGui.Command.get("MeshRound_ExportDeck").isActive())
    out = os.path.join(work_dir, "box_rounded.k")
    result = MeshRound.export_deck(rounding, out)
    reference = MeshRound.round_deck(path, os.path.join(work_dir, "reference.k"), list(rounding.Seeds),
                                     rounding.Radius.Value)
    with open(out, "rb") as a, open(reference.paths[0], "rb") as b:
        step("export", {"paths": result.paths, "same_as_round_deck": a.read() == b.read(),
                        "new_quads": result.report["deck"]["new_quads"]})
    # the picture, seen from behind: the deck (left) and the exported deck opened beside it (right)
    rounded = MeshRound.make_deck(out, doc, name="RoundedDeck")
    rounded.Placement.Base = FreeCAD.Vector(-75, 0, 0)
    rounding.ViewObject.Visibility = False
    deck.ViewObject.Visibility = True
    top = next(c for c in deck.PartObjects if c.PartId == 2)
    top.ViewObject.ShapeColor = next(c for c in rounded.PartObjects if c.PartId == 2).ViewObject.ShapeColor
    FreeCADGui.updateGui()
    step("rounded_deck", {"quads": rounded.Quads, "triangles": rounded.Triangles,
                          "display_mode": rounded.ViewObject.DisplayMode})
    view.setCameraOrientation(FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 200).multiply(
        FreeCAD.Rotation(FreeCAD.Vector(1, 0, 0), 55)))
    view.fitAll()
    camera = view.getCameraNode()
    if camera.isOfType(coin.SoOrthographicCamera.getClassTypeId()):  # fitAll leaves wide margins
        camera.height.setValue(camera.height.getValue() * 0.62)
    step("final_screenshot", screenshot("deck_in_freecad.png", 1000, 500))


def open_large_deck(work_dir):
    """The time to open (read, triangles, parts) and draw a deck of about 100k quads."""
    import MeshRound
    size = (600.0, 400.0, 300.0)
    xyz, quads, faces = deck_files.box_quads(size, 3.3)
    path = write_box_deck(work_dir, "nastran_free", xyz, quads, faces, size)
    started = time.perf_counter()
    deck = MeshRound.open_deck(path)
    opened = time.perf_counter() - started
    FreeCADGui.updateGui()
    view = FreeCADGui.ActiveDocument.ActiveView
    view.fitAll()
    first = redraw_seconds(view)
    step("large", {"elements": deck.Elements, "quads": deck.Quads, "open_s": opened, "first_frame_s": first,
                   "frame_s": redraw_seconds(view),
                   "polygons": sum(len(p.shells) for p in deck.ViewObject.Proxy.parts.values())})
