"""A solver deck in the real FreeCAD GUI under Xvfb (gui_deck.py, run by gui_macro.py with
MESHROUND_GUI_STEPS=deck): opened by File > Open's path, drawn as quads with their edges, a part hidden and
shown, a click that seeds a Rounding through the Round edges command, the Rounding exported as the deck.
Run with:  /usr/bin/python3 -m pytest tests/gui/test_gui_deck.py
"""
import json
import os

import sys

import numpy as np
import pytest

from test_gui import REPO, TIMINGS, freecad_home, read_png, run_gui_macro

sys.path.append(os.path.join(REPO, "tests", "python"))
import deck_files  # noqa: E402

QUADS = 2 * (24 * 16 + 16 * 12 + 24 * 12)   # the 60 x 40 x 30 box at h = 2.5
TOP_QUADS = 24 * 16                          # part 2, the top face


@pytest.fixture(scope="module")
def observed(tmp_path_factory):
    return run_gui_macro(freecad_home(tmp_path_factory, "freecad-home-deck"), MESHROUND_GUI_STEPS="deck")


def test_file_open_makes_a_deck_with_its_parts(observed):
    assert observed["commands"] == ["MeshRound_RoundEdges", "MeshRound_ExportDeck"]
    assert observed["import_modules"] == ["MeshRound.deck_import"]
    opened = observed["opened"]
    assert opened["document"] == "box" and opened["label"] == "box.k"
    assert "Invalid" not in opened["state"]
    assert opened["quads"] == QUADS and opened["triangles"] == 0
    assert opened["parts"] == [f"1 die body: {QUADS - TOP_QUADS} elements ({QUADS - TOP_QUADS} quads, 0 triangles)",
                               f"2 die top: {TOP_QUADS} elements ({TOP_QUADS} quads, 0 triangles)"]
    assert opened["display_mode"] == "Quads"
    assert opened["children"] == ["DeckPart", "DeckPart001"]


def test_quads_are_drawn_as_quads_with_their_edges_and_no_diagonals(observed):
    scene = observed["scene"]
    assert scene["in_scene_and_shown"]  # under the Deck's root, the display mode switched on
    assert scene["face_sets"] == 2 and scene["line_sets"] == 2  # one of each per part
    assert scene["polygon_corners"] == {"3": 0, "4": QUADS}      # every element one 4-corner polygon
    assert scene["diagonal_segments"] == 0 and scene["segments_not_sides"] == 0
    # every side once, but the sides on the boundary between the two parts, drawn by both
    assert scene["unique_segments"] == scene["element_sides"]
    assert scene["segments"] == scene["element_sides"] + 2 * (24 + 16)


def test_the_picture_shows_quads_with_their_edges(observed):
    pixels = read_png(observed["deck_screenshot"]).astype(int)
    dark = pixels.max(axis=2) < 80              # the edge lines
    model = (pixels < 235).any(axis=2)
    assert 0.15 < model.mean() < 0.9
    assert 0.05 < dark[model].mean() < 0.6, dark[model].mean()  # a grid of lines over the faces
    hidden = read_png(observed["top_hidden_screenshot"]).astype(int)
    changed = np.abs(hidden - pixels).max(axis=2) > 30
    assert changed.mean() > 0.03  # hiding the top face part changes a good part of the picture


def test_a_part_is_hidden_and_shown_by_its_child(observed):
    assert observed["top_hidden"] == {"switches": {"1": 0, "2": -1}, "visible": False}
    shown = observed["top_shown"]
    assert shown["switches"] == {"1": 0, "2": 0}
    assert shown["top_color"] == pytest.approx([0.9, 0.2, 0.2])


def test_a_click_on_the_deck_seeds_the_round_edges_command(observed):
    (name, subs, points), = observed["click_selection"]
    assert name == "Deck"
    x, y, z = points[0]
    assert z == pytest.approx(30.0, abs=1e-3) and y == pytest.approx(38.8, abs=0.3)
    # the element named is the one clicked: the deck's k-th element (the file's order), whose first
    # triangle is the Deck mesh's facet k
    xyz, quads, _ = deck_files.box_quads((60.0, 40.0, 30.0), 2.5)
    corners = xyz[quads[int(subs[0][len("Facet"):])]]
    assert np.all(corners.min(axis=0) - 1e-6 <= points[0]) and np.all(points[0] <= corners.max(axis=0) + 1e-6)
    panel = observed["panel"]
    assert panel["open"] and panel["base"] == "Deck" and len(panel["seeds"]) == 1
    assert panel["chain_lengths"] == pytest.approx([60.0])  # the whole top back edge
    assert panel["ghost_transparency"] == [0.7, 0.7]  # the deck ghosted, as any base


def test_ok_makes_a_rounding_on_the_deck_that_exports_as_the_deck(observed):
    rounding = observed["rounding"]
    assert "Invalid" not in rounding["state"] and rounding["base"] == "Deck"
    assert rounding["solid"] and rounding["facets"] > 2 * QUADS
    assert rounding["deck_visible"] is False and rounding["transparency_after"] == [0.0, 0.0]
    assert observed["export_command_active"]
    export = observed["export"]
    assert export["same_as_round_deck"] and export["new_quads"] > 0
    rounded = observed["rounded_deck"]  # the exported deck opens as a Deck again, its new quads drawn as quads
    assert rounded["quads"] > QUADS and rounded["display_mode"] == "Quads"


def test_a_saved_deck_reopens_drawn_with_its_parts_as_they_were(observed):
    reopened = observed["reopened"]
    assert reopened["proxy"] == "MeshRound.viewproviders.deck.ViewProviderDeck"
    assert reopened["display_mode"] == "Quads" and reopened["polygons"] == QUADS
    assert reopened["switches"] == {"1": 0, "2": -1}
    assert reopened["top_color"] == pytest.approx([0.2, 0.6, 0.3], abs=0.005)  # stored as 8-bit


def test_a_100k_element_deck_opens_and_draws(observed):
    large = observed["large"]
    assert large["elements"] > 95_000 and large["quads"] == large["elements"] == large["polygons"]
    try:
        with open(TIMINGS) as stream:
            timings = json.load(stream)
    except (OSError, ValueError):
        timings = {}
    timings["gui_deck_100k"] = large
    with open(TIMINGS, "w") as stream:
        json.dump(timings, stream, indent=1)
