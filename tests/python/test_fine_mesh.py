"""Meshes much finer than the round: no thin facets where the contact line crosses tiny elements.

A die mesh of 0.5 mm elements rounded at r = 5 has a trim line whose points are a fraction of an element
apart (a vertex just off the contact line leaves two cut points close together), while the round's own
rows are a profile step (about r/5) apart: without rows graded between the two, the round's first row
fans over those short steps in slivers (5 degrees at 0.08 r on the benchmark's box). And a row of
vertices a quarter of an element off the line leaves a strip of slivers between itself and the line
unless it moves onto the line. The box here is the 12-facet box split into k x k facets per triangle:
elements of 0.05-0.09 r, no input facet under 20 degrees, so any facet under 10 degrees is the engine's.
Before those two measures: k = 94 made 5.7 degrees (the row a quarter off), k = 138 / 162 made 9.8 / 8.5
(no graded rows).
"""
import numpy as np
import pytest

import die_meshes
import reference
from MeshRound import api

SIZE = (100.0, 60.0, 40.0)
RADIUS = 5.0
SEED = (37.0, 60.0, 40.0)  # on the top back edge (y = 60, z = 40)


def coarse_box():
    """The box as 8 corners and 12 right triangles, outward normals."""
    x, y, z = SIZE
    V = np.array([(0, 0, 0), (x, 0, 0), (x, y, 0), (0, y, 0), (0, 0, z), (x, 0, z), (x, y, z), (0, y, z)], float)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 4, 7, 3)]
    F = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))], dtype=np.int64)
    return V, F


@pytest.mark.parametrize("k", [94, 138, 162])
def test_fine_mesh_rounds_without_thin_facets(k):
    V, F = die_meshes.subdivide(*coarse_box(), k)
    assert reference.min_angles_deg(V, F).min() > 20
    element = SIZE[1] / k
    assert element <= 0.13 * RADIUS
    res = api.round_arrays(V, F, [SEED], RADIUS)
    angles = reference.min_angles_deg(res.vertices, res.triangles)
    assert angles.min() >= 10, f"{int((angles < 10).sum())} facets under 10 degrees, smallest {angles.min():.2f}"
    assert res.report["thin_facets"] == 0
    # The round is where it should be: every vertex in the band lies on the exact fillet, the cylinder
    # of axis (y, z) = (55, 35).
    W = res.vertices
    band = (W[:, 1] > 55 - 1e-9) & (W[:, 2] > 35 - 1e-9) & (W[:, 0] > 1) & (W[:, 0] < SIZE[0] - 1)  # not the end caps
    on_cylinder = np.abs(np.hypot(W[band, 1] - 55, W[band, 2] - 35) - RADIUS)
    assert on_cylinder.max() <= RADIUS / 100
