"""The console call's output Mesh.Mesh is the input's copy with the band edited (meshedit.py): the same mesh
as the engine's arrays, vertex for vertex and facet for facet; the input's kept vertices keep their float32
bits and their order; FreeCAD's own neighbour table is whole (a solid stays a solid); a mesh the edit cannot
take (a Placement, a facet FreeCAD refuses) is built from the arrays as before."""
import numpy as np
import pytest

import FreeCAD
import Mesh

import MeshRound
from MeshRound import meshconv, meshedit
from conftest import BOX_RADIUS, BOX_SEED

V = FreeCAD.Vector
CORNER_SEEDS = [V(50, 60, 40), V(100, 30, 40), V(100, 60, 20)]  # the three edges at (100, 60, 40)


def float32_arrays(mesh):
    """(points float32, facets) as FreeCAD holds them."""
    points, facets = meshconv.mesh_to_arrays(mesh)
    return points.astype(np.float32), facets


def expect_same_mesh(result):
    points, facets = float32_arrays(result.mesh)
    assert np.array_equal(facets, result.triangles)
    assert np.array_equal(points, result.vertices.astype(np.float32))


def expect_sound_freecad_mesh(mesh):
    assert mesh.isSolid()
    assert not mesh.hasInvalidNeighbourhood()
    assert not mesh.hasNonManifolds()
    assert mesh.countNonUniformOrientedFacets() == 0


@pytest.mark.parametrize("seeds", [[BOX_SEED], CORNER_SEEDS], ids=["one chain", "three chains and a sphere corner"])
def test_edited_copy_is_the_engines_mesh_and_keeps_the_inputs_bits(box, seeds):
    before = box.Topology
    res = MeshRound.round_edges(box, seeds, BOX_RADIUS)
    assert box.Topology == before
    assert res.report["seconds_stages"]["output_mesh"] >= 0
    expect_same_mesh(res)
    expect_sound_freecad_mesh(res.mesh)
    # Kept input vertices: first, in their order, with their float32 bits (FreeCAD's copy, never rewritten).
    delta = res.delta
    points, _ = float32_arrays(res.mesh)
    source, _ = float32_arrays(box)
    kept = np.setdiff1d(np.arange(len(source)), delta["freed"])
    still = ~np.isin(kept, delta["moved"])
    assert points[:len(kept)][still].tobytes() == source[kept[still]].tobytes()
    assert len(kept[still]) > 0.9 * len(source)


def test_the_edit_and_the_arrays_route_give_one_mesh(box):
    res = MeshRound.round_edges(box, BOX_SEED, BOX_RADIUS)
    vertices, triangles = meshconv.mesh_to_arrays(box)
    via_arrays = MeshRound.api.round_arrays(vertices, triangles, BOX_SEED, BOX_RADIUS)
    assert via_arrays.mesh.Topology == res.mesh.Topology
    assert np.array_equal(via_arrays.triangles, res.triangles)
    assert via_arrays.vertices.tobytes() == res.vertices.tobytes()


def fan_delta(mesh):
    """A hand-made delta that removes the facets around an inner vertex of the top face and makes them
    again: the vertex is freed and used again (the case where FreeCAD's removal drops a point that the
    new facets need)."""
    points, facets = meshconv.mesh_to_arrays(mesh)
    top = np.all(np.isclose(points[facets][:, :, 2], 40.0), axis=1)
    inner = np.nonzero((np.abs(points[:, 0] - 50) < 20) & (np.abs(points[:, 1] - 30) < 15) & np.isclose(points[:, 2], 40.0))[0]
    centre = int(inner[0])
    around = np.nonzero(np.any(facets == centre, axis=1))[0]
    assert top[around].all()
    delta = dict(input_vertices=len(points), input_facets=len(facets), removed=around.astype(np.int64),
                 freed=np.array([centre], dtype=np.int64), moved=np.zeros(0, dtype=np.int64),
                 moved_to=np.zeros((0, 3)), new_points=np.zeros((0, 3)), added=facets[around].astype(np.int32))
    return points, facets, delta, centre


def test_a_freed_vertex_used_again_goes_after_the_kept_ones(box):
    points, facets, delta, centre = fan_delta(box)
    edited = meshedit.edited_copy(box.copy(), delta, points)
    assert edited is not None
    expect_sound_freecad_mesh(edited)
    from MeshRound import _meshround_core as core
    want_points, want_facets = core.apply_delta(points, facets, delta)
    got_points, got_facets = float32_arrays(edited)
    assert np.array_equal(got_facets, want_facets)
    assert got_points.tobytes() == want_points.astype(np.float32).tobytes()
    assert got_points[-1].tobytes() == points[centre].astype(np.float32).tobytes()


def test_an_edit_freecad_would_not_take_falls_back(box):
    points, facets, delta, _ = fan_delta(box)
    delta["added"] = np.concatenate([delta["added"], facets[:1]])  # a facet that is already there: non-manifold
    assert meshedit.edited_copy(box.copy(), delta, points) is None


def test_a_placed_mesh_is_built_from_arrays_in_global_coordinates(box):
    placed = box.copy()
    placed.Placement = FreeCAD.Placement(V(10, 0, 0), FreeCAD.Rotation())
    res = MeshRound.round_edges(placed, BOX_SEED + V(10, 0, 0), BOX_RADIUS)
    assert res.mesh.Placement.isIdentity()
    assert res.mesh.BoundBox.XMin == pytest.approx(10.0)
    expect_same_mesh(res)
    expect_sound_freecad_mesh(res.mesh)
