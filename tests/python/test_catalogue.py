"""A catalogue of bad and edge-of-feasible inputs: each is refused with the right code and the input
left as it was, or rounded to a sound mesh (no new boundary, non-manifold, mis-oriented, degenerate or
self-intersecting facets).  The time of each call is recorded in tests/artifacts/catalogue.json (speed
is measured, not asserted)."""
import json
import os
import time

import numpy as np
import pytest

import cases  # first: it puts FreeCAD's modules on the path
import FreeCAD
import Part
import MeshRound
from MeshRound import api, meshconv
import die_meshes
import soundness
from conftest import BOX_SEED, REPO, grid_box

ARTIFACT = os.path.join(REPO, "tests", "artifacts", "catalogue.json")
SEED = tuple(BOX_SEED)  # the top back edge (y = 60, z = 40) of the 100 x 60 x 40 box


def mefisto_box(max_length=2.0):
    shape = Part.makeBox(100, 60, 40)
    return meshconv.mesh_to_arrays(cases.mesh_of(shape, MaxLength=max_length))


def shifted(mesh, offset):
    V, F = mesh
    return V + np.array(offset), F


def near_chain(V, F, distance, x=50.0, count=1):
    """Facets of the top face whose centroid is `distance` mm from the picked edge, near x."""
    c = V[F].mean(axis=1)
    hit = np.flatnonzero((np.abs(60 - distance - c[:, 1]) < 1.0) & (np.abs(c[:, 2] - 40) < 1e-6)
                         & (np.abs(c[:, 0] - x) < 3))
    assert hit.size >= count, "the test mesh has no facet there"
    return hit[:count]


def without(F, facets):
    return np.delete(F, facets, axis=0)


def flipped(F, facets):
    F = F.copy()
    F[facets] = F[facets][:, ::-1]
    return F


def finned(V, F):
    """A fin: a third facet on an edge of a facet beside the chain."""
    f = near_chain(V, F, 1.0)[0]
    a, b = F[f, 0], F[f, 1]
    V = np.vstack([V, 0.5 * (V[a] + V[b]) + [0, 0, 3.0]])
    return V, np.vstack([F, [a, b, len(V) - 1]])


def unwelded(V, F):
    """The facets beside the chain get vertices of their own (a crack along the chain)."""
    f = near_chain(V, F, 1.0, count=3)
    V = np.vstack([V, V[F[f]].reshape(-1, 3)])
    F = F.copy()
    F[f] = len(V) - 9 + np.arange(9).reshape(3, 3)
    return V, F


def far_control_points():
    return [((37.0, 60.0, 40.0), 4.0), ((3037.0, 60.0, 40.0), 6.0)]


def die(radius):
    V, F, seeds = die_meshes.die_arrays(1)
    return V, F, [tuple(seeds[0])], radius


def pocket_block():
    """A block with a round pocket of radius 20 mm; the seed is on its floor's concave rim."""
    block = Part.makeBox(80, 80, 30).cut(Part.makeCylinder(20, 20, FreeCAD.Vector(40, 40, 10)))
    V, F = meshconv.mesh_to_arrays(cases.mesh_of(block, MaxLength=3))
    return V, F, [(60.0, 40.0, 10.0)]


def box_case(radius, mesh=mefisto_box, seeds=(SEED,), **options):
    def make():
        V, F = mesh()
        return V, F, list(seeds), radius, options
    return make


def edited(edit, radius=5.0):
    def make():
        V, F = mefisto_box()
        out = edit(V, F)
        V, F = out if isinstance(out, tuple) else (V, out)
        return V, F, [SEED], radius, {}
    return make


SOUND = "sound"
# (name, make() -> (V, F, seeds, radius, options), outcomes allowed: codes and/or SOUND)
CATALOGUE = [
    ("empty mesh", lambda: (np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64), [SEED], 5.0, {}), {"invalid_input"}),
    ("NaN vertex", lambda: (np.array([[0, 0, 0], [1, 0, 0], [np.nan, 1, 0]], float), np.array([[0, 1, 2]]), [SEED], 5.0, {}),
     {"invalid_input"}),
    ("index out of range", lambda: (np.eye(3), np.array([[0, 1, 7]]), [SEED], 5.0, {}), {"invalid_input"}),
    ("NaN seed", box_case(5.0, seeds=[(np.nan, 60.0, 40.0)]), {"invalid_input"}),
    ("infinite radius", box_case(float("inf")), {"invalid_input"}),
    ("NaN radius", box_case(float("nan")), {"invalid_input"}),
    ("negative radius", box_case(-2.0), {"invalid_input"}),
    ("seed far from any edge", box_case(5.0, seeds=[(50.0, 30.0, 20.0)]), {"no_sharp_edge"}),
    ("reach out of range", box_case(5.0, reach=0.5), {"invalid_input"}),
    ("feature angle out of range", box_case(5.0, feature_angle=200.0), {"invalid_input"}),
    ("negative tolerance", box_case(5.0, tolerance=-1.0), {"invalid_input"}),
    ("radius just below the 40 mm face", box_case(39.0), {SOUND}),
    ("radius just above the 40 mm face", box_case(40.5), {"radius_too_large"}),
    ("radius 41 on a structured grid", box_case(41.0, mesh=grid_box), {"radius_too_large"}),
    ("radius 5 on a structured grid", box_case(5.0, mesh=grid_box), {SOUND}),
    ("radius far above what fits", box_case(1e5), {"radius_too_large"}),
    ("radius 1e5 on the S-rail die", lambda: (*die(1e5), {}), {"radius_too_large", "beyond_reach"}),
    ("radius larger than a pocket's bore", lambda: (*pocket_block(), 25.0, {}), {"radius_too_large", "beyond_reach"}),
    ("radius far below the element size", box_case(1e-4), {"radius_too_small", SOUND}),
    ("radius 0.05 on 2 mm facets", box_case(0.05), {"radius_too_small", SOUND}),
    ("tolerance far below the element size", box_case(5.0, tolerance=1e-7), {"radius_too_small", SOUND}),
    ("hole beside the chain", edited(lambda V, F: without(F, near_chain(V, F, 1.0))),
     {"non_manifold_input", SOUND}),
    ("hole inside the band", edited(lambda V, F: without(F, near_chain(V, F, 6.0, count=2))),
     {"non_manifold_input", "radius_too_large", SOUND}),
    ("flipped facet beside the chain", edited(lambda V, F: flipped(F, near_chain(V, F, 1.0))),
     {"non_manifold_input", SOUND}),
    ("flipped facets inside the band", edited(lambda V, F: flipped(F, near_chain(V, F, 6.0, count=3))),
     {"non_manifold_input", SOUND}),
    ("fin beside the chain", edited(finned), {"non_manifold_input"}),
    ("duplicated facet beside the chain", edited(lambda V, F: np.vstack([F, F[near_chain(V, F, 1.0)]])),
     {"non_manifold_input"}),
    ("unwelded facets beside the chain", edited(unwelded), {"non_manifold_input", "no_sharp_edge", SOUND}),
    ("control point 3 m away", box_case(far_control_points()), {"invalid_input"}),
    ("two top edges mitred at a corner", box_case(5.0, seeds=[SEED, (100.0, 30.0, 40.0)]), {SOUND}),
    ("box far from the origin", box_case(5.0, mesh=lambda: shifted(grid_box(), (1e6, -2e6, 5e5)),
                                         seeds=[(1e6 + 37, -2e6 + 60, 5e5 + 40)]), {SOUND, "radius_too_small"}),
    ("box very far from the origin", box_case(5.0, mesh=lambda: shifted(grid_box(), (3e9, 0, 0)),
                                              seeds=[(3e9 + 37, 60, 40)]), {"radius_too_small", SOUND}),
]

_timings = {}


@pytest.fixture(scope="module", autouse=True)
def record_timings():
    yield
    os.makedirs(os.path.dirname(ARTIFACT), exist_ok=True)
    with open(ARTIFACT, "w") as stream:
        json.dump(_timings, stream, indent=1, sort_keys=True)


@pytest.mark.parametrize("name, make, allowed", CATALOGUE, ids=[c[0] for c in CATALOGUE])
def test_refused_with_its_code_or_sound(name, make, allowed):
    V, F, seeds, radius, options = make()
    V_before, F_before = V.copy(), F.copy()
    started = time.perf_counter()
    try:
        result = api.round_arrays(V, F, seeds, radius, **options)
    except MeshRound.RoundingError as exc:
        outcome, message = exc.code, str(exc)
    else:
        outcome, message = SOUND, ""
    _timings[name] = dict(seconds=round(time.perf_counter() - started, 3), outcome=outcome)
    assert np.array_equal(V, V_before, equal_nan=True) and np.array_equal(F, F_before), "input changed"
    assert outcome in allowed, f"{name}: {outcome} ({message})"
    if outcome == SOUND:
        assert soundness.problems(V, F, result.vertices, result.triangles) == []
    else:
        assert message and len(message) > 20, message  # a sentence naming the cause


CLI_CASES = [
    ("radius too large", ["--radius", "41"], 1, "[radius_too_large]"),
    ("no sharp edge", ["--radius", "5", "--feature-angle", "120"], 1, "[no_sharp_edge]"),
    ("reach out of range", ["--radius", "5", "--reach", "0.9"], 2, "reach factor must be at least 1"),
]


@pytest.mark.parametrize("name, extra, status, expected", CLI_CASES, ids=[c[0] for c in CLI_CASES])
def test_command_line_prints_the_code(tmp_path, name, extra, status, expected):
    from test_cli import meshround
    source = tmp_path / "box.stl"
    meshconv.arrays_to_mesh(*mefisto_box()).write(str(source))
    out = tmp_path / "out.stl"
    run = meshround("round", source, out, "--seed", "37,60,40", *extra)
    assert run.returncode == status, run.stderr
    assert expected in run.stderr and not out.exists()
