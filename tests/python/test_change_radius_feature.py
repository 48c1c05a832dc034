"""The Rounding feature as "Change radius of existing round" (issue 15, point 3), headless.

Input: the mesh of OCCT's 5 mm fillet of the 60 x 40 x 30 box's top back edge (test_change_radius.py's
coarse box, 2-3 elements across the round) as a Mesh::Feature.  The feature in change mode:
  * at 8 mm: valid, FoundRadius / Statistics give the fillet's 5 mm within 1 %, and the output's round
    is found at 8 mm within 1 % (change_radius measuring the feature's own mesh);
  * Radius changed to 3.5 mm and recomputed: the output's round is found at 3.5 mm; the band controls
    (ElementAngle) reach the new round;
  * Radius 0: the sharp box again (the enclosed volume the sharp solid's), also made so by make_rounding;
  * a seed on a flat face: the feature in error naming not_a_round, its last good mesh and the Base kept;
  * saved and reopened: the Operation kept; a file without the Operation property (older versions)
    loads as "Round sharp edges" and still rounds sharp edges;
  * the facets the task panel highlights (reround.strip_facet_indices) are the strip's, by count.
"""
import pytest

import FreeCAD
import MeshPart
import Part

import MeshRound
import reference
import test_change_radius as reround_cases
from conftest import BOX_RADIUS, BOX_SEED
from MeshRound import meshconv, reround
from MeshRound.objects.rounding import CHANGE_RADIUS, ROUND
from test_feature import is_invalid, saved_and_reopened

R0 = reround_cases.SHAPES["box"][1]  # the fillet's radius in the input mesh: 5 mm
FOUND_WITHIN = 0.01                  # the bar for the found radius


def found_radius(mesh, r):
    """The radius change_radius finds on `mesh`'s round of the box edge, filleted at r."""
    seed = reround_cases.seed_on_round(reround_cases.case_at("box", r))
    return MeshRound.change_radius(mesh, [seed], 0).report["found_radius"][0]


@pytest.fixture
def rounded_box(doc):
    feature = doc.addObject("Mesh::Feature", "FilletedBox")
    feature.Mesh = reround_cases.rounded_mesh("box", "coarse")
    doc.recompute()
    return feature


@pytest.fixture
def change(doc, rounded_box):
    seed = reround_cases.seed_on_round(reround_cases.case_at("box", R0))
    obj = MeshRound.make_rounding(rounded_box, seed, 8.0, operation=CHANGE_RADIUS)
    doc.recompute()
    assert not is_invalid(obj), obj.getStatusString()
    return obj


def test_change_mode_finds_the_fillet_and_rounds_it_again_at_the_radius(change):
    assert change.Operation == CHANGE_RADIUS
    (found,) = change.FoundRadius
    assert abs(found - R0) <= FOUND_WITHIN * R0
    assert change.Statistics["strip1_found_radius"] == "5 mm (constant)"
    assert int(change.Statistics["strip1_facets"]) > 0 and int(change.Statistics["chains"]) == 1
    assert abs(found_radius(change.Mesh, 8.0) - 8.0) <= FOUND_WITHIN * 8.0
    assert change.Mesh.isSolid() and not change.Mesh.hasSelfIntersections()
    assert "FoundRadius" in change.PropertiesList and "ReadOnly" in change.getPropertyStatus("FoundRadius")


def test_changing_the_radius_recomputes(doc, change):
    change.Radius = 3.5
    doc.recompute()
    assert not is_invalid(change), change.getStatusString()
    assert abs(found_radius(change.Mesh, 3.5) - 3.5) <= FOUND_WITHIN * 3.5
    assert abs(change.FoundRadius[0] - R0) <= FOUND_WITHIN * R0  # the input's round, as before


def test_the_band_controls_apply_to_the_new_round(doc, change):
    rows = change.Statistics["band_elements"]
    change.ElementAngle = 10.0  # at most 10 deg of the 90 deg profile per element across: 9 rows at least
    doc.recompute()
    assert not is_invalid(change), change.getStatusString()
    assert int(change.Statistics["band_elements"]) > int(rows)


def test_radius_zero_sharpens(doc, rounded_box, change):
    sharp = Part.makeBox(60, 40, 30)
    fillet_volume = sharp.Volume - reround_cases.case_at("box", R0).reference.Volume
    change.Radius = 0.0
    doc.recompute()
    assert not is_invalid(change), change.getStatusString()
    volume = abs(reference.signed_volume(*reference.mesh_arrays(change.Mesh)))  # float64: Mesh.Volume is float32's
    assert abs(volume - sharp.Volume) <= 1e-3 * fillet_volume
    made = MeshRound.make_rounding(rounded_box, list(change.Seeds), 0, operation=CHANGE_RADIUS, name="Sharp")
    doc.recompute()
    assert not is_invalid(made) and made.Mesh.Topology == change.Mesh.Topology
    with pytest.raises(MeshRound.RoundingError, match="radius"):  # rounding a sharp edge at 0: refused as before
        MeshRound.make_rounding(rounded_box, list(change.Seeds), 0)


def test_a_seed_on_a_flat_face_is_refused_naming_not_a_round(doc, rounded_box, change):
    good, base = change.Mesh.Topology, rounded_box.Mesh.Topology
    change.Seeds = [FreeCAD.Vector(30, 20, 30)]  # the top face
    doc.recompute()
    assert is_invalid(change)
    status = change.getStatusString()
    assert status.startswith("not_a_round: ") and "flat face" in status, status
    assert change.Mesh.Topology == good and rounded_box.Mesh.Topology == base
    assert not is_invalid(rounded_box)


def test_the_operation_is_saved(doc, change, tmp_path):
    topology = change.Mesh.Topology
    with saved_and_reopened(doc, str(tmp_path / "change.FCStd")) as reopened:
        obj = reopened.getObject("Rounding")
        assert obj.Operation == CHANGE_RADIUS and list(obj.getEnumerationsOfProperty("Operation")) == [ROUND, CHANGE_RADIUS]
        obj.touch()
        reopened.recompute()
        assert not is_invalid(obj) and obj.Mesh.Topology == topology


def test_an_old_document_without_operation_still_rounds_sharp_edges(doc, tmp_path):
    box = doc.addObject("Mesh::Feature", "Box")
    box.Mesh = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=5.0)
    obj = MeshRound.make_rounding(box, BOX_SEED, BOX_RADIUS)
    obj.removeProperty("Operation")
    obj.removeProperty("FoundRadius")
    with saved_and_reopened(doc, str(tmp_path / "old.FCStd")) as reopened:
        obj = reopened.getObject("Rounding")
        assert obj.Operation == ROUND and list(obj.FoundRadius) == []
        reopened.recompute()
        assert not is_invalid(obj), obj.getStatusString()
        assert int(obj.Statistics["chains"]) == 1 and "strip1_found_radius" not in obj.Statistics
        assert list(obj.FoundRadius) == []


def test_make_rounding_refuses_an_unknown_operation(doc, rounded_box):
    with pytest.raises(MeshRound.RoundingError, match="operation"):
        MeshRound.make_rounding(rounded_box, (30, 37, 29), 8.0, operation="Fillet")
    assert [o.Name for o in doc.Objects] == ["FilletedBox"]


@pytest.mark.parametrize("name,variant", reround_cases.RUNS)
def test_the_highlighted_facets_are_the_strip(name, variant):
    mesh = reround_cases.rounded_mesh(name, variant)
    seed = reround_cases.seed_on_round(reround_cases.case_at(name, reround_cases.SHAPES[name][1]))
    (strip,) = MeshRound.change_radius(mesh, [seed], 0).report["strips"]
    vertices, triangles = meshconv.mesh_to_arrays(mesh)
    facets = reround.strip_facet_indices(vertices, triangles, strip)
    assert len(facets) == strip["strip_facets"]
