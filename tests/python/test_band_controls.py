"""Band element controls (round_edges(band=...), round_deck, the CLI, the Rounding feature) and the band's
quality report as CAE checks it.

The box's top back edge (y = 60, z = 40) rounded with r = 5 is a quarter cylinder about the line y = 55,
z = 35: each new facet on it is measured by hand here (its angle about the axis, its length along x)
against what the control asked for, and the same call without the control must miss it (so the test can
fail).  The quality figures are recomputed here with numpy from the written facets and elements, and the
rounded geometry is scored against OCCT's fillet of the box both ways (reference.py).
"""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import cases  # noqa: F401  (first: it puts FreeCAD's modules on the path)
import deck_files
import reference
import soundness
from conftest import BOX_SEED, MOD_DIR, grid_box
from MeshRound import api, decks
from MeshRound.errors import RoundingError, require_core

R = 5.0
AXIS_YZ = np.array([55.0, 35.0])


def round_facets(result):
    """(points (k, 3, 3) of the new facets lying on the quarter cylinder, all new facets' points)."""
    V, F = result.vertices, result.triangles
    new = F[len(F) - len(result.delta["added"]):]
    P = V[new]
    off = np.linalg.norm(P[..., 1:] - AXIS_YZ, axis=2)
    on = np.all((np.abs(off - R) < 0.06) & (P[..., 1] > 54.999) & (P[..., 2] > 34.999), axis=1)
    return P[on], P


def angular_extent_deg(P):
    """Each facet's spread about the cylinder's axis (degrees)."""
    a = np.degrees(np.arctan2(P[..., 2] - AXIS_YZ[1], P[..., 1] - AXIS_YZ[0]))
    return a.max(axis=1) - a.min(axis=1)


def length_along(P):
    return P[..., 0].max(axis=1) - P[..., 0].min(axis=1)


@pytest.fixture(scope="module")
def grid():
    return grid_box(2.0)


def rounded(grid, band):
    V, F = grid
    res = api.round_arrays(V, F, BOX_SEED, R, band=band)
    assert soundness.problems(V, F, res.vertices, res.triangles) == []
    return res


def test_element_angle_bounds_each_element_across(grid):
    default, _ = round_facets(rounded(grid, None))
    assert angular_extent_deg(default).max() > 10.5   # the chordal tolerance alone: 8 elements over 90 deg
    for step in (10.0, 5.0):
        res = rounded(grid, dict(max_element_angle=step))
        on, _ = round_facets(res)
        assert len(on) > 100
        assert angular_extent_deg(on).max() <= step + 1e-6
        assert res.report["per_chain"][0]["profile_rows"] == math.ceil(90 / step) + 1
        assert res.report["max_deviation"] <= R / 100


def test_element_length_sets_the_step_along(grid):
    default, _ = round_facets(rounded(grid, None))
    # the trim lines' own spacing: the 2 mm grid's facets cut by the contact lines, 1 mm apart
    assert length_along(default).max() == pytest.approx(1.0) and np.median(length_along(default)) == pytest.approx(1.0)
    on, _ = round_facets(rounded(grid, dict(element_length=0.5)))
    assert length_along(on).max() <= 0.5 + 1e-6
    # Coarser than the input: the inner rows are 2.4 mm apart (within the built-in shape bound of 2.5 steps
    # across); only the rows beside the trim lines keep their 1 mm points.
    on, _ = round_facets(rounded(grid, dict(element_length=2.4)))
    assert np.median(length_along(on)) > 2.0


def test_aspect_ratio_with_a_length_refines_across(grid):
    res = rounded(grid, dict(element_length=0.5, max_aspect_ratio=1.5))
    on, _ = round_facets(res)
    # across <= 1.5 x 0.5 mm = 0.75 mm on r = 5: at most 8.6 deg per element
    assert angular_extent_deg(on).max() <= math.degrees(0.75 / R) + 1e-6
    assert length_along(on).max() <= 0.5 + 1e-6
    # and without a length, along <= ratio x across (0.98 mm across here)
    on, _ = round_facets(rounded(grid, dict(max_aspect_ratio=1.0)))
    across = math.radians(90 / 8) * R
    assert length_along(on).max() <= 1.0 * across + 1e-6


def numpy_quality(P):
    """Smallest/largest angle, aspect ratio (longest / shortest side), shortest side of triangles P (k, 3, 3)."""
    e = [P[:, (i + 1) % 3] - P[:, i] for i in range(3)]
    sides = np.stack([np.linalg.norm(x, axis=1) for x in e], axis=1)
    angles = []
    for i in range(3):
        a, b = -e[(i + 2) % 3], e[i]
        angles.append(np.degrees(np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))))
    angles = np.stack(angles, axis=1)
    return dict(min_angle_deg=angles.min(), max_angle_deg=angles.max(),
                max_aspect_ratio=(sides.max(axis=1) / sides.min(axis=1)).max(), min_side=sides.min())


@pytest.mark.parametrize("band", [None, dict(max_element_angle=10)])
def test_report_gives_the_band_quality(grid, band):
    res = rounded(grid, band)
    q = res.report["band_quality"]
    _, new = round_facets(res)
    assert q["elements"] == len(new) == res.report["facets_added"] and q["quads"] == 0
    for key, value in numpy_quality(new).items():
        assert q[key] == pytest.approx(value, rel=1e-9, abs=1e-9), key


def test_element_quality_of_known_elements():
    core = require_core()
    h = 0.2
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, h], [0, 1, 0], [3, 0, 0], [3, 4, 0], [1, 1, 0]], float)
    flat_square = core.element_quality(points[[0, 1, 6, 3]], np.array([[0, 1, 2, 3]]))
    assert flat_square["min_angle_deg"] == pytest.approx(90) and flat_square["max_angle_deg"] == pytest.approx(90)
    assert flat_square["max_aspect_ratio"] == pytest.approx(1) and flat_square["max_warpage_deg"] == pytest.approx(0)
    warped = core.element_quality(points, np.array([[0, 1, 2, 3]]))
    # split on 0-2: normals (-h, 0, 1) and (0, -h, 1) -> acos(1 / (1 + h^2)); on 1-3 the same by symmetry
    assert warped["max_warpage_deg"] == pytest.approx(math.degrees(math.acos(1 / (1 + h * h))), rel=1e-9)
    triangle = core.element_quality(points, np.array([[0, 4, 5, -1]]))  # the 3-4-5 right triangle
    assert triangle["min_angle_deg"] == pytest.approx(math.degrees(math.atan2(3, 4)))
    assert triangle["max_angle_deg"] == pytest.approx(90)
    assert triangle["max_aspect_ratio"] == pytest.approx(5 / 3) and triangle["min_side"] == pytest.approx(3)
    assert triangle["quads"] == 0 and warped["quads"] == 1
    with pytest.raises(RoundingError, match="refers to point 9"):
        core.element_quality(points, np.array([[0, 1, 9, -1]]))


@pytest.mark.parametrize("variant", ["coarse", "cad"])
def test_controls_match_occt_fillet_both_ways(variant):
    case = cases.Case(f"band_box_{variant}", cases.box, R)
    inp = case.mesh(variant)
    res = api.round_edges(inp, case.seed, R, band=dict(max_element_angle=10, element_length=1.5, max_aspect_ratio=2))
    row = reference.score(case, inp, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= reference.allowed_deviation(row) <= 0.0125
    assert row["dev_ref_to_out"] <= reference.allowed_deviation(row)
    assert soundness.problems(*reference.mesh_arrays(inp), *reference.mesh_arrays(res.mesh)) == []


@pytest.mark.parametrize("band, words", [
    (dict(max_element_angle=-1), "largest element angle"),
    (dict(max_element_angle=91), "largest element angle"),
    (dict(element_length=-0.1), "element length"),
    (dict(element_length=float("nan")), "element length"),
    (dict(max_aspect_ratio=0.5), "largest aspect ratio"),
    (dict(max_spacing=2), "unknown band element control"),
    ("fine", "band must be a dict"),
])
def test_bad_controls_are_refused_by_name(grid, band, words):
    V, F = grid
    V0, F0 = V.copy(), F.copy()
    with pytest.raises(RoundingError, match=words) as err:
        api.round_arrays(V, F, BOX_SEED, R, band=band)
    assert err.value.code == "invalid_input"
    assert np.array_equal(V, V0) and np.array_equal(F, F0)


@pytest.mark.parametrize("band", [dict(max_element_angle=1e-3), dict(element_length=1e-4),
                                  dict(max_aspect_ratio=1, element_length=1e-3)])
def test_tiny_elements_are_refused_before_the_work(grid, band):
    V, F = grid
    with pytest.raises(RoundingError, match="rows and columns at its element steps") as err:
        api.round_arrays(V, F, BOX_SEED, R, band=band)
    assert err.value.code == "work_limit"


# ------------------------------------------------------------------------------------------- decks
@pytest.fixture(scope="module")
def quad_deck(tmp_path_factory):
    xyz, quads, faces = deck_files.box_quads((60.0, 40.0, 30.0), 2.5)
    folder = tmp_path_factory.mktemp("band_deck")
    return deck_files.write_deck(str(folder), "lsdyna_fixed", xyz, quads, faces, np.array([0]), np.array([1]),
                                 np.array([0]))


def new_elements(before, after):
    """(points (e, 4, 3) with the 4th = the 1st for a triangle, is_quad (e,)) of the elements after has
    that before had not."""
    new = ~np.isin(after["shell_ids"], before["shell_ids"])
    nodes = after["shell_nodes"][new]
    quad = after["shell_counts"][new] == 4
    nodes = np.where(quad[:, None], nodes, nodes[:, [0, 1, 2, 0]])
    return after["node_xyz"][nodes], quad


def test_deck_band_quality_and_controls(quad_deck, tmp_path):
    before = decks.read_deck(quad_deck)
    seed = (37.0, 40.0, 30.0)
    plain = decks.round_deck(quad_deck, str(tmp_path / "plain.k"), [seed], R)
    fine = decks.round_deck(quad_deck, str(tmp_path / "fine.k"), [seed], R,
                            band=dict(max_element_angle=10, element_length=1.25))
    for res, path in ((plain, "plain.k"), (fine, "fine.k")):
        q = res.report["deck"]["quality"]
        P, quad = new_elements(before, decks.read_deck(str(tmp_path / path)))
        assert q["elements"] == len(P) and q["quads"] == int(quad.sum()) == res.report["deck"]["new_quads"]
        sides = np.linalg.norm(np.roll(P, -1, axis=1) - P, axis=2)
        sides = np.where(quad[:, None], sides, np.c_[sides[:, :3], np.full(len(P), np.nan)])
        assert q["min_side"] == pytest.approx(np.nanmin(sides), rel=1e-6)   # the deck's text rounds coordinates
        assert q["max_aspect_ratio"] == pytest.approx(np.nanmax(np.nanmax(sides, 1) / np.nanmin(sides, 1)), rel=1e-5)
        assert q["max_warpage_deg"] <= decks.QuadOptions().max_warp + 1e-6
        assert res.report["deck"]["new_quad_share"] > 0.6
    # ten degrees across: more elements than the chordal tolerance's eight over the quarter circle
    assert fine.report["deck"]["new_quads"] > plain.report["deck"]["new_quads"]
    triangles = decks.round_deck(quad_deck, str(tmp_path / "tri.k"), [seed], R,
                                 quad_options=decks.QuadOptions(quads=False))
    assert triangles.report["deck"]["quality"]["quads"] == 0 and triangles.report["deck"]["new_quads"] == 0


def test_cli_takes_the_controls_and_prints_the_quality(quad_deck, tmp_path):
    def meshround(*args):
        env = dict(os.environ, PYTHONPATH=MOD_DIR)
        return subprocess.run(["/usr/bin/python3", "-m", "MeshRound.cli", *map(str, args)], capture_output=True,
                              text=True, env=env, timeout=120)
    out, report = tmp_path / "out.k", tmp_path / "out.json"
    run = meshround("round", quad_deck, out, "--seed", "37,40,30", "--radius", R, "--element-angle", 10,
                    "--element-length", 1.25, "--max-aspect", 3, "--report", report)
    assert run.returncode == 0, run.stderr
    q = json.loads(report.read_text())["deck"]["quality"]
    assert f"band elements: {q['elements']} ({q['quads']} quads)" in run.stdout
    run = meshround("round", quad_deck, tmp_path / "tri.k", "--seed", "37,40,30", "--radius", R, "--triangles")
    assert run.returncode == 0 and "(0 quads)" in run.stdout, run.stderr
    run = meshround("round", quad_deck, tmp_path / "bad.k", "--seed", "37,40,30", "--radius", R, "--max-aspect", 0.5)
    assert run.returncode == 2 and "largest aspect ratio" in run.stderr
    assert not (tmp_path / "bad.k").exists()


def test_feature_properties_drive_the_band(doc, box_feature):
    from MeshRound.objects.rounding import make_rounding
    obj = make_rounding(box_feature, [BOX_SEED], R)
    doc.recompute()
    plain = int(obj.Statistics["band_elements"])
    obj.ElementAngle = 5.0
    doc.recompute()
    assert obj.isValid(), obj.getStatusString()
    assert int(obj.Statistics["band_elements"]) > plain
    assert float(obj.Statistics["band_min_angle_deg"]) > 0
    obj.MaxAspectRatio = 0.5
    doc.recompute()
    assert not obj.isValid() and "aspect ratio" in obj.getStatusString()
