"""MeshRound.round_edges / trace_chains: results, immutability of the input, every bad input, the speed
beyond the engine on 1M facets, and `import MeshRound` in freecadcmd and plain /usr/bin/python3 scripts."""
import json
import math
import os
import re
import subprocess
import time

import numpy as np
import pytest

import FreeCAD
import Mesh
import Part

import MeshRound
from MeshRound import meshconv
from conftest import BOX_OTHER_SEED, BOX_RADIUS, BOX_SEED, MOD_DIR, REPO

import cases  # noqa: E402  (tests/python: the accuracy suite's CAD cases)
import die_meshes  # noqa: E402

TIMINGS = os.path.join(REPO, "tests", "artifacts", "workbench_timings.json")

REPORT_KEYS = {"chains", "facets_removed", "facets_added", "max_deviation", "min_new_angle_deg",
               "seconds", "facets_in", "facets_out"}


@pytest.fixture(scope="module")
def rounded(box):
    return MeshRound.round_edges(box, BOX_SEED, BOX_RADIUS)


def near_edge(points, y=60.0, z=40.0, distance=2 * BOX_RADIUS):
    """Which points lie within `distance` of the line y = y, z = z."""
    return np.hypot(points[:, 1] - y, points[:, 2] - z) < distance


def test_result_mesh_changes_only_near_the_edge(box, rounded):
    assert isinstance(rounded.mesh, Mesh.Mesh)
    before, _ = meshconv.mesh_to_arrays(box)
    after, _ = meshconv.mesh_to_arrays(rounded.mesh)
    assert rounded.mesh.CountFacets != box.CountFacets or not np.array_equal(before, after)
    # points that are not points of the input are new: they all lie near the rounded edge
    old = {tuple(p) for p in before.round(4).tolist()}
    new_points = np.array([p for p in after.round(4).tolist() if tuple(p) not in old])
    assert len(new_points) > 0
    assert near_edge(new_points).all()
    # the round removes the sharp corner: nothing is left within r of the corner line but the round
    corner_distance = np.hypot(after[:, 1] - 60.0, after[:, 2] - 40.0)
    on_round = corner_distance < BOX_RADIUS * (math.sqrt(2) - 1) * 0.9
    assert not on_round.any(), "the sharp corner is still there"


def test_result_mesh_is_closed_and_bounded_like_the_box(box, rounded):
    assert rounded.mesh.isSolid()
    bb, bb0 = rounded.mesh.BoundBox, box.BoundBox
    assert (bb.XLength, bb.YLength, bb.ZLength) == pytest.approx((bb0.XLength, bb0.YLength, bb0.ZLength),
                                                                abs=1e-3)
    # volume removed: (1 - pi / 4) r^2 per mm of edge
    removed = box.Volume - rounded.mesh.Volume
    assert removed == pytest.approx((1 - math.pi / 4) * BOX_RADIUS ** 2 * 100.0, rel=0.05)


def test_surfaces_spines_chains_contacts(rounded):
    assert len(rounded.surfaces) == 1
    for face in rounded.surfaces:
        assert isinstance(face, Part.Face)
        assert isinstance(face.Surface, Part.BSplineSurface)
    for wires in (rounded.spines, rounded.chains):
        assert len(wires) == 1 and all(isinstance(w, Part.Wire) for w in wires)
    assert len(rounded.contacts) == 2 and all(isinstance(w, Part.Wire) for w in rounded.contacts)
    assert rounded.chains[0].Length == pytest.approx(100.0, abs=1e-6)
    # the ball centre runs at r from both faces: y = 60 - r, z = 40 - r
    for vertex in rounded.spines[0].Vertexes:
        assert (vertex.Point.y, vertex.Point.z) == pytest.approx((60 - BOX_RADIUS, 40 - BOX_RADIUS), abs=1e-6)


def test_report(rounded):
    report = rounded.report
    assert REPORT_KEYS <= set(report)
    assert report["chains"] == 1
    assert report["facets_removed"] > 0 and report["facets_added"] > 0
    assert 0 <= report["max_deviation"] <= BOX_RADIUS / 100 * 1.5
    assert report["seconds"] > 0
    json.dumps(report)  # plain Python numbers only: the CLI writes it as JSON
    assert (MeshRound.quality_note(report) == "") == (report["thin_facets"] == 0)


@pytest.mark.parametrize("report, says", [
    (dict(thin_facets=3, min_new_angle_deg=2.44, input_forces_small_angles=True, min_input_angle_deg=1.8),
     "3 new facet(s) under 10 deg (smallest 2.4 deg): the input's own facets there have angles down to 1.8 deg."),
    (dict(thin_facets=37, min_new_angle_deg=4.57, input_forces_small_angles=False, reach_for_room=4.5),
     "37 new facet(s) under 10 deg (smallest 4.6 deg): the input facets the round cuts are too large for "
     "the reach; at reach 4.5 none is."),
    (dict(thin_facets=2, min_new_angle_deg=9.2, input_forces_small_angles=False, reach_for_room=0.0),
     "2 new facet(s) under 10 deg (smallest 9.2 deg)."),
    (dict(thin_facets=2, min_new_angle_deg=5.625, input_forces_small_angles=False, cusp_facets=2, cusp_angle_deg=5.625),
     "2 new facet(s) under 10 deg (smallest 5.6 deg): at the round's end cusps, where its end leaves a face "
     "tangentially, a facet's angle is half the profile's step, 5.6 deg (the tolerance t allows no more than "
     "acos(1 - t / r) there)."),
    (dict(thin_facets=5, min_new_angle_deg=1.37, input_forces_small_angles=False, cusp_facets=2, cusp_angle_deg=5.625,
          reach_for_room=0.0),
     "5 new facet(s) under 10 deg (smallest 1.4 deg) (2 at the round's end cusps, 5.6 deg)."),
])
def test_quality_note_names_the_cause(report, says):
    assert MeshRound.quality_note(report) == says


def test_input_mesh_is_not_modified(box):
    before = box.Topology
    placement = box.Placement
    MeshRound.round_edges(box, [BOX_SEED, BOX_OTHER_SEED], BOX_RADIUS)
    assert box.Topology == before
    assert box.Placement == placement


def test_seed_forms_and_two_chains(box):
    result = MeshRound.round_edges(box, [tuple(BOX_SEED), list(BOX_OTHER_SEED)], BOX_RADIUS)
    assert result.report["chains"] == 2
    assert len(result.surfaces) == 2


def test_variable_radius(box):
    law = [(FreeCAD.Vector(0, 60, 40), 3.0), (FreeCAD.Vector(100, 60, 40), 6.0)]
    result = MeshRound.round_edges(box, BOX_SEED, law)
    assert result.report["chains"] == 1
    # the radius grows along x: the ball centre is further from the corner at x = 100 than at x = 0
    spine = sorted((v.Point for v in result.spines[0].Vertexes), key=lambda p: p.x)
    assert 60 - spine[0].y == pytest.approx(3.0, abs=0.05)
    assert 60 - spine[-1].y == pytest.approx(6.0, abs=0.05)


def test_round_arrays_gives_arrays_and_a_matching_mesh(box, rounded):
    vertices, triangles = meshconv.mesh_to_arrays(box)
    result = MeshRound.api.round_arrays(vertices, triangles, BOX_SEED, BOX_RADIUS)
    assert result.vertices.shape[1] == 3 and result.triangles.dtype == np.int64
    assert result.mesh.Topology == rounded.mesh.Topology  # same engine run as round_edges'


def test_trace_chains(box):
    wires = MeshRound.trace_chains(box, BOX_SEED)
    assert len(wires) == 1 and isinstance(wires[0], Part.Wire)
    assert wires[0].Length == pytest.approx(100.0, abs=1e-6)


def test_deterministic(box, rounded):
    again = MeshRound.round_edges(box, BOX_SEED, BOX_RADIUS)
    assert again.mesh.Topology == rounded.mesh.Topology


@pytest.mark.parametrize("mesh, seeds, radius, expected", [
    ("empty", BOX_SEED, BOX_RADIUS, "empty"),
    ("not a mesh", BOX_SEED, BOX_RADIUS, "Mesh.Mesh"),
    ("part shape", BOX_SEED, BOX_RADIUS, "Mesh.Mesh"),
    ("box", BOX_SEED, 0.0, "radius"),
    ("box", BOX_SEED, -2.0, "radius"),
    ("box", BOX_SEED, float("nan"), "radius"),
    ("box", BOX_SEED, float("inf"), "radius"),
    ("box", BOX_SEED, "5", "radius"),
    ("box", BOX_SEED, [(BOX_SEED, 0.0)], "radius"),
    ("box", BOX_SEED, [], "control point"),
    ("box", (50.0, 30.0, 20.0), BOX_RADIUS, "sharp edge"),  # the middle of the box: no edge near
    ("box", [], BOX_RADIUS, "seed"),
    ("box", "abc", BOX_RADIUS, "seeds"),
    ("box", [(1.0, 2.0)], BOX_RADIUS, "seeds"),
    ("box", (float("nan"), 0.0, 0.0), BOX_RADIUS, "finite"),
])
def test_bad_input_raises_rounding_error(box, mesh, seeds, radius, expected):
    meshes = {"box": box, "empty": Mesh.Mesh(), "not a mesh": "box.stl", "part shape": Part.makeBox(1, 1, 1)}
    with pytest.raises(MeshRound.RoundingError, match=expected) as info:
        MeshRound.round_edges(meshes[mesh], seeds, radius)
    assert isinstance(info.value, ValueError)


@pytest.mark.parametrize("keyword, value, expected", [
    ("tolerance", -1.0, "tolerance"), ("tolerance", float("nan"), "tolerance"),
    ("feature_angle", 0.0, "feature angle"), ("feature_angle", 180.0, "feature angle"),
    ("reach", 0.0, "reach factor must be at least 1"), ("reach", 0.5, "reach factor must be at least 1"),
    ("reach", float("nan"), "reach factor"), ("tolerance", "fine", "tolerance must be a number"),
])
def test_bad_options_raise_rounding_error(box, keyword, value, expected):
    """One rule per option (the engine's validate_options): the API, the feature and the CLI agree."""
    with pytest.raises(MeshRound.RoundingError, match=expected) as info:
        MeshRound.round_edges(box, BOX_SEED, BOX_RADIUS, **{keyword: value})
    assert info.value.code == "invalid_input"


def test_trace_chains_far_seed_raises(box):
    with pytest.raises(MeshRound.RoundingError):
        MeshRound.trace_chains(box, (50.0, 30.0, 20.0))


def test_rounding_error_is_the_engines_class():
    from MeshRound import _meshround_core
    assert MeshRound.RoundingError is _meshround_core.RoundingError
    assert issubclass(MeshRound.RoundingError, ValueError)


def test_mesh_array_round_trip_keeps_order_and_placement(box):
    moved = box.copy()
    moved.Placement = FreeCAD.Placement(FreeCAD.Vector(10, 20, 30), FreeCAD.Rotation())
    vertices, triangles = meshconv.mesh_to_arrays(moved)
    points, facets = moved.Topology
    assert np.allclose(vertices, [tuple(p) for p in points], atol=1e-4)
    assert np.array_equal(triangles, facets)
    back = meshconv.arrays_to_mesh(vertices, triangles)
    assert back.Topology[1] == facets


def test_mesh_array_conversion_round_trips_1m_facets():
    """1M facets both ways, exactly (the time each way is printed; bench/cad_route.py measures the whole
    console call)."""
    n = 708
    u, v = np.meshgrid(np.linspace(0, 100, n), np.linspace(0, 100, n))
    vertices = np.column_stack([u.ravel(), v.ravel(), np.sin(u.ravel() / 9) * 5])
    index = np.arange(n * n).reshape(n, n)
    a, b, c, d = (index[:-1, :-1].ravel(), index[:-1, 1:].ravel(), index[1:, 1:].ravel(),
                  index[1:, :-1].ravel())
    triangles = np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    assert len(triangles) > 999_000
    started = time.perf_counter()
    mesh = meshconv.arrays_to_mesh(vertices, triangles)
    to_mesh = time.perf_counter() - started
    started = time.perf_counter()
    vertices2, triangles2 = meshconv.mesh_to_arrays(mesh)
    to_arrays = time.perf_counter() - started
    assert np.array_equal(triangles2, triangles)
    assert np.allclose(vertices2, vertices, atol=1e-4)
    print(f"1M facets: arrays -> mesh {to_mesh:.3f} s, mesh -> arrays {to_arrays:.3f} s")


# ------------------------------------------------------------------------- the contract on the engine's cases
@pytest.mark.parametrize("name", list(cases.SPECS))
def test_contract_on_the_engines_cases(name):
    """Every accuracy case (test_accuracy.py scores the geometry) through the public API: the result's
    types, one rounded mesh (closed where the input was), one B-spline face per chain, the report, the input
    untouched."""
    case = cases.case(name)
    mesh = case.mesh("fine")
    before = mesh.Topology
    res = MeshRound.round_edges(mesh, [case.seed], case.radius)
    assert mesh.Topology == before
    assert isinstance(res.mesh, Mesh.Mesh) and res.mesh.isSolid() == mesh.isSolid() and res.mesh.CountFacets > 0
    assert res.report["chains"] == 1 and REPORT_KEYS <= set(res.report)
    assert [type(f.Surface) for f in res.surfaces] == [Part.BSplineSurface]
    assert len(res.spines) == 1 and isinstance(res.spines[0], (Part.Wire, Part.Edge))
    assert res.report["facets_removed"] > 0 and res.report["facets_added"] > 0


@pytest.mark.parametrize("radius", [BOX_RADIUS, [(FreeCAD.Vector(0, 60, 40), 3.0),
                                                (FreeCAD.Vector(100, 60, 40), 6.0)]])
def test_default_tolerance_is_the_largest_radius_over_100(box, radius):
    largest = radius if isinstance(radius, float) else max(r for _, r in radius)
    default = MeshRound.round_edges(box, BOX_SEED, radius)
    explicit = MeshRound.round_edges(box, BOX_SEED, radius, tolerance=largest / 100)
    coarser = MeshRound.round_edges(box, BOX_SEED, radius, tolerance=largest / 20)
    assert default.mesh.Topology == explicit.mesh.Topology
    assert coarser.report["facets_added"] < default.report["facets_added"]
    assert default.report["max_deviation"] <= largest / 100 * 1.5


# --------------------------------------------------------------------------------------- speed, 1M facets
def test_a_1m_facet_die_rounds_end_to_end():
    """Mesh.Mesh in -> RoundingResult with a Mesh.Mesh out on a 1M-facet die: one chain, the mesh beyond
    the band kept.  The time beyond the engine's own run is recorded, not asserted (a shared machine's
    load decides it): bench/cad_route.py is the measurement."""
    vertices, triangles, seeds = die_meshes.die_arrays(11)
    mesh = meshconv.arrays_to_mesh(vertices, triangles)
    assert mesh.CountFacets > 1_000_000
    started = time.perf_counter()
    res = MeshRound.round_edges(mesh, seeds[0], 5.0)
    total = time.perf_counter() - started
    assert res.report["chains"] == 1 and res.report["facets_added"] > 0
    assert res.mesh.CountFacets == mesh.CountFacets - res.report["facets_removed"] + res.report["facets_added"]
    assert res.mesh.isSolid() == mesh.isSolid()
    record_timing("end_to_end_1m_facets_one_chain", dict(total_s=total, engine_s=res.report["seconds_total"],
                                                         beyond_engine_s=total - res.report["seconds_total"],
                                                         facets=mesh.CountFacets))


def record_timing(key, value):
    """Keep a measurement in tests/artifacts/workbench_timings.json (the GUI test adds its own)."""
    try:
        with open(TIMINGS) as stream:
            timings = json.load(stream)
    except (OSError, ValueError):
        timings = {}
    timings[key] = value
    os.makedirs(os.path.dirname(TIMINGS), exist_ok=True)
    with open(TIMINGS, "w") as stream:
        json.dump(timings, stream, indent=1)


# ------------------------------------------------------------------- import MeshRound outside the console
def run_python(code, *, cwd):
    """Run code in a fresh /usr/bin/python3; (stdout, stderr), failing the test on a non-zero exit."""
    run = subprocess.run(["/usr/bin/python3", "-c", code], cwd=cwd, capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, (f"exit {run.returncode}\nstdout:\n{run.stdout[-2000:]}"
                                 f"\nstderr:\n{run.stderr[-2000:]}")
    return run.stdout, run.stderr


WORKLOAD = """
import json, FreeCAD, Mesh, MeshPart, Part
import MeshRound
box = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=5.0)
res = MeshRound.round_edges(box, FreeCAD.Vector(37, 60, 40), 5.0)
print(json.dumps(dict(file=MeshRound.__file__, chains=res.report["chains"], solid=res.mesh.isSolid())))
"""


def readme_script_lines():
    """The README's code block that sets sys.path for a plain /usr/bin/python3 script."""
    with open(os.path.join(REPO, "README.md")) as stream:
        text = stream.read()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    found = [b for b in blocks if "sys.path" in b and "freecad-python3" in b]
    assert found, "README has no sys.path lines for /usr/bin/python3 scripts"
    return found[0]


def test_readme_sys_path_lines_work_in_a_plain_python3_script(tmp_path):
    lines = readme_script_lines()
    named = [p for p in re.findall(r'"(/[^"]+)"', lines) if "Mod/MeshRound" in p]
    missing = [p for p in named if not os.path.isdir(p)]
    if missing:
        pytest.skip(f"the README's lines name {missing}, which this machine does not have (not installed)")
    stdout, _ = run_python(lines + WORKLOAD, cwd=tmp_path)
    result = json.loads(stdout.strip().splitlines()[-1])
    assert result["chains"] == 1 and result["solid"]


def test_a_script_can_use_this_source_tree(tmp_path):
    """The lines to use a source tree in /usr/bin/python3 even when a copy of the workbench is installed
    (~/.local/share/FreeCAD/Mod): `import FreeCAD` puts the installed one first on sys.path, so the tree
    goes in front after it.  (Importing MeshRound before FreeCAD also works; the other order does not.)"""
    lines = ("import sys\n"
             "sys.path.append('/usr/lib/freecad-python3/lib')\n"
             "import FreeCAD\n"
             f"sys.path.insert(0, {MOD_DIR!r})\n")
    stdout, _ = run_python(lines + WORKLOAD, cwd=tmp_path)
    result = json.loads(stdout.strip().splitlines()[-1])
    assert result["file"].startswith(MOD_DIR) and result["chains"] == 1 and result["solid"]


def test_every_module_imports_first_in_a_plain_python3(tmp_path):
    """Any of the package's non-GUI modules may be the first thing a script imports (no FreeCAD before)."""
    for module in ("api", "inputs", "meshconv", "shapes", "errors", "progress", "objects.rounding",
                   "objects.surfaces", "resources"):
        run_python(f"import sys\nsys.path[:0] = [{MOD_DIR!r}, '/usr/lib/freecad-python3/lib']\n"
                   f"import MeshRound.{module}\n", cwd=tmp_path)


def test_import_in_freecadcmd(tmp_path):
    """freecadcmd finds the workbench in its user Mod folder (here a throw-away one linking this tree)."""
    home = tmp_path / "home"
    (home / "Mod").mkdir(parents=True)
    os.symlink(MOD_DIR, home / "Mod" / "MeshRound")
    script = tmp_path / "script.py"
    out = tmp_path / "out.json"
    script.write_text(WORKLOAD.replace("print(json.dumps(", f"open({str(out)!r}, 'w').write(json.dumps("))
    run = subprocess.run(["freecadcmd", str(script)], env=dict(os.environ, FREECAD_USER_HOME=str(home)),
                         capture_output=True, text=True, timeout=120)
    assert out.exists(), f"stdout:\n{run.stdout[-2000:]}\nstderr:\n{run.stderr[-2000:]}"
    result = json.loads(out.read_text())
    assert result["file"].startswith(str(home / "Mod" / "MeshRound"))
    assert result["chains"] == 1 and result["solid"]


# ------------------------------------------------------------------------------------- determinism
DETERMINISM_RUN = """
import sys
sys.path.append("/usr/lib/freecad-python3/lib")
import numpy as np
import FreeCAD, MeshPart, Part
sys.path.insert(0, {mod!r})  # after FreeCAD, which puts the user's Mod folders first
import MeshRound
assert MeshRound.__file__.startswith({mod!r})
res = MeshRound.round_edges(MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=2.0), [(37, 60, 40), (37, 0, 40)], [((37, 60, 40), 3.0), ((90, 60, 40), 6.0),
                            ((37, 0, 40), 4.0)])
np.save({out!r}, np.concatenate([res.vertices.ravel(), res.triangles.ravel().astype(np.float64)]))
"""


def test_same_input_gives_a_bit_identical_output(box, tmp_path):
    """Run after run, in this process and in a fresh one (other addresses, other hash seeds)."""
    seeds = [(37, 60, 40), (37, 0, 40)]
    law = [((37, 60, 40), 3.0), ((90, 60, 40), 6.0), ((37, 0, 40), 4.0)]
    runs = [MeshRound.round_edges(box, seeds, law) for _ in range(2)]
    flat = [np.concatenate([r.vertices.ravel(), r.triangles.ravel().astype(np.float64)]) for r in runs]
    out = tmp_path / "fresh.npy"
    run_python(DETERMINISM_RUN.format(mod=MOD_DIR, out=str(out)), cwd=tmp_path)
    flat.append(np.load(out))
    assert all(f.tobytes() == flat[0].tobytes() for f in flat[1:])
