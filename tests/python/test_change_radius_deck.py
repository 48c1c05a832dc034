"""Changing an existing round's radius in a solver deck (issue 15 with issue 14's decks):
MeshRound.change_radius_deck and `meshround reround IN.k OUT.k`.

Inputs: OCCT's 5 mm fillet of the box's top back edge (test_change_radius's "box" case), meshed by MeshPart
at 0.4 r0 and written as an LS-DYNA deck (deck_files.py: triangles as shells with n3 = n4; part 2 the top
face's elements, part 1 the rest; an element set along the round, one far from it, a node set); and
deck_files' structured quad box rounded by round_deck at 5 mm (a quad-dominant round, MeshRound's own).
Bounds:
  * found radius within 1 % of r0;
  * the round at the new radius (larger and smaller) within 0.01 r of OCCT's fillet of the sharp box both
    ways (reference.score on the deck's shells), the written deck watertight as the input;
  * outside the band nothing changed: every element farther than reach x max(r0, r) from the edge keeps its
    ID, part and node IDs, every node of those keeps its ID and coordinates (as read back, bit for bit);
  * a refusal (a seed on a flat face: not_a_round) writes nothing, by the API and by the command line.
"""
import os

import numpy as np
import pytest

import deck_files
import reference
from conftest import MeshRound
from test_change_radius import case_at, rounded_mesh, seed_on_round

from MeshRound import cli, decks, meshconv

R0 = 5.0
FLAT_SEED = (30.0, 20.0, 30.0)  # on the box's flat top face
REACH = 3.0


def edge_distance(p):
    """Distance of points to the box's top back edge (y = 40, z = 30, 0 <= x <= 60)."""
    p = np.atleast_2d(p)
    x = np.clip(p[:, 0], 0, 60.0)
    return np.linalg.norm(p - np.column_stack([x, np.full(len(p), 40.0), np.full(len(p), 30.0)]), axis=1)


def _mesh(path):
    vertices, triangles, _, _ = decks.deck_triangles(MeshRound.read_deck(path))
    return meshconv.arrays_to_mesh(vertices, triangles)


@pytest.fixture(scope="module")
def filleted_deck(tmp_path_factory):
    """The OCCT-filleted box (fine mesh) as an LS-DYNA deck of triangles."""
    xyz, tris = reference.mesh_arrays(rounded_mesh("box", "fine"))
    shells = np.column_stack([tris, tris[:, 2]])                  # n4 = n3: a triangle
    centroid = xyz[tris].mean(axis=1)
    faces = np.where(np.abs(centroid[:, 2] - 30.0) < 1e-6, 5, 0)   # the flat top: part 2
    near = np.flatnonzero(edge_distance(centroid) < 2 * R0)
    far = np.flatnonzero(centroid[:, 2] < 1e-6)                    # the bottom face
    edge = np.flatnonzero(edge_distance(xyz) < 1.5 * R0)
    folder = tmp_path_factory.mktemp("filleted")
    return deck_files.write_deck(str(folder), "lsdyna_fixed", xyz, shells, faces, near, far, edge, name="fillet")


def _far_unchanged(before, after, radius, tol=0.0):
    """Elements (and their nodes) farther than the reach from the edge: same IDs, parts, nodes, coordinates."""
    margin = REACH * max(R0, radius) + 2.0  # the reach plus an element
    counts = before["shell_counts"]
    nodes = before["shell_nodes"]
    xyz = before["node_xyz"]
    cent = np.array([xyz[n[:c]].mean(axis=0) for n, c in zip(nodes, counts)])
    far = np.flatnonzero(edge_distance(cent) > margin)
    assert len(far) > 0.3 * len(counts)
    at = {int(e): i for i, e in enumerate(after["shell_ids"])}
    node_at = {int(n): i for i, n in enumerate(after["node_ids"])}
    for e in far:
        j = at.get(int(before["shell_ids"][e]))
        assert j is not None, f"element {before['shell_ids'][e]} far from the round was removed"
        assert after["shell_parts"][j] == before["shell_parts"][e]
        ids0 = before["shell_node_ids"][e][:counts[e]]
        ids1 = after["shell_node_ids"][j][:after["shell_counts"][j]]
        assert list(ids0) == list(ids1)
        for n in ids0:
            i0 = int(np.flatnonzero(before["node_ids"] == n)[0])
            assert np.array_equal(after["node_xyz"][node_at[int(n)]], xyz[i0])
    return len(far)


@pytest.mark.parametrize("radius", [8.0, 3.5])
def test_deck_round_changed_like_occt_ids_outside_the_band_kept(filleted_deck, tmp_path, radius):
    out = str(tmp_path / "fillet_new.k")
    seed = seed_on_round(case_at("box", R0))
    res = MeshRound.change_radius_deck(filleted_deck, out, [tuple(seed)], radius)
    assert res.paths == [out] and os.path.exists(out)
    found = res.report["found_radius"]
    assert len(found) == 1 and abs(found[0] - R0) <= 0.01 * R0, found
    row = reference.score(case_at("box", radius), _mesh(filleted_deck), _mesh(out), res.report)
    assert row["dev_out_to_ref"] <= 0.01 and row["dev_ref_to_out"] <= 0.01, row
    d = res.report["deck"]
    assert d["check"]["open_edges_after"] == 0 and d["check"]["nonmanifold_edges_after"] == 0, d["check"]
    assert d["elements_removed"] > 0 and d["new_quads"] + d["new_triangles"] > 0
    before, after = MeshRound.read_deck(filleted_deck), MeshRound.read_deck(out)
    kept = _far_unchanged(before, after, radius)
    # only the band changed: the elements removed are near the round
    gone = np.setdiff1d(before["shell_ids"], after["shell_ids"])
    idx = np.flatnonzero(np.isin(before["shell_ids"], gone))
    xyz = before["node_xyz"]
    cent = np.array([xyz[before["shell_nodes"][i][:before["shell_counts"][i]]].mean(axis=0) for i in idx])
    assert edge_distance(cent).max() <= REACH * max(R0, radius) + 2.0
    assert kept + len(gone) <= len(before["shell_ids"])
    # every element that stays (near the band too) keeps its nodes, and they their coordinates
    stay = np.flatnonzero(~np.isin(before["shell_ids"], gone))
    at = np.searchsorted(after["shell_ids"], before["shell_ids"][stay])
    assert np.array_equal(after["shell_ids"][at], before["shell_ids"][stay])
    assert np.array_equal(after["shell_node_ids"][at], before["shell_node_ids"][stay])
    used = np.unique(before["shell_node_ids"][stay][:, :3])
    i0, i1 = np.searchsorted(before["node_ids"], used), np.searchsorted(after["node_ids"], used)
    assert np.array_equal(after["node_xyz"][i1], before["node_xyz"][i0])
    # the element set along the round holds the new elements that replace its removed ones
    shoulder = [x for x in after["sets"] if x["id"] == 11][0]
    new_elements = np.setdiff1d(after["shell_ids"], before["shell_ids"])
    assert np.isin(new_elements, shoulder["members"]).any() and not np.isin(gone, shoulder["members"]).any()


def test_deck_refusal_writes_nothing(filleted_deck, tmp_path, capsys):
    out = str(tmp_path / "x.k")
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.change_radius_deck(filleted_deck, out, [FLAT_SEED], 8.0)
    assert err.value.code == "not_a_round" and "flat face" in str(err.value)
    assert not os.path.exists(out) and os.listdir(tmp_path) == []
    status = cli.main(["reround", filleted_deck, out, "--seed", "30,20,30", "--radius", "8"])
    assert status == 1 and "not_a_round" in capsys.readouterr().err and not os.path.exists(out)


def test_cli_rerounds_a_deck_by_extension(filleted_deck, tmp_path, capsys):
    out, report = str(tmp_path / "r8.k"), str(tmp_path / "r8.json")
    seed = seed_on_round(case_at("box", R0))
    status = cli.main(["reround", filleted_deck, out, "--seed", f"{seed.x},{seed.y},{seed.z}", "--radius", "8",
                       "--node-id-start", "900001", "--element-id-start", "800001", "--report", report])
    printed = capsys.readouterr().out
    assert status == 0 and os.path.exists(out) and os.path.exists(report), printed
    assert "r = 5 mm" in printed and "elements replaced" in printed
    after = MeshRound.read_deck(out)
    before = MeshRound.read_deck(filleted_deck)
    new = np.setdiff1d(after["shell_ids"], before["shell_ids"])
    assert len(new) and new.min() >= 800001
    new_nodes = np.setdiff1d(after["node_ids"], before["node_ids"])
    assert len(new_nodes) and new_nodes.min() >= 900001
    # a mesh out of a deck in (or the other way) is a wrong command line: no conversion
    with pytest.raises(SystemExit):
        cli.main(["reround", filleted_deck, str(tmp_path / "y.bdf"), "--seed", "1,2,3", "--radius", "8"])


@pytest.mark.parametrize("style", ["lsdyna_fixed", "nastran_small", "abaqus"])
def test_quad_deck_rounded_by_meshround_then_changed(tmp_path, style):
    """deck_files' quad box (LS-DYNA, Nastran, Abaqus) rounded at 5 mm by round_deck (a quad-dominant band),
    then its round changed to 8 mm by change_radius_deck: found 5 mm, within 0.01 r of OCCT's 8 mm fillet,
    the far quads kept."""
    xyz, quads, faces = deck_files.box_quads((60.0, 40.0, 30.0), 2.5)
    centroid = xyz[quads].mean(axis=1)
    near = np.flatnonzero(edge_distance(centroid) < 5.0)
    far = np.flatnonzero(faces == 4)
    edge = np.flatnonzero(edge_distance(xyz) < 1e-9)
    path = deck_files.write_deck(str(tmp_path), style, xyz, quads, faces, near, far, edge)
    ext = os.path.splitext(path)[1]
    r5 = str(tmp_path / ("r5" + ext))
    MeshRound.round_deck(path, r5, [(37.0, 40.0, 30.0)], R0)
    r8 = str(tmp_path / ("r8" + ext))
    seed = (37.0, 35.0 + R0 * np.cos(0.7), 25.0 + R0 * np.sin(0.7))  # on the 5 mm round
    res = MeshRound.change_radius_deck(r5, r8, [seed], 8.0)
    assert abs(res.report["found_radius"][0] - R0) <= 0.01 * R0, res.report["strips"]
    row = reference.score(case_at("box", 8.0), _mesh(r5), _mesh(r8), res.report)
    assert row["dev_out_to_ref"] <= 0.01 and row["dev_ref_to_out"] <= 0.01, row
    d = res.report["deck"]
    assert d["new_quad_share"] >= 0.5, d
    _far_unchanged(MeshRound.read_deck(r5), MeshRound.read_deck(r8), 8.0)


def test_export_of_a_change_radius_rounding_on_a_deck(doc, tmp_path):
    """A Deck feature, a Rounding at 5 mm on it and a Rounding changing that round to 8 mm: export_deck
    writes what round_deck then change_radius_deck write by hand, byte for byte."""
    xyz, quads, faces = deck_files.box_quads((60.0, 40.0, 30.0), 2.5)
    centroid = xyz[quads].mean(axis=1)
    path = deck_files.write_deck(str(tmp_path), "lsdyna_fixed", xyz, quads, faces,
                                 np.flatnonzero(edge_distance(centroid) < 5.0), np.flatnonzero(faces == 4),
                                 np.flatnonzero(edge_distance(xyz) < 1e-9))
    from MeshRound.objects.rounding import CHANGE_RADIUS
    deck = MeshRound.make_deck(path, doc)
    first = MeshRound.make_rounding(deck, (37.0, 40.0, 30.0), R0)
    doc.recompute()
    seed = (37.0, 35.0 + R0 * np.cos(0.7), 25.0 + R0 * np.sin(0.7))
    second = MeshRound.make_rounding(first, seed, 8.0, operation=CHANGE_RADIUS)
    doc.recompute()
    assert "Invalid" not in second.State, second.getStatusString()
    (tmp_path / "export").mkdir()
    (tmp_path / "by_hand").mkdir()
    res = MeshRound.export_deck(second, str(tmp_path / "export" / "out.k"))
    MeshRound.round_deck(path, str(tmp_path / "by_hand" / "r5.k"), [(37.0, 40.0, 30.0)], R0)
    ref = MeshRound.change_radius_deck(str(tmp_path / "by_hand" / "r5.k"), str(tmp_path / "by_hand" / "out.k"),
                                       [seed], 8.0)
    with open(res.paths[0], "rb") as a, open(ref.paths[0], "rb") as b:
        assert a.read() == b.read()
    assert abs(res.report["found_radius"][0] - R0) <= 0.01 * R0 and len(res.report["export_stages"]) == 2
