"""A busy indicator around long engine runs (status-bar progress in the GUI, a line on the console)."""
import contextlib

import FreeCAD


@contextlib.contextmanager
def busy(text):
    """Show `text` with an indeterminate progress indicator while the block runs."""
    indicator = FreeCAD.Base.ProgressIndicator()
    indicator.start(text, 0)  # 0 steps: indeterminate, the engine reports no progress of its own
    try:
        yield
    finally:
        indicator.stop()
