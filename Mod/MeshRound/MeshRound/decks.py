"""Solver decks (LS-DYNA .k/.key/.dyn, Nastran .bdf/.nas/.dat, Abaqus .inp): read, round, write back.

    import MeshRound
    deck = MeshRound.read_deck("die.k")                 # nodes, shells, parts, sets (numpy arrays)
    res = MeshRound.round_deck("die.k", "die_r5.k", seeds=[(x, y, z)], radius=5, part=None)
    res.report                                           # engine report + what happened to the deck
    res = MeshRound.change_radius_deck("die.k", "die_r8.k", seeds=[(x, y, z)], radius=8)  # an existing round

The reading and writing are the engine's (cpp_core deck.h): every line that does not describe a changed
node, element or set is written back byte for byte.  Here the deck's shells are given to the engine as
triangles (a quad as two, split on its shorter diagonal, each triangle remembering its element), and the
rounded mesh is turned back into elements:
  - an element whose triangles all survive is kept as it was (its line untouched);
  - the rest is removed; what survives of a cut quad and the new facets are paired into quads where two
    triangles share an edge and form a good convex quad (the round's rows x columns), else triangles;
  - new nodes and elements get IDs above the deck's largest (or from node_id_start / element_id_start);
  - a new element takes the part of the nearest removed element; sets that held removed elements/nodes
    hold the new elements/nodes that replace them (nearest removed one in the set); a Nastran SET1 whose
    IDs do not tell grids from elements refuses the rounding if it holds a removed ID;
  - nodes no element uses any more are removed (keep_unused_nodes=True keeps them).
The written deck is read again and checked (IDs unique, every node defined, everything outside the band
as in the input, no new open or non-manifold edge: deck_check.py) before it replaces out_path; on any
failure nothing is written.
"""
import dataclasses
import os
import shutil
import tempfile
import time

import numpy as np

from . import api
from .deck_formats import DECK_EXTENSIONS, deck_family
from .errors import RoundingError, require_core

__all__ = ["DECK_EXTENSIONS", "is_deck_path", "read_deck", "deck_triangles", "round_deck", "change_radius_deck",
           "edit_deck", "DeckRoundingResult", "QuadOptions"]

def is_deck_path(path):
    return deck_family(path) is not None


@dataclasses.dataclass
class QuadOptions:
    """When two triangles to be written share an edge and make a quad good enough to write as one."""
    quads: bool = True             # False: every new element a triangle
    max_corner_skew: float = 60.0  # degrees: every quad corner within 90 +- this (convex, not a sliver)
    max_warp: float = 15.0         # degrees between the two triangles' normals


@dataclasses.dataclass
class DeckRoundingResult:
    paths: list          # the files written (out_path first, then changed/copied includes)
    report: dict         # the engine's report plus "deck": what happened to nodes, elements and sets
    result: object       # the engine's api.RoundingResult (triangles; .surfaces are the exact rounds)


def read_deck(path):
    """The deck at `path` (format by extension, includes followed) as a dict of arrays (CONTRACT.md):
    node_ids, node_xyz, shell_ids, shell_parts, shell_counts, shell_nodes (indices), shell_node_ids,
    parts [(id, name)], sets [{of_nodes, kind_known, name, id, members, ...}] (Nastran SET1/SET3 too),
    files, max_node_id, max_element_id;
    plus "deck", the engine's Deck (its .texts() are the files' bytes).  Raises RoundingError
    (invalid_input) naming file:line and the reason for a malformed line."""
    _check_extension(path)
    if not os.path.isfile(path):
        raise RoundingError(f"cannot read '{path}': no such file", code="invalid_input")
    deck = require_core().read_deck(os.fspath(path))
    arrays = deck.arrays()
    arrays["deck"] = deck
    return arrays


@dataclasses.dataclass
class ShellTriangles:
    """The shells (of one part) as the engine's triangles (deck_triangles), and what round_deck needs of them."""
    vertices: np.ndarray     # (k, 3): the nodes the shells use
    triangles: np.ndarray    # (t, 3) into vertices, turned consistently (orient)
    tri_shell: np.ndarray    # (t,): the shell (index into the deck's shells) of each triangle
    vertex_node: np.ndarray  # (k,): the node (index) of each vertex
    shells: np.ndarray       # the shells split, ascending: triangle i < len(shells) is shells[i]'s first
    quads: np.ndarray        # ... and those of them that are quads: triangle len(shells) + j is quads[j]'s second
    open_edges: int          # edges of one triangle, and of more than two (counted while orienting)
    nonmanifold_edges: int

    def of_shells(self, shells):
        """The triangles of the given (split) shells, ascending: at the band's cost (both halves' lists are sorted)."""
        shells = np.asarray(shells, np.int64)
        first = np.searchsorted(self.shells, shells)
        at = np.minimum(np.searchsorted(self.quads, shells), max(len(self.quads) - 1, 0))
        second = len(self.shells) + at[self.quads[at] == shells] if len(self.quads) else np.zeros(0, np.int64)
        return np.sort(np.concatenate([first, second]))


def deck_triangles(arrays, part=None):
    """(vertices (k, 3), triangles (t, 3), tri_shell (t,), vertex_node (k,)): the shells (of one part) as
    triangles over the nodes they use; a quad is split on its shorter diagonal."""
    split = shell_triangles(arrays, part)
    return split.vertices, split.triangles, split.tri_shell, split.vertex_node


def shell_triangles(arrays, part=None):
    """deck_triangles as a ShellTriangles."""
    shells = np.arange(len(arrays["shell_ids"]))
    if part is not None:
        shells = shells[arrays["shell_parts"] == part]
        if len(shells) == 0:
            known = sorted({int(p) for p in arrays["shell_parts"]})
            raise RoundingError(f"part {part} has no shell elements (parts with shells: {known[:20]})",
                                code="invalid_input")
    if len(shells) == 0:
        raise RoundingError("the deck has no 3- or 4-node shell elements", code="invalid_input")
    xyz = arrays["node_xyz"]
    tri_nodes, quad = split_shells(arrays["shell_nodes"][shells], arrays["shell_counts"][shells], xyz)
    used = np.zeros(len(xyz), bool)
    used[tri_nodes.ravel()] = True
    vertex_node = np.flatnonzero(used)
    renumber = np.cumsum(used) - 1  # node index -> vertex index (for the nodes the shells use)
    triangles, open_edges, nonmanifold = _orient(renumber[tri_nodes])
    return ShellTriangles(xyz[vertex_node], triangles, np.concatenate([shells, shells[quad]]), vertex_node, shells,
                          shells[quad], open_edges, nonmanifold)


def split_shells(nodes, counts, xyz):
    """Shells (rows of 4 node indices, counts 3 or 4) as triangles: each shell's first, then the quads'
    (quad: counts == 4) second halves; a quad is split on its shorter diagonal."""
    quad = counts == 4
    d02 = np.linalg.norm(xyz[nodes[:, 0]] - xyz[nodes[:, 2]], axis=1)
    d13 = np.linalg.norm(xyz[np.where(quad, nodes[:, 1], nodes[:, 0])] - xyz[np.where(quad, nodes[:, 3], nodes[:, 0])], axis=1)
    on13 = quad & (d13 < d02)
    first = np.where(on13[:, None], nodes[:, [0, 1, 3]], nodes[:, [0, 1, 2]])
    second = np.where(on13[:, None], nodes[:, [1, 2, 3]], nodes[:, [0, 2, 3]])[quad]
    return np.concatenate([first, second]), quad


def orient(triangles):
    """The triangles turned consistently across every edge two of them share (solver decks' shells often
    face either way; the engine needs one turn).  In each connected piece the turn most of its triangles
    have is kept.  A piece that cannot be turned consistently (a Moebius band) is left as it is."""
    return _orient(triangles)[0]


def _orient(triangles):
    """(orient(triangles), open edges, non-manifold edges): the edge counts come with the edge sort."""
    t = np.asarray(triangles, np.int64)
    tail, head = t.ravel(), np.roll(t, -1, axis=1).ravel()
    key = np.minimum(tail, head) * (int(t.max()) + 1) + np.maximum(tail, head)
    order = np.argsort(key, kind="stable")
    k = key[order]
    runs = np.diff(np.flatnonzero(np.r_[True, k[1:] != k[:-1], True]))  # how many triangles share each edge
    defects = int(np.sum(runs == 1)), int(np.sum(runs > 2))
    pair = np.flatnonzero((k[1:] == k[:-1]) & ((np.r_[k[2:], -1] != k[1:])) & (np.r_[-1, k[:-2]] != k[1:]))
    a, b = order[pair], order[pair + 1]
    same = tail[a] == tail[b]  # both run the edge the same way: one of them must turn
    if not same.any():
        return (t, *defects)
    ta, tb = a // 3, b // 3
    # Breadth-first over shared edges; flip[t] is whether triangle t turns.
    n = len(t)
    nbr = np.concatenate([tb, ta])
    rel = np.concatenate([same, same])
    src = np.concatenate([ta, tb])
    srt = np.argsort(src, kind="stable")
    nbr, rel = nbr[srt], rel[srt]
    start = np.searchsorted(src[srt], np.arange(n + 1))
    flip = np.zeros(n, bool)
    seen = np.zeros(n, bool)
    for root in range(n):
        if seen[root]:
            continue
        seen[root] = True
        piece, queue, consistent = [root], [root], True
        while queue:
            x = queue.pop()
            for j in range(start[x], start[x + 1]):
                y, want = nbr[j], flip[x] ^ rel[j]
                if not seen[y]:
                    seen[y] = True
                    flip[y] = want
                    piece.append(y)
                    queue.append(y)
                elif flip[y] != want:
                    consistent = False
        piece = np.array(piece)
        if not consistent:
            flip[piece] = False
        elif flip[piece].sum() * 2 > len(piece):
            flip[piece] = ~flip[piece]
    t = t.copy()
    t[flip] = t[flip][:, ::-1]
    return (t, *defects)




def round_deck(in_path, out_path, seeds, radius, part=None, tolerance=None, feature_angle=30.0, reach=3.0,
               quad_options=None, node_id_start=None, element_id_start=None, keep_unused_nodes=False,
               cancel=None, band=None):
    """Round the sharp-edge chains nearest to `seeds` in the deck at in_path and write the deck to out_path
    (same format family, by extension).  part: a part ID (LS-DYNA/Nastran PID, Abaqus: the index of the
    ELSET in read_deck()["parts"]) to round alone; the other parts are kept as they are.  Other arguments as
    round_edges (band: the band's element controls).  report["deck"]["quality"]: the new elements' quality.
    Returns DeckRoundingResult; raises RoundingError (nothing written)."""
    def run(split):
        return api.round_arrays(split.vertices, split.triangles, seeds, radius, tolerance=tolerance,
                                feature_angle=feature_angle, reach=reach, cancel=cancel, band=band, arrays=False)
    return edit_deck(in_path, out_path, run, part, quad_options, node_id_start, element_id_start, keep_unused_nodes)


def change_radius_deck(in_path, out_path, seeds, radius, part=None, tolerance=None, feature_angle=30.0, reach=3.0,
                       quad_options=None, node_id_start=None, element_id_start=None, keep_unused_nodes=False,
                       cancel=None, band=None, fit_tolerance=0.01):
    """Change the radius of the existing rounds `seeds` pick in the deck at in_path (MeshRound.change_radius
    on its shells: radius 0 sharpens them) and write the deck to out_path, as round_deck does: only the
    band's elements and nodes change, the rest keeps its IDs and lines.  report["found_radius"] and
    report["strips"] say what was found.  Returns DeckRoundingResult; raises RoundingError (not_a_round
    and the others; nothing written)."""
    from . import reround

    def run(split):
        return reround.change_radius_arrays(split.vertices, split.triangles, seeds, radius, tolerance, feature_angle,
                                            reach, None, cancel, fit_tolerance, band, arrays=False)
    return edit_deck(in_path, out_path, run, part, quad_options, node_id_start, element_id_start, keep_unused_nodes)


def edit_deck(in_path, out_path, run, part=None, quad_options=None, node_id_start=None, element_id_start=None,
              keep_unused_nodes=False):
    """The deck edit round_deck and change_radius_deck share: the deck at in_path read, its shells (of
    `part`) given as triangles (ShellTriangles) to run(split), which returns an api.RoundingResult whose
    delta edits them; the delta turned into elements and nodes (deck_edit.py), the deck written to out_path
    and checked (deck_check.py), all or nothing."""
    from . import deck_check, deck_edit  # the mesh -> elements step and the written deck's check
    stamps = [_stamp()]
    _check_extension(out_path)
    if DECK_EXTENSIONS[_ext(in_path)] != DECK_EXTENSIONS[_ext(out_path)]:
        raise RoundingError(f"'{out_path}' is not the same deck format as '{in_path}' (no conversion between formats)",
                            code="invalid_input")
    arrays = read_deck(in_path)
    stamps.append(_stamp())
    split = shell_triangles(arrays, part)
    stamps.append(_stamp())
    # The result is used as its delta (the band); its whole arrays are made only if asked for.
    result = run(split)
    stamps.append(_stamp())
    edits, summary, band = deck_edit.edits_for(arrays, split, result, quad_options or QuadOptions(),
                                               node_id_start, element_id_start, keep_unused_nodes)
    stamps.append(_stamp())
    texts = arrays["deck"].write(**edits)
    stamps.append(_stamp())
    paths = _write_checked(arrays, texts, in_path, out_path,
                           lambda path: deck_check.check_written(path, arrays, part, split, edits, band, summary))
    stamps.append(_stamp())
    report = dict(result.report)
    report["deck"] = summary
    steps = ("read", "split", "round", "elements", "write", "save_and_check")
    # Wall and processor seconds of each step (on a shared machine the second is the steadier figure).
    report["seconds_deck"] = {k: b[0] - a[0] for k, a, b in zip(steps, stamps, stamps[1:])}
    report["cpu_seconds_deck"] = {k: b[1] - a[1] for k, a, b in zip(steps, stamps, stamps[1:])}
    report["seconds"] = stamps[-1][0] - stamps[0][0]
    return DeckRoundingResult(paths=paths, report=report, result=result)


def _stamp():
    return time.perf_counter(), time.process_time()


def _ext(path):
    return os.path.splitext(str(path))[1].lower()


def _check_extension(path):
    if _ext(path) not in DECK_EXTENSIONS:
        raise RoundingError(f"'{path}' is not a solver deck by its extension (.k .key .dyn: LS-DYNA, "
                            ".bdf .nas .dat: Nastran, .inp: Abaqus)", code="invalid_input")


def _write_checked(arrays, texts, in_path, out_path, check):
    """Writes the files into a temporary folder beside out_path, reads them back and checks them, then moves
    them into place.  Included files go beside out_path under their relative names; an unchanged one in the
    same place as the input's is shared, a changed one there is refused (it would overwrite the input)."""
    in_dir = os.path.dirname(os.path.abspath(in_path))
    out_dir = os.path.dirname(os.path.abspath(out_path))
    old_texts = arrays["deck"].texts() if len(texts) > 1 else []  # (only the includes' are compared)
    rels, targets = [os.path.basename(out_path)], [os.path.abspath(out_path)]
    for path, old, new in zip(arrays["files"][1:], old_texts[1:], texts[1:]):
        rel = os.path.relpath(os.path.abspath(path), in_dir)
        if rel.startswith(".."):
            raise RoundingError(f"the included file '{path}' is outside the deck's folder: cannot place its copy",
                                code="invalid_input")
        target = os.path.join(out_dir, rel)
        if target == os.path.abspath(path):
            if old != new:
                raise RoundingError(f"the rounding changes the included file '{path}'; writing it beside "
                                    f"'{out_path}' would overwrite the input: choose another output folder",
                                    code="invalid_input")
            target = None  # shared, unchanged
        rels.append(rel)
        targets.append(target)
    stage = tempfile.mkdtemp(prefix=".meshround-deck-", dir=out_dir)
    try:
        for rel, text in zip(rels, texts):
            path = os.path.join(stage, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "wb") as stream:
                stream.write(text)
        check(os.path.join(stage, rels[0]))  # raises: nothing written
        written = []
        for rel, target in zip(rels, targets):
            if target is not None:
                os.makedirs(os.path.dirname(target), exist_ok=True)
                os.replace(os.path.join(stage, rel), target)
                written.append(target)
        return written
    finally:
        shutil.rmtree(stage, ignore_errors=True)
