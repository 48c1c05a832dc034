"""Mesh.Mesh <-> numpy arrays, without a Python loop over facets.

FreeCAD 0.20 has no buffer interface on Mesh.Mesh, and its Python paths are slow for big meshes:
`Mesh.Mesh((points, facets))` needs one Base.Vector and one tuple per element and takes ~3.5 s for
1M facets, `mesh.Topology` ~0.3-0.8 s one way.  Binary PLY is a format that Mesh's own C++ reader and
writer handle in bulk, keeps point and facet order, and numpy packs/unpacks with one structured dtype.
So both directions go through a binary PLY file in a private temporary folder (measured on 1M facets:
mesh -> arrays ~0.1 s, arrays -> mesh ~0.5 s, most of it FreeCAD building its neighbour table).
Streams are not used for writing: Mesh.write(Stream=...) loses data on large meshes in 0.20.

Points are float32 inside FreeCAD (like STL); coordinates are global (the mesh's Placement applied),
because Mesh's writer applies the mesh transform.
"""
import itertools
import os
import tempfile

import numpy as np

import FreeCAD  # noqa: F401  (first: importing Mesh before FreeCAD crashes a plain Python)
import Mesh

_PLY_POINT = np.dtype("<f4")
_PLY_FACET = np.dtype([("count", "u1"), ("index", "<i4", (3,))])

# The header FreeCAD 0.20 writes for a mesh without colours; anything else takes the slow path.
_EXPECTED_PROPERTIES = [
    "property float32 x", "property float32 y", "property float32 z",
    "property list uchar int vertex_index",
]


def mesh_to_arrays(mesh):
    """(vertices float64 (n, 3), triangles int64 (m, 3)) of a Mesh.Mesh, in global coordinates."""
    with tempfile.TemporaryDirectory(prefix="meshround-") as folder:
        path = os.path.join(folder, "mesh.ply")
        mesh.write(path, "PLY")
        with open(path, "rb") as stream:
            raw = stream.read()
    arrays = _parse_freecad_ply(raw)
    if arrays is None:
        arrays = _arrays_from_topology(mesh)
    return arrays


def arrays_to_mesh(vertices, triangles):
    """A Mesh.Mesh made from vertices (n, 3) and 0-based triangles (m, 3); order is kept."""
    vertices = np.ascontiguousarray(vertices, dtype=_PLY_POINT).reshape(-1, 3)
    triangles = np.asarray(triangles).reshape(-1, 3)
    facets = np.empty(len(triangles), dtype=_PLY_FACET)
    facets["count"] = 3
    facets["index"] = triangles
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(vertices)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        f"element face {len(triangles)}\n"
        "property list uchar int vertex_indices\nend_header\n"
    ).encode("ascii")
    with tempfile.TemporaryDirectory(prefix="meshround-") as folder:
        path = os.path.join(folder, "mesh.ply")
        with open(path, "wb") as stream:
            stream.write(header)
            stream.write(vertices.tobytes())
            stream.write(facets.tobytes())
        return Mesh.Mesh(path)


def _parse_freecad_ply(raw):
    """Arrays from the binary PLY that Mesh.write produces, or None if the layout is not the known one."""
    end = raw.find(b"end_header\n")
    if end < 0:
        return None
    body = end + len(b"end_header\n")
    lines = raw[:end].decode("ascii", "replace").splitlines()
    counts = {}
    properties = []
    for line in lines:
        words = line.split()
        if words[:1] == ["element"] and len(words) == 3:
            counts[words[1]] = int(words[2])
        elif words[:1] == ["property"]:
            properties.append(" ".join(words))
    if "format binary_little_endian 1.0" not in lines or properties != _EXPECTED_PROPERTIES:
        return None
    n_points, n_facets = counts.get("vertex", 0), counts.get("face", 0)
    if len(raw) != body + n_points * 3 * _PLY_POINT.itemsize + n_facets * _PLY_FACET.itemsize:
        return None
    points = np.frombuffer(raw, _PLY_POINT, n_points * 3, body).reshape(-1, 3)
    facets = np.frombuffer(raw, _PLY_FACET, n_facets, body + points.nbytes)
    if n_facets and not np.all(facets["count"] == 3):
        return None
    return points.astype(np.float64), facets["index"].astype(np.int64)


def _arrays_from_topology(mesh):
    """Fallback through mesh.Topology, flattened by C iterators (no Python loop per element)."""
    points, facets = mesh.Topology
    vertices = np.fromiter(itertools.chain.from_iterable(points), np.float64, 3 * len(points))
    triangles = np.fromiter(itertools.chain.from_iterable(facets), np.int64, 3 * len(facets))
    return vertices.reshape(-1, 3), triangles.reshape(-1, 3)
