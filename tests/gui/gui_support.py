"""Helpers of the GUI macro (run inside FreeCAD's GUI): recording observations, real mouse clicks,
screenshots, the macro recorder, and sampling the status bar while FreeCAD works."""
import os
import time

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

ARTIFACTS = os.environ.get("MESHROUND_GUI_ARTIFACTS", "")
observed = {"steps": []}


def step(name, value=True):
    """Record an observation (the test asserts on them); the order shows how far the macro got."""
    observed[name] = value
    observed["steps"].append(name)
    return value


def close_message_boxes():
    """A modal message box would hang the test: record its text and dismiss it."""
    for widget in QtGui.QApplication.topLevelWidgets():
        if isinstance(widget, QtGui.QMessageBox) and widget.isVisible():
            observed.setdefault("message_boxes", []).append(widget.text())
            widget.reject()


def screenshot(name, width=800, height=600):
    FreeCADGui.updateGui()
    path = os.path.join(ARTIFACTS, name)
    FreeCADGui.ActiveDocument.ActiveView.saveImage(path, width, height, "White")
    return path


def show_model(view):
    """A view from the front right, above: unlike the isometric view, the three visible faces of a box
    get different shading from the headlight."""
    view.setCameraOrientation(FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 35).multiply(
        FreeCAD.Rotation(FreeCAD.Vector(1, 0, 0), 60)))
    view.fitAll()
    FreeCADGui.updateGui()


def view_widget():
    return next(w for w in FreeCADGui.getMainWindow().findChildren(QtGui.QWidget)
                if w.metaObject().className().endswith("QuarterWidget") and w.isVisible())


def click(view, point):
    """A left click at the screen position of 3D `point`, sent to the view's widget like a real one."""
    FreeCADGui.updateGui()
    widget = view_widget()
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


def wait_until(condition, timeout_s=10.0):
    """Process events until condition() is true; the seconds it took (None on timeout)."""
    started = time.perf_counter()
    while not condition():
        if time.perf_counter() - started > timeout_s:
            return None
        QtGui.QApplication.processEvents()
        time.sleep(0.002)
    return time.perf_counter() - started


def redraw_seconds(view):
    """Seconds to draw one frame of the 3D view (software OpenGL under Xvfb: slow, whatever is shown)."""
    started = time.perf_counter()
    view.redraw()
    FreeCADGui.updateGui()
    return time.perf_counter() - started


def start_macro_recording(folder, name):
    """Macro > Macro recording..., as a user: the recorder's dialog gets a name and Record is pressed."""
    FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Macro").SetString("MacroPath", folder + os.sep)

    def fill_in():
        dialog = QtGui.QApplication.activeModalWidget()
        dialog.findChild(QtGui.QLineEdit, "lineEditPath").setText(name)
        dialog.findChild(QtGui.QPushButton, "buttonStart").click()

    QtCore.QTimer.singleShot(300, fill_in)
    FreeCADGui.runCommand("Std_DlgMacroRecord")  # modal: returns once Record was pressed
    FreeCADGui.updateGui()
    return os.path.join(folder, name + ".FCMacro")


def stop_macro_recording():
    FreeCADGui.runCommand("Std_MacroStopRecord")


class StatusSampler:
    """Samples the status bar every 50 ms of event processing: its message and whether FreeCAD's progress
    bar shows.  Samples only come while FreeCAD processes events, so their count also tells whether the
    window stayed alive during a long run."""

    def __init__(self):
        self.samples = []
        self.bar_first_seen = None  # time.perf_counter() of the first sample that saw the bar
        bars = FreeCADGui.getMainWindow().statusBar().findChildren(QtGui.QProgressBar)
        self._bars = bars
        self._timer = QtCore.QTimer()
        self._timer.timeout.connect(self.sample)
        self._timer.start(50)

    def sample(self):
        status = FreeCADGui.getMainWindow().statusBar()
        texts = [status.currentMessage()] + [w.text() for w in status.findChildren(QtGui.QLabel)]
        visible = any(b.isVisible() for b in self._bars)
        if visible and self.bar_first_seen is None:
            self.bar_first_seen = time.perf_counter()
        self.samples.append((" | ".join(t for t in texts if t), visible))

    def stop(self):
        self._timer.stop()
        return self.samples

    def messages(self):
        return sorted({m for m, _ in self.samples if m})

    def bar_seen(self):
        return any(visible for _, visible in self.samples)

    def bar_visible(self):
        return any(b.isVisible() for b in self._bars)


def report_view_text():
    """The text of FreeCAD's Report view (where console messages and recompute errors go)."""
    for widget in FreeCADGui.getMainWindow().findChildren(QtGui.QTextEdit):
        if widget.metaObject().className().endswith("ReportOutput"):
            return widget.toPlainText()
    return ""


def press_task_button(which):
    """Press OK or Cancel of the open task dialog, as a user would ("ok" / "cancel")."""
    standard = {"ok": QtGui.QDialogButtonBox.Ok, "cancel": QtGui.QDialogButtonBox.Cancel}[which]
    for box in FreeCADGui.getMainWindow().findChildren(QtGui.QDialogButtonBox):
        button = box.button(standard)
        if button is not None and button.isVisible():
            button.click()
            FreeCADGui.updateGui()
            return True
    return False


def type_into(box, text):
    """Type into a field as a user does: select what is there, type the keys (key events sent to the field's
    line edit, as the keyboard gives them).  No Enter: in a task panel it presses OK."""
    box.setFocus()
    line = box.findChild(QtGui.QLineEdit)
    line.selectAll()
    keys = [(QtCore.Qt.Key(ord(ch.upper())), ch) for ch in text]
    for key, char in keys:
        for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):
            QtGui.QApplication.sendEvent(line, QtGui.QKeyEvent(kind, key, QtCore.Qt.NoModifier, char))
    FreeCADGui.updateGui()
