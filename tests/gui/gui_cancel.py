"""The cancel part of the GUI macro: Esc and Cancel during long runs of the task panel.

The long run: the test box (2 mm facets) rounded at r = 0.05 mm, whose trim and round make 50k-125k
facets: seconds of engine time (a preview about 7 s, OK about 18 s on a loaded 2-core machine).  Esc and
mouse clicks are sent as events to the widgets, as the window system would deliver them, from a timer
that fires while the run goes (the panel processes events meanwhile).
"""
import os
import time

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from gui_support import ARTIFACTS, step, wait_until

RADIUS = 0.05
SEED = FreeCAD.Vector(37, 60, 40)  # the box's top back edge
REQUEST_AFTER_MS = 700


def run():
    import MeshPart
    import Part
    from MeshRound.taskpanels.round_edges import active_panel

    doc = FreeCAD.newDocument("CancelTest")
    doc.UndoMode = 1
    ridge = doc.addObject("Mesh::Feature", "Ridge")
    ridge.Mesh = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=2.0)
    doc.recompute()
    doc.openTransaction("Label")  # an undo step of its own: the cancelled runs must add none
    ridge.Label = "Ridge"
    doc.commitTransaction()
    doc.recompute()
    FreeCADGui.updateGui()
    view = FreeCADGui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()

    def open_panel():
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(doc.Name, ridge.Name)
        FreeCADGui.runCommand("MeshRound_RoundEdges")
        FreeCADGui.updateGui()
        panel = active_panel()
        panel.form.live_preview.setChecked(False)  # the runs below are started by hand
        panel.set_radius(RADIUS)
        panel.add_seed(SEED)
        return panel

    def state():
        return {"objects": [o.Name for o in doc.Objects], "undo": doc.UndoCount, "undo_names": doc.UndoNames}

    # ---- Esc during a preview: the run stops, the panel stays and says so
    panel = open_panel()
    before = state()  # (FreeCAD closes the macro's "Label" transaction when the command runs)
    timing = request_later(press_escape)
    started = time.perf_counter()
    result = panel.preview_now()
    returned = time.perf_counter()
    step("esc_preview", {
        "latency_s": returned - timing["at"] if "at" in timing else None,
        "run_s": returned - started, "result": result is not None, "cancelled_by": panel.cancelled_by,
        "status": panel.form.status.text(), "panel_open": active_panel() is panel,
        "dialog_open": bool(FreeCADGui.Control.activeDialog()), "before": before, "after": state()})
    show_widget(panel.form.status)
    step("esc_preview_screenshot", window_screenshot("gui_cancel_preview.png"))

    # ---- Cancel during OK: the recompute stops, the transaction is undone, the panel closes
    timing = request_later(lambda: click_widget(task_button(QtGui.QDialogButtonBox.Cancel)))
    started = time.perf_counter()
    press(QtGui.QDialogButtonBox.Ok)
    returned = time.perf_counter()
    closed_after = wait_until(lambda: not FreeCADGui.Control.activeDialog(), 5.0)
    step("cancel_ok", {
        "latency_s": returned - timing["at"] if "at" in timing else None, "run_s": returned - started,
        "closed_after_s": closed_after, "cancelled_by": panel.cancelled_by,
        "dialog_open": bool(FreeCADGui.Control.activeDialog()), "before": before, "after": state(),
        "base_visible": ridge.ViewObject.Visibility, "base_transparency": ridge.ViewObject.Transparency})

    # ---- Esc during OK: the recompute stops, nothing is made, the panel stays
    panel = open_panel()
    timing = request_later(press_escape)
    started = time.perf_counter()
    press(QtGui.QDialogButtonBox.Ok)
    returned = time.perf_counter()
    FreeCADGui.updateGui()
    step("esc_ok", {
        "latency_s": returned - timing["at"] if "at" in timing else None, "run_s": returned - started,
        "cancelled_by": panel.cancelled_by, "status": panel.form.status.text(),
        "panel_open": active_panel() is panel, "dialog_open": bool(FreeCADGui.Control.activeDialog()),
        "before": before, "after": state()})

    # ---- Cancel during a preview: the run stops and the panel closes
    timing = request_later(lambda: click_widget(task_button(QtGui.QDialogButtonBox.Cancel)))
    started = time.perf_counter()
    panel.preview_now()
    returned = time.perf_counter()
    closed_after = wait_until(lambda: not FreeCADGui.Control.activeDialog(), 5.0)
    step("cancel_preview", {
        "latency_s": returned - timing["at"] if "at" in timing else None, "run_s": returned - started,
        "closed_after_s": closed_after, "cancelled_by": panel.cancelled_by,
        "dialog_open": bool(FreeCADGui.Control.activeDialog()), "before": before, "after": state()})

    # ---- a recompute of the feature outside the panel: Esc stops it (FreeCAD's progress indicator)
    import MeshRound
    doc.openTransaction("Round")
    rounding = MeshRound.make_rounding(ridge, [SEED], RADIUS)
    doc.commitTransaction()
    timing = request_later(press_escape)
    started = time.perf_counter()
    doc.recompute()
    returned = time.perf_counter()
    step("esc_recompute", {
        "latency_s": returned - timing["at"] if "at" in timing else None, "run_s": returned - started,
        "state": rounding.State, "status": rounding.getStatusString()})


def request_later(action):
    """Run action() REQUEST_AFTER_MS from now (while the run goes); the returned dict gets its time."""
    timing = {}

    def fire():
        timing["at"] = time.perf_counter()
        action()

    QtCore.QTimer.singleShot(REQUEST_AFTER_MS, fire)
    return timing


def press_escape():
    """Esc, as the keyboard gives it: to the widget with the focus (else the main window)."""
    target = QtGui.QApplication.focusWidget() or FreeCADGui.getMainWindow()
    for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):
        QtGui.QApplication.sendEvent(target, QtGui.QKeyEvent(kind, QtCore.Qt.Key_Escape, QtCore.Qt.NoModifier))


def task_button(which):
    for box in FreeCADGui.getMainWindow().findChildren(QtGui.QDialogButtonBox):
        button = box.button(which)
        if button is not None and button.isVisible():
            return button
    return None


def click_widget(widget):
    """A left click in the middle of widget, as mouse events (not QAbstractButton.click())."""
    centre = widget.rect().center()
    left, none = QtCore.Qt.LeftButton, QtCore.Qt.NoButton
    for kind, button, buttons in ((QtCore.QEvent.MouseButtonPress, left, left),
                                  (QtCore.QEvent.MouseButtonRelease, left, none)):
        QtGui.QApplication.sendEvent(widget, QtGui.QMouseEvent(kind, centre, button, buttons,
                                                               QtCore.Qt.NoModifier))


def press(which):
    """Press a task dialog button with a real click (its handler runs the engine, events processed)."""
    click_widget(task_button(which))
    FreeCADGui.updateGui()


def show_widget(widget):
    """Scroll the task panel so that widget shows."""
    parent = widget.parentWidget()
    while parent is not None and not isinstance(parent, QtGui.QScrollArea):
        parent = parent.parentWidget()
    if parent is not None:
        parent.ensureWidgetVisible(widget)


def window_screenshot(name):
    FreeCADGui.updateGui()
    path = os.path.join(ARTIFACTS, name)
    FreeCADGui.getMainWindow().grab().save(path)
    return path
