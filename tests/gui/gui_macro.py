"""FreeCAD GUI macro run by test_gui.py:  xvfb-run -a freecad gui_macro.py

It drives the workbench as a user would (real mouse clicks on the 3D view where it matters), records what
it observes in $MESHROUND_GUI_RESULT (JSON), saves screenshots in $MESHROUND_GUI_ARTIFACTS, and quits.
Every step is recorded, so a failing step shows in the JSON instead of hanging the test.
"""
import json
import os
import traceback

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

RESULT = os.environ["MESHROUND_GUI_RESULT"]
ARTIFACTS = os.environ["MESHROUND_GUI_ARTIFACTS"]
observed = {"steps": []}


def step(name, value=True):
    observed[name] = value
    observed["steps"].append(name)


def close_message_boxes():
    """A modal message box would hang the test: record its text and dismiss it."""
    for widget in QtGui.QApplication.topLevelWidgets():
        if isinstance(widget, QtGui.QMessageBox) and widget.isVisible():
            observed.setdefault("message_boxes", []).append(widget.text())
            widget.reject()


def screenshot(name):
    FreeCADGui.updateGui()
    path = os.path.join(ARTIFACTS, name)
    FreeCADGui.ActiveDocument.ActiveView.saveImage(path, 800, 600, "White")
    return path


def show_model(view):
    """A view from the front right, above: unlike the isometric view, the three visible faces of the
    box get different shading from the headlight."""
    view.setCameraOrientation(FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 35).multiply(
        FreeCAD.Rotation(FreeCAD.Vector(1, 0, 0), 60)))
    view.fitAll()
    FreeCADGui.updateGui()


def click(view, point):
    """A left click at the screen position of 3D `point`, sent to the view's widget like a real one."""
    FreeCADGui.updateGui()
    widget = next(w for w in FreeCADGui.getMainWindow().findChildren(QtGui.QWidget)
                  if w.metaObject().className().endswith("QuarterWidget") and w.isVisible())
    # Coin pixels (origin bottom left, the GL viewport's size) -> Qt widget pixels (origin top left)
    x, y = view.getPointOnScreen(point)
    width, height = view.getSize()
    position = QtCore.QPoint(round(x * widget.width() / width),
                             round((height - y) * widget.height() / height))
    left, none = QtCore.Qt.LeftButton, QtCore.Qt.NoButton
    for kind, button, buttons in ((QtCore.QEvent.MouseMove, none, none),
                                  (QtCore.QEvent.MouseButtonPress, left, left),
                                  (QtCore.QEvent.MouseButtonRelease, left, none)):
        QtGui.QApplication.sendEvent(widget, QtGui.QMouseEvent(kind, position, button, buttons,
                                                               QtCore.Qt.NoModifier))
        FreeCADGui.updateGui()


def run():
    import MeshPart
    import Part
    from MeshRound.taskpanels.round_edges import active_panel

    FreeCADGui.activateWorkbench("MeshRoundWorkbench")
    step("workbench", FreeCADGui.activeWorkbench().name())
    step("command_registered", "MeshRound_RoundEdges" in FreeCADGui.listCommands())

    doc = FreeCAD.newDocument("GuiTest")
    box = doc.addObject("Mesh::Feature", "Box")
    box.Mesh = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=2.0)
    doc.recompute()
    view = FreeCADGui.ActiveDocument.ActiveView
    show_model(view)

    FreeCADGui.Selection.addSelection(doc.Name, box.Name)
    FreeCADGui.runCommand("MeshRound_RoundEdges")
    FreeCADGui.updateGui()
    panel = active_panel()
    step("panel_open", panel is not None and FreeCADGui.Control.activeDialog())
    layers = panel.overlays()
    step("overlays_in_scene", [layer.in_scene() for layer in layers])

    # a scripted pick: the top back edge (y = 60, z = 40)
    step("scripted_seed_added", panel.add_seed(FreeCAD.Vector(37, 60, 40)))
    step("chain_lengths", [w.Length for w in panel.chain_wires])

    # a real mouse click on the top face, 1.5 mm from the top front edge (y = 0, z = 40)
    click(view, FreeCAD.Vector(60, 1.5, 40))
    step("seeds_after_click", [tuple(s) for s in panel.seeds])
    step("chain_lengths_after_click", sorted(w.Length for w in panel.chain_wires))

    # an impossible radius shows a red error in the panel, then a good one previews
    panel.set_radius(0.0)
    panel.preview_now()
    step("error_text", panel.form.status.text())
    step("error_style", panel.form.status.styleSheet())
    panel.set_radius(4.0)
    result = panel.preview_now()
    step("preview_report", result.report if result else None)
    step("status_text", panel.form.status.text())
    screenshot("gui_preview.png")

    # in radius-point mode a click adds a row to the variable-radius table instead of a seed
    panel.form.pick_law.setChecked(True)
    click(view, FreeCAD.Vector(50, 58.5, 40))
    step("law_rows_after_click", panel.form.law_rows())
    step("radius_field_enabled_with_law", panel.form.radius.isEnabled())
    panel.form.law_table.selectRow(0)
    panel.form.remove_law_button.click()
    panel.form.pick_seed.setChecked(True)
    step("law_rows_after_remove", panel.form.law_rows())

    step("accepted", panel.accept())
    FreeCADGui.updateGui()
    rounding = doc.getObject("Rounding")
    step("feature", rounding is not None and {
        "state": rounding.State, "facets": rounding.Mesh.CountFacets, "radius": rounding.Radius.Value,
        "seeds": len(rounding.Seeds), "base_visible": box.ViewObject.Visibility,
        "children": [o.Name for o in rounding.ViewObject.claimChildren()],
        "view_provider": rounding.ViewObject.TypeId,
        "base_transparency": box.ViewObject.Transparency,
        "surfaces_visible": rounding.Surfaces.ViewObject.Visibility})
    step("dialog_closed", not FreeCADGui.Control.activeDialog())
    step("overlays_removed", not any(layer.in_scene() for layer in layers))
    step("undo_names", doc.UndoNames)
    show_model(view)
    observed["screenshot"] = screenshot("gui_rounded.png")

    # double click -> edit in the same panel, change the radius, OK
    facets_before = rounding.Mesh.Topology
    rounding.ViewObject.Proxy.doubleClicked(rounding.ViewObject)
    FreeCADGui.updateGui()
    edit_panel = active_panel()
    step("edit_panel_open", edit_panel is not None and edit_panel.feature == rounding)
    step("edit_panel_seeds", len(edit_panel.seeds))
    edit_panel.set_radius(6.0)
    step("edit_accepted", edit_panel.accept())
    FreeCADGui.updateGui()
    step("edited", {"radius": rounding.Radius.Value, "mesh_changed": rounding.Mesh.Topology != facets_before,
                    "state": rounding.State, "editing": bool(FreeCADGui.ActiveDocument.getInEdit())})
    doc.undo()
    step("undone_radius", rounding.Radius.Value)

    # delete the Rounding as a user would: its surfaces child goes too, the base shows again
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(rounding)
    FreeCADGui.runCommand("Std_Delete")
    FreeCADGui.updateGui()
    step("after_delete", {"objects": [o.Name for o in doc.Objects],
                          "base_visible": box.ViewObject.Visibility})


guard = QtCore.QTimer()
guard.timeout.connect(close_message_boxes)
guard.start(100)
try:
    run()
except Exception:
    observed["error"] = traceback.format_exc()
finally:
    with open(RESULT, "w") as stream:
        json.dump(observed, stream, indent=1, default=str)
    os._exit(0)  # quit FreeCAD at once: no "save changes?" dialog, no session restore
