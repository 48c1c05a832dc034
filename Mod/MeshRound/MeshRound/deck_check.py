"""The written deck's check before it replaces out_path (decks.round_deck's last step), at the cost of
reading it back plus the band's.

  1. The written deck is read back: the reader refuses IDs defined twice and elements on undefined nodes.
  2. What it holds outside the band is the input's: its nodes are the input's less the removed ones (IDs
     and coordinates bit for bit, in order) then the new ones; its shells the input's less the removed
     ones (IDs, parts, node IDs, in order) then the new ones (IDs, node IDs).  Compared as arrays.
  3. So its shells are the input's less the removed elements plus the new ones, and an edge's count of
     triangles changes only on the edges of those: open and non-manifold edges are counted there, before
     and after, and added to the input's (counted while its triangles were oriented, decks.ShellTriangles).
     The triangles are decks.deck_triangles' (the part's shells, quads split on the shorter diagonal, the
     new elements' at their written coordinates), so the counts are those of the whole written deck.
Any difference raises RoundingError (result_invalid): nothing is written.
"""
import numpy as np

from .errors import RoundingError, require_core


def check_written(path, arrays, part, split, edits, band, summary):
    back = require_core().read_deck(path).arrays()
    _same_outside_band(arrays, back, edits, band)
    before = split.open_edges, split.nonmanifold_edges
    change = _band_edge_change(arrays, back, part, split, edits, band)
    after = before[0] + change[0], before[1] + change[1]
    summary["check"] = {"open_edges_before": before[0], "open_edges_after": after[0],
                        "nonmanifold_edges_before": before[1], "nonmanifold_edges_after": after[1]}
    if after[0] > before[0] or after[1] > before[1]:
        raise RoundingError(f"the written deck's shells have {after[0]} open and {after[1]} non-manifold edges "
                            f"(the input: {before[0]} and {before[1]}); nothing was written", code="result_invalid")


def _same_outside_band(arrays, back, edits, band):
    keep_nodes = np.ones(len(arrays["node_ids"]), bool)
    keep_nodes[band["removed_nodes"]] = False
    keep_shells = np.ones(len(arrays["shell_ids"]), bool)
    keep_shells[band["lost"]] = False
    kn, ks = int(keep_nodes.sum()), int(keep_shells.sum())
    # The new elements by ID (Abaqus writes them in blocks of one part and type).
    new_ids = np.asarray(edits["shell_ids"], np.int64)
    new_nodes = np.asarray(edits["shell_nodes"], np.int64).reshape(-1, 4)
    by_id, back_by_id = np.argsort(new_ids), ks + np.argsort(back["shell_ids"][ks:])
    expected = {
        "node IDs": (back["node_ids"], np.concatenate([arrays["node_ids"][keep_nodes], edits["node_ids"]])),
        "node coordinates": (back["node_xyz"][:kn].view(np.uint64), arrays["node_xyz"][keep_nodes].view(np.uint64)),
        "element IDs": (back["shell_ids"][:ks], arrays["shell_ids"][keep_shells]),
        "new element IDs": (back["shell_ids"][back_by_id], new_ids[by_id]),
        "element parts": (back["shell_parts"][:ks], arrays["shell_parts"][keep_shells]),
        "element nodes": (back["shell_node_ids"][:ks], arrays["shell_node_ids"][keep_shells]),
        "new element nodes": (back["shell_node_ids"][back_by_id], new_nodes[by_id]),
    }
    for what, (got, want) in expected.items():
        if got.shape != want.shape or not np.array_equal(got, want):
            raise RoundingError(f"the written deck does not read back as written ({what} differ from the input's "
                                "and the rounding's); nothing was written", code="result_invalid")


def _band_edge_change(arrays, back, part, split, edits, band):
    """(change of open edges, change of non-manifold edges) from the input's shells to the written deck's."""
    from .decks import split_shells
    node_of_vertex = arrays["node_ids"][split.vertex_node]
    gone = split.of_shells(band["lost"])                     # the removed elements' triangles
    new = len(back["shell_ids"]) - len(edits["shell_ids"]) + np.arange(len(edits["shell_ids"]))
    if part is not None:
        new = new[back["shell_parts"][new] == part]
    new_tris, _ = split_shells(back["shell_nodes"][new], back["shell_counts"][new], back["node_xyz"])
    new_edges = _edges(back["node_ids"][new_tris])
    # Every input triangle on an edge of those has both its ends among their input vertices.
    ends = np.concatenate([split.triangles[gone].ravel(), band["element_vertices"][band["element_vertices"] >= 0]])
    mark = np.zeros(len(split.vertices), bool)
    mark[ends] = True
    near = np.flatnonzero(mark[split.triangles].sum(axis=1) >= 2)
    stays = np.setdiff1d(near, gone)
    before = _edges(node_of_vertex[split.triangles[near]])
    after = np.concatenate([_edges(node_of_vertex[split.triangles[stays]]), new_edges])
    touched = np.unique(np.concatenate([_edges(node_of_vertex[split.triangles[gone]]), new_edges]), axis=0)
    c0, c1 = _counts(before, touched), _counts(after, touched)
    return (int(np.sum(c1 == 1) - np.sum(c0 == 1)), int(np.sum(c1 > 2) - np.sum(c0 > 2)))


def _edges(triangles):
    """The edges of triangles (node IDs) as rows (low, high), one per triangle side."""
    t = np.asarray(triangles, np.int64).reshape(-1, 3)
    e = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    return np.sort(e, axis=1)


def _counts(edges, of):
    """How many rows of `edges` equal each row of `of`."""
    _, inverse, counts = np.unique(np.concatenate([edges, of]), axis=0, return_inverse=True, return_counts=True)
    return counts[inverse.ravel()[len(edges):]] - 1
