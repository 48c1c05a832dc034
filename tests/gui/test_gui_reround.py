"""Changing the radius of an existing round in the real FreeCAD GUI under Xvfb (gui_reround.py, run by
gui_macro.py with MESHROUND_GUI_STEPS=reround): the Change round radius command opens the task panel in its
"Existing round" mode; a click on the round shows the found radius and highlights the round's facets; a
click on a flat face is refused in red; the preview and OK at the new radius.
Run with:  /usr/bin/python3 -m pytest tests/gui/test_gui_reround.py
"""
import os

import pytest

from test_gui import freecad_home, read_png, run_gui_macro


@pytest.fixture(scope="module")
def observed(tmp_path_factory):
    return run_gui_macro(freecad_home(tmp_path_factory, "freecad-home-reround"), MESHROUND_GUI_STEPS="reround")


def test_the_command_opens_the_panel_in_existing_round_mode(observed):
    opened = observed["opened"]
    assert opened["pick"] == "Existing round" and opened["title"] == "Change round radius"
    assert opened["status"].startswith("Click on an existing round")


def test_a_click_on_the_round_shows_its_radius_and_highlights_it(observed):
    picked = observed["picked"]
    (seed,) = picked["seeds"]
    assert seed[0] == pytest.approx(30, abs=1.0) and seed[1] < 5 and seed[2] > 25  # on the round
    assert picked["found"] == "Found radius: 5 mm"
    assert "c00000" not in picked["status_style"]
    (facets,) = picked["strip_facets"]
    assert facets > 50 and picked["listed_facets"] == facets and picked["highlighted_facets"] == facets
    pixels = read_png(observed["highlight_screenshot"]).astype(int)
    r, g, b = pixels[..., 0], pixels[..., 1], pixels[..., 2]
    magenta = (r > 180) & (g < 90) & (b > 130)
    assert magenta.sum() > 500, magenta.sum()


def test_a_click_on_a_flat_face_is_refused_in_red(observed):
    flat = observed["flat_face"]
    assert flat["seeds"] == 1
    assert flat["status"].startswith("Seed not added: not_a_round: ") and "flat face" in flat["status"]
    assert "c00000" in flat["style"]


def test_the_preview_and_ok_change_the_radius(observed):
    preview = observed["preview"]
    assert preview["found_radius"] == [pytest.approx(5.0, rel=0.01)]
    assert preview["status"].startswith("Preview:")
    made = observed["made"]
    assert made["operation"] == "Change radius of existing round" and made["radius"] == 8.0
    assert made["found"] == [pytest.approx(5.0, rel=0.01)] and "Invalid" not in made["state"]
    assert made["panel_closed"] and made["icon"].endswith("MeshRound_ChangeRadius.svg")
    assert observed["edit"] == {"pick": "Existing round", "found": "Found radius: 5 mm"}
    assert os.path.isfile(observed["preview_screenshot"])
