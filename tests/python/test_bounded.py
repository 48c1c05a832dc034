"""Bounded work: every call rounds or refuses at a cost that follows the band.  Radii and tolerances
below what the mesh's float32-level coordinates can carry are refused (radius_too_small, naming the
smallest value that works), a rounding that would make more facets than the work budget is refused
(work_limit), and a radius control point far from the chain is refused before anything costly.  The
input is never touched.  (Times are measured by bench/bounded_cases.py, not asserted here.)"""
import re

import numpy as np
import pytest

import cases  # noqa: F401  (first: it puts FreeCAD's modules on the path)
import FreeCAD
import MeshRound
from MeshRound import api, meshconv, reround
import soundness
from conftest import BOX_SEED, grid_box


@pytest.fixture(scope="module")
def arrays(box):
    return meshconv.mesh_to_arrays(box)


def refused(arrays, code, seed=BOX_SEED, **kw):
    V, F = arrays
    V0, F0 = V.copy(), F.copy()
    with pytest.raises(MeshRound.RoundingError) as err:
        api.round_arrays(V, F, seed, **kw)
    assert err.value.code == code, str(err.value)
    assert np.array_equal(V, V0) and np.array_equal(F, F0)  # the input is untouched
    return str(err.value)


def smallest_value(message):
    return float(re.search(r"smallest \w+ that works is ([0-9.e+-]+) mm", message).group(1))


def test_radius_below_the_coordinates_precision_is_refused_naming_the_smallest_that_works(arrays):
    message = refused(arrays, "radius_too_small", radius=1e-4)
    smallest = smallest_value(message)
    assert smallest == pytest.approx(1e-2)  # 100 x 1e-6 x the box's largest coordinate (100 mm)
    res = api.round_arrays(*arrays, BOX_SEED, radius=5.0, tolerance=smallest * 10)
    assert res.report["facets_added"] > 0


def test_tolerance_below_the_coordinates_precision_is_refused_naming_the_smallest_that_works(arrays):
    message = refused(arrays, "radius_too_small", radius=5.0, tolerance=1e-7)
    assert smallest_value(message) == pytest.approx(1e-4)


def test_smallest_radius_of_a_radius_law_is_checked(arrays):
    refused(arrays, "radius_too_small", radius=[(FreeCAD.Vector(0, 60, 40), 4.0), (FreeCAD.Vector(100, 60, 40), 1e-3)])


def test_the_limits_follow_the_coordinates_magnitude(arrays):
    # The same box 100x smaller: its coordinates carry 100x smaller radii.
    V, F = arrays
    res = api.round_arrays(V / 100, F, BOX_SEED / 100, radius=0.05)
    assert res.report["facets_added"] > 0
    refused((V / 100, F), "radius_too_small", radius=5e-5)


def test_work_budget_refuses_before_running_away(arrays):
    message = refused(arrays, "work_limit", radius=5.0, max_new_facets=100)
    assert "max_new_facets" in message and "100" in message


def test_work_budget_counts_profile_stations(arrays):
    # r = 0.05 along a 100 mm edge: ~4000 stations (8000 facets' worth) before any surface is made.
    message = refused(arrays, "work_limit", radius=0.05, max_new_facets=5000)
    assert "profile stations" in message


def test_a_rounding_within_the_budget_is_made_and_counts_its_work(arrays):
    V, F = arrays
    full = api.round_arrays(V, F, BOX_SEED, radius=5.0)
    added = full.report["facets_added"]
    same = api.round_arrays(V, F, BOX_SEED, radius=5.0, max_new_facets=2 * added + 1000)
    assert same.report["facets_added"] == added
    assert np.array_equal(same.triangles, full.triangles)


@pytest.mark.parametrize("bad", [0, -5, 2.5, True])
def test_budget_must_be_a_positive_whole_number(arrays, bad):
    refused(arrays, "invalid_input", radius=5.0, max_new_facets=bad)


def test_control_point_far_from_the_chain_is_refused(arrays):
    message = refused(arrays, "invalid_input", radius=[(FreeCAD.Vector(0, 60, 40), 4.0), (FreeCAD.Vector(37, 60, 3040), 6.0)])
    assert "3000 mm from the chain" in message


def test_radius_far_below_the_element_size_rounds_soundly(arrays):
    # r = 0.05 on elements of ~2 mm: allowed, within the default budget.
    res = api.round_arrays(*arrays, BOX_SEED, radius=0.05)
    rep = res.report
    assert 0 < rep["facets_added"] < 2_000_000
    assert rep["max_deviation"] <= 0.05 / 100 * 1.01


def test_the_smallest_radius_that_works_makes_a_sound_mesh_as_stored():
    # A 10 mm length of the box's edge on a structured grid: 0.006 mm is its smallest radius (100 x 1e-6 x
    # 60 mm). The end caps are facets of a few thousandths of a mm cut into the end faces' 2 mm facets,
    # checked as FreeCAD stores them (float32) and confirmed exactly (soundness).
    V, F = grid_box(2.0, (10.0, 60.0, 40.0))
    seed = FreeCAD.Vector(5, 60, 40)
    refused((V, F), "radius_too_small", seed, radius=0.0059)
    radius = 0.006
    res = api.round_arrays(V, F, seed, radius=radius)
    assert soundness.problems(V, F, res.vertices, res.triangles) == []
    # and from that round to a larger one, and back to the smallest
    larger = reround.change_radius_arrays(res.vertices, res.triangles, seed, radius=2.0)
    assert soundness.problems(V, F, larger.vertices, larger.triangles) == []
    again = reround.change_radius_arrays(larger.vertices, larger.triangles, seed, radius=radius)
    assert soundness.problems(V, F, again.vertices, again.triangles) == []
