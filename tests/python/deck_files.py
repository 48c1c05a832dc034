"""Solver decks written by hand for the deck tests and benchmark (independent of the engine's writer).

`box_quads(size, h)`: a structured quad mesh of an axis box (the CAD solid cases.box() is), each face a grid
of near-square quads sharing nodes along the box's edges, outward turn.  `write_deck(path, style, ...)`
writes it as one deck in one field style (see STYLES), with two parts (the top face and the rest), an
element set and a node set along the top back edge, a set far from it, comments and unknown cards; some
styles put the nodes in an included file.
"""
import os

import numpy as np

STYLES = ("lsdyna_fixed", "lsdyna_long", "lsdyna_i10_free", "nastran_small", "nastran_large", "nastran_free",
          "abaqus")
EXTENSION = {"lsdyna": ".k", "nastran": ".bdf", "abaqus": ".inp"}


def box_quads(size, h):
    """(xyz (n, 3), quads (m, 4) 0-based, face (m,) index 0..5 with 5 = the top z = size[2])."""
    L = np.asarray(size, float)
    n = np.maximum(1, np.round(L / h).astype(int))
    points, quads, faces = [], [], []
    for axis in range(3):
        for side in (0, 1):
            u, v = [(1, 2), (2, 0), (0, 1)][axis]
            if side == 0:
                u, v = v, u  # u x v outward
            i, j = np.meshgrid(np.arange(n[u] + 1), np.arange(n[v] + 1), indexing="ij")
            p = np.zeros(i.shape + (3,))
            p[..., axis] = side * L[axis]
            p[..., u] = i * L[u] / n[u]
            p[..., v] = j * L[v] / n[v]
            ids = sum(len(x) for x in points) + np.arange(i.size).reshape(i.shape)
            quads.append(np.stack([ids[:-1, :-1], ids[1:, :-1], ids[1:, 1:], ids[:-1, 1:]], axis=-1).reshape(-1, 4))
            faces.append(np.full(len(quads[-1]), 2 * axis + side))
            points.append(p.reshape(-1, 3))
    # The faces' own points merged where they meet (the box's edges and corners).
    xyz, merged = np.unique(np.round(np.concatenate(points), 9), axis=0, return_inverse=True)
    return xyz, merged.ravel()[np.concatenate(quads)], np.concatenate(faces)


def family(style):
    return style.split("_")[0]


def write_deck(folder, style, xyz, quads, faces, near, far_elements, edge_nodes, name="box"):
    """Writes the deck (and its include, if the style has one) into folder; returns the main file's path.
    IDs: node i -> 1001 + i, element e -> 5001 + e; part 2 = the top face, part 1 = the rest."""
    node_ids = 1001 + np.arange(len(xyz))
    elem_ids = 5001 + np.arange(len(quads))
    parts = np.where(faces == 5, 2, 1)
    nodes = quads + 1001
    writer = {"lsdyna": _lsdyna, "nastran": _nastran, "abaqus": _abaqus}[family(style)]
    main, include = writer(style, xyz, node_ids, elem_ids, parts, nodes, elem_ids[near], elem_ids[far_elements],
                           node_ids[edge_nodes])
    path = os.path.join(folder, name + EXTENSION[family(style)])
    with open(path, "w", newline="") as f:
        f.write(main)
    if include is not None:
        with open(os.path.join(folder, include[0]), "w", newline="") as f:
            f.write(include[1])
    return path


def _rows(ids, per, fmt, sep=""):
    ids = list(ids)
    return [sep.join(fmt % x for x in ids[k:k + per]) for k in range(0, len(ids), per)]


def _lsdyna(style, xyz, node_ids, elem_ids, parts, nodes, near, far, edge):
    long_, i10, free = style == "lsdyna_long", style == "lsdyna_i10_free", False
    head = ["*KEYWORD", "$ a stamping die, written by tests/python/deck_files.py", "*TITLE", "box die",
            "*PART", "die body", "%10d%10d%10d" % (1, 1, 1), "*PART", "die top", "%10d%10d%10d" % (2, 1, 1),
            "*MAT_RIGID", "$#     mid        ro         e        pr", "         1   7.8E-09  210000.0       0.3",
            "*SECTION_SHELL", "         1         2       1.0"]
    node_lines = ["*NODE +" if long_ else ("*NODE %" if i10 else "*NODE")]
    for i, p in zip(node_ids, xyz):
        if long_:
            node_lines.append("%20d%20.10f%20.10f%20.10f" % (i, *p))
        elif i10:
            node_lines.append("%10d%16.8f%16.8f%16.8f%10d%10d" % (i, *p, 0, 0))
        else:
            node_lines.append("%8d%16.8f%16.8f%16.8f%8d%8d" % (i, *p, 0, 0))
    elems = ["*ELEMENT_SHELL %" if i10 else ("*ELEMENT_SHELL +" if long_ else "*ELEMENT_SHELL")]
    for k, (e, pid, n) in enumerate(zip(elem_ids, parts, nodes)):
        if i10 and k % 2:
            free = True
            elems.append(",".join(str(x) for x in (e, pid, *n)))  # comma free format, every other line
        else:
            w = 10 if i10 else (20 if long_ else 8)
            elems.append(("%" + str(w) + "d") * 6 % (e, pid, *n))
    sets = ["*SET_SHELL_LIST_TITLE", "shoulder", "%10d" % 11, *_rows(near, 8, "%10d"),
            "*SET_SHELL_LIST", "%10d" % 12, *_rows(far, 8, "%10d"),
            "*SET_NODE_LIST", "%10d" % 13, *_rows(edge, 8, "%10d"),
            "*BOUNDARY_SPC_SET", "%10d%10d%10d" % (13, 0, 1)]
    assert free or not i10
    if long_:  # nodes in an included file
        main = head + ["*INCLUDE", "box_nodes.k"] + elems + sets + ["*END"]
        return "\n".join(main) + "\n", ("box_nodes.k", "\n".join(["*KEYWORD"] + node_lines + ["*END"]) + "\n")
    return "\n".join(head + node_lines + elems + sets + ["*END"]) + "\n", None


def _nastran(style, xyz, node_ids, elem_ids, parts, nodes, near, far, edge):
    head = ["SOL 101", "CEND", "TITLE = box die", "BEGIN BULK", "$ written by tests/python/deck_files.py",
            "PSHELL  1       1       1.0", "PSHELL  2       1       1.0", "MAT1    1       210000.         0.3"]
    grids, elems = [], []
    for i, p in zip(node_ids, xyz):
        if style == "nastran_small":
            grids.append("GRID    %-8d        %-8s%-8s%-8s" % (i, *("%.4f" % c for c in p)))
        elif style == "nastran_large":
            grids.append("GRID*   %16d%16s%16.9f%16.9f" % (i, "", p[0], p[1]))
            grids.append("*       %16.9f" % p[2])
        else:
            grids.append("GRID,%d,,%.10g,%.10g,%.10g" % (i, *p))
    for e, pid, n in zip(elem_ids, parts, nodes):
        if style == "nastran_free":
            elems.append("CQUAD4,%d,%d,%d,%d,%d,%d" % (e, pid, *n))
        else:  # small fields with a continuation carrying the thickness flag
            elems.append("CQUAD4  %-8d%-8d%-8d%-8d%-8d%-8d0.      +" % (e, pid, *n))
            elems.append("+               1.0")
    sets = [*_nastran_set(style, 11, near), *_nastran_set(style, 12, far), *_nastran_set(style, 13, edge)]
    tail = sets + ["SPC1    1       123456  %-8d" % edge[0], "ENDDATA"]
    if style == "nastran_large":
        return "\n".join(head + ["INCLUDE 'box_grids.bdf'"] + elems + tail) + "\n", ("box_grids.bdf", "\n".join(grids) + "\n")
    return "\n".join(head + grids + elems + tail) + "\n", None


def _thru(ids):
    """IDs with runs of three or more written as `first THRU last`."""
    out, k = [], 0
    while k < len(ids):
        j = k
        while j + 1 < len(ids) and ids[j + 1] == ids[j] + 1:
            j += 1
        out += [str(ids[k]), "THRU", str(ids[j])] if j - k >= 2 else [str(x) for x in ids[k:j + 1]]
        k = j + 1
    return out


def _nastran_set(style, sid, ids):
    """A SET1 card (elements or grids: Nastran does not say) in the style's fields, with continuations: small
    field with markers in field 10 and field 1, large field with `*`, free field with a blank field 1."""
    fields = [str(sid)] + _thru(list(ids))
    if style == "nastran_free":
        return [("SET1," if k == 0 else ",") + ",".join(fields[k:k + 8]) for k in range(0, len(fields), 8)]
    per, width = (4, 16) if style == "nastran_large" else (8, 8)
    rows = [fields[k:k + per] for k in range(0, len(fields), per)]
    out = []
    for n, row in enumerate(rows):
        if style == "nastran_large":
            head = "SET1*   " if n == 0 else "*       "
            out.append(head + "".join("%-16s" % x for x in row))
        else:
            head = "SET1    " if n == 0 else "%-8s" % ("+S%d%d" % (sid, n))
            mark = "+S%d%d" % (sid, n + 1) if n + 1 < len(rows) else ""
            out.append((head + "".join("%-8s" % x for x in row)).ljust(72) + mark)
    return out


def _abaqus(style, xyz, node_ids, elem_ids, parts, nodes, near, far, edge):
    out = ["*HEADING", "box die", "** written by tests/python/deck_files.py", "*NODE, NSET=NALL"]
    out += ["%d, %.10g, %.10g, %.10g" % (i, *p) for i, p in zip(node_ids, xyz)]
    for pid, name in ((1, "BODY"), (2, "TOP")):
        out.append(f"*ELEMENT, TYPE=S4R, ELSET={name}")
        out += ["%d, %d, %d, %d, %d" % (e, *n) for e, p, n in zip(elem_ids, parts, nodes) if p == pid]
    out += ["*ELSET, ELSET=SHOULDER", *_rows(near, 16, "%d", ", "),
            "*ELSET, ELSET=FAR, GENERATE", "%d, %d, 1" % (far[0], far[-1]),
            "*NSET, NSET=EDGE", *_rows(edge, 16, "%d", ", "),
            "*SHELL SECTION, ELSET=BODY, MATERIAL=STEEL", "1.0", "*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3"]
    return "\n".join(out) + "\n", None
