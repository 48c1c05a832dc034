"""Public LS-DYNA keyword decks that are not ours, kept outside the repository (MESHROUND_PUBLIC_DECKS,
default /work/decks-data): read and written back byte-identical, and one rounded against OCCT's fillet.

Where they come from (fetch them there to run these tests; each test is skipped when its file is missing):
  lsdyna-mesh-reader/*   github.com/akaszynski/lsdyna-mesh-reader, src/lsdyna_mesh_reader/examples/ (its
                         README: "obtained from ... dynaexamples.com"): a screw joint of eight closed shell
                         plates (EXP_SC_JOINT_SCREW.key), a bird and a bird on a ball (bird strike), a
                         bracket, a wheel
  pydyna_metalforming_model.k   github.com/ansys/pydyna, examples/Metalforming/output/model.k at 80e2de6
                         (a draw: blank, punch, die and binders, forming contacts, adaptivity)
  pydyna_beer_can_mesh.k        github.com/ansys/pydyna, examples/keywords/Buckling_Beer_Can/mesh.k
"""
import os

import numpy as np
import pytest

import cases  # noqa: F401  (first: it puts FreeCAD's modules on the path)
import FreeCAD
import Part
import reference
import soundness
from MeshRound import decks
from test_decks import _without_subsequence, lines, record_lines

ROOT = os.environ.get("MESHROUND_PUBLIC_DECKS", "/work/decks-data")
ROUND_TRIP = ["lsdyna-mesh-reader/EXP_SC_JOINT_SCREW.key", "lsdyna-mesh-reader/bird.k",
              "lsdyna-mesh-reader/birdball.k", "lsdyna-mesh-reader/bracket.k", "lsdyna-mesh-reader/wheel.k",
              "lsdyna-mesh-reader/ex_13_thick_shell_elform_2.k", "pydyna_metalforming_model.k",
              "pydyna_beer_can_mesh.k"]
JOINT = os.path.join(ROOT, "lsdyna-mesh-reader/EXP_SC_JOINT_SCREW.key")


def public(name):
    path = os.path.join(ROOT, name)
    if not os.path.exists(path):
        pytest.skip(f"the public deck is not fetched to {path}")
    return path


@pytest.mark.parametrize("name", ROUND_TRIP)
def test_public_deck_reads_and_writes_back_byte_identical(name):
    path = public(name)
    deck = decks.read_deck(path)
    assert deck["deck"].write() == deck["deck"].texts()
    with open(path, "rb") as f:
        assert deck["deck"].texts()[0] == f.read()
    if len(deck["shell_ids"]):
        assert len(np.unique(deck["shell_ids"])) == len(deck["shell_ids"])


def test_public_draw_deck_keeps_its_parts():
    deck = decks.read_deck(public("pydyna_metalforming_model.k"))
    counts = {int(p): int(n) for p, n in zip(*np.unique(deck["shell_parts"], return_counts=True))}
    assert counts == {1: 474, 2: 1500, 3: 1500, 4: 44, 5: 44}  # blank, punch, die, two binders
    assert np.all(deck["shell_counts"] == 4)


def plate_solid(vertices, triangles):
    """The closed plate the deck's shells mesh, as an OCCT solid (its planar faces merged). The deck's
    coordinates carry single-precision noise (135.00002 for 135); they are rounded to 0.001 mm first."""
    V = np.round(vertices, 3)
    faces = [Part.Face(Part.makePolygon([FreeCAD.Vector(*V[i]) for i in (*t, t[0])])) for t in triangles]
    return Part.Solid(Part.Shell(faces)).removeSplitter()


def test_public_joint_deck_rounds_like_occt_both_ways(tmp_path):
    path = public("lsdyna-mesh-reader/EXP_SC_JOINT_SCREW.key")
    part, seed, r = 1000000, (0.0, 60.0, 0.0), 5.0  # the first plate's 150 mm edge at x = 0, z = 0 (along y)
    before = decks.read_deck(path)
    V0, T0, _, _ = decks.deck_triangles(before, part)
    out = str(tmp_path / "joint_r5.k")
    res = decks.round_deck(path, out, [seed], r, part=part)
    d = res.report["deck"]
    assert d["elements_removed"] > 0 and d["new_quad_share"] > 0.7
    after = decks.read_deck(out)
    V1, T1, _, _ = decks.deck_triangles(after, part)
    assert soundness.problems(V0, T0, V1, T1) == []
    # Every line that is not a node or element record is kept, in order; what the output has beyond them
    # is the kept records and the new ones (a few keyword lines opening the new blocks at most).
    kept_text = [t for k, t in enumerate(lines(path)) if (0, k + 1) not in record_lines(before)]
    extra = _without_subsequence(lines(out), kept_text)
    new_records = d["nodes_new"] + d["new_quads"] + d["new_triangles"]
    kept_records = len(record_lines(before)) - d["nodes_removed"] - d["elements_removed"]
    assert new_records + kept_records <= len(extra) <= new_records + kept_records + 4
    others = before["shell_parts"] != part
    assert np.isin(before["shell_ids"][others], after["shell_ids"]).all()

    solid = plate_solid(V0, T0)
    assert solid.isValid() and len(solid.Faces) < len(T0) / 4
    edge = [e for e in solid.Edges if e.distToShape(Part.Vertex(FreeCAD.Vector(*seed)))[0] < 1e-6]
    assert len(edge) == 1 and abs(edge[0].Length - 150) < 1e-3
    case = cases.Case("public_joint_plate_r5", lambda: (solid, edge), r)
    row = reference.score(case, _mesh_of_part(path, part), _mesh_of_part(out, part), res.report)
    bound = reference.allowed_deviation(row)
    print(f"joint plate r=5: dev_out_to_ref {row['dev_out_to_ref']:.4f} r, dev_ref_to_out {row['dev_ref_to_out']:.4f} r, "
          f"bound {bound:.4f} r; {d}")
    assert bound <= 0.0125
    assert row["dev_out_to_ref"] <= bound and row["dev_ref_to_out"] <= bound, (row, bound)


def _mesh_of_part(path, part):
    from MeshRound import meshconv
    vertices, triangles, _, _ = decks.deck_triangles(decks.read_deck(path), part)
    return meshconv.arrays_to_mesh(vertices, triangles)

