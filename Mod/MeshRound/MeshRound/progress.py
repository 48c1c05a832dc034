"""A progress indicator around long engine runs that keeps FreeCAD's window alive meanwhile.

    with progress.busy("Rounding edges of Die"):
        ...                                     # Python work, on the calling thread
        raw = progress.wait_for(core.round_edges, vertices, ...)   # the engine call itself

busy() starts FreeCAD's progress indicator (Base.ProgressIndicator: in the GUI the status-bar progress
bar, the status text and the wait cursor; nothing in a plain script).  wait_for() runs a function that
releases the GIL (the compiled engine does) on a worker thread when the GUI is up inside a busy() block,
and meanwhile, every STEP_S, steps the indicator and processes events: the window repaints, the bar
appears after FreeCAD's own delay (2 s) and moves, and the indicator's event filter (installed by start)
keeps the user from editing the document mid-run (clicks beep, keys are eaten; the engine cannot be
interrupted).
Only the function runs on the worker; everything touching FreeCAD objects stays on the calling thread.
Outside busy(), without the GUI, or when already waiting, the function is simply called.
"""
import contextlib
import threading

import FreeCAD

STEP_S = 0.05

_state = threading.local()  # .indicator: the open busy() block's (None outside); .waiting: in wait_for


@contextlib.contextmanager
def busy(text):
    """Show `text` with an indeterminate progress indicator while the block runs."""
    indicator = FreeCAD.Base.ProgressIndicator()
    indicator.start(text, 0)  # 0 steps: indeterminate, the engine reports no progress of its own
    outer = getattr(_state, "indicator", None)
    _state.indicator = indicator
    try:
        yield
    finally:
        _state.indicator = outer
        indicator.stop()


def wait_for(function, *args, **kwargs):
    """function(*args, **kwargs), on a worker thread with a live indicator when that helps (see above)."""
    indicator = getattr(_state, "indicator", None)
    if indicator is None or not FreeCAD.GuiUp or getattr(_state, "waiting", False):
        return function(*args, **kwargs)
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
            indicator.next()     # advances the bar (FreeCAD processes events only twice a second there)
            FreeCADGui.updateGui()  # so process them here: the window repaints, the bar shows
    finally:
        _state.waiting = False
    if "error" in outcome:
        raise outcome["error"]
    return outcome["value"]
