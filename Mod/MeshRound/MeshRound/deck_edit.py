"""The rounded triangles turned back into deck edits (decks.round_deck's middle step), at the band's cost.

Input: the deck's arrays (decks.read_deck), the triangles given to the engine (decks.ShellTriangles) and
the engine's result, used as its delta (api.RoundingResult.delta: the input facets removed, the input
vertices moved, the points and facets added; mesh_delta.h).  Output: the keyword arguments of Deck.write
(removed node and element IDs, new nodes, new elements, sets with new members), a summary for the report
and the band (what decks' check needs).

  1. An input vertex the rounding neither moved nor made is its node.  A moved vertex or a new point equal
     (bit for bit) to one of the band's input vertices (those of removed facets, of facets added, moved
     ones, at their input position) is that vertex's node; the others are new nodes.
  2. An input facet the engine did not remove and whose vertices are their nodes is kept; so is a removed
     one the engine added again (same nodes, same turn).  An element is kept when all its triangles are.
  3. The triangles to write are the new ones and the kept halves of removed quads; two of them that share an
     edge become one quad when the quad is convex, its corners within 90 +- max_corner_skew degrees and
     the two halves within max_warp degrees of each other (best quads first).
  4. A new element takes the part of the removed element nearest to it (centroids); a set that held
     removed elements (nodes) gets the new elements (nodes) whose nearest removed one it held, and the new
     one nearest to each removed member.  A Nastran SET1 whose IDs do not tell grids from elements
     (kind_known False) is kept as it is, unless it holds an ID the rounding removes: then the rounding is
     refused (which to put in its place is not known).
Work: the band's, but for two boolean gathers over all shells (the nodes removed elements leave unused,
and -- only when the rounding moved a vertex to another node -- the facets using it): ~10 ms per million.
"""
import numpy as np

from .errors import RoundingError, require_core

_CHUNK = 256  # rows per block of the nearest-point search (memory: CHUNK x targets x 3 doubles)


def edits_for(arrays, split, result, quad_options, node_id_start, element_id_start, keep_unused_nodes):
    """(edits, summary, band): band = {"lost": removed shells (indices), "removed_nodes": removed nodes
    (indices), "element_vertices": each new element's nodes as input vertices (-1: a new node or none)}."""
    d = result.delta
    V, T, n = split.vertices, split.triangles, len(split.vertices)
    removed = np.asarray(d["removed"], np.int64)
    added = np.asarray(d["added"], np.int64).reshape(-1, 3)
    moved = np.asarray(d["moved"], np.int64)
    moved_to = np.asarray(d["moved_to"], np.float64).reshape(-1, 3)
    new_points = np.asarray(d["new_points"], np.float64).reshape(-1, 3)
    # 1. Delta ids (< n: input vertices, else new points) -> the input vertex whose node they are, or -1.
    near = np.unique(np.concatenate([T[removed].ravel(), added[added < n], moved]))
    hit = _lookup_rows(V[near] + 0.0, np.concatenate([moved_to, new_points]) + 0.0)
    as_input = np.where(hit >= 0, near[np.maximum(hit, 0)], -1)
    moved_as, new_as = as_input[:len(moved)], as_input[len(moved):]

    def node_vertex(ids):
        ids = np.asarray(ids, np.int64)
        out = np.where(ids < n, ids, -1)
        if len(new_as):
            out = np.where(ids >= n, new_as[np.clip(ids - n, 0, len(new_as) - 1)], out)
        if len(moved):
            at = np.minimum(np.searchsorted(moved, ids), len(moved) - 1)
            out = np.where((ids < n) & (moved[at] == ids), moved_as[at], out)
        return out

    def position(ids):
        out = np.empty((len(ids), 3))
        old = ids < n
        out[old] = V[ids[old]]
        out[~old] = new_points[ids[~old] - n]
        if len(moved):
            at = np.minimum(np.searchsorted(moved, ids), len(moved) - 1)
            is_moved = old & (moved[at] == ids)
            out[is_moved] = moved_to[at[is_moved]]
        return out

    # 2. Removed facets added again as they were; kept facets whose moved vertex is another node now.
    added_as = node_vertex(added)
    full = np.all(added_as >= 0, axis=1)
    again = np.full(len(added), -1)
    if np.any(full) and len(removed):
        hit = _lookup_rows(_canonical(T[removed]), _canonical(added_as[full]))
        again[np.flatnonzero(full)[hit >= 0]] = removed[hit[hit >= 0]]
    gone = np.setdiff1d(removed, again[again >= 0])
    changed = moved[moved_as != moved]
    if len(changed):  # (a gather over all facets, only for such a rounding)
        mark = np.zeros(n, bool)
        mark[changed] = True
        gone = np.union1d(gone, np.flatnonzero(mark[T].any(axis=1)))
    lost_shells = np.unique(split.tri_shell[gone])
    lost = np.zeros(len(arrays["shell_ids"]), bool)
    lost[lost_shells] = True
    # 3. Triangles to write (delta ids): kept facets of removed shells, then the new ones (and ones added
    # again whose element is removed).
    in_lost = split.of_shells(lost_shells)
    keep_in = np.setdiff1d(in_lost, removed)
    write_added = (again < 0) | lost[split.tri_shell[np.maximum(again, 0)]]
    rows = np.concatenate([T[keep_in], added[write_added]])
    ids, local = np.unique(rows, return_inverse=True)
    points, vertex_as = position(ids), node_vertex(ids)
    elements = _pair_quads(points, local.reshape(-1, 3), quad_options)  # (e, 4) into points, -1 4th: a triangle

    used = np.unique(elements[elements >= 0])
    new_vertices = used[vertex_as[used] < 0]
    first_node = int(node_id_start) if node_id_start is not None else int(arrays["max_node_id"]) + 1
    vertex_id = np.zeros(len(points), np.int64)
    matched = vertex_as >= 0
    vertex_id[matched] = arrays["node_ids"][split.vertex_node[vertex_as[matched]]]
    vertex_id[new_vertices] = first_node + np.arange(len(new_vertices))
    first_element = int(element_id_start) if element_id_start is not None else int(arrays["max_element_id"]) + 1
    element_ids = first_element + np.arange(len(elements))
    element_nodes = np.where(elements >= 0, vertex_id[np.maximum(elements, 0)], 0)

    # Parts: the nearest removed element's.
    centroids = _centroids(points, elements)
    removed_centroids = _shell_centroids(arrays, lost_shells)
    if len(elements) and not len(lost_shells):
        raise RoundingError("the rounding added facets but removed no element", code="result_invalid")
    replaces = lost_shells[_nearest(centroids, removed_centroids)] if len(elements) else np.zeros(0, int)
    parts = arrays["shell_parts"][replaces]

    removed_node_index = _removed_nodes(arrays, lost, lost_shells, element_nodes, keep_unused_nodes)
    removed_nodes = arrays["node_ids"][removed_node_index]
    set_members = _set_updates(arrays,
                               {"elements": (arrays["shell_ids"][lost_shells], removed_centroids),
                                "nodes": (removed_nodes, arrays["node_xyz"][removed_node_index])},
                               {"elements": (element_ids, centroids), "nodes": (vertex_id[new_vertices], points[new_vertices])})
    edits = dict(removed_nodes=removed_nodes, removed_shells=arrays["shell_ids"][lost_shells],
                 node_ids=vertex_id[new_vertices], node_xyz=points[new_vertices],
                 shell_ids=element_ids, shell_parts=parts, shell_nodes=element_nodes, set_members=set_members)
    quads = int(np.sum(elements[:, 3] >= 0))
    quads_in = int(len(split.quads))
    summary = {
        "format": arrays["format"], "elements_in": int(len(split.shells)),
        "elements_kept": int(len(split.shells) - len(lost_shells)), "elements_removed": int(len(lost_shells)),
        "quads_in": quads_in, "quads_kept": quads_in - int(np.sum(arrays["shell_counts"][lost_shells] == 4)),
        "new_quads": quads, "new_triangles": int(len(elements) - quads),
        "new_quad_share": float(quads / len(elements)) if len(elements) else 0.0,
        "nodes_new": int(len(new_vertices)), "nodes_removed": int(len(removed_nodes)),
        "node_ids": [int(first_node), int(first_node + len(new_vertices) - 1)] if len(new_vertices) else [],
        "element_ids": [int(first_element), int(element_ids[-1])] if len(elements) else [],
        "sets_updated": [int(i) for i, _ in set_members],
        # The new elements as CAE checks them (angles, aspect ratio, quads' warpage, shortest side).
        "quality": require_core().element_quality(points, elements),
    }
    band = {"lost": lost_shells, "removed_nodes": removed_node_index,
            "element_vertices": np.where(elements >= 0, vertex_as[np.maximum(elements, 0)], -1)}
    return edits, summary, band


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


def _canonical(tris):
    """Triangles rotated to start at their smallest index (the turn kept)."""
    k = np.argmin(tris, axis=1)
    idx = (k[:, None] + np.arange(3)[None, :]) % 3
    return np.take_along_axis(tris, idx, axis=1).astype(np.int64)


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


def _removed_nodes(arrays, lost, lost_shells, element_nodes, keep_unused):
    """Indices of the nodes that only removed elements used and no new element uses (none with keep_unused):
    the removed elements' nodes, less those a kept shell of any part uses (one gather over all shells)."""
    if keep_unused or not len(lost_shells):
        return np.zeros(0, np.int64)
    nodes = arrays["shell_nodes"]
    candidates = np.unique(nodes[lost_shells])
    candidates = candidates[candidates >= 0]
    mark = np.zeros(len(arrays["node_ids"]) + 1, bool)  # the last one: a triangle's 4th node (-1), never marked
    mark[candidates] = True
    touching = np.flatnonzero(mark[nodes].any(axis=1))
    still = nodes[touching[~lost[touching]]]
    unused = np.setdiff1d(candidates, still[still >= 0])
    return unused[~np.isin(arrays["node_ids"][unused], element_nodes[element_nodes > 0])]


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
