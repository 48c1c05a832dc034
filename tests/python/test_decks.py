"""Solver decks in and out (issue 14): LS-DYNA, Nastran and Abaqus decks written here in every field style
(deck_files.py: a structured quad mesh of cases.box()'s solid, two parts, sets, comments, unknown cards,
includes), read and written back byte-identical, rounded with MeshRound.round_deck, and checked line by
line, for quads kept outside the band, a quad-dominant band, IDs, parts and sets, and the geometry against
OCCT's fillet of the box both ways (reference.py)."""
import os

import numpy as np
import pytest

import cases
import deck_files
import reference
from conftest import MeshRound

from MeshRound import _meshround_core as core
from MeshRound import decks, meshconv

SIZE, H, R = (60.0, 40.0, 30.0), 2.5, 5.0
SEED = (37.0, 40.0, 30.0)  # on the box's top back edge (y = 40, z = 30): cases.box()'s chain
REACH = 3.0


def edge_distance(p):
    """Distance of points to the top back edge segment."""
    p = np.atleast_2d(p)
    x = np.clip(p[:, 0], 0, SIZE[0])
    return np.linalg.norm(p - np.column_stack([x, np.full(len(p), 40.0), np.full(len(p), 30.0)]), axis=1)


@pytest.fixture(scope="module")
def box():
    xyz, quads, faces = deck_files.box_quads(SIZE, H)
    centroid = xyz[quads].mean(axis=1)
    near = np.flatnonzero(edge_distance(centroid) < 2 * H)       # elements along the edge (in the band)
    far = np.flatnonzero(faces == 4)                              # the bottom face: far from the band
    edge = np.flatnonzero(edge_distance(xyz) < 1e-9)               # nodes on the edge
    return xyz, quads, faces, near, far, edge


@pytest.fixture(scope="module")
def case():
    return cases.Case("deck_box_r5", cases.box, R)


def lines(path):
    with open(path, "rb") as f:
        return f.read().splitlines(keepends=True)


def record_lines(arrays):
    """{(file, 1-based line) of a node/element record} of a deck."""
    out = set()
    for kind in ("node", "shell"):
        for f, l, s in zip(arrays[kind + "_file"], arrays[kind + "_line"], arrays[kind + "_span"]):
            out.update((int(f), int(l) + k) for k in range(int(s)))
    return out


@pytest.fixture(scope="module", params=deck_files.STYLES)
def rounded(request, box, tmp_path_factory):
    folder = tmp_path_factory.mktemp(request.param)
    path = deck_files.write_deck(str(folder), request.param, *box)
    out = str(folder / "out" / ("box" + os.path.splitext(path)[1]))  # a folder of its own: includes are copied
    os.makedirs(os.path.dirname(out))
    res = MeshRound.round_deck(path, out, [SEED], R)
    return request.param, path, out, res


def test_every_style_reads_to_the_values_written_and_round_trips_byte_identical(box, tmp_path):
    xyz, quads, faces, near, far, edge = box
    for style in deck_files.STYLES:
        folder = tmp_path / style
        folder.mkdir()
        path = deck_files.write_deck(str(folder), style, *box)
        deck = MeshRound.read_deck(path)
        order = np.argsort(deck["node_ids"])
        np.testing.assert_array_equal(deck["node_ids"][order], 1001 + np.arange(len(xyz)))
        np.testing.assert_allclose(deck["node_xyz"][order], xyz, atol=1e-9, err_msg=style)
        shells = np.argsort(deck["shell_ids"])
        np.testing.assert_array_equal(deck["shell_node_ids"][shells], quads + 1001, err_msg=style)
        assert list(deck["shell_counts"]) == [4] * len(quads)
        np.testing.assert_array_equal(deck["shell_parts"][shells], np.where(faces == 5, 2, 1), err_msg=style)
        members = [(s["of_nodes"], set(s["members"])) for s in deck["sets"]]
        assert (False, set(5001 + near)) in members and (False, set(5001 + far)) in members, style
        assert (True, set(1001 + edge)) in members, style
        texts = deck["deck"].texts()
        assert deck["deck"].write() == texts, style
        assert texts[0] == open(path, "rb").read()
        assert len(texts) == (2 if style in ("lsdyna_long", "nastran_large") else 1), style


def test_rounded_deck_keeps_every_other_line_and_record(rounded):
    style, path, out, res = rounded
    before, after = MeshRound.read_deck(path), MeshRound.read_deck(out)
    d = res.report["deck"]
    assert d["elements_removed"] > 0 and d["new_quads"] > 0
    # Records kept: same ID, same text.  Removed: the band's.  New: IDs above the input's largest.
    text0, text1 = lines(path), lines(out)
    kept_ids = np.intersect1d(before["shell_ids"], after["shell_ids"])
    assert len(kept_ids) == d["elements_kept"] == len(before["shell_ids"]) - d["elements_removed"]
    at0 = dict(zip(before["shell_ids"], before["shell_line"]))
    at1 = dict(zip(after["shell_ids"], after["shell_line"]))
    if style not in ("lsdyna_long", "nastran_large"):  # (the node records are in the include there)
        for i in kept_ids[::7]:
            assert text0[at0[i] - 1] == text1[at1[i] - 1]
    new_elements = np.setdiff1d(after["shell_ids"], before["shell_ids"])
    new_nodes = np.setdiff1d(after["node_ids"], before["node_ids"])
    assert new_elements.min() > before["max_element_id"] and new_nodes.min() > before["max_node_id"]
    assert len(new_elements) == d["new_quads"] + d["new_triangles"] and len(new_nodes) == d["nodes_new"]
    # Every line that is no node or element record, and no line of a rewritten set, is in the output in order.
    changed_sets = [before["sets"][i] for i in d["sets_updated"]]
    skip = record_lines(before) | {(s["file"], l) for s in changed_sets for l in range(*s["data_lines"])}
    skip |= {(s["file"], s["line"]) for s in changed_sets if s["generate"]}
    other0 = [t for k, t in enumerate(text0) if (0, k + 1) not in skip]
    skip1 = record_lines(after) | {(s["file"], l) for i in d["sets_updated"] for s in [after["sets"][i]]
                                   for l in range(*s["data_lines"])}
    other1 = [t for k, t in enumerate(text1) if (0, k + 1) not in skip1]
    # ... all of them, in order; the only lines more are Abaqus's headers of the new *NODE / *ELEMENT blocks.
    extra = _without_subsequence(other1, other0)
    if style == "abaqus":
        assert 1 <= len(extra) <= 5 and all(t.startswith((b"*NODE\n", b"*ELEMENT, TYPE=")) for t in extra), extra
    else:
        assert extra == []


def test_quads_outside_the_band_stay_and_the_band_is_quad_dominant(rounded, box):
    style, path, out, res = rounded
    before, after = MeshRound.read_deck(path), MeshRound.read_deck(out)
    xyz0 = before["node_xyz"]
    far = edge_distance(xyz0[before["shell_nodes"]].reshape(-1, 3)).reshape(-1, 4).min(axis=1) > (REACH + 1) * R
    assert np.all(np.isin(before["shell_ids"][far], after["shell_ids"])), "an element beyond the band was changed"
    new = ~np.isin(after["shell_ids"], before["shell_ids"])
    quad = after["shell_counts"][new] == 4
    area = _areas(after["node_xyz"], after["shell_nodes"][new])
    assert quad.mean() >= 0.6, f"{style}: {quad.mean():.2f} of the band's new elements are quads"
    assert area[quad].sum() >= 0.7 * area.sum(), f"{style}: quads cover {area[quad].sum() / area.sum():.2f}"
    # New quads are convex and planar to within the chordal tolerance's worth (warp < 15 deg).
    q = after["shell_nodes"][new][quad]
    P = after["node_xyz"][q]
    n1 = np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0])
    n2 = np.cross(P[:, 2] - P[:, 0], P[:, 3] - P[:, 0])
    cos = np.sum(n1 * n2, axis=1) / np.linalg.norm(n1, axis=1) / np.linalg.norm(n2, axis=1)
    assert np.all(cos > np.cos(np.radians(15.0)))


def test_parts_sets_and_ids_carry_over(rounded):
    style, path, out, res = rounded
    before, after = MeshRound.read_deck(path), MeshRound.read_deck(out)
    new = ~np.isin(after["shell_ids"], before["shell_ids"])
    c = after["node_xyz"][after["shell_nodes"][new]].mean(axis=1)
    part = after["shell_parts"][new]
    top = c[:, 2] > 30 - 1e-6   # flat on the top face: its part (2)
    back = c[:, 1] > 40 - 1e-6  # flat on the back face: the body (1)
    assert top.any() and back.any()
    assert np.all(part[top] == 2) and np.all(part[back] == 1)
    assert set(part) <= {1, 2}
    removed_e = np.setdiff1d(before["shell_ids"], after["shell_ids"])
    removed_n = np.setdiff1d(before["node_ids"], after["node_ids"])
    for s0, s1 in zip(before["sets"], after["sets"]):
        gone = removed_n if s0["of_nodes"] else removed_e
        held = np.isin(s0["members"], gone)
        assert not np.isin(s1["members"], gone).any()
        np.testing.assert_array_equal(s1["members"][:np.sum(~held)], s0["members"][~held])
        if held.any():  # replaced by new entities, near the removed ones
            added = s1["members"][np.sum(~held):]
            assert len(added) > 0
            ids, where = (after["node_ids"], after["node_xyz"]) if s0["of_nodes"] else (after["shell_ids"], None)
            if where is not None:
                assert np.all(edge_distance(where[np.isin(ids, added)]) < (REACH + 1) * R)
        else:
            assert len(s1["members"]) == len(s0["members"])


def test_sets_touching_the_band_hold_the_replacements_the_far_one_is_kept(rounded, box):
    """The element set along the edge and the node set on it hold the new elements and nodes in place of the
    removed ones (Nastran: SET1 cards, rewritten in the deck's own fields); the far set's lines are as they were."""
    style, path, out, res = rounded
    xyz, quads, faces, near, far, edge = box
    before, after = MeshRound.read_deck(path), MeshRound.read_deck(out)
    index = {key: next(i for i, s in enumerate(before["sets"]) if set(s["members"]) == set(ids))
             for key, ids in (("near", 5001 + near), ("far", 5001 + far), ("edge", 1001 + edge))}
    assert sorted(res.report["deck"]["sets_updated"]) == sorted([index["near"], index["edge"]])
    text0, text1 = lines(path), lines(out)
    for key, ids, new in (("near", after["shell_ids"], after["shell_ids"] > before["max_element_id"]),
                          ("edge", after["node_ids"], after["node_ids"] > before["max_node_id"])):
        s0, s1 = before["sets"][index[key]], after["sets"][index[key]]
        assert s1["kind_known"] and s1["of_nodes"] == s0["of_nodes"] == (key == "edge")
        assert np.all(np.isin(s1["members"], ids)), "a set names an ID the deck no longer has"
        added = np.setdiff1d(s1["members"], s0["members"])
        assert len(added) and np.all(np.isin(added, ids[new])), (key, added)
        if key == "edge":
            assert np.all(edge_distance(after["node_xyz"][np.isin(ids, added)]) < R + 1e-6)
        first = text1[s1["data_lines"][0] - 1]
        if style.startswith("nastran"):  # the card in the deck's own fields
            head = {"nastran_small": b"SET1    ", "nastran_large": b"SET1*   ", "nastran_free": b"SET1,"}[style]
            assert first.startswith(head + str(s0["id"]).encode()), first
    s0, s1 = before["sets"][index["far"]], after["sets"][index["far"]]
    assert text0[s0["data_lines"][0] - 1:s0["data_lines"][1] - 1] == text1[s1["data_lines"][0] - 1:s1["data_lines"][1] - 1]
    np.testing.assert_array_equal(s0["members"], s1["members"])


def test_nastran_set1_of_unknown_kind_is_kept_unless_the_rounding_removes_its_ids(box, tmp_path):
    """A SET1 naming an element and a grid is neither a grid nor an element set: kept as it is far from the
    band; holding IDs the rounding removes, the rounding is refused naming its card (nothing written)."""
    xyz, quads, faces, near, far, edge = box
    path = deck_files.write_deck(str(tmp_path), "nastran_small", *box)
    low = np.flatnonzero(np.abs(xyz[:, 2]) < 1e-9)[0]  # a grid on the bottom face
    text = lines(path)
    at = next(k for k, t in enumerate(text) if t.startswith(b"ENDDATA"))
    text.insert(at, b"SET1    14      %-8d%-8d\n" % (5001 + far[0], 1001 + low))
    with open(path, "wb") as f:
        f.write(b"".join(text))
    out = str(tmp_path / "out" / "box.bdf")
    os.makedirs(os.path.dirname(out))
    MeshRound.round_deck(path, out, [SEED], R)
    s = next(s for s in MeshRound.read_deck(out)["sets"] if s["id"] == 14)
    assert not s["kind_known"] and lines(out)[s["line"] - 1] == text[at]
    text[at] = b"SET1    14      %-8d%-8d\n" % (5001 + near[0], 1001 + edge[len(edge) // 2])
    with open(path, "wb") as f:
        f.write(b"".join(text))
    os.remove(out)
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_deck(path, out, [SEED], R)
    assert err.value.code == "invalid_input" and f"{path}:{at + 1}: SET1 14 holds IDs the rounding removes" in str(err.value)
    assert "SET3 with GRID or ELEM" in str(err.value) and not os.path.exists(out)


def test_rounded_deck_matches_occt_fillet_both_ways(rounded, case):
    style, path, out, res = rounded
    row = reference.score(case, _mesh(path), _mesh(out), res.report, reach=REACH)
    bound = reference.allowed_deviation(row)
    assert bound <= 0.0125  # r/100 (the tolerance) + the yardstick's own precision: the input box is exact
    assert row["dev_out_to_ref"] <= bound, (style, row["dev_out_to_ref"])
    assert row["dev_ref_to_out"] <= bound, (style, row["dev_ref_to_out"])
    check = res.report["deck"]["check"]
    assert check["open_edges_after"] == 0 and check["nonmanifold_edges_after"] == 0


def test_part_limits_the_pick_and_other_parts_stay_byte_identical(box, tmp_path):
    path = deck_files.write_deck(str(tmp_path), "lsdyna_fixed", *box)
    out = str(tmp_path / "body.k")
    # Part 1 alone (the box without its top) has the back face's top edge as an open boundary, no sharp
    # edge there: the seed finds none.  Its bottom back edge rounds, and part 2 is untouched.
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_deck(path, out, [SEED], R, part=1)
    assert err.value.code == "no_sharp_edge" and not os.path.exists(out)
    res = MeshRound.round_deck(path, out, [(37.0, 40.0, 0.0)], R, part=1)
    before, after = MeshRound.read_deck(path), MeshRound.read_deck(out)
    top0 = before["shell_ids"][before["shell_parts"] == 2]
    assert np.all(np.isin(top0, after["shell_ids"]))
    assert res.report["deck"]["elements_removed"] > 0
    with pytest.raises(MeshRound.RoundingError, match="part 9 has no shell elements"):
        MeshRound.round_deck(path, out, [SEED], R, part=9)


@pytest.mark.parametrize("style,line,bad,expect", [
    ("lsdyna_fixed", 20, "       1      2.5x            0.0             0.0\n", "bad coordinate"),
    ("nastran_free", 12, "GRID,7,3,0.,0.,0.\n", "coordinate system 3"),
    ("abaqus", 6, "1002, 0.0, 2.5\n", None),  # a node with only two coordinates is 0 in z: valid
    ("abaqus", 9, "1005, 1.0, 2.0, nan\n", "bad coordinate"),
])
def test_malformed_line_refused_with_file_and_line_nothing_written(box, tmp_path, style, line, bad, expect):
    path = deck_files.write_deck(str(tmp_path), style, *box)
    text = lines(path)
    text[line - 1] = bad.encode()
    with open(path, "wb") as f:
        f.write(b"".join(text))
    out = str(tmp_path / ("out" + os.path.splitext(path)[1]))
    if expect is None:
        MeshRound.read_deck(path)
        return
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_deck(path, out, [SEED], R)
    assert err.value.code == "invalid_input"
    assert f"{path}:{line}: " in str(err.value) and expect in str(err.value)
    assert not os.path.exists(out) and not [n for n in os.listdir(tmp_path) if n.startswith(".meshround")]


def test_all_triangle_option_and_id_range(box, tmp_path):
    path = deck_files.write_deck(str(tmp_path), "abaqus", *box)
    out = str(tmp_path / "tri.inp")
    res = MeshRound.round_deck(path, out, [SEED], R, quad_options=decks.QuadOptions(quads=False),
                               node_id_start=900000, element_id_start=800000)
    after = MeshRound.read_deck(out)
    new = after["shell_ids"] >= 800000
    assert res.report["deck"]["new_quads"] == 0 and np.all(after["shell_counts"][new] == 3)
    assert after["node_ids"].max() == 900000 + res.report["deck"]["nodes_new"] - 1
    assert b"*ELEMENT, TYPE=S3R, ELSET=TOP" in open(out, "rb").read()  # S4R's triangle is S3R


def test_shells_facing_either_way_are_rounded_and_kept_as_they_face(box, tmp_path):
    """Solver decks' shells often face either way: every third quad here runs the other way round."""
    xyz, quads, faces, near, far, edge = box
    flipped = quads.copy()
    flipped[::3] = flipped[::3, ::-1]
    path = deck_files.write_deck(str(tmp_path), "lsdyna_fixed", xyz, flipped, faces, near, far, edge)
    out = str(tmp_path / "out.k")
    res = MeshRound.round_deck(path, out, [SEED], R)
    before, after = MeshRound.read_deck(path), MeshRound.read_deck(out)
    kept = np.isin(before["shell_ids"], after["shell_ids"])
    rows = np.searchsorted(after["shell_ids"], before["shell_ids"][kept])
    np.testing.assert_array_equal(after["shell_node_ids"][rows], before["shell_node_ids"][kept])
    assert res.report["deck"]["elements_removed"] == len(before["shell_ids"]) - kept.sum() > 0
    assert res.report["deck"]["check"]["open_edges_after"] == 0


def test_a_changed_include_is_never_written_over_the_input(box, tmp_path):
    path = deck_files.write_deck(str(tmp_path), "lsdyna_long", *box)  # nodes in box_nodes.k
    with pytest.raises(MeshRound.RoundingError, match="would overwrite the input") as err:
        MeshRound.round_deck(path, str(tmp_path / "out.k"), [SEED], R)
    assert err.value.code == "invalid_input" and not os.path.exists(tmp_path / "out.k")


def test_cli_rounds_a_deck_by_extension(box, tmp_path):
    from MeshRound import cli
    path = deck_files.write_deck(str(tmp_path), "nastran_small", *box)
    out = str(tmp_path / "die_r5.nas")
    assert cli.main(["round", path, out, "--seed", "37,40,30", "--radius", "5"]) == 0
    assert len(MeshRound.read_deck(out)["shell_ids"]) > len(box[1])
    assert cli.main(["round", path, str(tmp_path / "x.nas"), "--seed", "37,40,30", "--radius", "5",
                     "--part", "7"]) == 1
    with pytest.raises(SystemExit):
        cli.main(["round", path, str(tmp_path / "x.stl"), "--seed", "37,40,30", "--radius", "5", "--part", "1"])


def test_cli_numbers_new_nodes_and_elements_from_the_given_ids(box, tmp_path):
    from MeshRound import cli
    path = deck_files.write_deck(str(tmp_path), "lsdyna_fixed", *box)
    before = MeshRound.read_deck(path)
    out = str(tmp_path / "ids.k")
    assert cli.main(["round", path, out, "--seed", "37,40,30", "--radius", "5", "--node-id-start", "700001",
                     "--element-id-start", "900001"]) == 0
    after = MeshRound.read_deck(out)
    new_nodes = np.setdiff1d(after["node_ids"], before["node_ids"])
    new_elements = np.setdiff1d(after["shell_ids"], before["shell_ids"])
    assert new_nodes.min() == 700001 and new_nodes.max() == 700000 + len(new_nodes)
    assert new_elements.min() == 900001 and new_elements.max() == 900000 + len(new_elements)
    # A start inside the deck's own IDs collides: refused by the written deck's check, nothing written.
    clash = str(tmp_path / "clash.k")
    assert cli.main(["round", path, clash, "--seed", "37,40,30", "--radius", "5",
                     "--element-id-start", str(int(before["shell_ids"][-1]))]) == 1
    assert not os.path.exists(clash)


def _without_subsequence(longer, shorter):
    """The lines of `longer` left when `shorter` is matched in it in order (fails if it is not)."""
    extra, k = [], 0
    for t in longer:
        if k < len(shorter) and t == shorter[k]:
            k += 1
        else:
            extra.append(t)
    assert k == len(shorter), f"line {shorter[k]!r} of the input is missing from the output"
    return extra


def _mesh(path):
    vertices, triangles, _, _ = decks.deck_triangles(MeshRound.read_deck(path))
    return meshconv.arrays_to_mesh(vertices, triangles)


def _areas(xyz, nodes):
    a = 0.5 * np.linalg.norm(np.cross(xyz[nodes[:, 1]] - xyz[nodes[:, 0]], xyz[nodes[:, 2]] - xyz[nodes[:, 0]]), axis=1)
    quad = nodes[:, 3] >= 0
    a[quad] += 0.5 * np.linalg.norm(np.cross(xyz[nodes[quad, 2]] - xyz[nodes[quad, 0]],
                                             xyz[nodes[quad, 3]] - xyz[nodes[quad, 0]]), axis=1)
    return a


# A real public deck: NX Nastran's "2 bars" contact example (a 100 x 20 x 5 mm bar as 256 CQUAD4 shells,
# NX v8.5 output with its banner, case control, PSHELL/MAT1, contact cards), from pyNastran's model
# collection (github.com/SteveDoyle2/pyNastran, models/contact/2bars_shell_s-contact.dat), kept outside
# the repository: fetch it there to run this test.
REAL_DECK = "/work/decks-data/pyNastran/models/contact/2bars_shell_s-contact.dat"


@pytest.mark.skipif(not os.path.exists(REAL_DECK), reason=f"the public deck is not fetched to {REAL_DECK}")
def test_real_public_nastran_deck_round_trips_and_rounds_like_occt(tmp_path):
    import Part
    from FreeCAD import Vector
    deck = MeshRound.read_deck(REAL_DECK)
    assert deck["deck"].write() == deck["deck"].texts()  # byte-identical without a rounding
    shell_points = decks.deck_triangles(deck)[0]  # (the deck's other bar is solid elements: not rounded)
    lo, hi = shell_points.min(axis=0), shell_points.max(axis=0)
    seed = (lo[0] + 0.6 * (hi[0] - lo[0]), hi[1], hi[2])  # the top back edge of the bar
    out = str(tmp_path / "bar_r2.dat")
    res = MeshRound.round_deck(REAL_DECK, out, [seed], 2.0)
    d = res.report["deck"]
    assert d["new_quads"] > d["new_triangles"] and d["elements_kept"] > 0
    extra = _without_subsequence(lines(out), [t for k, t in enumerate(lines(REAL_DECK))
                                              if (0, k + 1) not in record_lines(deck)])
    assert all(t.startswith((b"GRID", b"*", b"CQUAD4", b"CTRIA3")) for t in extra)

    def bar():
        solid = Part.makeBox(*(float(x) for x in hi - lo), Vector(*(float(x) for x in lo)))
        return solid, cases.edges_where(solid, lambda p: abs(p.y - hi[1]) < 1e-6 and abs(p.z - hi[2]) < 1e-6)

    row = reference.score(cases.Case("nx_2bars_r2", bar, 2.0), _mesh(REAL_DECK), _mesh(out), res.report, reach=REACH)
    bound = reference.allowed_deviation(row)
    print(f"nx_2bars r=2: dev_out_to_ref {row['dev_out_to_ref']:.4f} r, dev_ref_to_out {row['dev_ref_to_out']:.4f} r, bound {bound:.4f} r; {d}")
    assert bound <= 0.0125  # r/100 + the yardstick's precision: the deck's bar is an exact box
    assert row["dev_out_to_ref"] <= bound and row["dev_ref_to_out"] <= bound, (row, bound)


def _edge_defects(triangles):
    edges = np.sort(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return int(np.sum(counts == 1)), int(np.sum(counts > 2))


def test_band_local_check_counts_the_whole_written_deck_and_refuses_a_bad_read_back(box, tmp_path, monkeypatch):
    xyz, quads, faces, near, far, edge = box
    open_box = np.flatnonzero(faces != 4)  # without its bottom: open edges before and after
    path = deck_files.write_deck(str(tmp_path), "lsdyna_fixed", xyz, quads[open_box], faces[open_box],
                                 np.searchsorted(open_box, near[np.isin(near, open_box)]), np.zeros(0, int), edge)
    out = str(tmp_path / "out.k")
    check = MeshRound.round_deck(path, out, [SEED], R).report["deck"]["check"]
    before = _edge_defects(decks.deck_triangles(MeshRound.read_deck(path))[1])
    after = _edge_defects(decks.deck_triangles(MeshRound.read_deck(out))[1])
    assert before[0] > 0 and (check["open_edges_before"], check["nonmanifold_edges_before"]) == before
    assert (check["open_edges_after"], check["nonmanifold_edges_after"]) == after
    # A read-back that differs outside the band (a node moved) is refused, and nothing is written.
    from MeshRound import deck_check

    class Core:
        def read_deck(self, p):
            deck = core.read_deck(p)

            class Moved:
                def arrays(self):
                    a = deck.arrays()
                    a["node_xyz"][0, 0] += 1e-9
                    return a
            return Moved()
    monkeypatch.setattr(deck_check, "require_core", Core)
    os.remove(out)
    with pytest.raises(MeshRound.RoundingError, match="node coordinates differ") as err:
        MeshRound.round_deck(path, out, [SEED], R)
    assert err.value.code == "result_invalid" and not os.path.exists(out)
