"""Cancelling a run through the API: MeshRound.round_edges / round_arrays(..., cancel=token), and
token.cancel() from another thread (threading.Timer, as the GUI's Esc does from the event loop).

The run stops with RoundingError code "cancelled"; the input mesh is as it was.  The latency (from
cancel() to the exception in the caller) is recorded in tests/artifacts/cancel_latency.json; the engine
polls every few milliseconds, so 0.5 s leaves a wide margin even on a loaded machine.
"""
import json
import os
import threading
import time

import numpy as np
import pytest

import cases
import die_meshes

import MeshRound
from MeshRound import api

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ARTIFACTS = os.path.join(REPO, "tests", "artifacts")
LATENCIES = os.path.join(ARTIFACTS, "cancel_latency.json")
LATENCY_BOUND_S = 0.5


def record(key, value):
    os.makedirs(ARTIFACTS, exist_ok=True)
    try:
        with open(LATENCIES) as stream:
            data = json.load(stream)
    except (OSError, ValueError):
        data = {}
    data[key] = value
    with open(LATENCIES, "w") as stream:
        json.dump(data, stream, indent=1)


def cancelled_run(call, after_s, tries=4):
    """call(token) with token.cancel() from a timer thread after_s seconds in; returns (the error, the
    seconds from cancel() to the error reaching this thread).  A run that ends before the request (the
    machine was less loaded than when its length was measured) is made again with the request at half
    the time, up to tries runs in all."""
    for _ in range(tries):
        token = MeshRound.CancelToken()
        fired = {}

        def fire():
            fired["at"] = time.perf_counter()
            token.cancel()

        timer = threading.Timer(after_s, fire)
        timer.start()
        try:
            call(token)
        except MeshRound.RoundingError as exc:
            caught = time.perf_counter()
            timer.join()
            assert "at" in fired, f"the run failed before the request: {exc}"
            return exc, caught - fired["at"]
        finally:
            timer.cancel()
        after_s *= 0.5
    pytest.fail(f"the run was not cancelled in {tries} tries (the last with the request {2 * after_s:.2f} s in)")


@pytest.fixture(scope="module")
def big_die():
    vertices, triangles, seeds = die_meshes.die_arrays(11)  # 1.1M facets
    return vertices, triangles, seeds[0]


def test_a_token_cancelled_before_the_call_is_refused_at_once(box):
    token = MeshRound.CancelToken()
    assert not token.is_cancelled
    token.cancel()
    assert token.is_cancelled and "cancelled" in repr(token)
    started = time.perf_counter()
    with pytest.raises(MeshRound.RoundingError) as info:
        MeshRound.round_edges(box, [(37, 60, 40)], 5.0, cancel=token)
    assert info.value.code == "cancelled" and str(info.value) == "the rounding was cancelled"
    assert time.perf_counter() - started < 0.1


def test_cancel_must_be_a_token(box):
    with pytest.raises(MeshRound.RoundingError) as info:
        MeshRound.round_edges(box, [(37, 60, 40)], 5.0, cancel=True)
    assert info.value.code == "invalid_input" and "CancelToken" in str(info.value)


def test_a_token_never_cancelled_changes_nothing(box):
    plain = MeshRound.round_edges(box, [(37, 60, 40)], 5.0)
    with_token = MeshRound.round_edges(box, [(37, 60, 40)], 5.0, cancel=MeshRound.CancelToken())
    assert np.array_equal(plain.vertices, with_token.vertices)
    assert np.array_equal(plain.triangles, with_token.triangles)


def test_cancel_from_another_thread_stops_a_run_on_a_1m_facet_die(big_die):
    vertices, triangles, seed = big_die
    kept = vertices.copy(), triangles.copy()
    full = float("inf")  # the warm run's time: a first run (cold caches) can take half as long again
    for _ in range(2):
        started = time.perf_counter()
        api.round_arrays(vertices, triangles, [seed], 5.0)
        full = min(full, time.perf_counter() - started)
    latencies = {}
    for share in (0.3, 0.7):
        error, latency = cancelled_run(
            lambda token: api.round_arrays(vertices, triangles, [seed], 5.0, cancel=token), share * full)
        assert error.code == "cancelled"
        latencies[f"at_{int(share * 100)}pct_s"] = round(latency, 4)
    assert np.array_equal(vertices, kept[0]) and np.array_equal(triangles, kept[1])  # input untouched
    record("api_1m_facet_die", {"facets": len(triangles), "uncancelled_run_s": round(full, 3), **latencies})
    assert max(latencies.values()) < LATENCY_BOUND_S, latencies


def test_cancel_reaches_the_room_probe():
    """The acute ridge's CAD mesh at r = 2 makes thin facets, so the engine rounds the chain again at
    wider reaches (the room probe, most of the run): a request then still stops the run."""
    case = cases.Case("acute_ridge_r2", cases.acute_ridge, 2.0)
    mesh = case.mesh("cad")
    points_before = [tuple(p) for p in mesh.Topology[0]]
    started = time.perf_counter()
    full_run = MeshRound.round_edges(mesh, [case.seed], 2.0, tolerance=case.tolerance)
    full = time.perf_counter() - started
    room_s = full_run.report["seconds_per_pass"].get("room", 0.0)
    assert room_s > 0.5 * full_run.report["seconds_total"], full_run.report["seconds_per_pass"]
    error, latency = cancelled_run(
        lambda token: MeshRound.round_edges(mesh, [case.seed], 2.0, tolerance=case.tolerance, cancel=token),
        full - 0.6 * room_s)  # well inside the probe
    assert error.code == "cancelled"
    assert [tuple(p) for p in mesh.Topology[0]] == points_before
    record("api_room_probe_acute_ridge", {"uncancelled_run_s": round(full, 3), "room_probe_s": round(room_s, 3),
                                          "latency_s": round(latency, 4)})
    assert latency < LATENCY_BOUND_S
