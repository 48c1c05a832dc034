"""The box workflow of the GUI macro: workbench, command, task panel (picks, fields, errors, OK/Cancel),
the feature, macro recording and replay, editing, undo, the report view, the saved file, deleting."""
import os
import re
import zipfile

import FreeCAD
import FreeCADGui
from PySide import QtGui

from gui_support import (click, press_task_button, redraw_seconds, report_view_text, screenshot,
                         show_model, start_macro_recording, step, stop_macro_recording, type_into)

BACK_EDGE_SEED = FreeCAD.Vector(37, 60, 40)  # on the top back edge (y = 60, z = 40)


def run(work_dir):
    import MeshPart
    import Part
    from MeshRound.taskpanels.round_edges import active_panel

    check_workbench()
    doc = FreeCAD.newDocument("GuiTest")
    box = doc.addObject("Mesh::Feature", "Box")
    box.Mesh = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=2.0)
    doc.recompute()
    view = FreeCADGui.ActiveDocument.ActiveView
    show_model(view)
    step("sharp_screenshot", screenshot("gui_sharp.png"))  # the same view before rounding, to compare

    ok_failure_then_cancel(doc, box, active_panel)

    # ---- the main run, recorded as a macro
    macro = step("macro_path", start_macro_recording(work_dir, "round_box"))
    FreeCADGui.Selection.addSelection(doc.Name, box.Name)
    FreeCADGui.runCommand("MeshRound_RoundEdges")
    FreeCADGui.updateGui()
    panel = active_panel()
    step("panel_open", panel is not None and FreeCADGui.Control.activeDialog())
    layers = panel.overlays()
    step("overlays_in_scene", [layer.in_scene() for layer in layers])

    step("scripted_seed_added", panel.add_seed(BACK_EDGE_SEED))
    step("chain_lengths", [w.Length for w in panel.chain_wires])

    # a real mouse click on the top face, 1.5 mm from the top front edge (y = 0, z = 40)
    click(view, FreeCAD.Vector(60, 1.5, 40))
    step("seeds_after_click", [tuple(s) for s in panel.seeds])
    step("chain_lengths_after_click", sorted(w.Length for w in panel.chain_wires))

    # the feature angle field: above 90 deg the box has no sharp edge; back at 30 both chains return
    panel.form.feature_angle.setProperty("rawValue", 100.0)
    step("feature_angle_100", {"chains": len(panel.chain_wires), "status": panel.form.status.text()})
    panel.form.feature_angle.setProperty("rawValue", 30.0)
    step("feature_angle_30_chains", len(panel.chain_wires))

    # a third chain meeting both (the right top edge): the panel names the two mitres and marks them
    panel.add_seed(FreeCAD.Vector(100, 30, 40))
    step("corners_with_side_edge", {"text": panel.form.corners.text(), "style": panel.form.corners.styleSheet(),
                                    "marks": [[list(p), list(c)] for p, c in panel.corner_marks()]})
    panel.set_radius(4.0)
    panel.law = []
    panel.form.show_law([(50.0, 60.0, 40.0, 3.0), (50.0, 0.0, 40.0, 3.0), (100.0, 30.0, 40.0, 4.0)])
    panel._law_edited()
    panel.preview_now()
    step("corners_with_a_law", {"text": panel.form.corners.text(), "style": panel.form.corners.styleSheet()})
    panel.form.law_table.selectAll()
    panel.form.remove_law_button.click()
    panel.remove_seeds([2])
    step("corners_after_remove", {"text": panel.form.corners.text(), "chains": len(panel.chain_wires)})

    # an impossible radius shows a red error in the panel, then a good one previews
    panel.set_radius(0.0)
    panel.preview_now()
    step("error_text", panel.form.status.text())
    step("error_style", panel.form.status.styleSheet())
    panel.set_radius(4.0)
    step("radius_text", panel.form.radius.text())  # a field with units
    step("tolerance_automatic", panel.form.tolerance.text())  # at 0 it says what automatic is, for r = 4
    # the rule check beside the limit: a sheet thickness typed in, the tool type switched
    rules = {"none": panel.form.rule_check.text()}
    type_into(panel.form.thickness, "0.9")
    rules["die"] = {"thickness": panel.form.thickness.property("rawValue"), "text": panel.form.rule_check.text(),
                    "style": panel.form.rule_check.styleSheet()}
    panel.form.tool.setCurrentText("punch")
    rules["punch"] = {"text": panel.form.rule_check.text(), "style": panel.form.rule_check.styleSheet()}
    type_into(panel.form.thickness, "0")
    panel.form.tool.setCurrentText("die")
    rules["cleared"] = panel.form.rule_check.text()
    step("rules", rules)
    panel.form.tolerance.setValue(0.05)  # the tolerance field
    result = panel.preview_now()
    step("preview_report", result.report if result else None)
    step("status_text", panel.form.status.text())
    step("parameters", {k: v for k, v in panel.parameters().items() if k in ("tolerance", "feature_angle")})
    screenshot("gui_preview.png")

    # in radius-point mode a click adds a row to the variable-radius table, on the chain
    panel.form.pick_law.setChecked(True)
    click(view, FreeCAD.Vector(50, 58.5, 40))
    step("law_rows_after_click", panel.form.law_rows())
    step("radius_field_enabled_with_law", panel.form.radius.isEnabled())
    panel.form.law_table.selectRow(0)
    panel.form.remove_law_button.click()
    panel.form.pick_seed.setChecked(True)
    step("law_rows_after_remove", panel.form.law_rows())

    undo_count = doc.UndoCount
    step("accepted", press_task_button("ok"))
    FreeCADGui.updateGui()
    stop_macro_recording()
    rounding = doc.getObject("Rounding")
    step("feature", rounding is not None and {
        "state": rounding.State, "facets": rounding.Mesh.CountFacets, "radius": rounding.Radius.Value,
        "tolerance": rounding.Tolerance.Value, "seeds": len(rounding.Seeds),
        "base_visible": box.ViewObject.Visibility,
        "children": [o.Name for o in rounding.ViewObject.claimChildren()],
        "view_provider": rounding.ViewObject.TypeId,
        "base_transparency": box.ViewObject.Transparency,
        "surfaces_visible": rounding.Surfaces.ViewObject.Visibility})
    step("dialog_closed", not FreeCADGui.Control.activeDialog())
    step("overlays_removed", not any(layer.in_scene() for layer in layers))
    step("undo_names", doc.UndoNames)
    step("undo_entries_added", doc.UndoCount - undo_count)
    with open(macro) as stream:
        step("macro_text", stream.read())
    first_topology = rounding.Mesh.Topology
    show_model(view)
    step("screenshot", screenshot("gui_rounded.png"))

    # double click -> edit in the same panel, change the radius, OK; then undo
    rounding.ViewObject.Proxy.doubleClicked(rounding.ViewObject)
    FreeCADGui.updateGui()
    edit_panel = active_panel()
    step("edit_panel_open", edit_panel is not None and edit_panel.feature == rounding)
    step("edit_panel_seeds", len(edit_panel.seeds))
    edit_panel.set_radius(6.0)
    step("edit_accepted", press_task_button("ok"))
    FreeCADGui.updateGui()
    step("edited", {"radius": rounding.Radius.Value, "mesh_changed": rounding.Mesh.Topology != first_topology,
                    "state": rounding.State, "editing": bool(FreeCADGui.ActiveDocument.getInEdit())})
    doc.undo()
    step("undone_radius", rounding.Radius.Value)

    # a failed recompute: the error goes to the report view, the feature is invalid, the base unchanged
    rounding.Radius = 0.0
    doc.recompute()
    redraw_seconds(view)
    step("failed", {"state": rounding.State, "report_view": report_view_text()[-3000:],
                    "base_state": box.State})
    rounding.ViewObject.Proxy.doubleClicked(rounding.ViewObject)  # the panel of a failed feature says why
    step("failed_edit_status", active_panel().form.status.text())  # before the preview's timer fires
    FreeCADGui.updateGui()
    step("failed_edit_cancelled", press_task_button("cancel") and not FreeCADGui.Control.activeDialog())
    rounding.Radius = 4.0
    doc.recompute()

    # the saved file names the view provider's module and class
    path = os.path.join(work_dir, "gui.FCStd")
    doc.saveAs(path)
    with zipfile.ZipFile(path) as archive:
        gui_document = archive.read("GuiDocument.xml").decode()
    step("gui_document_proxies", sorted(set(re.findall(r'module="([^"]*)" class="([^"]*)"', gui_document))))

    # delete the Rounding as a user would: its surfaces child goes too, the base shows again
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(rounding)
    FreeCADGui.runCommand("Std_Delete")
    FreeCADGui.updateGui()
    step("after_delete", {"objects": [o.Name for o in doc.Objects],
                          "base_visible": box.ViewObject.Visibility})

    # the recorded macro, run again, makes the same rounding
    namespace = {"App": FreeCAD, "FreeCAD": FreeCAD, "Gui": FreeCADGui, "FreeCADGui": FreeCADGui}
    exec(compile(open(macro).read(), macro, "exec"), namespace)
    replayed = [o for o in doc.Objects if o.TypeId == "Mesh::FeaturePython"]
    step("replayed", {"count": len(replayed),
                      "same_mesh": bool(replayed) and replayed[0].Mesh.Topology == first_topology,
                      "state": replayed[0].State if replayed else None})


def check_workbench():
    FreeCADGui.activateWorkbench("MeshRoundWorkbench")
    step("workbench", FreeCADGui.activeWorkbench().name())
    step("command_registered", "MeshRound_RoundEdges" in FreeCADGui.listCommands())
    step("workbench_icon", FreeCADGui.listWorkbenches()["MeshRoundWorkbench"].Icon)
    window = FreeCADGui.getMainWindow()
    step("toolbar_actions", [a.text() for bar in window.findChildren(QtGui.QToolBar)
                             if bar.windowTitle() == "MeshRound" and bar.isVisible() for a in bar.actions()])
    step("menu_actions", [a.text() for top in window.menuBar().actions()
                          if top.text().replace("&", "") == "MeshRound" for a in top.menu().actions()])


def ok_failure_then_cancel(doc, box, active_panel):
    """OK with a radius the engine refuses: the panel stays open and says why, the document is as it was;
    then Cancel: nothing happened, no undo step, the view as before."""
    objects, undo_count = [o.Name for o in doc.Objects], doc.UndoCount
    FreeCADGui.Selection.addSelection(doc.Name, box.Name)
    FreeCADGui.runCommand("MeshRound_RoundEdges")
    FreeCADGui.updateGui()
    panel = active_panel()
    panel.add_seed(BACK_EDGE_SEED)
    panel.set_radius(70.0)  # larger than the box: the ball reaches past the next sharp edges
    panel.preview_now()  # refused before the engine runs: the limit (max_radius) and why, beside the field
    step("past_limit", {"limit": panel.form.radius_limit.text(), "style": panel.form.radius_limit.styleSheet(),
                        "status": panel.form.status.text(), "no_preview": panel.result is None,
                        "tolerance_label": panel.form.tolerance.parent().layout().labelForField(panel.form.tolerance).text(),
                        "tolerance_text": panel.form.tolerance.text(), "rules": panel.form.rule_check.text(),
                        "rules_style": panel.form.rule_check.styleSheet()})
    press_task_button("ok")
    step("ok_failure", {
        "panel_open": active_panel() is panel and bool(FreeCADGui.Control.activeDialog()),
        "status": panel.form.status.text(), "objects": [o.Name for o in doc.Objects],
        "undo_entries_added": doc.UndoCount - undo_count, "base_transparency": box.ViewObject.Transparency,
        "base_visible": box.ViewObject.Visibility})
    layers = panel.overlays()
    press_task_button("cancel")
    step("cancelled", {
        "dialog_closed": not FreeCADGui.Control.activeDialog(), "objects": [o.Name for o in doc.Objects],
        "objects_before": objects, "undo_entries_added": doc.UndoCount - undo_count,
        "overlays_removed": not any(layer.in_scene() for layer in layers),
        "base_transparency": box.ViewObject.Transparency, "base_visible": box.ViewObject.Visibility})
    FreeCADGui.Selection.clearSelection()
