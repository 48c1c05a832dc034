"""Shared set-up of the Python tests: FreeCAD and the workbench on sys.path, small test meshes.

Run with Debian's interpreter (FreeCAD 0.20's modules are built for it):  /usr/bin/python3 -m pytest tests
"""
import ctypes
import gc
import os
import sys

import numpy as np
import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# MESHROUND_MOD_DIR: another copy of the workbench (tools/sanitize.sh: the one with the ASan-built module).
MOD_DIR = os.environ.get("MESHROUND_MOD_DIR") or os.path.join(REPO, "Mod", "MeshRound")
FREECAD_LIB = "/usr/lib/freecad-python3/lib"
for _path in (FREECAD_LIB, os.path.dirname(os.path.abspath(__file__))):
    if _path not in sys.path:
        sys.path.append(_path)

import FreeCAD  # noqa: E402
import MeshPart  # noqa: E402
import Part  # noqa: E402

# `import FreeCAD` puts the user's Mod folders first on sys.path, and an installed copy of the workbench
# (cmake --install: ~/.local/share/FreeCAD/Mod/MeshRound) would shadow this source tree: test the tree.
sys.path.insert(0, MOD_DIR)
import MeshRound  # noqa: E402

assert os.path.dirname(MeshRound.__file__) == os.path.join(MOD_DIR, "MeshRound"), MeshRound.__file__

# The standard case: a 100 x 60 x 40 box, its top back edge (y = 60, z = 40) picked at x = 37, r = 5.
BOX_SIZE = (100.0, 60.0, 40.0)
BOX_SEED = FreeCAD.Vector(37.0, 60.0, 40.0)
BOX_OTHER_SEED = FreeCAD.Vector(37.0, 0.0, 40.0)    # the top front edge, for a second rounding
BOX_RADIUS = 5.0


def box_mesh(max_length=2.0):
    return MeshPart.meshFromShape(Shape=Part.makeBox(*BOX_SIZE), MaxLength=max_length)


def grid_box(step=2.0, size=BOX_SIZE):
    """(vertices, triangles) of a box (the standard one by default) whose faces are structured grids of
    step x step squares, two facets each, outward."""
    points, facets, index = [], [], {}

    def vertex(p):
        key = tuple(np.round(p, 9))
        if key not in index:
            index[key] = len(points)
            points.append(key)
        return index[key]

    for axis in range(3):
        u_axis, v_axis = [(1, 2), (2, 0), (0, 1)][axis]
        nu, nv = round(size[u_axis] / step), round(size[v_axis] / step)
        for high in (0, 1):
            for i in range(nu):
                for j in range(nv):
                    quad = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = np.zeros(3)
                        p[axis] = size[axis] * high
                        p[u_axis] = size[u_axis] * (i + di) / nu
                        p[v_axis] = size[v_axis] * (j + dj) / nv
                        quad.append(vertex(p))
                    a, b, c, d = quad if high else quad[::-1]
                    facets += [(a, b, c), (a, c, d)]
    return np.array(points, dtype=np.float64), np.array(facets, dtype=np.int64)


@pytest.fixture(scope="session")
def box():
    """The box mesh (shared: tests must not modify it -- the API never does)."""
    return box_mesh()


@pytest.fixture
def doc():
    """A fresh document with undo enabled (FreeCAD disables it headless), closed afterwards."""
    document = FreeCAD.newDocument("MeshRoundTest")
    document.UndoMode = 1
    name = document.Name
    yield document
    if name in FreeCAD.listDocuments():  # a save/reload test may have closed it already
        FreeCAD.closeDocument(name)


@pytest.fixture
def box_feature(doc, box):
    """A Mesh::Feature holding the box mesh, recomputed."""
    feature = doc.addObject("Mesh::Feature", "Box")
    feature.Mesh = box
    doc.recompute()
    return feature


@pytest.fixture(scope="module", autouse=True)
def give_back_memory(request):
    """After each test file, the memory its results held goes back to the system (a file's meshes and OCCT
    solids run to gigabytes; two pytest-xdist workers share the machine's memory). The caches of cases,
    references and meshes are emptied first: a worker kept every earlier file's (12.5 GB at the end of a run,
    where the heaviest file alone peaks at 7 GB)."""
    yield
    import cases
    import die_meshes
    import reference
    reference._CACHE.clear()
    for module in (request.module, cases, die_meshes):
        for value in list(vars(module).values()):
            if callable(getattr(value, "cache_clear", None)):
                value.cache_clear()
    gc.collect()
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):  # not glibc
        pass
