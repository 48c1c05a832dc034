"""Solver decks in FreeCAD, headless (issue 14): a deck of every format and field style (deck_files.py) opens
as a Deck feature with its parts, counts and mesh; a Rounding takes it as its Base; the Rounding exports
as the deck, byte for byte what round_deck writes with the feature's arguments (chains of Roundings
too); the refusals; recompute re-reads the file; save and reopen; File > Open's registration.  The GUI
side (the quads drawn, a part hidden, a click seeding the command) is tests/gui/test_gui_deck.py."""
import os
import re
import shutil
import subprocess

import numpy as np
import pytest

import FreeCAD

import deck_files
import soundness
from conftest import MOD_DIR, MeshRound

from MeshRound import deck_drawing, meshconv
from MeshRound.objects.deck import Deck, DeckPart

SIZE, H, R = (60.0, 40.0, 30.0), 2.5, 5.0
SEED = (37.0, 40.0, 30.0)        # the top back edge
OTHER_SEED = (37.0, 0.0, 30.0)   # the top front edge
PART_NAMES = {"lsdyna": ["die body", "die top"], "nastran": ["", ""], "abaqus": ["BODY", "TOP"]}


@pytest.fixture(scope="module")
def box():
    xyz, quads, faces = deck_files.box_quads(SIZE, H)
    centroid = xyz[quads].mean(axis=1)
    near = np.flatnonzero(np.linalg.norm(centroid[:, 1:] - SIZE[1:], axis=1) < 2 * H)
    edge = np.flatnonzero(np.linalg.norm(xyz[:, 1:] - SIZE[1:], axis=1) < 1e-9)
    return xyz, quads, faces, near, np.flatnonzero(faces == 4), edge


def write(folder, style, box, name="box"):
    return deck_files.write_deck(str(folder), style, *box, name=name)


def read(path):
    with open(path, "rb") as stream:
        return stream.read()


@pytest.mark.parametrize("style", deck_files.STYLES)
def test_every_format_opens_as_a_deck_with_its_parts_counts_and_mesh(doc, box, tmp_path, style):
    xyz, quads, faces = box[:3]
    path = write(tmp_path, style, box)
    deck = MeshRound.make_deck(path, doc)
    assert isinstance(deck.Proxy, Deck) and deck.TypeId == "Mesh::FeaturePython"
    assert "Invalid" not in deck.State and deck.Label == os.path.basename(path)
    family = deck_files.family(style)
    assert deck.Format == family and deck.File == path
    assert (deck.Nodes, deck.Elements, deck.Quads, deck.Triangles) == (len(xyz), len(quads), len(quads), 0)
    top = int(np.sum(faces == 5))
    names = PART_NAMES[family]
    assert list(deck.Parts) == [f"{f'1 {names[0]}'.rstrip()}: {len(quads) - top} elements ({len(quads) - top} quads, 0 triangles)",
                                f"{f'2 {names[1]}'.rstrip()}: {top} elements ({top} quads, 0 triangles)"]
    parts = deck.PartObjects
    assert [p.PartId for p in parts] == [1, 2] and all(isinstance(p.Proxy, DeckPart) for p in parts)
    assert [p.PartName for p in parts] == names
    assert [(p.Elements, p.Quads, p.Triangles) for p in parts] == [(len(quads) - top, len(quads) - top, 0), (top, top, 0)]
    # the mesh: every quad as two triangles over the shells' nodes; facet k lies in element k
    assert deck.Mesh.CountFacets == 2 * len(quads) and deck.Mesh.CountPoints == len(xyz)
    vertices, triangles = meshconv.mesh_to_arrays(deck.Mesh)
    arrays = MeshRound.read_deck(path)
    element_nodes = arrays["node_xyz"][arrays["shell_nodes"]]          # (m, 4, 3) in the deck's order
    lo, hi = element_nodes.min(axis=1) - 1e-4, element_nodes.max(axis=1) + 1e-4
    first = vertices[triangles[:len(quads)]]                            # (m, 3, 3)
    assert np.all((first >= lo[:, None]) & (first <= hi[:, None]))
    assert deck.Mesh.isSolid() and not deck.Mesh.hasNonManifolds()
    assert doc.recompute() == 0  # read once: nothing left to recompute (a big deck takes seconds)


def test_a_rounding_on_a_deck_recomputes_and_its_mesh_is_sound(doc, box, tmp_path):
    deck = MeshRound.make_deck(write(tmp_path, "lsdyna_fixed", box), doc)
    rounding = MeshRound.make_rounding(deck, SEED, R)
    doc.recompute()
    assert "Invalid" not in rounding.State, rounding.getStatusString()
    assert rounding.Base == deck and int(rounding.Statistics["chains"]) == 1
    V0, F0 = meshconv.mesh_to_arrays(deck.Mesh)
    V1, F1 = meshconv.mesh_to_arrays(rounding.Mesh)
    assert len(F1) != len(F0) and soundness.problems(V0, F0, V1, F1) == []
    # the round is there: no vertex of the result within 0.9 (sqrt 2 - 1) r of the sharp edge's line
    gap = np.linalg.norm(V1[:, 1:] - SIZE[1:], axis=1)
    assert gap.min() > 0.9 * (np.sqrt(2) - 1) * R


@pytest.mark.parametrize("style", ["lsdyna_fixed", "lsdyna_long", "nastran_large", "abaqus"])
def test_export_is_what_round_deck_writes_with_the_features_arguments(doc, box, tmp_path, style):
    path = write(tmp_path, style, box)
    deck = MeshRound.make_deck(path, doc)
    rounding = MeshRound.make_rounding(deck, SEED, R, tolerance=0.04, feature_angle=40, reach=3.5)
    doc.recompute()
    ext = os.path.splitext(path)[1]
    (tmp_path / "export").mkdir()
    (tmp_path / "reference").mkdir()
    out = str(tmp_path / "export" / ("out" + ext))
    res = MeshRound.export_deck(rounding, out)
    ref = MeshRound.round_deck(path, str(tmp_path / "reference" / ("out" + ext)), [SEED], R, tolerance=0.04,
                               feature_angle=40, reach=3.5)
    assert [os.path.relpath(p, tmp_path / "export") for p in res.paths] == \
        [os.path.relpath(p, tmp_path / "reference") for p in ref.paths]
    assert len(res.paths) == (2 if style in ("lsdyna_long", "nastran_large") else 1)  # the include beside it
    for mine, theirs in zip(res.paths, ref.paths):
        assert read(mine) == read(theirs), mine
    assert read(out) != read(path) and res.report["deck"]["new_quads"] > 0
    assert res.report["export_stages"] == [res.report["deck"]]
    assert sorted(os.listdir(tmp_path / "export")) == sorted(os.path.basename(p) for p in res.paths)  # no leftovers


def test_a_variable_radius_and_a_chain_of_roundings_export_stage_by_stage(doc, box, tmp_path):
    path = write(tmp_path, "nastran_small", box)
    deck = MeshRound.make_deck(path, doc)
    law = [(FreeCAD.Vector(0, 40, 30), 3.0), (FreeCAD.Vector(60, 40, 30), 6.0)]
    first = MeshRound.make_rounding(deck, SEED, law)
    doc.recompute()
    second = MeshRound.make_rounding(first, OTHER_SEED, 4.0)
    doc.recompute()
    assert "Invalid" not in second.State, second.getStatusString()
    res = MeshRound.export_deck(second, str(tmp_path / "out.bdf"))
    stage = MeshRound.round_deck(path, str(tmp_path / "stage1.bdf"), [SEED], [((0, 40, 30), 3.0), ((60, 40, 30), 6.0)])
    ref = MeshRound.round_deck(stage.paths[0], str(tmp_path / "ref.bdf"), [OTHER_SEED], 4.0)
    assert read(tmp_path / "out.bdf") == read(ref.paths[0])
    assert [s["elements_in"] for s in res.report["export_stages"]] == \
        [stage.report["deck"]["elements_in"], ref.report["deck"]["elements_in"]]
    after = MeshRound.read_deck(str(tmp_path / "out.bdf"))
    # both edges rounded: the new elements' IDs above the first stage's, which are above the input's
    assert after["max_element_id"] > stage.report["deck"]["element_ids"][1] > 5001 + len(box[1])


def test_export_refusals_name_the_cause_and_write_nothing(doc, box, box_feature_on, tmp_path):
    path = write(tmp_path, "abaqus", box)
    deck = MeshRound.make_deck(path, doc)
    rounding = MeshRound.make_rounding(deck, SEED, R)
    on_mesh = MeshRound.make_rounding(box_feature_on(doc), (37.0, 60.0, 40.0), R)
    doc.recompute()
    out = tmp_path / "out"
    out.mkdir()
    cases = [(rounding, "x.k", "x.k' is in the LS-DYNA (.k .key .dyn) format, but 'box.inp' is in the "
                               "Abaqus (.inp) format"),
             (rounding, "x.stl", "is not a solver deck"),
             (on_mesh, "x.inp", "is not built on a solver deck: its Base chain ends at 'Box'"),
             (deck, "x.inp", "'box.inp' is not a Rounding")]
    for obj, name, message in cases:
        with pytest.raises(MeshRound.RoundingError, match=re.escape(message)) as caught:
            MeshRound.export_deck(obj, str(out / name))
        assert caught.value.code == "invalid_input"
    with pytest.raises(MeshRound.RoundingError, match="is the file of 'box.inp'"):
        MeshRound.export_deck(rounding, path)
    deck.Placement.Base = FreeCAD.Vector(10, 0, 0)
    with pytest.raises(MeshRound.RoundingError, match="has been moved"):
        MeshRound.export_deck(rounding, str(out / "x.inp"))
    assert os.listdir(out) == []


@pytest.fixture
def box_feature_on(box):
    def make(doc):
        from conftest import box_mesh
        feature = doc.addObject("Mesh::Feature", "Box")
        feature.Mesh = box_mesh(5.0)
        return feature
    return make


def test_recompute_reads_the_file_again_and_follows_its_parts(doc, box, tmp_path):
    xyz, quads, faces, near, far, edge = box
    path = write(tmp_path, "lsdyna_fixed", box)
    deck = MeshRound.make_deck(path, doc)
    top_part = deck.PartObjects[1].Name
    finer = deck_files.box_quads(SIZE, 2.0)
    write(tmp_path, "lsdyna_fixed", (*finer, near[:1], far[:1], edge[:1]))  # same file, finer mesh
    deck.touch()
    doc.recompute()
    assert deck.Quads == len(finer[1]) and deck.Mesh.CountFacets == 2 * len(finer[1])
    assert [p.Name for p in deck.PartObjects][1] == top_part  # the same children, updated
    one_part = (finer[0], finer[1], np.zeros(len(finer[1]), int), near[:1], far[:1], edge[:1])
    write(tmp_path, "lsdyna_fixed", one_part)
    deck.touch()
    doc.recompute()
    assert [p.PartId for p in deck.PartObjects] == [1] and doc.getObject(top_part) is None
    assert "Invalid" not in deck.State


def test_a_broken_deck_is_refused_naming_the_line(doc, box, tmp_path):
    path = write(tmp_path, "lsdyna_fixed", box)
    deck = MeshRound.make_deck(path, doc)
    with open(path) as stream:
        text = stream.read().replace("0.00000000", "0.0x000000", 1)
    with open(path, "w") as stream:
        stream.write(text)
    deck.touch()
    doc.recompute()
    assert "Invalid" in deck.State and "bad coordinate" in deck.getStatusString()
    names = [o.Name for o in doc.Objects]
    with pytest.raises(MeshRound.RoundingError, match=r"box\.k:\d+: bad coordinate"):
        MeshRound.make_deck(path, doc)
    assert [o.Name for o in doc.Objects] == names  # nothing added
    with pytest.raises(MeshRound.RoundingError, match="not a solver deck"):
        MeshRound.make_deck(str(tmp_path / "box.stl"), doc)


def test_saved_deck_reopens_and_its_rounding_recomputes(doc, box, tmp_path):
    path = write(tmp_path, "abaqus", box)
    deck = MeshRound.make_deck(path, doc)
    rounding = MeshRound.make_rounding(deck, SEED, R)
    doc.recompute()
    facets = rounding.Mesh.CountFacets
    saved = str(tmp_path / "deck.FCStd")
    doc.saveAs(saved)
    FreeCAD.closeDocument(doc.Name)
    reopened = FreeCAD.openDocument(saved)
    try:
        deck = reopened.getObject("Deck")
        assert isinstance(deck.Proxy, Deck) and deck.Mesh.CountFacets == 2 * len(box[1])
        assert [p.PartName for p in deck.PartObjects] == ["BODY", "TOP"]
        data = deck.Proxy.draw_data(deck)  # what the view provider draws, read again from the file
        assert int(np.sum(data.counts == 4)) == len(box[1]) and [p for p, _ in data.part_list] == [1, 2]
        rounding = reopened.getObject("Rounding")
        rounding.Radius = 6.0
        reopened.recompute()
        assert "Invalid" not in rounding.State and rounding.Mesh.CountFacets != facets
        assert MeshRound.export_deck(rounding, str(tmp_path / "out.inp")).report["deck"]["new_quads"] > 0
    finally:
        FreeCAD.closeDocument(reopened.Name)


def test_drawing_index_arrays_keep_quads_and_skip_diagonals():
    nodes = np.array([[0, 1, 2, 3], [1, 4, 5, 2], [4, 6, 5, 5]])  # two quads, a triangle (4th unused)
    counts = np.array([4, 4, 3])
    assert deck_drawing.polygon_index(nodes, counts).tolist() == [0, 1, 2, 3, -1, 1, 4, 5, 2, -1, 4, 6, 5, -1]
    edges = deck_drawing.element_edges(nodes, counts).tolist()
    assert edges == [[0, 1], [0, 3], [1, 2], [1, 4], [2, 3], [2, 5], [4, 5], [4, 6], [5, 6]]  # [1, 2] once
    assert [0, 2] not in edges and [1, 3] not in edges and [1, 5] not in edges
    assert deck_drawing.edge_index(nodes, counts)[:6].tolist() == [0, 1, -1, 0, 3, -1]


def test_a_deck_with_triangles_counts_them(doc, tmp_path):
    path = tmp_path / "mixed.k"
    path.write_text("*KEYWORD\n*NODE\n"
                    + "".join("%8d%16.8f%16.8f%16.8f\n" % (i + 1, x, y, 0.0)
                              for i, (x, y) in enumerate([(0, 0), (1, 0), (1, 1), (0, 1), (2, 0)]))
                    + "*ELEMENT_SHELL\n" + "%8d%8d%8d%8d%8d%8d\n" % (1, 7, 1, 2, 3, 4)
                    + "%8d%8d%8d%8d%8d%8d\n" % (2, 7, 2, 5, 3, 3) + "*END\n")
    deck = MeshRound.make_deck(str(path), doc)
    assert (deck.Elements, deck.Quads, deck.Triangles, deck.Nodes) == (2, 1, 1, 5)
    assert list(deck.Parts) == ["7: 2 elements (1 quads, 1 triangles)"] and deck.Mesh.CountFacets == 3
    data = deck.Proxy.draw_data(deck)
    assert deck_drawing.polygon_index(data.nodes, data.counts).tolist() == [0, 1, 2, 3, -1, 1, 4, 2, -1]


def test_file_open_and_import_are_registered_beside_fems(tmp_path, box):
    """In freecadcmd started as a user would (the workbench in the user's Mod folder): .k has our module,
    .inp ours beside Fem's; open() (what File > Open calls), insert() (File > Import) and FreeCAD.loadFile
(the module found by the extension) make the Deck."""
    home = tmp_path / "home"
    (home / "Mod").mkdir(parents=True)
    os.symlink(MOD_DIR, home / "Mod" / "MeshRound")
    path = write(tmp_path, "nastran_free", box)
    k_path = write(tmp_path, "lsdyna_fixed", box)
    script = tmp_path / "open.py"
    result = tmp_path / "result.txt"
    script.write_text(
        "import FreeCAD\n"
        "lines = [repr(FreeCAD.getImportType('k')), repr(FreeCAD.getImportType('inp')),\n"
        "         repr(FreeCAD.getExportType('bdf'))]\n"
        "import MeshRound.deck_import as importer\n"
        f"doc = importer.open({path!r})\n"
        "lines.append(doc.Name + ' ' + ' '.join(o.Name for o in doc.Objects))\n"
        "other = FreeCAD.newDocument('Other')\n"
        f"importer.insert({path!r}, 'Other')\n"
        "lines.append(' '.join(o.Name + ':' + str(getattr(o, 'Quads', '')) for o in other.Objects))\n"
        f"FreeCAD.loadFile({k_path!r})\n"  # the module registered for .k, found by FreeCAD
        "deck = FreeCAD.ActiveDocument.getObject('Deck')\n"
        "lines.append(deck.Name + ' ' + str(deck.Quads))\n"
        f"open({str(result)!r}, 'w').write(chr(10).join(lines))\n")
    run = subprocess.run(["freecadcmd", str(script)], env=dict(os.environ, FREECAD_USER_HOME=str(home)),
                         capture_output=True, text=True, timeout=120)
    assert result.exists(), run.stdout[-2000:] + run.stderr[-2000:]
    lines = result.read_text().splitlines()
    assert lines[0] == "['MeshRound.deck_import']"
    assert "'MeshRound.deck_import'" in lines[1] and "'Fem'" in lines[1]
    assert "'MeshRound.deck_import'" in lines[2]  # File > Export (Fem's Nastran mesh export beside it)
    assert lines[3] == "box Deck DeckPart DeckPart001"
    top = int(np.sum(box[2] == 5))
    assert lines[4] == f"Deck:{len(box[1])} DeckPart:{len(box[1]) - top} DeckPart001:{top}"
    assert lines[5] == f"Deck {len(box[1])}"
    shutil.rmtree(home)
