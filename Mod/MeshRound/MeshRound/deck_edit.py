"""The rounded triangles turned back into deck edits (decks.round_deck's middle step).

Input: the deck's arrays (decks.read_deck), the triangles given to the engine (with their shell and node
maps) and the engine's result.  Output: the keyword arguments of Deck.write (removed node and element IDs,
new nodes, new elements, sets with new members) and a summary for the report.

  1. Output vertices equal (bit for bit) to an input vertex are that node; the others are new nodes.
  2. An output triangle equal to an input triangle (same nodes, same turn) is that triangle kept; an element
     is kept when all its triangles are.
  3. The triangles to write are the new ones and the kept halves of removed quads; two of them that share an
     edge become one quad when the quad is convex, its corners within 90 +- max_corner_skew degrees and
     the two halves within max_warp degrees of each other (best quads first).
  4. A new element takes the part of the removed element nearest to it (centroids); a set that held
     removed elements (nodes) gets the new elements (nodes) whose nearest removed one it held, and the new
     one nearest to each removed member.  A Nastran SET1 whose IDs do not tell grids from elements
     (kind_known False) is kept as it is, unless it holds an ID the rounding removes: then the rounding is
     refused (which to put in its place is not known).
"""
import numpy as np

from .errors import RoundingError, require_core

_CHUNK = 256  # rows per block of the nearest-point search (memory: CHUNK x targets x 3 doubles)


def edits_for(arrays, vertices, triangles, tri_shell, vertex_node, result, quad_options, node_id_start,
              element_id_start, keep_unused_nodes):
    out_v, out_t = result.vertices, result.triangles
    match = _match_rows(vertices, out_v)
    in_kept, out_is_input = _kept_triangles(triangles, match, out_t)
    shells = np.unique(tri_shell)
    lost = np.zeros(len(arrays["shell_ids"]), bool)
    lost[tri_shell[~in_kept]] = True
    removed_shells = np.flatnonzero(lost)
    # Triangles to write: new ones, and kept halves of removed quads (their element is rewritten).
    out_shell = np.full(len(out_t), -1)
    out_shell[out_is_input >= 0] = tri_shell[out_is_input[out_is_input >= 0]]
    write = np.flatnonzero((out_is_input < 0) | lost[np.maximum(out_shell, 0)] & (out_shell >= 0))
    elements = _pair_quads(out_v, out_t[write], quad_options)  # (e, 4) rows into out_v, -1 4th for a triangle

    used = np.unique(elements[elements >= 0])
    new_vertices = used[match[used] < 0]
    first_node = int(node_id_start) if node_id_start is not None else int(arrays["max_node_id"]) + 1
    vertex_id = np.zeros(len(out_v), np.int64)
    matched = match >= 0
    vertex_id[matched] = arrays["node_ids"][vertex_node[match[matched]]]
    vertex_id[new_vertices] = first_node + np.arange(len(new_vertices))
    first_element = int(element_id_start) if element_id_start is not None else int(arrays["max_element_id"]) + 1
    element_ids = first_element + np.arange(len(elements))
    element_nodes = np.where(elements >= 0, vertex_id[np.maximum(elements, 0)], 0)

    # Parts: the nearest removed element's.
    centroids = _centroids(out_v, elements)
    removed_centroids = _shell_centroids(arrays, removed_shells)
    if len(elements) and not len(removed_shells):
        raise RoundingError("the rounding added facets but removed no element", code="result_invalid")
    replaces = removed_shells[_nearest(centroids, removed_centroids)] if len(elements) else np.zeros(0, int)
    parts = arrays["shell_parts"][replaces]

    removed_nodes = _removed_nodes(arrays, lost, element_nodes, keep_unused_nodes)
    removed_node_xyz = arrays["node_xyz"][_lookup_rows(arrays["node_ids"][:, None], removed_nodes[:, None])]
    set_members = _set_updates(arrays,
                               {"elements": (arrays["shell_ids"][removed_shells], removed_centroids),
                                "nodes": (removed_nodes, removed_node_xyz)},
                               {"elements": (element_ids, centroids), "nodes": (vertex_id[new_vertices], out_v[new_vertices])})
    edits = dict(removed_nodes=removed_nodes, removed_shells=arrays["shell_ids"][removed_shells],
                 node_ids=vertex_id[new_vertices], node_xyz=out_v[new_vertices],
                 shell_ids=element_ids, shell_parts=parts, shell_nodes=element_nodes, set_members=set_members)
    quads = int(np.sum(elements[:, 3] >= 0))
    selected_quads = arrays["shell_counts"][shells] == 4
    summary = {
        "format": arrays["format"], "elements_in": int(len(shells)),
        "elements_kept": int(len(shells) - len(removed_shells)), "elements_removed": int(len(removed_shells)),
        "quads_in": int(np.sum(selected_quads)), "quads_kept": int(np.sum(selected_quads & ~lost[shells])),
        "new_quads": quads, "new_triangles": int(len(elements) - quads),
        "new_quad_share": float(quads / len(elements)) if len(elements) else 0.0,
        "nodes_new": int(len(new_vertices)), "nodes_removed": int(len(removed_nodes)),
        "node_ids": [int(first_node), int(first_node + len(new_vertices) - 1)] if len(new_vertices) else [],
        "element_ids": [int(first_element), int(element_ids[-1])] if len(elements) else [],
        "sets_updated": [int(i) for i, _ in set_members],
        # The new elements as CAE checks them (angles, aspect ratio, quads' warpage, shortest side).
        "quality": require_core().element_quality(out_v, elements),
    }
    return edits, summary


def _mix(words):
    """splitmix64's finaliser on each 64-bit word (coordinates on a grid differ only in a few bits)."""
    x = words.copy()
    with np.errstate(over="ignore"):
        x ^= x >> np.uint64(30)
        x *= np.uint64(0xBF58476D1CE4E5B9)
        x ^= x >> np.uint64(27)
        x *= np.uint64(0x94D049BB133111EB)
        x ^= x >> np.uint64(31)
    return x


def _row_hash(rows):
    words = rows.view(np.uint64).reshape(len(rows), -1)
    key = np.zeros(len(rows), np.uint64)
    with np.errstate(over="ignore"):
        for j in range(words.shape[1]):
            key = _mix(key * np.uint64(31) + words[:, j])
    return key


def _lookup_rows(table, query):
    """For each row of query, the index of an equal row (bit for bit) of table, or -1: rows hashed to one
    64-bit key each, sorted, and every candidate checked in full (a key shared by unequal rows is walked)."""
    table, query = np.ascontiguousarray(table), np.ascontiguousarray(query)
    if len(table) == 0 or len(query) == 0:
        return np.full(len(query), -1)
    tk = _row_hash(table)
    order = np.argsort(tk)
    sorted_keys = tk[order]
    qk = _row_hash(query)
    by_key = np.argsort(qk)  # queries in key order: the search walks the table once (3x faster on 2M)
    at = np.empty(len(qk), np.int64)
    at[by_key] = np.minimum(np.searchsorted(sorted_keys, qk[by_key]), len(table) - 1)
    found = np.all(table[order[at]] == query, axis=1)
    out = np.where(found, order[at], -1)
    for q in np.flatnonzero(~found & (sorted_keys[at] == qk)):  # same key, other row: look further
        j = at[q] + 1
        while j < len(table) and sorted_keys[j] == qk[q]:
            if np.array_equal(table[order[j]], query[q]):
                out[q] = order[j]
                break
            j += 1
    return out


def _match_rows(vertices, out_v):
    """For each output vertex, the input vertex with the same coordinates (bit for bit), or -1."""
    return _lookup_rows(np.asarray(vertices, np.float64) + 0.0, np.asarray(out_v, np.float64) + 0.0)


def _canonical(tris):
    """Triangles rotated to start at their smallest index (the turn kept)."""
    k = np.argmin(tris, axis=1)
    idx = (k[:, None] + np.arange(3)[None, :]) % 3
    return np.take_along_axis(tris, idx, axis=1).astype(np.int64)


def _kept_triangles(triangles, match, out_t):
    """(in_kept: bool per input triangle, out_is_input: per output triangle its input triangle or -1)."""
    mapped = match[out_t]
    full = np.all(mapped >= 0, axis=1)
    out_is_input = np.full(len(out_t), -1)
    if np.any(full):
        out_is_input[full] = _lookup_rows(_canonical(np.asarray(triangles)), _canonical(mapped[full]))
    in_kept = np.zeros(len(triangles), bool)
    in_kept[out_is_input[out_is_input >= 0]] = True
    return in_kept, out_is_input


def _pair_quads(points, tris, options):
    """Rows (a, b, c, d) of quads and (a, b, c, -1) of triangles covering `tris` (each used once)."""
    tris = np.asarray(tris, np.int64)
    single = np.column_stack([tris, np.full(len(tris), -1)])
    if not options.quads or len(tris) < 2:
        return single
    n = len(tris)
    tail, head = tris, np.roll(tris, -1, axis=1)  # directed edge k: tris[:, k] -> tris[:, k+1]
    lo, hi = np.minimum(tail, head).ravel(), np.maximum(tail, head).ravel()
    keys = lo * (int(points.shape[0]) + 1) + hi
    order = np.argsort(keys, kind="stable")
    k_sorted = keys[order]
    twin = np.flatnonzero(k_sorted[1:] == k_sorted[:-1])
    if len(twin) == 0:
        return single
    # Edges shared by exactly two triangles (a third would make the pair ambiguous).
    ok = np.ones(len(twin), bool)
    ok &= (twin + 2 >= len(k_sorted)) | (k_sorted[np.minimum(twin + 2, len(k_sorted) - 1)] != k_sorted[twin])
    ok &= (twin == 0) | (k_sorted[np.maximum(twin - 1, 0)] != k_sorted[twin])
    a_slot, b_slot = order[twin[ok]], order[twin[ok] + 1]
    ti, ki = a_slot // 3, a_slot % 3
    tj, kj = b_slot // 3, b_slot % 3
    p0, p1, p2 = tris[ti, ki], tris[ti, (ki + 1) % 3], tris[ti, (ki + 2) % 3]
    q = tris[tj, (kj + 2) % 3]
    same_turn = tris[tj, (kj + 1) % 3] == p0  # the other triangle runs the edge the other way
    quads = np.column_stack([p0, q, p1, p2])
    skew, warp, convex = _quad_quality(points, quads, points[tris[ti]], points[tris[tj]])
    good = same_turn & convex & (skew <= options.max_corner_skew) & (warp <= options.max_warp) & (ti != tj)
    ti, tj, quads, skew = ti[good], tj[good], quads[good], skew[good]
    taken = np.zeros(n, bool)
    rows = []
    for c in np.argsort(skew, kind="stable"):
        i, j = ti[c], tj[c]
        if taken[i] or taken[j]:
            continue
        taken[i] = taken[j] = True
        rows.append(quads[c])
    paired = np.array(rows, np.int64).reshape(-1, 4)
    return np.concatenate([paired, single[~taken]])


def _quad_quality(points, quads, tri_i, tri_j):
    """Per quad: largest corner departure from 90 deg, angle between its halves' normals, convex."""
    P = points[quads]  # (q, 4, 3)
    prev, nxt = np.roll(P, 1, axis=1) - P, np.roll(P, -1, axis=1) - P
    cos = np.sum(prev * nxt, axis=2) / np.maximum(np.linalg.norm(prev, axis=2) * np.linalg.norm(nxt, axis=2), 1e-300)
    skew = np.max(np.abs(np.degrees(np.arccos(np.clip(cos, -1, 1))) - 90.0), axis=1)
    ni = np.cross(tri_i[:, 1] - tri_i[:, 0], tri_i[:, 2] - tri_i[:, 0])
    nj = np.cross(tri_j[:, 1] - tri_j[:, 0], tri_j[:, 2] - tri_j[:, 0])
    cosw = np.sum(ni * nj, axis=1) / np.maximum(np.linalg.norm(ni, axis=1) * np.linalg.norm(nj, axis=1), 1e-300)
    warp = np.degrees(np.arccos(np.clip(cosw, -1, 1)))
    normal = ni + nj
    turn = np.cross(nxt, prev)  # at each corner, along the normal for a convex corner (counter-clockwise)
    convex = np.all(np.sum(turn * normal[:, None, :], axis=2) > 0, axis=1)
    return skew, warp, convex


def _centroids(points, elements):
    valid = elements >= 0
    sums = np.einsum("ek,ekj->ej", valid.astype(float), points[np.maximum(elements, 0)])
    return sums / valid.sum(axis=1)[:, None]


def _shell_centroids(arrays, shells):
    nodes = arrays["shell_nodes"][shells]
    valid = nodes >= 0
    sums = np.einsum("ek,ekj->ej", valid.astype(float), arrays["node_xyz"][np.maximum(nodes, 0)])
    return sums / valid.sum(axis=1)[:, None]


def _nearest(points, targets):
    """For each point, the index of the nearest target: scipy's k-d tree when scipy is there (Debian's
    python3-scipy), else brute force in blocks (fine for bands of a few thousand elements)."""
    points = np.asarray(points, np.float64).reshape(-1, 3)
    try:
        from scipy.spatial import cKDTree
    except ImportError:
        cKDTree = None
    if cKDTree is not None and len(targets):
        return cKDTree(targets).query(points)[1].astype(np.int64)
    out = np.zeros(len(points), np.int64)
    t2 = np.sum(targets * targets, axis=1)
    for a in range(0, len(points), _CHUNK):
        block = points[a:a + _CHUNK]
        d = t2[None, :] - 2.0 * block @ targets.T
        out[a:a + _CHUNK] = np.argmin(d, axis=1)
    return out


def _removed_nodes(arrays, lost, element_nodes, keep_unused):
    """IDs of nodes that only removed elements used (none with keep_unused)."""
    if keep_unused or not np.any(lost):
        return np.zeros(0, np.int64)
    nodes = arrays["shell_nodes"]
    before = np.zeros(len(arrays["node_ids"]), bool)
    still = np.zeros(len(arrays["node_ids"]), bool)
    before[nodes[lost][nodes[lost] >= 0]] = True
    kept = nodes[~lost]
    still[kept[kept >= 0]] = True
    ids = arrays["node_ids"][before & ~still]
    return np.setdiff1d(ids, element_nodes[element_nodes > 0])


def _set_updates(arrays, removed, new):
    """[(set index, new member IDs)] for the sets that held a removed element or node.  removed/new:
    {"elements"/"nodes": (IDs, points)}.  A set gets the new entities whose nearest removed one it held, and
    for each removed member the new entity nearest to it (so each removed member has a replacement)."""
    nearest = {}
    for kind in ("elements", "nodes"):
        (gone, gone_at), (made, made_at) = removed[kind], new[kind]
        if len(gone) and len(made):
            nearest[kind] = (gone[_nearest(made_at, gone_at)], made[_nearest(gone_at, made_at)])
    updates = []
    for index, s in enumerate(arrays["sets"]):
        if not s.get("kind_known", True):
            _refuse_if_touched(arrays, s, removed)
            continue
        kind = "nodes" if s["of_nodes"] else "elements"
        members = np.asarray(s["members"], np.int64)
        held = np.isin(members, removed[kind][0])
        if not np.any(held):
            continue
        added = np.zeros(0, np.int64)
        if kind in nearest:
            by, closest = nearest[kind]
            made = new[kind][0]
            added = np.union1d(made[np.isin(by, members[held])], closest[np.isin(removed[kind][0], members[held])])
        updates.append((index, np.concatenate([members[~held], added])))
    return updates


def _refuse_if_touched(arrays, s, removed):
    """A set of unknown kind (a Nastran SET1 whose IDs are grid and element IDs alike, or neither) that holds an
    ID the rounding removes as a grid or as an element: RoundingError (invalid_input) naming its card."""
    members = np.asarray(s["members"], np.int64)
    gone = [f"{what} {int(x)}" for what, kind in (("grid", "nodes"), ("element", "elements"))
            for x in members[np.isin(members, removed[kind][0])][:3]]
    if gone:
        raise RoundingError(f"{arrays['files'][s['file']]}:{s['line']}: SET1 {s['id']} holds IDs the rounding "
                            f"removes ({', '.join(gone)}), and whether it is a set of grids or of elements is not "
                            "clear from its IDs (they are not all grid IDs alone or all element IDs alone): give it "
                            "as SET3 with GRID or ELEM to round this deck", code="invalid_input")
