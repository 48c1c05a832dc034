"""Long engine runs that keep FreeCAD's window alive and can be cancelled with Esc.

    with progress.busy("Rounding edges of Die") as token:    # FreeCAD's progress indicator; Esc cancels
        ...                                                  # Python work, on the calling thread
        res = api.round_edges(mesh, seeds, r, cancel=token)  # the engine call runs on a worker thread

busy() starts FreeCAD's progress indicator (Base.ProgressIndicator: in the GUI the status-bar progress
bar, the status text and the wait cursor; nothing in a plain script) and yields a CancelToken for the
block's engine calls.  busy(text, indicator=False) (the task panel's preview) shows only a wait cursor
and leaves the window fully usable: keys and clicks reach the widgets meanwhile.

wait_for() runs a function that releases the GIL (the compiled engine does) on a worker thread when the
GUI is up inside a busy() block, and meanwhile, every STEP_S, steps the indicator and processes events:
the window repaints, the bar appears after FreeCAD's own delay (2 s) and moves.  The indicator's event
filter (installed by its start) keeps the user from editing the document mid-run (clicks beep, keys are
eaten), but Esc reaches a CancelWatch first: its filter goes in front of the indicator's.  Esc cancels
every token of the open busy() blocks; so does a click on one of the watch's cancel buttons (the task
panel's Cancel), and the watch remembers which it was.  A cancelled engine run raises RoundingError with
code "cancelled" within about 0.1 s.  FreeCAD's own Esc handling (a user break, then a "Do you really
want to abort?" question at the next indicator.next(True)) is never reached: the watch eats the Esc.
Only the function runs on the worker; everything touching FreeCAD objects stays on the calling thread.
Outside busy(), without the GUI, or when already waiting, the function is simply called.
"""
import contextlib
import threading

import FreeCAD

from .errors import CancelToken

STEP_S = 0.05

_state = threading.local()  # .runs: the open busy() blocks ([_Run]); .waiting: in wait_for
_watches = []  # the open CancelWatch blocks, innermost last (GUI thread only)


class _Run:
    def __init__(self, indicator, token):
        self.indicator, self.token = indicator, token


def _runs():
    if not hasattr(_state, "runs"):
        _state.runs = []
    return _state.runs


@contextlib.contextmanager
def busy(text, indicator=True):
    """Show `text` with a progress indicator (or only a wait cursor) while the block runs; yields the
    block's CancelToken (Esc cancels it in the GUI)."""
    token = CancelToken()
    progress = None
    if indicator:
        progress = FreeCAD.Base.ProgressIndicator()
        progress.start(text, 0)  # 0 steps: indeterminate, the engine reports no progress of its own
    watch = CancelWatch() if FreeCAD.GuiUp else contextlib.nullcontext()
    cursor = _wait_cursor() if FreeCAD.GuiUp and not indicator else contextlib.nullcontext()
    runs = _runs()
    runs.append(_Run(progress, token))
    try:
        with watch, cursor:  # the watch's filter now goes in front of the indicator's
            for outer in _watches:
                outer.front()
            yield token
    finally:
        runs.pop()
        if progress is not None:
            progress.stop()


def cancel_all():
    """Cancel the engine runs of every open busy() block (Esc does this in the GUI)."""
    for run in _runs():
        run.token.cancel()


def running():
    """True inside a busy() block."""
    return bool(_runs())


def wait_for(function, *args, **kwargs):
    """function(*args, **kwargs), on a worker thread with a live window when that helps (see above)."""
    runs = _runs()
    if not runs or not FreeCAD.GuiUp or getattr(_state, "waiting", False):
        return function(*args, **kwargs)
    indicator = runs[-1].indicator
    outcome = {}

    def work():
        try:
            outcome["value"] = function(*args, **kwargs)
        except BaseException as exc:  # handed to the caller's thread below
            outcome["error"] = exc

    import FreeCADGui
    worker = threading.Thread(target=work, name="MeshRound engine", daemon=True)
    _state.waiting = True
    try:
        worker.start()
        while True:
            worker.join(STEP_S)  # releases the GIL: the worker's Python parts run meanwhile
            if not worker.is_alive():
                break
            if indicator is not None:
                indicator.next()  # advances the bar (no user-break question: canAbort is False)
            FreeCADGui.updateGui()  # FreeCAD processes events only twice a second there: do it here
    finally:
        _state.waiting = False
    if "error" in outcome:
        raise outcome["error"]
    return outcome["value"]


class CancelWatch:
    """While open (GUI only): Esc, or a click on one of `buttons`, cancels the open busy() blocks' runs
    and is eaten (the task dialog does not see it: Esc does not close it, Cancel does not reject it
    mid-run).  `.by` says what cancelled: None, "esc" or "button"."""

    def __init__(self, buttons=()):
        self.buttons = list(buttons)
        self.by = None
        self._filter = None

    def __enter__(self):
        if FreeCAD.GuiUp:
            self._filter = _make_filter(self)
            _watches.append(self)
        return self

    def __exit__(self, *exc):
        if self._filter is not None:
            from PySide import QtGui
            QtGui.QApplication.instance().removeEventFilter(self._filter)
            _watches.remove(self)
            self._filter = None
        return False

    def front(self):
        """(Re)install the filter so that it acts before every filter installed so far."""
        if self._filter is not None:
            from PySide import QtGui
            QtGui.QApplication.instance().installEventFilter(self._filter)

    def cancel(self, by):
        for watch in _watches:  # whichever watch's filter saw it first, all of them know
            if watch.by is None:
                watch.by = by
        cancel_all()

    def is_cancel_button(self, widget):
        return any(widget is b or (b is not None and b.isAncestorOf(widget)) for b in self.buttons
                   if _alive(b))


def _make_filter(watch):
    from PySide import QtCore, QtGui

    class _Filter(QtCore.QObject):
        def eventFilter(self, obj, event):
            kind = event.type()
            if not running():
                return False
            if kind == QtCore.QEvent.KeyPress and event.key() == QtCore.Qt.Key_Escape:
                watch.cancel("esc")
                return True
            if kind == QtCore.QEvent.KeyRelease and event.key() == QtCore.Qt.Key_Escape:
                return True
            if kind in (QtCore.QEvent.MouseButtonPress, QtCore.QEvent.MouseButtonRelease,
                        QtCore.QEvent.MouseButtonDblClick) and isinstance(obj, QtGui.QWidget) \
                    and watch.is_cancel_button(obj):
                if kind == QtCore.QEvent.MouseButtonRelease:
                    watch.cancel("button")
                return True
            return False

    event_filter = _Filter()
    QtGui.QApplication.instance().installEventFilter(event_filter)
    return event_filter


def _alive(widget):
    try:
        import shiboken2
        return shiboken2.isValid(widget)
    except ImportError:
        return widget is not None


@contextlib.contextmanager
def _wait_cursor():
    from PySide import QtCore, QtGui
    QtGui.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
    try:
        yield
    finally:
        QtGui.QApplication.restoreOverrideCursor()
