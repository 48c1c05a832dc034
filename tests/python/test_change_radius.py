"""MeshRound.change_radius (issue 15) on meshes of OCCT-filleted solids, against OCCT.

Inputs: the CAD solids of cases.py (box edge: convex 90 deg; L-channel: concave 90 deg; drafted shoulder:
convex 100 deg), filleted by OCCT (Part.Shape.makeFillet) at r0 and meshed by MeshPart with MaxLength
0.4 r0 ("fine", ~4 elements across the round) or 0.7 r0 ("coarse", 2-3 elements across: pi/2 / 0.7).
Every mesh vertex lies on the CAD faces (float32), so the radius measured at each is the exact one.
Bounds:
  * found radius within 1 % (fine) / 5 % (coarse) of r0, reported constant;
  * radius 0: the rebuilt sharp edge -- every vertex near the chain on the sharp solid's faces (1e-4 r0),
    the enclosed volume the sharp solid's (to 1e-3 of the fillet's volume), watertight, no crossing;
  * a larger and a smaller radius: deviation <= 0.01 r both ways from OCCT's fillet of the SHARP solid at
    the new radius (reference.score), topology sound, nothing beyond the reach touched;
  * round trip (sharpen, round at the found radius): within 0.01 r0 of OCCT's fillet at r0, both ways;
  * a strip that is not a round (an elliptic blend; a flat face) is refused with code not_a_round and the
    input mesh is left as it was.
"""
import functools
import math
import re

import numpy as np
import pytest

import cases
import reference
import soundness
import FreeCAD
import Part
import MeshRound
from MeshRound import cli, reround

V = FreeCAD.Vector
MAX_LENGTH = {"fine": 0.4, "coarse": 0.7}     # / r0
# A CAD export's tessellation (cases.MESH_VARIANTS "cad"): a few long facets on the flat faces, the round in
# strips the whole length of the edge (60 mm by 0.36 mm on the box: sharpened, its sides are such strips too).
CAD_MESH = dict(LinearDeflection=0.004, AngularDeflection=0.2, Relative=False)
FOUND_WITHIN = {"fine": 0.01, "coarse": 0.05, "cad": 0.01}  # relative error of the found radius (the bars)
DEVIATION = 0.01                              # / r: the bar, both ways
# name -> (builder, r0, larger radius, smaller radius)
SHAPES = {
    "box": (cases.box, 5.0, 8.0, 3.5),
    "lchannel": (cases.lchannel, 4.0, 6.0, 3.0),
    "draft_shoulder": (cases.draft_shoulder, 5.0, 7.0, 3.5),
}


@functools.lru_cache(maxsize=None)
def case_at(name, r):
    """OCCT's fillet of the sharp solid at r (a cases.Case: reference.score's yardstick)."""
    return cases.Case(f"reround_{name}_{r:g}", SHAPES[name][0], r)


@functools.lru_cache(maxsize=None)
def rounded_mesh(name, variant):
    r0 = SHAPES[name][1]
    if variant == "cad":
        return cases.mesh_of(case_at(name, r0).reference, **CAD_MESH)
    return cases.mesh_of(case_at(name, r0).reference, MaxLength=MAX_LENGTH[variant] * r0)


def seed_on_round(case):
    """A point on the round's face, 63 % along it, half way across."""
    face = max(case.rounds, key=lambda f: f.Area)
    u0, u1, v0, v1 = face.ParameterRange
    return face.valueAt(0.37 * u0 + 0.63 * u1, 0.5 * (v0 + v1))


def topology_sound(mesh):
    V1, F1 = reference.mesh_arrays(mesh)
    t = reference.edge_table(F1)
    assert (t["count"] == 1).sum() == 0, "a hole"
    assert (t["count"] > 2).sum() == 0, "a non-manifold edge"
    assert t["misoriented"] == 0, "facets facing against their neighbours"
    assert not mesh.hasSelfIntersections()


def assert_sound_and_local(row):
    """A scored rounding (reference.score) is watertight, manifold, oriented as its input, free of crossings, and
    touched nothing beyond the reach."""
    assert row["boundary_edges_out"] == 0 and row["nonmanifold_edges"] == 0 and row["misoriented_edges"] == 0, row
    assert not row["self_intersections"] and row["orientation_kept"], row
    assert row["far_vertices_lost"] == 0 and row["far_facets_lost"] == 0 and row["far_facets_added"] == 0, row


def assert_sharp_edge_rebuilt(old, sharpened, r0):
    """Every vertex within 2 r0 of the chain on the sharp solid's faces (1e-4 r0), the sharp solid's volume (to
    1e-3 of the fillet's), watertight and free of crossings."""
    geo = reference.exact_geometry(old, 3.0)
    V1, F1 = reference.mesh_arrays(sharpened)
    near = V1[geo["chain"].distance(V1) <= 2 * r0]
    assert geo["sharp"].distance(near).max() <= 1e-4 * r0
    fillet_volume = abs(old.solid.Volume - old.reference.Volume)
    assert abs(abs(reference.signed_volume(V1, F1)) - old.solid.Volume) <= 1e-3 * fillet_volume
    topology_sound(sharpened)


RUNS = [(n, v) for n in SHAPES for v in FOUND_WITHIN]


@pytest.mark.parametrize("name,variant", RUNS)
def test_found_radius_and_sharp_edge(name, variant):
    r0 = SHAPES[name][1]
    old, mesh = case_at(name, r0), rounded_mesh(name, variant)
    res = MeshRound.change_radius(mesh, [seed_on_round(old)], 0)
    strip = res.report["strips"][0]
    assert len(res.report["strips"]) == 1
    assert abs(res.report["found_radius"][0] - r0) <= FOUND_WITHIN[variant] * r0, strip
    assert strip["constant"] and strip["recognised"]
    assert strip["convex"] == (name != "lchannel")
    assert_sharp_edge_rebuilt(old, res.mesh, r0)


@pytest.mark.parametrize("which", ["larger", "smaller"])
@pytest.mark.parametrize("name,variant", [(n, v) for n, v in RUNS if v != "fine" or n == "box"])  # fine: the box only (time)
def test_new_radius_against_occt(name, variant, which):
    builder, r0, larger, smaller = SHAPES[name]
    r1 = larger if which == "larger" else smaller
    mesh = rounded_mesh(name, variant)
    res = MeshRound.change_radius(mesh, [seed_on_round(case_at(name, r0))], r1)
    row = reference.score(case_at(name, r1), mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= DEVIATION, row
    assert row["dev_ref_to_out"] <= DEVIATION, row
    assert_sound_and_local(row)


def assert_original_radius_returns_the_input(old, mesh, r0, deviation=DEVIATION):
    """Sharpened, then rounded at the radius found: within 0.01 r of OCCT's fillet at r0 both ways, and within the
    tolerance plus the input's own chordal error of the input mesh itself (measured: the exact rounds' farthest
    point from the input's facets near the chain; MeshPart's 2 mm mesh of the box spans the 5 mm round in chords
    of 30 deg, which sag 0.17 mm, more than its element length makes one expect)."""
    found = MeshRound.change_radius(mesh, [seed_on_round(old)], 0).report["found_radius"][0]
    res = MeshRound.change_radius(mesh, [seed_on_round(old)], found)
    row = reference.score(old, mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= deviation and row["dev_ref_to_out"] <= deviation, row
    assert_sound_and_local(row)
    V0, F0 = reference.mesh_arrays(mesh)
    V1, F1 = reference.mesh_arrays(res.mesh)
    chain = reference.Chain(old)
    P = reference.surface_samples(V1, F1)
    P = P[chain.distance(P) <= 2 * r0]
    input_facets = reference.TriangleSet(V0, F0)
    own = input_facets.distance(P).max()
    geo = reference.exact_geometry(old, 3.0)
    sag = input_facets.distance(geo["rounds"]).max()  # the input's own chordal error on its rounds
    assert own <= r0 / 100 + sag + reference.MEASURE * r0, (own, sag)


@pytest.mark.parametrize("name,variant", [("box", "coarse"), ("lchannel", "coarse"), ("draft_shoulder", "fine"), ("lchannel", "cad")])
def test_sharpen_then_original_radius_returns_the_input(name, variant):
    r0 = SHAPES[name][1]
    assert_original_radius_returns_the_input(case_at(name, r0), rounded_mesh(name, variant), r0)


def elliptic_blend():
    """The box's top back edge blended by a quarter ellipse (6 x 3 mm) tangent to both faces: a strip
    between two flat sides, but no ball fits it."""
    arc = Part.ArcOfEllipse(Part.Ellipse(V(0, 40, 27), V(0, 34, 30), V(0, 34, 27)), 0, math.pi / 2)
    edges = [Part.LineSegment(V(0, 34, 30), V(0, 0, 30)).toShape(), Part.LineSegment(V(0, 0, 30), V(0, 0, 0)).toShape(),
             Part.LineSegment(V(0, 0, 0), V(0, 40, 0)).toShape(), Part.LineSegment(V(0, 40, 0), V(0, 40, 27)).toShape(),
             arc.toShape()]
    return Part.Face(Part.Wire(Part.__sortEdges__(edges))).extrude(V(60, 0, 0))


def test_not_a_round_is_refused():
    solid = elliptic_blend()
    mesh = cases.mesh_of(solid, MaxLength=1.5)
    before = mesh.Topology
    seed = V(25, 34 + 6 * math.cos(0.8), 27 + 3 * math.sin(0.8))
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.change_radius(mesh, [seed], 4.0)
    assert err.value.code == "not_a_round" and "radius is not defined" in str(err.value)
    with pytest.raises(MeshRound.RoundingError) as err:
        MeshRound.change_radius(mesh, [V(30, 20, 30)], 4.0)  # the flat top face
    assert err.value.code == "not_a_round" and "flat face" in str(err.value)
    assert mesh.Topology == before


def test_cli_reround(tmp_path, capsys):
    old = case_at("box", 5.0)
    src, dst = tmp_path / "in.stl", tmp_path / "out.stl"
    rounded_mesh("box", "coarse").write(str(src))
    seed = seed_on_round(old)
    status = cli.main(["reround", str(src), str(dst), "--seed", f"{seed.x},{seed.y},{seed.z}", "--radius", "8",
                       "--report", str(tmp_path / "r.json")])
    assert status == 0 and dst.exists()
    assert "r = 5 mm" in capsys.readouterr().out
    status = cli.main(["reround", str(src), str(tmp_path / "x.stl"), "--seed", "30,20,30", "--radius", "8"])
    assert status == 1 and "not_a_round" in capsys.readouterr().err and not (tmp_path / "x.stl").exists()


def test_variable_round_measured_law_and_made_constant():
    """OCCT's 2 -> 8 mm variable fillet of the box edge (cases "box_var"): the law found along the strip
    matches OCCT's own radius on sections (cases.measured_law) within 1 % of r_max; rounded again at a
    constant 5 mm it is OCCT's 5 mm fillet of the sharp box within 0.01 r both ways."""
    var = cases.case("box_var")
    mesh = cases.mesh_of(var.reference, MaxLength=1.6)  # (at 2.0 a sliver at the end tilts 57 deg: refused)
    seed = seed_on_round(var)
    strip = MeshRound.change_radius(mesh, [seed], 0).report["strips"][0]
    assert not strip["constant"]
    assert abs(strip["radius_min"] - 2.0) <= 0.02 and abs(strip["radius_max"] - 8.0) <= 0.08
    law = np.array(strip["law"])
    for p, r in var.radius:  # OCCT's radius at chain points: the found law there (nearest station, linear)
        s = np.linalg.norm(law[:, :3] - np.array(tuple(p)), axis=1)
        i, j = np.argsort(s)[:2]
        found = (law[i, 3] * s[j] + law[j, 3] * s[i]) / (s[i] + s[j])
        assert abs(found - r) <= 0.01 * var.r_max, (tuple(p), r, found)
    res = MeshRound.change_radius(mesh, [seed], 5.0)
    row = reference.score(cases.case("box"), mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= DEVIATION and row["dev_ref_to_out"] <= DEVIATION, row
    assert row["boundary_edges_out"] == 0 and not row["self_intersections"] and row["far_facets_lost"] == 0, row


def s_plate(r0, bend=30.0, turn_deg=40.0):
    """A plate (10 mm thick) whose top edge follows an S in plan -- two arcs of radius `bend`, each turning
    turn_deg, tangent at the middle -- with that edge filleted by OCCT at r0: a round whose one side (the top)
    is flat and whose other side (the wall) is curved along it.  Returns (filleted solid, a seed on the round)."""
    a = math.radians(turn_deg)
    c1 = V(0, -bend, 0)
    arc1 = Part.ArcOfCircle(Part.Circle(c1, V(0, 0, 1), bend), math.pi / 2 - a, math.pi / 2)
    pm = c1 + V(bend * math.cos(math.pi / 2 - a), bend * math.sin(math.pi / 2 - a), 0)
    n = pm - c1
    n.normalize()
    c2 = pm + n * bend
    arc2 = Part.ArcOfCircle(Part.Circle(c2, V(0, 0, 1), bend), -math.pi / 2 - a, -math.pi / 2)
    p1 = c2 + V(0, -bend, 0)
    edges = [arc1.toShape(), arc2.toShape(), Part.LineSegment(p1, V(p1.x, -25, 0)).toShape(),
             Part.LineSegment(V(p1.x, -25, 0), V(0, -25, 0)).toShape(), Part.LineSegment(V(0, -25, 0), V(0, 0, 0)).toShape()]
    solid = Part.Face(Part.Wire(Part.__sortEdges__(edges))).extrude(V(0, 0, 10))
    top = [e for e in solid.Edges if e.BoundBox.ZMin > 10 - 1e-9 and isinstance(e.Curve, Part.Circle)]
    filleted = solid.makeFillet(r0, top)
    face = max((f for f in filleted.Faces if isinstance(f.Surface, Part.Toroid)), key=lambda f: f.Area)
    u0, u1, v0, v1 = face.ParameterRange
    return filleted, face.valueAt(0.3 * u0 + 0.7 * u1, 0.5 * (v0 + v1))


def test_round_with_a_side_curved_in_plan_found_and_sharpened():
    """A round whose wall side curves along it (an S of two 40 degree arcs of 30 mm, r0 = 3): recognised
    with a flat side and a curved one, its radius found within 1 %, sharpened (the corner line on the top's
    plane), sound.  (A new radius on this plate is refused by round_edges' output check at the chain's end
    faces -- result_invalid, nothing changed -- as round_edges refuses it on the sharp plate's own MeshPart
    mesh: a round_edges limit at these ends, not the sharpening's.)"""
    solid, seed = s_plate(3.0)
    assert solid.isValid()
    mesh = cases.mesh_of(solid, MaxLength=0.4 * 3.0)
    before = mesh.Topology
    res = MeshRound.change_radius(mesh, [seed], 0)
    strip = res.report["strips"][0]
    assert abs(strip["found_radius"] - 3.0) <= 0.01 * 3.0 and strip["constant"], strip
    assert "curved along the round" in strip["recognised"] and len(strip["corner_line"]) > 10
    line = np.array(strip["corner_line"])
    assert np.abs(line[:, 2] - 10.0).max() <= 1e-4
    topology_sound(res.mesh)
    assert mesh.Topology == before


S_R0 = 4.0  # cases.s_plate: the S-shaped chain (a 20 mm plate whose top back edge follows an S)


@functools.lru_cache(maxsize=None)
def s_case(r):
    return cases.Case(f"reround_s_chain_{r:g}", cases.s_plate, r)


@functools.lru_cache(maxsize=None)
def s_mesh():
    return cases.mesh_of(s_case(S_R0).reference, MaxLength=0.4 * S_R0)


def test_s_chain_found_radius_and_sharp_edge():
    """The S-shaped chain filleted by OCCT at 4 mm (tori along the arcs, cylinders along the straight runs),
    meshed at 0.4 r0: the round found at 4 mm within 1 % (one side flat, the wall curved in plan), the sharp
    edge rebuilt section by section within 0.004 r0 of the sharp solid's faces (0.0026 r0 measured; 0.0045 r0
    while each vertex took its station's tangent plane, before the stations' tilts were smoothed), watertight."""
    old = s_case(S_R0)
    res = MeshRound.change_radius(s_mesh(), [seed_on_round(old)], 0)
    strip = res.report["strips"][0]
    # (the radii measured at its vertices spread by about +-1 %: those nearest a side measure the side's
    # position to a thousandth of a millimetre; so the strip may not be reported constant)
    assert abs(strip["found_radius"] - S_R0) <= 0.01 * S_R0, strip
    assert "curved along the round" in strip["recognised"], strip
    # the task panel's highlight of the round's facets (reround.strip_facet_indices, along the polyline)
    from MeshRound import meshconv, reround
    V0, T0 = meshconv.mesh_to_arrays(s_mesh())
    assert abs(len(reround.strip_facet_indices(V0, T0, strip)) - strip["strip_facets"]) <= 0.1 * strip["strip_facets"]
    geo = reference.exact_geometry(old, 3.0)
    V1, F1 = reference.mesh_arrays(res.mesh)
    near = V1[geo["chain"].distance(V1) <= 2 * S_R0]
    assert geo["sharp"].distance(near).max() <= 0.004 * S_R0
    fillet_volume = abs(old.solid.Volume - old.reference.Volume)
    assert abs(abs(reference.signed_volume(V1, F1)) - old.solid.Volume) <= 0.01 * fillet_volume
    topology_sound(res.mesh)


@pytest.mark.parametrize("r1", [6.0, 3.2])
def test_s_chain_new_radius_against_occt(r1):
    """The S-shaped chain's 4 mm round made 6 and 3.2 mm: within 0.01 r of OCCT's fillet of the sharp S plate
    at r both ways, sound, nothing beyond the reach touched. (The 1.6 mm mesh is fine, elements <= 0.5 r, for
    r >= 3.2; at r = 3 the result is 0.0108 r off, as round_edges on a 1.6 mm mesh of the sharp plate: 0.0112 r.)"""
    mesh = s_mesh()
    res = MeshRound.change_radius(mesh, [seed_on_round(s_case(S_R0))], r1)
    row = reference.score(s_case(r1), mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= DEVIATION and row["dev_ref_to_out"] <= DEVIATION, row
    assert_sound_and_local(row)


def test_s_chain_on_a_finer_mesh_against_occt():
    """The S plate meshed finer (1.4 mm, 0.35 r0): found at 4 mm within 1 % and made 6 mm within 0.01 r of OCCT's
    fillet both ways (0.009 measured). Its vertices next to the wall measured the radius 1.3 % low (a side's
    offset of 0.01 mm moves the ball through a vertex 0.02 r off it five times as much) and it was refused
    as not a round, until such vertices were left out of the measure (SharpenOptions::measure_clearance)."""
    old = s_case(S_R0)
    mesh = cases.mesh_of(old.reference, MaxLength=0.35 * S_R0)
    res = MeshRound.change_radius(mesh, [seed_on_round(old)], 6.0)
    assert abs(res.report["strips"][0]["found_radius"] - S_R0) <= 0.01 * S_R0, res.report["strips"][0]
    row = reference.score(s_case(6.0), mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= DEVIATION and row["dev_ref_to_out"] <= DEVIATION, row
    assert_sound_and_local(row)


@pytest.mark.parametrize("max_length", [1.0, 1.1, 1.2])
def test_s_chain_on_meshes_with_slivers_along_the_contact_line(max_length):
    """The S plate meshed at 1.0, 1.1 and 1.2 mm (0.25-0.3 r0): MeshPart leaves rows of slivers along the round's
    contact with the wall (vertices 0.66 and 5.6 deg up the round), so some border vertices of the strip sit
    0.02 mm off the wall and their only wall facet is a 3.8 deg sliver whose normal is 1.4 deg off in plan.
    The 1.0 and 1.2 mm meshes were refused as not a round (radii 3.92-4.01 measured where the wall's plane was
    taken through such a vertex); the 1.1 mm one ("it ends on a face that is not flat") until a mesher's cap
    between the round and the wall joined the strip (its longest side on the contact line, its apex 0.009 mm
    up the round: its normal, 124 deg from the top face, made it an end face mid-strip, or a wall facet whose
    apex bent the wall's plane). Now: found within 1 % (3.9996 / 4.00003 / 3.9998 measured), made 6 mm within 0.01 r
    of OCCT's fillet both ways (0.0061 / 0.0064 / 0.0058 measured), sound and local."""
    old = s_case(S_R0)
    mesh = cases.mesh_of(old.reference, MaxLength=max_length)
    res = MeshRound.change_radius(mesh, [seed_on_round(old)], 6.0)
    assert abs(res.report["strips"][0]["found_radius"] - S_R0) <= FOUND_WITHIN["fine"] * S_R0, res.report["strips"][0]
    row = reference.score(s_case(6.0), mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= DEVIATION and row["dev_ref_to_out"] <= DEVIATION, row
    assert_sound_and_local(row)


def test_s_chain_on_coarse_meshes():
    """The S plate meshed coarsely, 2-3 elements across its 4 mm round (MaxLength 2.4 and 3.2 mm): found within
    the issue's 5 % (0.02 % / 0.25 % measured) and, on the 2.4 mm mesh, made 6 mm within 0.02 r of OCCT's fillet
    both ways (0.0096 measured; the coarse bar, as the loop's: the wall's 2.4 mm chords stand 0.036 mm off its
    20 mm arc). They were refused as not a round: the radii measured off the wall's chords stray from their
    law by that chords' sag (0.041 / 0.060 mm, over 1 % of r), which the law's fit now allows where a side
    curves (strip.cpp measure_law)."""
    old = s_case(S_R0)
    for max_length in (2.4, 3.2):
        mesh = cases.mesh_of(old.reference, MaxLength=max_length)
        res = MeshRound.change_radius(mesh, [seed_on_round(old)], 0 if max_length > 3 else 6.0)
        strip = res.report["strips"][0]
        assert abs(strip["found_radius"] - S_R0) <= FOUND_WITHIN["coarse"] * S_R0, strip
        if max_length < 3:
            row = reference.score(s_case(6.0), mesh, res.mesh, res.report)
            assert row["dev_out_to_ref"] <= 0.02 and row["dev_ref_to_out"] <= 0.02, row
            assert_sound_and_local(row)
        else:
            topology_sound(res.mesh)


def test_s_chain_on_coarse_meshes_with_folded_caps():
    """The S plate's 2.1 and 3.5 mm meshes: MeshPart folds a cap (a facet with an angle of 150 deg or more, its
    normal anywhere) into the round where its cylinder meets its torus. On the 2.1 mm mesh the flood met it first
    from the neighbour it turns 81 deg from and took it for an end face mid-strip; on the 3.5 mm mesh, its normal
    88 deg off the round's, for the wall's. Both were refused as not a round; now found within 5 % (0.03 % / 0.02 %
    measured) and made 6 mm within the coarse bar of OCCT's fillet both ways (0.0093 / 0.0156 mm measured), sound
    and local. The 2.0 and 2.6 mm meshes are still refused, by name, the input kept (a row of the round 0.025 mm
    off the wall taken for the wall tilts its plane: the radii stray by 0.064 mm; a corner line turning by 31 deg
    where a cap lies between the round and a wall chord tilted by 1.5 deg)."""
    old = s_case(S_R0)
    for max_length, bar in ((2.1, 0.02), (3.5, 0.03)):
        mesh = cases.mesh_of(old.reference, MaxLength=max_length)
        res = MeshRound.change_radius(mesh, [seed_on_round(old)], 6.0)
        strip = res.report["strips"][0]
        assert abs(strip["found_radius"] - S_R0) <= FOUND_WITHIN["coarse"] * S_R0, strip
        row = reference.score(s_case(6.0), mesh, res.mesh, res.report)
        assert row["dev_out_to_ref"] <= bar and row["dev_ref_to_out"] <= bar, (max_length, row)
        assert_sound_and_local(row)
    for max_length in (2.0, 2.6):
        mesh = cases.mesh_of(old.reference, MaxLength=max_length)
        before = mesh.Topology
        with pytest.raises(MeshRound.RoundingError) as refused:
            MeshRound.change_radius(mesh, [seed_on_round(old)], 6.0)
        message = str(refused.value)
        assert refused.value.code == "not_a_round" and re.search(r"\(-?[\d.]+, -?[\d.]+, -?[\d.]+\)", message), message
        assert mesh.Topology == before


@pytest.mark.parametrize("r1", [6.0, 3.2])
def test_s_chain_on_a_cad_mesh_against_occt(r1):
    """The S plate's CAD tessellation (CAD_MESH: the straight runs in facets their whole length, the arcs in
    strips): found at 4 mm within 1 % and made 6 and 3.2 mm within 0.01 r of OCCT's fillet both ways (0.0058 /
    0.0055 measured), sound, nothing beyond the reach touched. It was refused as not a round between two flat
    sides: the wall, curved in plan, is flooded with the round, and its level normals passed for a straight
    round's turning about the vertical (strip.cpp turning_axis)."""
    old = s_case(S_R0)
    mesh = cases.mesh_of(old.reference, **CAD_MESH)
    res = MeshRound.change_radius(mesh, [seed_on_round(old)], r1)
    strip = res.report["strips"][0]
    assert abs(strip["found_radius"] - S_R0) <= 0.01 * S_R0 and "curved along the round" in strip["recognised"], strip
    row = reference.score(s_case(r1), mesh, res.mesh, res.report)
    assert row["dev_out_to_ref"] <= DEVIATION and row["dev_ref_to_out"] <= DEVIATION, row
    assert_sound_and_local(row)


LOOP_R0 = 3.0  # cases.pocket_rim: the top rim of a 25 mm radius circular pocket, filleted by OCCT (a torus)


@functools.lru_cache(maxsize=None)
def loop_case(r):
    return cases.Case(f"reround_pocket_rim_{r:g}", cases.pocket_rim, r)


@functools.lru_cache(maxsize=None)
def loop_mesh(variant):
    if variant == "cad":
        return cases.mesh_of(loop_case(LOOP_R0).reference, **CAD_MESH)
    return cases.mesh_of(loop_case(LOOP_R0).reference, MaxLength=MAX_LENGTH[variant] * LOOP_R0)


@pytest.mark.parametrize("variant", ["fine", "coarse"])
def test_a_round_all_around_a_loop_is_found_and_sharpened(variant):
    """A circular pocket's rim rounded all around (no end): found at r0 within 1 % / 5 %, the sharp rim rebuilt
    as a closed corner line (section by section, as any round with a side curved along it) within 0.008 r0 of
    the sharp block's faces (0.0019 / 0.0054 r0 measured; 0.015 r0 while each vertex took its station's tangent
    plane, before the stations' tilts were smoothed), its volume a mesh of the
    sharp block's within 2 % of the fillet's volume, watertight."""
    old = loop_case(LOOP_R0)
    res = MeshRound.change_radius(loop_mesh(variant), [seed_on_round(old)], 0)
    strip = res.report["strips"][0]
    assert abs(strip["found_radius"] - LOOP_R0) <= FOUND_WITHIN[variant] * LOOP_R0, strip
    assert "curved along the round" in strip["recognised"], strip
    geo = reference.exact_geometry(old, 3.0)
    V1, F1 = reference.mesh_arrays(res.mesh)
    near = V1[geo["chain"].distance(V1) <= 2 * LOOP_R0]
    assert len(near) > 50 and geo["sharp"].distance(near).max() <= 0.008 * LOOP_R0
    fillet_volume = abs(old.solid.Volume - old.reference.Volume)
    # against a mesh of the sharp block alike (its bore's chords as the input's; the exact volume differs by them)
    sharp = cases.mesh_of(old.solid, MaxLength=MAX_LENGTH[variant] * LOOP_R0)
    Vs, Fs = reference.mesh_arrays(sharp)
    off = abs(reference.signed_volume(V1, F1)) - abs(reference.signed_volume(Vs, Fs))
    assert abs(off) <= 0.02 * fillet_volume, (off, fillet_volume)
    topology_sound(res.mesh)


@pytest.mark.parametrize("variant,r1", [("fine", 4.5), ("fine", 1.8), ("coarse", 4.5), ("coarse", 1.8), ("cad", 1.8)])
def test_a_round_all_around_a_loop_made_larger_and_smaller_against_occt(variant, r1):
    """The rim's 3 mm round made 4.5 and 1.8 mm: against OCCT's fillet of the sharp block at r1 both ways, sound,
    nothing beyond the reach touched: fine within the issue's 0.01 r1 (0.0048 / 0.0068 r measured; 0.0051 / 0.0129
    while each vertex took its station's tangent plane), the CAD mesh too (1.8 mm: 0.0064 measured; 4.5 mm,
    0.0051, is left out for time); coarse within 0.02 r1 (0.008 / 0.017 measured): the
    issue's coarse bar is the input's own chordal error, and the bore's 2.1 mm chords stand 0.022 mm (0.012 r of
    1.8) off it, with the tolerance 0.01 r on top."""
    mesh = loop_mesh(variant)
    res = MeshRound.change_radius(mesh, [seed_on_round(loop_case(LOOP_R0))], r1)
    row = reference.score(loop_case(r1), mesh, res.mesh, res.report)
    bound = 0.02 if variant == "coarse" else DEVIATION
    assert row["dev_out_to_ref"] <= bound and row["dev_ref_to_out"] <= bound, row
    assert_sound_and_local(row)


RIM_R0, WALL_R = 2.0, 6.0  # cases.pocket_rim_round_walls: the rim of a pocket with rounded wall corners, filleted by OCCT


@functools.lru_cache(maxsize=None)
def rim_case(r):
    return cases.Case(f"reround_rim_round_walls_{r:g}", cases.pocket_rim_round_walls(WALL_R), r)


def rim_mesh(variant):
    old = rim_case(RIM_R0)
    if variant == "cad":
        return cases.mesh_of(old.reference, **CAD_MESH)
    return cases.mesh_of(old.reference, MaxLength=MAX_LENGTH[variant] * RIM_R0)


@pytest.mark.parametrize("variant,r1", [("fine", 3.0), ("fine", 1.5), ("cad", 1.5), ("coarse", 3.0), ("coarse", 2.1),
                                        ("coarse", 1.5)])
def test_a_rim_rolling_around_rounded_wall_corners_made_larger_and_smaller_against_occt(variant, r1):
    """A rectangular pocket's rim round (2 mm) that rolls on around the pocket's rounded wall corners (R 6, tori):
    one strip all around, its wall side straight and curved in turn. Found at 2 mm within 1 % (coarse 5 %), made
    3 and 1.5 mm: against OCCT's fillet of the sharp rim at r1 both ways, sound and local. MeshPart's facets across
    the seams between the straight rounds and the tori (an angle of 166-168 deg, their normals 130 deg off their
    neighbours') are crossed as caps (strip_facets.h); the stations are taken in their order along the wall
    (a CAD mesh's straight walls are one facet long, its arcs many); on 1.4 mm elements the wall's facets around
    its corners tilt by up to 3 deg and its corner line turns by up to 19 deg from one station to the next.
    Bound: the issue's 0.01 r1, plus the walls' own chordal error around their corners, which the round follows
    -- the 0.8 mm mesh's chords on the R 6 arcs sag 0.013 mm (0.009 r1 at 1.5), the 1.4 mm mesh's 0.041 mm (0.027
    r1 at 1.5, 0.014 r1 at 3; the issue's coarse bar). Measured: 0.0055 r at 3 mm and 0.0128 r at 1.5 mm (largest
    mid-arc) on the 0.8 mm mesh; 0.0065 r at 1.5 mm on the CAD mesh (3 mm: 0.0056, left out for time); 0.0172 /
    0.0128 r at 3 mm and 0.0251 / 0.0151 r at 1.5 mm on the 1.4 mm mesh. The 1.4 mm mesh made 3 mm was refused
    (facets crossing on the wall) until the sharpened wall's slivers along the old contact line were flipped
    against the facets above them (sharpen_line.h unkink_borders): their corners on the wall, their planes
    tilted 30 deg by the wall's sag across their 0.06 mm height, read as a sharp edge. Made 2.1 mm it was refused
    (a hole on the top face) until a vertex stopped snapping onto the new contact line where its facet's two other
    corners were on it already (trim_lines.cpp closes_facet_on_line): two old contact vertices 0.1 mm inside the
    line and one 0.11 mm outside between them, all three snapped, left a facet of 0.013 deg along the line."""
    old = rim_case(RIM_R0)
    mesh = rim_mesh(variant)
    res = MeshRound.change_radius(mesh, [seed_on_round(old)], r1)
    strip = res.report["strips"][0]
    assert abs(strip["found_radius"] - RIM_R0) <= FOUND_WITHIN[variant] * RIM_R0, strip
    assert "curved along the round" in strip["recognised"], strip
    row = reference.score(rim_case(r1), mesh, res.mesh, res.report)
    h = 0.0 if variant == "cad" else MAX_LENGTH[variant] * RIM_R0  # (CAD: the arcs' chords sag 0.004 mm at most)
    bound = DEVIATION + h * h / (8 * WALL_R) / r1
    assert row["dev_out_to_ref"] <= bound and row["dev_ref_to_out"] <= bound, row
    assert_sound_and_local(row)


def test_a_rim_around_rounded_wall_corners_sharpened_on_a_coarse_mesh_flips_the_slivers_along_its_walls():
    """The 1.4 mm mesh's walls keep, along the old contact line near each wall corner, slivers whose corners lie
    on the wall but whose planes tilt by up to 32 deg (the wall's sag across their 0.06 mm height). Sharpened,
    each would stand against the rebuilt wall above it as a kink that round_edges reads as a sharp edge (the
    radius found was refused "too large" there, 3 mm crossed facets). On the sharpened mesh no wall facet within
    3 mm of the rim tilts by more than 10 deg (the input's slivers there: 30.8 deg), the report counts the flips, and
    made 3 mm it is sound."""
    mesh = rim_mesh("coarse")
    V, F = reference.mesh_arrays(mesh)
    seed = seed_on_round(rim_case(RIM_R0))
    sharp = reround.change_radius_arrays(V, F, [tuple(seed)], 0.0)
    assert sharp.report["strips"][0]["border_flips"] > 0, sharp.report["strips"][0]
    W, G = np.asarray(sharp.vertices), np.asarray(sharp.triangles)
    # The wall's facets from 3 to 0.05 mm below the rim: on the sharp block they are one vertical surface,
    # the pocket's outline (x 20..60, y 15..45, corners R 6) swept down.
    def wall_facets(W, G):
        centroid = W[G].mean(axis=1)
        q = np.abs(centroid[:, :2] - (40.0, 30.0)) - (20.0 - WALL_R, 15.0 - WALL_R)
        off = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0) - WALL_R
        normal = np.cross(W[G[:, 1]] - W[G[:, 0]], W[G[:, 2]] - W[G[:, 0]])
        normal /= np.linalg.norm(normal, axis=1)[:, None]
        wall = (np.abs(off) < 0.1) & (centroid[:, 2] > 27.0) & (centroid[:, 2] < 29.95)
        return np.degrees(np.arcsin(np.abs(normal[wall, 2]))), centroid[wall]
    tilt, where = wall_facets(W, G)
    assert len(tilt) > 100 and tilt.max() <= 10.0, (len(tilt), tilt.max(), where[np.argmax(tilt)])
    assert soundness.problems(V, F, W, G) == []
    res = reround.change_radius_arrays(V, F, [tuple(seed)], 3.0)
    assert soundness.problems(V, F, res.vertices, res.triangles) == []


@pytest.mark.parametrize("variant", ["fine", "coarse", "cad"])
def test_a_rim_around_rounded_wall_corners_sharpened_then_made_at_its_own_radius_returns_the_input(variant):
    """The rim of the pocket with rounded wall corners, sharpened and rounded again at the radius found (1.99875,
    2.0014 and 1.99997 mm on the 0.8 mm, 1.4 mm and CAD meshes): within 0.01 r of OCCT's fillet at 2 mm both ways,
    plus the walls' own chordal error around their corners (1.4 mm: 0.041 mm, 0.0205 r), and within the tolerance
    plus the input's own chordal error of the input itself. Measured 0.0065 / 0.0064, 0.0186 / 0.0188 and 0.0050 /
    0.0051 r. Both MeshPart meshes were refused (facets crossing on the wall), where the new contact line runs
    along the rows of old contact vertices: on the 1.4 mm mesh a point of it fell 0.26 tolerances outside a
    flipped sliver's facet (now left out within the tolerance; trim.cpp side_stands_for_line, it was a quarter of it), on
    the 0.8 mm one it dipped 0.044 mm below such a row onto the tilt of the wall's chords, outside the facet it
    was cut in, into one that nothing cuts (now left out: that facet's side stands for it)."""
    h = 0.0 if variant == "cad" else MAX_LENGTH[variant] * RIM_R0
    assert_original_radius_returns_the_input(rim_case(RIM_R0), rim_mesh(variant), RIM_R0, DEVIATION + h * h / (8 * WALL_R) / RIM_R0)


@pytest.mark.parametrize("where,refused", [((40.0, 14.6, 29.4), True), ((40.0, 12.5, 30.0), False), ((40.0, 15.0, 26.0), False)],
                         ids=["in-the-round", "on-top-in-the-new-band", "on-the-wall-beyond"])
def test_a_hole_near_a_rim_round_is_named_or_kept(where, refused):
    """One facet taken out of the rim's 0.8 mm mesh, the 2 mm rim made 3 mm. In the old round: refused
    non_manifold_input naming the hole when the strip is recognised (its open edges are not an end of the round:
    its vertices would be folded onto an end face; on the box's top corner that made a vertex that is not a
    number), the input untouched. On the top face 1.8 mm from the rim (inside what the 3 mm round
    replaces, as in the CAD fillet): the hole goes with it, the result watertight. On the wall 4 mm down (beyond
    the new round): the hole is kept as it was, its three edges the result's only boundary."""
    V, F = reference.mesh_arrays(rim_mesh("fine"))
    centroids = V[F].mean(axis=1)
    i = int(np.argmin(np.linalg.norm(centroids - np.array(where), axis=1)))
    F = np.delete(F, i, axis=0)
    seed = seed_on_round(rim_case(RIM_R0))
    if refused:
        with pytest.raises(MeshRound.RoundingError) as err:
            reround.change_radius_arrays(V, F, [tuple(seed)], 3.0)
        assert err.value.code == "non_manifold_input", str(err.value)
        at = np.array([float(x) for x in re.search(r"where the rounding goes, at \(([^)]*)\)", str(err.value)).group(1).split(",")])
        assert np.linalg.norm(at - centroids[i]) < 1.0, (at, centroids[i])
        return
    res = reround.change_radius_arrays(V, F, [tuple(seed)], 3.0)
    assert soundness.problems(V, F, res.vertices, res.triangles) == []
    assert (reference.edge_table(res.triangles)["count"] == 1).sum() == (0 if where[2] == 30.0 else 3)
