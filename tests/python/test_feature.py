"""The parametric Rounding feature: recompute on any change, chaining, expressions, save/reload, undo/redo,
failures (invalid feature, error on the console, document consistent), STEP export, stored proxy paths."""
import contextlib
import os
import re
import subprocess
import zipfile

import pytest

import FreeCAD
import Part

import MeshRound
from conftest import BOX_OTHER_SEED, BOX_RADIUS, BOX_SEED, MOD_DIR

import Spreadsheet  # noqa: F401,E402  (registers Spreadsheet::Sheet)


def is_invalid(obj):
    return "Invalid" in obj.State


@contextlib.contextmanager
def saved_and_reopened(doc, path):
    """Save `doc` as `path`, close it and open the file again: the reopened document (closed after)."""
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    reopened = FreeCAD.openDocument(path)
    try:
        yield reopened
    finally:
        FreeCAD.closeDocument(reopened.Name)


@pytest.fixture
def rounding(doc, box_feature):
    obj = MeshRound.make_rounding(box_feature, BOX_SEED, BOX_RADIUS)
    doc.recompute()
    assert not is_invalid(obj), obj.getStatusString()
    return obj


def test_make_rounding_and_recompute(box_feature, rounding):
    assert rounding.TypeId == "Mesh::FeaturePython"
    assert rounding.Name == "Rounding"
    assert rounding.Base == box_feature
    assert rounding.Mesh.CountFacets != box_feature.Mesh.CountFacets
    assert rounding.Mesh.isSolid()
    assert int(rounding.Statistics["chains"]) == 1
    assert rounding.Radius.Value == BOX_RADIUS and rounding.Reach == 3.0
    assert rounding.FeatureAngle.Value == 30.0 and rounding.Tolerance.Value == 0.0


def test_surfaces_child_shows_the_rounding_faces(doc, rounding):
    surfaces = rounding.Surfaces
    assert surfaces.Name == "RoundingSurfaces" and surfaces.TypeId == "Part::Feature"
    assert len(surfaces.Shape.Faces) == 1
    assert isinstance(surfaces.Shape.Faces[0].Surface, Part.BSplineSurface)
    assert "Touched" not in rounding.State and "Touched" not in surfaces.State  # no recompute loop
    assert doc.recompute() == 0  # nothing left to do


def test_surfaces_follow_a_recompute(doc, rounding):
    area = rounding.Surfaces.Shape.Area
    rounding.Radius = 8.0
    doc.recompute()
    assert rounding.Surfaces.Shape.Area > area * 1.4  # the arc grows with r
    assert "Touched" not in rounding.Surfaces.State and doc.recompute() == 0


def test_deleting_the_surfaces_child_keeps_the_rounding_working(doc, rounding):
    doc.removeObject("RoundingSurfaces")
    assert rounding.Surfaces is None
    rounding.Radius = 6.0
    doc.recompute()
    assert not is_invalid(rounding), rounding.getStatusString()


def test_base_is_not_modified(box_feature, box, rounding):
    assert box_feature.Mesh.Topology == box.Topology


def test_rounding_of_a_rounding(doc, rounding):
    second = MeshRound.make_rounding(rounding, BOX_OTHER_SEED, 3.0)
    doc.recompute()
    assert not is_invalid(second), second.getStatusString()
    assert second.Name == "Rounding001" and second.Base == rounding
    assert second.Mesh.Volume < rounding.Mesh.Volume
    assert second.Surfaces.Name == "Rounding001Surfaces" and rounding.Surfaces.Name == "RoundingSurfaces"
    # changing the first re-rounds the second
    before = second.Mesh.Topology
    rounding.Radius = 6.0
    doc.recompute()
    assert second.Mesh.Topology != before


def test_radius_expression_from_spreadsheet(doc, rounding):
    sheet = doc.addObject("Spreadsheet::Sheet", "Spreadsheet")
    sheet.set("A1", "7")
    sheet.setAlias("A1", "r")
    doc.recompute()
    before = rounding.Mesh.Topology
    rounding.setExpression("Radius", "Spreadsheet.r")
    doc.recompute()
    assert rounding.Radius.Value == 7.0
    assert rounding.Mesh.Topology != before
    seven = rounding.Mesh.Topology
    sheet.set("A1", "4")
    doc.recompute()
    assert rounding.Radius.Value == 4.0
    assert rounding.Mesh.Topology != seven


def test_variable_radius_law(doc, box_feature):
    law = [(FreeCAD.Vector(0, 60, 40), 3.0), (FreeCAD.Vector(100, 60, 40), 6.0)]
    obj = MeshRound.make_rounding(box_feature, BOX_SEED, law)
    doc.recompute()
    assert not is_invalid(obj), obj.getStatusString()
    assert [tuple(p) for p in obj.RadiusLaw] == [(0, 60, 40), (100, 60, 40)]
    assert obj.RadiusLawRadii == [3.0, 6.0]
    assert obj.Radius.Value == 6.0


def test_save_and_reload_give_the_identical_mesh(doc, rounding, tmp_path):
    path = str(tmp_path / "rounding.FCStd")
    topology = rounding.Mesh.Topology
    faces = rounding.Surfaces.Shape.Faces
    with saved_and_reopened(doc, path) as reopened:
        obj = reopened.getObject("Rounding")
        assert isinstance(obj.Proxy, MeshRound.objects.rounding.Rounding)
        assert obj.Mesh.Topology == topology  # stored in the file, bit for bit
        assert obj.Surfaces.Name == "RoundingSurfaces" and len(obj.Surfaces.Shape.Faces) == len(faces)
        obj.touch()
        reopened.recompute()
        assert not is_invalid(obj)
        assert obj.Mesh.Topology == topology  # and the engine is deterministic


def test_reload_adds_missing_properties(doc, rounding, tmp_path):
    """A file from an older version (a property missing) still loads and gets the property back."""
    rounding.removeProperty("Reach")
    path = str(tmp_path / "old.FCStd")
    with saved_and_reopened(doc, path) as reopened:
        obj = reopened.getObject("Rounding")
        assert obj.Reach == 3.0
        reopened.recompute()
        assert not is_invalid(obj), obj.getStatusString()


def test_undo_redo(doc, box_feature):
    doc.openTransaction("Round edges")
    obj = MeshRound.make_rounding(box_feature, BOX_SEED, BOX_RADIUS)
    doc.recompute()
    doc.commitTransaction()
    first = obj.Mesh.Topology

    doc.openTransaction("Radius")
    obj.Radius = 8.0
    doc.recompute()
    doc.commitTransaction()
    second = obj.Mesh.Topology
    assert second != first

    doc.undo()
    assert obj.Radius.Value == BOX_RADIUS and obj.Mesh.Topology == first
    doc.redo()
    assert obj.Radius.Value == 8.0 and obj.Mesh.Topology == second
    doc.undo()
    doc.undo()
    assert doc.getObject("Rounding") is None and doc.getObject("RoundingSurfaces") is None
    doc.redo()
    assert doc.getObject("Rounding") is not None


@pytest.mark.parametrize("change", [
    "radius zero", "radius nan", "seed far", "no seeds", "law mismatch", "no base", "part base",
    "empty base", "feature angle"])
def test_bad_input_marks_the_feature_invalid(doc, box_feature, box, rounding, change):
    good = rounding.Mesh.Topology
    if change == "radius zero":
        rounding.Radius = 0.0
    elif change == "radius nan":
        rounding.Radius = float("nan")
    elif change == "seed far":
        rounding.Seeds = [FreeCAD.Vector(50, 30, 20)]
    elif change == "no seeds":
        rounding.Seeds = []
    elif change == "law mismatch":
        rounding.RadiusLaw = [BOX_SEED]
    elif change == "no base":
        rounding.Base = None
    elif change == "part base":
        rounding.Base = doc.addObject("Part::Box", "PartBox")
    elif change == "empty base":
        rounding.Base = doc.addObject("Mesh::Feature", "Empty")
    elif change == "feature angle":
        rounding.FeatureAngle = 0.0
    doc.recompute()
    assert is_invalid(rounding)
    assert rounding.getStatusString()  # the cause, as FreeCAD shows it
    assert rounding.Mesh.Topology == good  # the last good mesh stays
    assert box_feature.Mesh.Topology == box.Topology
    assert not is_invalid(box_feature)


def test_feature_recovers_after_a_failure(doc, rounding):
    rounding.Radius = 0.0
    doc.recompute()
    assert is_invalid(rounding)
    rounding.Radius = 4.0
    doc.recompute()
    assert not is_invalid(rounding)


@pytest.mark.parametrize("kwargs, expected", [
    (dict(radius=-1.0), "radius"), (dict(radius=float("nan")), "radius"), (dict(seeds="x"), "seeds"),
    (dict(seeds=[]), "seed"), (dict(feature_angle=200.0), "feature angle"), (dict(reach=0.0), "reach"),
    (dict(reach=0.5), "reach factor must be at least 1"),
])
def test_make_rounding_rejects_bad_arguments(doc, box_feature, kwargs, expected):
    arguments = dict(base=box_feature, seeds=BOX_SEED, radius=BOX_RADIUS)
    arguments.update(kwargs)
    with pytest.raises(MeshRound.RoundingError, match=expected):
        MeshRound.make_rounding(**arguments)
    assert [o.Name for o in doc.Objects] == ["Box"]


def test_make_rounding_rejects_a_part_base(doc):
    part = doc.addObject("Part::Box", "PartBox")
    doc.recompute()
    with pytest.raises(MeshRound.RoundingError, match="not a mesh"):
        MeshRound.make_rounding(part, BOX_SEED, BOX_RADIUS)


def test_make_rounding_in_the_base_document_only(doc, box_feature):
    other = FreeCAD.newDocument("MeshRoundOther")
    try:
        assert MeshRound.make_rounding(box_feature, BOX_SEED, BOX_RADIUS, doc=doc).Document.Name == doc.Name
        with pytest.raises(MeshRound.RoundingError, match="document"):
            MeshRound.make_rounding(box_feature, BOX_SEED, BOX_RADIUS, doc=other)
        assert other.Objects == []
    finally:
        FreeCAD.closeDocument(other.Name)


def test_surfaces_export_to_step(rounding, tmp_path):
    path = str(tmp_path / "surfaces.step")
    rounding.Surfaces.Shape.exportStep(path)
    assert os.path.getsize(path) > 0
    assert len(Part.read(path).Faces) == 1


@pytest.mark.parametrize("name, value, changes_mesh", [
    ("Seeds", [BOX_SEED, BOX_OTHER_SEED], True),
    ("Radius", 6.0, True),
    ("Tolerance", 0.01, True),
    ("FeatureAngle", 60.0, False),  # the box's 90 deg edges stay sharp: same chain, same round
    ("Reach", 2.0, False),
    ("RadiusLaw", None, True),      # with RadiusLawRadii, below
    ("Base", None, True),           # the base feature's mesh changes, below
])
def test_any_property_change_recomputes(doc, box_feature, rounding, name, value, changes_mesh):
    before = rounding.Mesh.Topology
    if name == "RadiusLaw":
        rounding.RadiusLaw = [FreeCAD.Vector(0, 60, 40), FreeCAD.Vector(100, 60, 40)]
        rounding.RadiusLawRadii = [3.0, 6.0]
    elif name == "Base":  # another mesh feature: the box 10 mm higher (the seed still selects its edge)
        moved = doc.addObject("Mesh::Feature", "Moved")
        mesh = box_feature.Mesh.copy()
        mesh.translate(0, 0, 10)
        moved.Mesh = mesh
        rounding.Base = moved
    else:
        setattr(rounding, name, value)
    assert "Touched" in rounding.State
    assert doc.recompute() >= 1
    assert not is_invalid(rounding), rounding.getStatusString()
    assert (rounding.Mesh.Topology != before) == changes_mesh
    if name == "Base":
        assert rounding.Mesh.BoundBox.ZMax == pytest.approx(50.0, abs=1e-4)


def test_proxy_module_paths_stored_in_the_file(doc, rounding, tmp_path):
    """.FCStd files name the proxy's module and class: these must never change once released."""
    path = str(tmp_path / "paths.FCStd")
    doc.saveAs(path)
    with zipfile.ZipFile(path) as archive:
        document = archive.read("Document.xml").decode()
    proxies = set(re.findall(r'<Python [^>]*module="([^"]*)" class="([^"]*)"', document))
    assert proxies == {("MeshRound.objects.rounding", "Rounding")}
    assert MeshRound.objects.rounding.Rounding.__module__ == "MeshRound.objects.rounding"


def test_surfaces_export_to_step_as_the_gui_does(rounding, tmp_path):
    """File > Export of the RoundingSurfaces object (Import.export), read back as one B-spline face."""
    import Import
    path = str(tmp_path / "gui_export.step")
    Import.export([rounding.Surfaces], path)
    faces = Part.read(path).Faces
    assert len(faces) == 1 and isinstance(faces[0].Surface, Part.BSplineSurface)
    assert faces[0].Area == pytest.approx(rounding.Surfaces.Shape.Area, rel=1e-6)


def test_a_failed_feature_undoes_saves_and_reloads_cleanly(doc, box_feature, rounding, tmp_path):
    good = rounding.Mesh.Topology
    doc.openTransaction("Bad radius")
    rounding.Radius = 0.0
    doc.recompute()
    doc.commitTransaction()
    assert is_invalid(rounding) and rounding.Mesh.Topology == good
    doc.undo()
    doc.recompute()
    assert not is_invalid(rounding) and rounding.Radius.Value == BOX_RADIUS
    doc.redo()
    doc.recompute()
    assert is_invalid(rounding) and rounding.Radius.Value == 0.0
    path = str(tmp_path / "failed.FCStd")
    with saved_and_reopened(doc, path) as reopened:
        obj = reopened.getObject("Rounding")
        assert obj.Radius.Value == 0.0 and obj.Mesh.Topology == good  # the last good mesh was saved
        obj.Radius = 3.0
        reopened.recompute()
        assert not is_invalid(obj), obj.getStatusString()


def test_failure_is_reported_on_freecads_console(tmp_path):
    """In freecadcmd (as in the GUI's report view) a failed recompute prints the RoundingError's message."""
    home = tmp_path / "home"
    (home / "Mod").mkdir(parents=True)
    os.symlink(MOD_DIR, home / "Mod" / "MeshRound")
    script = tmp_path / "fail.py"
    script.write_text(
        "import FreeCAD, MeshPart, Part, MeshRound\n"
        "doc = FreeCAD.newDocument('Fail')\n"
        "box = doc.addObject('Mesh::Feature', 'Box')\n"
        "box.Mesh = MeshPart.meshFromShape(Shape=Part.makeBox(100, 60, 40), MaxLength=5.0)\n"
        "rounding = MeshRound.make_rounding(box, FreeCAD.Vector(37, 60, 40), 5.0)\n"
        "doc.recompute()\n"
        "rounding.Seeds = [FreeCAD.Vector(50, 30, 20)]\n"
        "doc.recompute()\n"
        f"open({str(tmp_path / 'state.txt')!r}, 'w').write(' '.join(rounding.State))\n")
    run = subprocess.run(["freecadcmd", str(script)], env=dict(os.environ, FREECAD_USER_HOME=str(home)),
                         capture_output=True, text=True, timeout=120)
    assert "Invalid" in (tmp_path / "state.txt").read_text()
    console = run.stdout + run.stderr
    assert "RoundingError" in console and "sharp edge" in console, console[-2000:]


# ----------------------------------------------------------------------------- the workbench's package layout
GUI_MODULES = {"InitGui.py", "MeshRoundGui.py", "MeshRound/commands.py"}
GUI_FOLDERS = ("MeshRound/viewproviders/", "MeshRound/taskpanels/")


def package_files():
    for folder, _, files in os.walk(MOD_DIR):
        for name in files:
            if name.endswith(".py"):
                path = os.path.join(folder, name)
                yield os.path.relpath(path, MOD_DIR), path


def test_freecadgui_is_imported_only_by_gui_modules_or_when_the_gui_is_up():
    """Objects, API, CLI: no FreeCADGui at import time; GUI code lives in its own modules, which are
    imported only when FreeCAD.GuiUp (or from code that runs only in the GUI)."""
    import ast
    for relative, path in package_files():
        with open(path) as stream:
            tree = ast.parse(stream.read())
        top_level = [node for node in tree.body if isinstance(node, (ast.Import, ast.ImportFrom))]
        names = [alias.name for node in top_level for alias in node.names]
        names += [node.module or "" for node in top_level if isinstance(node, ast.ImportFrom)]
        imports_gui = any(name.split(".")[0] in ("FreeCADGui", "PySide", "PySide2", "pivy") for name in names)
        if imports_gui:
            assert relative in GUI_MODULES or relative.startswith(GUI_FOLDERS), relative


def test_layout_follows_freecads_conventions():
    import xml.etree.ElementTree as ElementTree
    for name in ("Init.py", "InitGui.py", "package.xml", "Resources/icons/MeshRound.svg",
                 "Resources/icons/MeshRound_RoundEdges.svg", "MeshRound/objects/rounding.py",
                 "MeshRound/viewproviders/rounding.py", "MeshRound/taskpanels/round_edges.py",
                 "MeshRound/commands.py"):
        assert os.path.isfile(os.path.join(MOD_DIR, name)), name
    ns = {"p": "https://wiki.freecad.org/Package_Metadata"}
    package = ElementTree.parse(os.path.join(MOD_DIR, "package.xml")).getroot()
    workbench = package.find("p:content/p:workbench", ns)
    assert workbench.find("p:classname", ns).text == "MeshRoundWorkbench"
    assert os.path.isfile(os.path.join(MOD_DIR, workbench.find("p:icon", ns).text))
    assert package.find("p:version", ns).text == MeshRound.__version__
    with open(os.path.join(MOD_DIR, "InitGui.py")) as stream:
        assert "class MeshRoundWorkbench(" in stream.read()
    for _, path in package_files():
        with open(path) as stream:
            assert sum(1 for _ in stream) <= 600, path


def test_the_gui_registration_does_nothing_headless():
    """MeshRoundGui is imported by recorded macros: replayed in freecadcmd it must not fail."""
    import importlib
    module = importlib.import_module("MeshRoundGui")
    assert not hasattr(module, "COMMANDS")


def test_files_with_the_old_radius_law_property_name_load(doc, rounding, tmp_path):
    rounding.removeProperty("RadiusLaw")
    rounding.addProperty("App::PropertyVectorList", "RadiusLawPoints", "Rounding")
    rounding.RadiusLawPoints = [FreeCAD.Vector(0, 60, 40), FreeCAD.Vector(100, 60, 40)]
    rounding.RadiusLawRadii = [3.0, 6.0]
    path = str(tmp_path / "old_law.FCStd")
    with saved_and_reopened(doc, path) as reopened:
        obj = reopened.getObject("Rounding")
        assert "RadiusLawPoints" not in obj.PropertiesList
        assert [tuple(p) for p in obj.RadiusLaw] == [(0, 60, 40), (100, 60, 40)]
        obj.touch()
        reopened.recompute()
        assert not is_invalid(obj), obj.getStatusString()
