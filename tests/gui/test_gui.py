"""The workbench in a real FreeCAD GUI under Xvfb: command, task panel, picks, preview, OK, edit, undo.

FreeCAD finds the workbench through a throw-away user folder: FREECAD_USER_HOME=<tmp> makes FreeCAD 0.20
use <tmp> as its user data folder, whose Mod/MeshRound is a symlink to this repository's Mod/MeshRound
(the real ~/.local/share/FreeCAD and its settings stay untouched).
Run with:  /usr/bin/python3 -m pytest tests/gui
"""
import json
import os
import signal
import subprocess

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
ARTIFACTS = os.path.join(REPO, "tests", "artifacts")
TIMEOUT_S = 120

@pytest.fixture(scope="module")
def observed(tmp_path_factory):
    home = tmp_path_factory.mktemp("freecad-home")
    os.makedirs(home / "Mod")
    os.symlink(os.path.join(REPO, "Mod", "MeshRound"), home / "Mod" / "MeshRound")
    os.makedirs(ARTIFACTS, exist_ok=True)
    for name in ("gui_rounded.png", "gui_preview.png"):
        if os.path.exists(os.path.join(ARTIFACTS, name)):
            os.remove(os.path.join(ARTIFACTS, name))
    result = home / "observed.json"
    env = dict(os.environ, FREECAD_USER_HOME=str(home), QTWEBENGINE_CHROMIUM_FLAGS="--no-sandbox",
               MESHROUND_GUI_RESULT=str(result), MESHROUND_GUI_ARTIFACTS=ARTIFACTS)
    run = run_in_own_session(["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "freecad",
                              os.path.join(HERE, "gui_macro.py")], env)
    assert result.exists(), (f"the macro wrote no result\nstdout:\n{run.stdout[-3000:]}"
                             f"\nstderr:\n{run.stderr[-3000:]}")
    data = json.loads(result.read_text())
    assert "error" not in data, data["error"]
    return data


def test_workbench_and_command(observed):
    assert observed["workbench"] == "MeshRoundWorkbench"
    assert observed["command_registered"]
    assert observed["panel_open"]
    assert observed["overlays_in_scene"] == [True, True]  # chain marks + preview layer


def test_scripted_pick_highlights_the_chain(observed):
    assert observed["scripted_seed_added"]
    assert observed["chain_lengths"] == pytest.approx([100.0])


def test_mouse_click_adds_a_seed_and_its_chain(observed):
    seeds = observed["seeds_after_click"]
    assert len(seeds) == 2
    x, y, z = seeds[1]
    assert z == pytest.approx(40.0, abs=1e-3) and y < 5  # on the top face, next to the front edge
    assert observed["chain_lengths_after_click"] == pytest.approx([100.0, 100.0])


def test_radius_point_mode(observed):
    (row,) = observed["law_rows_after_click"]
    assert row[2] == pytest.approx(40.0, abs=1e-3) and row[1] > 55 and row[3] == 4.0
    assert observed["radius_field_enabled_with_law"] is False
    assert observed["law_rows_after_remove"] == []


def test_errors_show_in_red_and_preview_works(observed):
    assert "radius" in observed["error_text"]
    assert "color" in observed["error_style"]
    assert observed["preview_report"]["chains"] == 2
    assert observed["status_text"].startswith("Preview:")


def test_accept_creates_the_feature(observed):
    feature = observed["feature"]
    assert observed["accepted"] and feature
    assert "Invalid" not in feature["state"]
    assert feature["radius"] == 4.0 and feature["seeds"] == 2
    assert feature["base_visible"] is False
    assert feature["children"] == ["Box", "RoundingSurfaces"]
    assert feature["base_transparency"] == 0  # the ghosting was undone
    assert feature["surfaces_visible"] is False  # in the tree, shown on demand
    assert observed["dialog_closed"] and observed["overlays_removed"]
    assert "Round edges" in observed["undo_names"]


def test_double_click_edits_and_undo_restores(observed):
    assert observed["edit_panel_open"] and observed["edit_panel_seeds"] == 2
    assert observed["edit_accepted"]
    edited = observed["edited"]
    assert edited["radius"] == 6.0 and edited["mesh_changed"] and not edited["editing"]
    assert "Invalid" not in edited["state"]
    assert observed["undone_radius"] == 4.0


def test_delete_removes_the_surfaces_child_and_shows_the_base(observed):
    assert observed["after_delete"] == {"objects": ["Box"], "base_visible": True}
    assert "message_boxes" not in observed  # no "referencing objects might break" warning


def test_screenshot_shows_the_model(observed):
    pixels = read_png(observed["screenshot"])
    assert pixels.shape[:2] == (600, 800)
    not_white = (pixels < 235).any(axis=2)
    assert 0.1 < not_white.mean() < 0.9  # a model fills part of the picture, not all of it
    centre = not_white[150:450, 200:600]
    assert centre.mean() > 0.5  # and it is in the middle (view fitted)
    # shaded: the visible faces of the box differ in brightness (not a flat silhouette)
    assert len(np.unique(pixels[150:450, 200:600].reshape(-1, 3), axis=0)) >= 3


def run_in_own_session(command, env):
    """Run command; on timeout kill its whole process group (xvfb-run, Xvfb and FreeCAD), not just
    xvfb-run, so a hung GUI cannot outlive the test."""
    process = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               start_new_session=True)
    try:
        stdout, stderr = process.communicate(timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        stdout, stderr = process.communicate()
        pytest.fail(f"FreeCAD did not finish within {TIMEOUT_S} s\nstdout:\n{stdout[-3000:]}")
    return subprocess.CompletedProcess(command, process.returncode, stdout, stderr)


def read_png(path):
    """(h, w, 3) uint8 pixels, decoded by Qt (PySide2 comes with FreeCAD)."""
    from PySide2.QtGui import QImage
    image = QImage(path)
    assert not image.isNull(), f"cannot read {path}"
    image = image.convertToFormat(QImage.Format_RGB888)
    height, width, stride = image.height(), image.width(), image.bytesPerLine()
    data = np.frombuffer(image.constBits(), np.uint8, count=height * stride)
    # copy: the buffer belongs to `image`, which is freed when this function returns
    return data.reshape(height, stride)[:, :width * 3].reshape(height, width, 3).copy()
