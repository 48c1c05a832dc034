"""Index arrays that draw a deck's shells as they are (quads as quads), for Coin's SoIndexedFaceSet and
SoIndexedLineSet; numpy only (no GUI), so the headless tests check them too.

    faces = polygon_index(nodes, counts)   # [a, b, c, d, -1, a, b, c, -1, ...]: one polygon per element
    lines = edge_index(nodes, counts)      # [a, b, -1, ...]: each element edge once, no quad diagonal
"""
import numpy as np


def polygon_index(nodes, counts):
    """int32 coordIndex of an SoIndexedFaceSet: each element's nodes (3 or 4) then -1."""
    nodes = np.asarray(nodes)
    counts = np.asarray(counts)
    table = np.full((len(nodes), 5), -1, np.int32)
    table[:, :4] = nodes[:, :4]
    table[counts == 3, 3] = -1
    keep = np.arange(5)[None, :] <= counts[:, None]  # the nodes and one -1 after them
    return table[keep]


def element_edges(nodes, counts):
    """(k, 2) int64: each edge of the elements' outlines once (sorted pair), diagonals never."""
    nodes = np.asarray(nodes, np.int64)
    counts = np.asarray(counts)
    pairs = []
    for count in (3, 4):
        ring = nodes[counts == count, :count]
        if len(ring):
            pairs.append(np.stack([ring, np.roll(ring, -1, axis=1)], axis=-1).reshape(-1, 2))
    if not pairs:
        return np.zeros((0, 2), np.int64)
    edges = np.sort(np.concatenate(pairs), axis=1)
    base = int(edges.max()) + 1
    keys = np.unique(edges[:, 0] * base + edges[:, 1])  # one int64 per edge: fast to sort
    return np.stack([keys // base, keys % base], axis=1)


def edge_index(nodes, counts):
    """int32 coordIndex of an SoIndexedLineSet: [a, b, -1] per element edge."""
    edges = element_edges(nodes, counts)
    table = np.full((len(edges), 3), -1, np.int32)
    table[:, :2] = edges
    return table.ravel()
