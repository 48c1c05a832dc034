"""FreeCAD GUI macro run by test_gui.py:  xvfb-run -a freecad gui_macro.py

It drives the workbench as a user would (real mouse clicks and the task dialog's own OK/Cancel buttons
where it matters), records what it observes in $MESHROUND_GUI_RESULT (JSON), saves screenshots in
$MESHROUND_GUI_ARTIFACTS, and quits.  Every step is recorded, so a failing step shows in the JSON instead
of hanging the test.  The steps are in gui_box.py (the workflow on a box), gui_die.py (progress, and
the preview's speed on a 147k-facet die) and gui_cancel.py (Esc and Cancel during long runs); with
MESHROUND_GUI_STEPS=deck, only gui_deck.py (a solver deck opened, drawn, rounded, exported); with
MESHROUND_GUI_STEPS=reround, only gui_reround.py (the radius of an existing round changed).
"""
import json
import os
import sys
import traceback

HERE = os.environ["MESHROUND_GUI_DIR"]
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path[:0] = [HERE, os.path.join(REPO, "tests", "python")]  # the steps; the die meshes

from PySide import QtCore  # noqa: E402

import gui_support  # noqa: E402

RESULT = os.environ["MESHROUND_GUI_RESULT"]

guard = QtCore.QTimer()
guard.timeout.connect(gui_support.close_message_boxes)
guard.start(100)
try:
    if os.environ.get("MESHROUND_GUI_STEPS") == "deck":  # test_gui_deck.py: the solver deck steps alone
        import gui_deck
        gui_deck.run(os.path.dirname(RESULT))
    elif os.environ.get("MESHROUND_GUI_STEPS") == "reround":  # test_gui_reround.py: the existing-round mode
        import gui_reround
        gui_reround.run()
    else:
        import gui_box
        import gui_cancel
        import gui_die
        gui_box.run(os.path.dirname(RESULT))
        gui_die.run()
        gui_cancel.run()
except Exception:
    gui_support.observed["error"] = traceback.format_exc()
finally:
    with open(RESULT, "w") as stream:
        json.dump(gui_support.observed, stream, indent=1, default=str)
    os._exit(0)  # quit FreeCAD at once: no "save changes?" dialog, no session restore
