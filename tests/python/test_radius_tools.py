"""Radius tools (issue 16): max_radius against closed forms and against the engine itself, sweeps, the k.t
rule, the optimiser hook.

Closed forms (the ball of a 2-face wedge of opening angle a touches each face r / tan(a/2) from the edge):
box 100 x 60 x 40, its top edge at y = 60: the 40 mm side face -> 40; draft shoulder (cases.py, wall drafted
10 deg, 22 deep): wall slant 22 / cos 10 at 0.839 r -> 22 / cos(10) x tan(50) = 26.623; a channel 12 deep:
its shoulder -> 12; a channel floor 10 wide -> 10; the S chain's R20 bend (plate 40 thick, so the bend and
not the wall limits) -> 20; an open sheet (top and side faces only, 40 high) -> 40 at the mesh boundary.
Each answer must be within 0.5%, and the engine must round 0.98x of it to a sound mesh and refuse 1.02x
with radius_too_large.
"""
import csv
import json
import math
import os
import subprocess
import sys

import pytest

import cases
import Mesh
import MeshPart
import Part
import soundness

import MeshRound
from MeshRound import meshconv

V = cases.V
HERE = os.path.dirname(os.path.abspath(__file__))
MOD = os.path.join(os.path.dirname(os.path.dirname(HERE)), "Mod", "MeshRound")


def channel(width, depth):
    """A 100 x 60 x 30 block with a channel along x, `width` wide (from y = 15) and `depth` deep."""
    return Part.makeBox(100, 60, 30).cut(Part.makeBox(100, width, depth, V(0, 15, 30 - depth))).removeSplitter()


def s_plate(height):
    s_wire = cases.s_outline()
    rest = Part.makePolygon([V(120, 10, 0), V(120, -20, 0), V(0, -20, 0), V(0, 60, 0)])
    return Part.Face(Part.Wire(Part.__sortEdges__(s_wire.Edges + rest.Edges))).extrude(V(0, 0, height))


def open_sheet():
    """The top and back faces of a 100 x 60 x 40 box only: the back face ends at the mesh boundary."""
    box = Part.makeBox(100, 60, 40)
    return Part.makeShell([f for f in box.Faces if abs(f.CenterOfMass.z - 40) < 1e-9 or abs(f.CenterOfMass.y - 60) < 1e-9])


DRAFT_LIMIT = 22 / math.cos(math.radians(cases.DRAFT_DEG)) * math.tan(math.radians((90 + cases.DRAFT_DEG) / 2))
# (name, solid, seed, true limit, why, a check of where)
CLOSED_FORMS = [
    ("box top edge", lambda: Part.makeBox(100, 60, 40), V(50, 60, 40), 40.0, "opposite_wall", lambda w: abs(w.z) < 1e-3 and abs(w.y - 60) < 1e-3),
    ("drafted shoulder", lambda: cases.draft_shoulder()[0], V(30, 25, 30), DRAFT_LIMIT, "face_end", lambda w: abs(w.z - 8) < 1e-3),
    ("channel shoulder, 12 deep", lambda: channel(30, 12), V(50, 15, 30), 12.0, "face_end", lambda w: abs(w.z - 18) < 1e-3 and abs(w.y - 15) < 1e-3),
    ("channel floor, 10 wide", lambda: channel(10, 12), V(50, 15, 18), 10.0, "opposite_wall", lambda w: abs(w.y - 25) < 1e-3 and abs(w.z - 18) < 1e-3),
    ("S chain's R20 bend", lambda: s_plate(40), V(10, 60, 40), 20.0, "curvature", lambda w: (w - V(30, 40, 40)).Length < 0.2),
    ("open sheet", open_sheet, V(50, 60, 40), 40.0, "boundary", lambda w: abs(w.z) < 1e-3),
]


def test_the_draft_limit_is_the_wedge_formula():
    """The 100 degree wedge: contacts 0.839 r from the edge, the wall 22.34 mm long -> 26.623 mm."""
    assert DRAFT_LIMIT == pytest.approx(22.3395 * math.tan(math.radians(50)), rel=1e-4)


@pytest.mark.parametrize("name, solid, seed, limit, why, where", CLOSED_FORMS, ids=[c[0] for c in CLOSED_FORMS])
def test_max_radius_matches_the_closed_form_and_the_engine(name, solid, seed, limit, why, where):
    mesh = MeshPart.meshFromShape(Shape=solid(), MaxLength=2.0)
    V0, F0 = meshconv.mesh_to_arrays(mesh)
    (found,) = MeshRound.max_radius(mesh, [seed])
    assert abs(found.radius - limit) <= 0.005 * limit, (found.radius, limit)
    assert found.radius < found.radius_refused <= found.radius * 1.001
    assert found.why == why, found.reason
    assert where(found.where), found.where
    if why == "curvature":
        assert found.curvature_radius == pytest.approx(20.0, rel=2e-3)  # from the chain point, on a chord
    res = MeshRound.round_edges(mesh, [seed], 0.98 * found.radius)
    # (the open sheet's chain runs off the mesh's edge at both ends: its end profiles become part of that edge)
    ends = [((x, 60, 40), found.radius) for x in (0, 100)] if name == "open sheet" else []
    assert soundness.problems(V0, F0, res.vertices, res.triangles, open_ends=ends) == []
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_edges(mesh, [seed], 1.02 * found.radius)
    assert err.value.code == "radius_too_large"
    assert meshconv.mesh_to_arrays(mesh)[1].tolist() == F0.tolist()  # the input untouched


def test_neighbouring_chains_share_the_face_between_them():
    """A plate 20 wide with both top edges picked: each round may take half the top face -> 10 (alone: 20);
    round_edges, rounding one after the other, agrees: 0.98x sound, 1.02x refused."""
    mesh = MeshPart.meshFromShape(Shape=Part.makeBox(100, 20, 40), MaxLength=2.0)
    V0, F0 = meshconv.mesh_to_arrays(mesh)
    seeds = [V(50, 0, 40), V(50, 20, 40)]
    alone = MeshRound.max_radius(mesh, seeds[:1])[0]
    assert alone.radius == pytest.approx(20.0, rel=5e-3) and alone.why == "opposite_wall"
    both = MeshRound.max_radius(mesh, seeds)
    for found in both:
        assert found.radius == pytest.approx(10.0, rel=5e-3) and found.why == "neighbouring_chain"
        assert abs(found.where.y - 10) < 1e-2 and abs(found.where.z - 40) < 1e-3
    res = MeshRound.round_edges(mesh, seeds, 0.98 * both[0].radius)
    assert soundness.problems(V0, F0, res.vertices, res.triangles) == []
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_edges(mesh, seeds, 1.02 * both[0].radius)
    assert err.value.code == "radius_too_large"


# Networks (issue 12's corners), measured by the rules round_edges ends its rounds by (ends.h plan_ends):
# within an end's setback no ball is solved, and the setbacks must leave room on the chain.
#  * the square and the 10 deg drafted pocket rim (cases.pocket_block: 12 deep), four chains mitred at its
#    corners: the wall's slant 12 / cos(draft) at r / tan((90 + draft) / 2) -> 12 and 14.516 (the contact
#    that runs off the wall at the floor); before, the drafted rim read 0.40 (a ball near the corner
#    touching the next wall, which the end plane cuts away);
#  * a box corner with its three edges: the 40 mm vertical chain's sphere-corner setback r (1 + 0.02) may
#    take half of it -> 20 / 1.02 = 19.608 (before: 39.998, the face's limit; round_edges refused 20.5).
def rim_limit(draft_deg):
    return 12 / math.cos(math.radians(draft_deg)) * math.tan(math.radians((90 + draft_deg) / 2))


NETWORK_FORMS = [  # (name, solid and edges, true limit, why, a check of where)
    ("square rim", lambda: cases.pocket_rim_square(0.0)(), rim_limit(0.0), "face_end", lambda w: abs(w.z - 18) < 0.2),
    ("drafted rim", lambda: cases.pocket_rim_square(10.0)(), rim_limit(10.0), "face_end", lambda w: abs(w.z - 18) < 0.2),
    ("box corner, three rounds", lambda: (Part.makeBox(100, 60, 40), None), 20 / 1.02, "end_setback",
     lambda w: (w - V(100, 60, 40)).Length < 1e-6),
]


@pytest.mark.parametrize("name, build, limit, why, where", NETWORK_FORMS, ids=[c[0] for c in NETWORK_FORMS])
def test_max_radius_of_a_network_matches_its_closed_form_and_the_engine(name, build, limit, why, where):
    solid, edges = build()
    seeds = ([e.valueAt(0.5 * (e.FirstParameter + e.LastParameter)) for e in edges] if edges
             else [V(50, 60, 40), V(100, 30, 40), V(100, 60, 20)])
    mesh = MeshPart.meshFromShape(Shape=solid, MaxLength=2.0)
    V0, F0 = meshconv.mesh_to_arrays(mesh)
    found = MeshRound.max_radius(mesh, seeds)
    tightest = min(found, key=lambda f: f.radius)
    assert abs(tightest.radius - limit) <= 0.005 * limit, (tightest.radius, limit)
    assert tightest.why == why, tightest.reason
    assert where(tightest.where), tightest.where  # the floor's edge; the corner the setbacks run into
    res = MeshRound.round_edges(mesh, seeds, 0.98 * tightest.radius)
    assert soundness.problems(V0, F0, res.vertices, res.triangles) == []
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_edges(mesh, seeds, 1.02 * tightest.radius)
    assert err.value.code == "radius_too_large", str(err.value)


def test_max_radius_of_a_pocket_with_rolled_corners_is_what_round_edges_takes():
    """Every edge of the 10 deg drafted pocket (rim, wall corners, floor): round_edges makes the wall corners and
    the floor first (rolled corners at the rim, network.h), so a wall corner's round ends at a sphere corner on
    the floor, whose setback may take half the 12.4 mm chain. max_radius plans the ends with the corners of the
    chains made in the same stage: before, it planned none (the network's corners as one stage are refused) and
    read 7.26 where round_edges refused 7.1 (the setbacks)."""
    solid, edges = cases.pocket_all(10.0)()
    seeds = [e.valueAt(0.5 * (e.FirstParameter + e.LastParameter)) for e in edges]
    mesh = MeshPart.meshFromShape(Shape=solid, MaxLength=2.0)
    V0, F0 = meshconv.mesh_to_arrays(mesh)
    found = MeshRound.max_radius(mesh, seeds)
    limit = min(f.radius for f in found)
    # (the wall corner's setbacks; the floor chains meeting it there stop at the same radius)
    setback = [f for f in found if f.radius <= limit * (1 + 1e-3) and f.why == "end_setback"]
    assert setback, [f.reason for f in found]
    assert abs(setback[0].where.z - 18) < 0.1 or abs(setback[0].where.z - 30) < 0.1, setback[0].where  # a wall corner's end
    tightest = setback[0]
    res = MeshRound.round_edges(mesh, seeds, 0.98 * tightest.radius)
    assert soundness.problems(V0, F0, res.vertices, res.triangles) == []
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.round_edges(mesh, seeds, 1.02 * tightest.radius)
    assert err.value.code == "radius_too_large" and "too short" in str(err.value), str(err.value)


def test_bad_input_is_refused_with_its_code():
    mesh = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=8.0)
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.max_radius(mesh, [V(50, 30, 20)])  # the middle of the box: no sharp edge near
    assert err.value.code == "no_sharp_edge"
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.max_radius(mesh, [V(50, 60, 40)], reach=0.5)
    assert err.value.code == "invalid_input"


def test_rules_flag_below_k_t_and_above_the_limit():
    """The shoulder and the floor edge of one 12 mm channel wall: picked together they share the wall,
    6 mm each (alone 12)."""
    mesh = MeshPart.meshFromShape(Shape=channel(30, 12), MaxLength=4.0)
    assert round(MeshRound.max_radius(mesh, [V(50, 15, 30)])[0].radius, 1) == 12.0
    limits = MeshRound.max_radius(mesh, [V(50, 15, 30), V(50, 15, 18)])
    assert [round(lim.radius, 1) for lim in limits] == [6.0, 6.0]
    assert [lim.why for lim in limits] == ["neighbouring_chain"] * 2
    rows = MeshRound.check_rules(limits, [3.0, 7.0], thickness=1.0, tool=["die", "punch"])
    assert rows[0]["flags"] == ["below_k_t"] and rows[0]["min_radius"] == 5.0   # die: 5 t
    assert rows[1]["flags"] == ["above_limit"] and rows[1]["min_radius"] == 4.0  # punch: 4 t
    assert "6 mm" in rows[1]["message"] or "5.99" in rows[1]["message"]
    assert MeshRound.check_rules(limits, 5.5, thickness=1.0)[0]["flags"] == []
    assert MeshRound.check_rules(limits, 5.5, thickness=1.0, k={"die": 7})[0]["flags"] == ["below_k_t"]
    assert MeshRound.check_rules(None, 5.5)[0]["flags"] == []  # no limits, no thickness: nothing to flag


def box_edge_mesh():
    return MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=4.0), [V(50, 60, 40)]


def test_sweep_makes_one_variant_per_radius_and_stops_at_the_limit(tmp_path):
    mesh, seeds = box_edge_mesh()
    radii = [4.0, 12.0, 39.0, 41.0]
    result = MeshRound.sweep(mesh, seeds, radii, out_dir=str(tmp_path), fmt="obj", jobs=2, thickness=1.0)
    assert result.jobs == 2
    assert [row["status"] for row in result.rows] == ["ok", "ok", "ok", "above_limit"]
    assert "41" in result.stopped and "39.99" in result.stopped
    for row, r in zip(result.rows[:3], radii):
        variant = MeshRound.round_edges(mesh, seeds, r)  # the same rounding made here
        written = Mesh.Mesh(str(tmp_path / row["file"]))
        assert written.CountFacets == variant.mesh.CountFacets
        assert row["facets_added"] == variant.report["facets_added"]
        # the round removes (1 - pi/4) r^2 of the section along the 100 mm edge, and its chords (within the
        # tolerance r / 100 of the arc) at most the band between the arc and its tolerance
        exact = 100 * 60 * 40 - (1 - math.pi / 4) * r * r * 100
        assert exact - (r / 100) * (math.pi / 2 * r) * 100 <= written.Volume <= exact + 1e-3 * exact
    assert result.rows[0]["rules"][0]["flags"] == ["below_k_t"]  # 4 < 5 t
    with open(result.table_csv, newline="") as stream:
        table = list(csv.DictReader(stream))
    assert [t["status"] for t in table] == ["ok", "ok", "ok", "above_limit"]
    assert table[0]["rule_flags"] == "below_k_t" and table[1]["rule_flags"] == ""
    data = json.load(open(result.table_json))
    assert data["rows"][2]["report"]["facets_added"] == result.rows[2]["facets_added"]
    assert data["limits"][0]["why"] == "opposite_wall"


def test_sweep_takes_per_chain_radii(tmp_path):
    mesh = MeshPart.meshFromShape(Shape=channel(30, 12), MaxLength=4.0)
    seeds = [V(50, 15, 30), V(50, 45, 18)]  # a shoulder and the far floor edge
    result = MeshRound.sweep(mesh, seeds, [[3.0, 5.0], [6.0, 2.0]], out_dir=str(tmp_path), jobs=1)
    assert [row["status"] for row in result.rows] == ["ok", "ok"]
    both = MeshRound.round_edges(mesh, seeds, [(seeds[0], 3.0), (seeds[1], 5.0)])
    assert result.rows[0]["facets_added"] == both.report["facets_added"]


def test_optimiser_finds_a_closed_form_minimum(tmp_path):
    """Objective from the variant's file: its volume against the volume of the r = 12 round (a closed form)."""
    mesh, seeds = box_edge_mesh()
    import Mesh
    target = 100 * 60 * 40 - (1 - math.pi / 4) * 12.0 ** 2 * 100

    def objective(path):
        return (Mesh.Mesh(path).Volume - target) ** 2

    # a fine chordal tolerance: the chords' own volume (within 0.01 mm of the arc) moves the minimum by < 0.01 mm
    best = MeshRound.optimise_radius(mesh, seeds, objective, out_dir=str(tmp_path), xatol=0.05, tolerance=0.01)
    assert best.bounds[1] == pytest.approx(40.0, rel=1e-3)  # the default: up to max_radius
    assert best.radius == pytest.approx(12.0, abs=0.06)
    assert os.path.isfile(best.path) and len(best.evaluations) <= 25


def run_cli(*args):
    env = dict(os.environ, PYTHONPATH=MOD)
    return subprocess.run(["/usr/bin/python3", "-m", "MeshRound.cli", *args], capture_output=True, text=True, env=env, timeout=300)


def test_command_line_max_radius_and_sweep(tmp_path):
    mesh, _ = box_edge_mesh()
    src = str(tmp_path / "box.stl")
    mesh.write(src)
    out = run_cli("max-radius", src, "--seed", "50,60,40", "--json", str(tmp_path / "limits.json"))
    assert out.returncode == 0, out.stderr
    assert "max radius 39.99" in out.stdout and "opposite_wall" in out.stdout
    assert json.load(open(tmp_path / "limits.json"))["chains"][0]["radius"] == pytest.approx(40, rel=5e-3)
    (tmp_path / "radii.csv").write_text("shoulder\n5\n38\n45\n")
    out = run_cli("sweep", src, str(tmp_path / "variants"), "--seed", "50,60,40", "--radius-csv", str(tmp_path / "radii.csv"))
    assert out.returncode == 0, out.stderr
    assert "sweep stopped at the feasible limit" in out.stdout and "2 of 3 variant(s) made" in out.stdout
    assert len([f for f in os.listdir(tmp_path / "variants") if f.endswith(".stl")]) == 2
    out = run_cli("sweep", src, str(tmp_path / "v2"), "--seed", "50,60,40", "--radius", "3:10:0.5x")
    assert out.returncode == 2


def test_sweep_features_make_one_parametric_rounding_per_radius():
    import FreeCAD
    mesh, seeds = box_edge_mesh()
    doc = FreeCAD.newDocument("SweepFeatures")
    try:
        base = doc.addObject("Mesh::Feature", "Box")
        base.Mesh = mesh
        features = MeshRound.sweep_features(base, seeds, [4.0, 8.5])
        doc.recompute()
        assert [f.Name for f in features] == ["Rounding_r4", "Rounding_r8_5"]
        for f, r in zip(features, (4.0, 8.5)):
            assert f.Radius.Value == r and "Invalid" not in f.State
            assert f.Mesh.Volume == pytest.approx(100 * 60 * 40 - (1 - math.pi / 4) * r * r * 100, rel=2e-3)
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_sweep_sheet_drives_one_rounding_from_a_spreadsheet_column(tmp_path):
    """Column B of a sheet (a header, 4, 6 mm, 41 past the 40 mm limit, 8.5): one variant file per cell from the
    one Rounding, the same table as sweep's, the limit's line for 41; the Rounding's own radius expression
    (Spreadsheet.r) is back afterwards."""
    import FreeCAD
    import Spreadsheet  # noqa: F401  (registers Spreadsheet::Sheet)
    mesh, seeds = box_edge_mesh()
    doc = FreeCAD.newDocument("SweepSheet")
    try:
        base = doc.addObject("Mesh::Feature", "Box")
        base.Mesh = mesh
        sheet = doc.addObject("Spreadsheet::Sheet", "Spreadsheet")
        for cell, text in (("A1", "5"), ("B1", "radius"), ("B2", "4"), ("B3", "6 mm"), ("B4", "41"),
                           ("B5", "8.5"), ("C2", "99")):
            sheet.set(cell, text)
        sheet.setAlias("A1", "r")
        rounding = MeshRound.make_rounding(base, seeds, 5.0)
        rounding.setExpression("Radius", "Spreadsheet.r")
        doc.recompute()
        before = rounding.Mesh.Topology
        result = MeshRound.sweep_sheet(rounding, sheet, "B", str(tmp_path), fmt="obj", thickness=1.0)
        assert [row["cell"] for row in result.rows] == ["B2", "B3", "B4", "B5"]
        assert [row["radii"] for row in result.rows] == [[4.0], [6.0], [41.0], [8.5]]
        assert [row["status"] for row in result.rows] == ["ok", "ok", "above_limit", "ok"]
        assert "41" in result.stopped and "39.99" in result.stopped and "above the feasible limit" in result.stopped
        assert "largest feasible radius 39.99" in result.rows[2]["message"]
        for row in (result.rows[0], result.rows[1], result.rows[3]):
            r = row["radii"][0]
            assert row["file"] == f"Rounding_{row['index']:03d}_r{r:g}.obj"
            written = Mesh.Mesh(str(tmp_path / row["file"]))
            assert row["facets_added"] == MeshRound.round_edges(mesh, seeds, r).report["facets_added"]
            assert written.Volume == pytest.approx(100 * 60 * 40 - (1 - math.pi / 4) * r * r * 100, rel=2e-3)
        assert result.rows[0]["rules"][0]["flags"] == ["below_k_t"] and result.rows[1]["rules"][0]["flags"] == []
        with open(result.table_csv, newline="") as stream:
            table = list(csv.DictReader(stream))
        assert [t["status"] for t in table] == ["ok", "ok", "above_limit", "ok"]
        assert table[0]["rule_flags"] == "below_k_t" and table[3]["file"] == "Rounding_003_r8.5.obj"
        data = json.load(open(result.table_json))
        assert data["rows"][1]["cell"] == "B3" and data["rows"][1]["report"]["facets_added"] > 0
        assert "above the feasible limit" in data["stopped"]
        # the Rounding as it was: its expression, its radius, its mesh
        assert dict(rounding.ExpressionEngine) == {"Radius": "Spreadsheet.r"} or \
            dict((p.lstrip("."), e) for p, e in rounding.ExpressionEngine) == {"Radius": "Spreadsheet.r"}
        assert rounding.Radius.Value == 5.0 and rounding.Mesh.Topology == before and "Invalid" not in rounding.State
        # without the limit check the engine is asked and refuses 45 mm: a "failed" row with its reason, the
        # Rounding as it was afterwards
        sheet.set("E1", "45")
        sheet.set("E2", "3")
        doc.recompute()
        failed = MeshRound.sweep_sheet(rounding, sheet, "E", str(tmp_path / "f"), check_limits=False)
        assert [row["status"] for row in failed.rows] == ["failed", "ok"] and failed.limits == []
        assert "too large" in failed.rows[0]["message"] and failed.rows[0]["file"] is None
        assert rounding.Radius.Value == 5.0 and "Invalid" not in rounding.State
        with pytest.raises(MeshRound.RoundingError, match="no radii in column D"):
            MeshRound.sweep_sheet(rounding, sheet, "D", str(tmp_path / "d"))
        sheet.set("B6", "wide")
        doc.recompute()
        with pytest.raises(MeshRound.RoundingError, match="B6 is not a radius"):
            MeshRound.sweep_sheet(rounding, sheet, "B", str(tmp_path / "e"))
    finally:
        FreeCAD.closeDocument(doc.Name)


def deck_box(folder, style):
    """tests/python/deck_files.py's box deck (60 x 40 x 30, quads 2.5): its top back edge at y = 40, z = 30."""
    import deck_files
    import numpy as np
    xyz, quads, faces = deck_files.box_quads((60.0, 40.0, 30.0), 2.5)
    centroid = xyz[quads].mean(axis=1)
    near = np.flatnonzero((np.abs(centroid[:, 1] - 40) < 5) & (np.abs(centroid[:, 2] - 30) < 5))
    edge = np.flatnonzero((np.abs(xyz[:, 1] - 40) < 1e-9) & (np.abs(xyz[:, 2] - 30) < 1e-9))
    return deck_files.write_deck(folder, style, xyz, quads, faces, near, np.flatnonzero(faces == 4), edge)


DECK_SEED = (37.0, 40.0, 30.0)


def test_sweep_of_a_deck_writes_decks_the_same_as_round_deck(tmp_path):
    """Each variant of an LS-DYNA deck is the deck round_deck writes for that radius, byte for byte (IDs and
    every line outside the band kept); 45 mm is past the 30 mm side face: not made, said so."""
    path = deck_box(str(tmp_path), "lsdyna_fixed")
    result = MeshRound.sweep(path, [DECK_SEED], [3.0, 5.0, 45.0], out_dir=str(tmp_path / "variants"), jobs=2)
    assert [row["status"] for row in result.rows] == ["ok", "ok", "above_limit"]
    assert "45" in result.stopped and result.limits[0].radius == pytest.approx(30.0, rel=5e-3)
    before = MeshRound.read_deck(path)
    for row, r in zip(result.rows[:2], (3.0, 5.0)):
        assert row["file"].endswith(f"_r{r:g}.k")
        single = str(tmp_path / f"single_r{r:g}.k")
        MeshRound.round_deck(path, single, [DECK_SEED], r)
        variant = tmp_path / "variants" / row["file"]
        assert variant.read_bytes() == open(single, "rb").read()
        after = MeshRound.read_deck(str(variant))
        assert len(after["shell_ids"]) > len(before["shell_ids"]) and after["format"] == "lsdyna"
        assert row["report"]["deck"]["elements_removed"] > 0 and row["facets_added"] > 0
    with pytest.raises(MeshRound.RoundingError, match="no conversion"):
        MeshRound.sweep(path, [DECK_SEED], [3.0], out_dir=str(tmp_path / "x"), fmt="stl")


def test_sweep_of_a_deck_with_includes_and_from_the_command_line(tmp_path):
    """A deck whose nodes are in an include: each variant in a folder of its own with its include; the
    command line sweeps a Nastran deck into Nastran decks."""
    path = deck_box(str(tmp_path), "lsdyna_long")  # box.k includes box_nodes.k
    result = MeshRound.sweep(path, [DECK_SEED], [4.0, 6.0], out_dir=str(tmp_path / "v"), jobs=1)
    assert [row["status"] for row in result.rows] == ["ok", "ok"]
    for row in result.rows:
        folder = tmp_path / "v" / os.path.dirname(row["file"])
        assert os.path.basename(row["file"]) == "box.k" and (folder / "box_nodes.k").is_file()
        assert len(MeshRound.read_deck(str(folder / "box.k"))["node_ids"]) > len(MeshRound.read_deck(path)["node_ids"])
    nastran = tmp_path / "n"
    nastran.mkdir()
    src = deck_box(str(nastran), "nastran_small")
    out = run_cli("sweep", src, str(tmp_path / "nv"), "--seed", "37,40,30", "--radius", "3,5,45", "--jobs", "1")
    assert out.returncode == 0, out.stderr
    assert "sweep stopped at the feasible limit" in out.stdout and "2 of 3 variant(s) made" in out.stdout
    made = sorted(f for f in os.listdir(tmp_path / "nv") if f.endswith(".bdf"))
    assert len(made) == 2
    assert MeshRound.read_deck(str(tmp_path / "nv" / made[0]))["format"] == "nastran"
    out = run_cli("sweep", src, str(tmp_path / "nm"), "--seed", "37,40,30", "--radius", "3", "--format", "stl")
    assert out.returncode == 0, out.stderr  # --format stl: the deck's shells swept as a triangle mesh
    assert [f for f in os.listdir(tmp_path / "nm") if f.endswith(".stl")]


def test_round_edges_report_has_the_rule_check_when_a_thickness_is_given():
    mesh, seeds = box_edge_mesh()
    assert "rules" not in MeshRound.round_edges(mesh, seeds, 4.0).report  # no thickness: no entry
    (rule,) = MeshRound.round_edges(mesh, seeds, 4.0, thickness=1.0).report["rules"]
    assert rule["flags"] == ["below_k_t"] and rule["min_radius"] == 5.0 and rule["tool"] == "die"
    assert "below 5 t = 5 mm" in rule["message"]
    assert MeshRound.round_edges(mesh, seeds, 4.0, thickness=1.0, tool="punch").report["rules"][0]["flags"] == []
    assert MeshRound.round_edges(mesh, seeds, 4.0, thickness=1.0, tool="punch", k={"punch": 6}).report["rules"][0][
        "min_radius"] == 6.0
    law = [(V(0, 60, 40), 6.0), (V(100, 60, 40), 3.0)]  # a variable radius: its smallest is checked
    assert MeshRound.round_edges(mesh, seeds, law, thickness=0.7).report["rules"][0]["flags"] == ["below_k_t"]
    with pytest.raises(MeshRound.RoundingError, match="unknown tool type"):
        MeshRound.round_edges(mesh, seeds, 4.0, thickness=1.0, tool="blank")
    with pytest.raises(MeshRound.RoundingError, match="thickness must be a positive number"):
        MeshRound.round_edges(mesh, seeds, 4.0, thickness=-1.0)
