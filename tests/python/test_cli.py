"""The `meshround` command line, run as a user would: a subprocess of Debian's Python."""
import json
import os
import subprocess

import pytest

import Mesh

from conftest import MOD_DIR, box_mesh
from MeshRound import cli

WRAPPER = os.path.join(MOD_DIR, "meshround")
SEED = "37,60,40"


def meshround(*args, via_wrapper=False):
    command = [WRAPPER] if via_wrapper else ["/usr/bin/python3", "-m", "MeshRound.cli"]
    env = dict(os.environ, PYTHONPATH=MOD_DIR)
    return subprocess.run(command + [str(a) for a in args], capture_output=True, text=True, env=env,
                          timeout=120)


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cli")
    mesh = box_mesh()
    for ext in ("stl", "obj", "ply"):
        mesh.write(str(folder / f"box.{ext}"))
    (folder / "garbage.stl").write_text("this is not a mesh\n")
    (folder / "empty.stl").write_bytes(b"")
    for name in ("box.3mf", "box"):  # a real mesh, under a name that says no readable format
        (folder / name).write_bytes((folder / "box.stl").read_bytes())
    return folder


@pytest.mark.parametrize("ext", ["stl", "obj", "ply"])
def test_round_each_format(inputs, tmp_path, ext):
    out = tmp_path / f"rounded.{ext}"
    report = tmp_path / "report.json"
    run = meshround("round", inputs / f"box.{ext}", out, "--seed", SEED, "--radius", 5,
                    "--report", report)
    assert run.returncode == 0, run.stderr
    rounded = Mesh.Mesh(str(out))
    assert rounded.CountFacets != Mesh.Mesh(str(inputs / f"box.{ext}")).CountFacets
    assert rounded.isSolid()
    data = json.loads(report.read_text())
    assert data["chains"] == 1 and data["facets_added"] > 0
    assert "1 chain(s) rounded" in run.stdout
    assert sorted(os.listdir(tmp_path)) == sorted([out.name, report.name])  # no temporary files left


def test_variable_radius_and_options(inputs, tmp_path):
    out = tmp_path / "law.off"
    run = meshround("round", inputs / "box.stl", out, "--seed", SEED,
                    "--radius-at", "0,60,40:3", "--radius-at", "100,60,40:6",
                    "--tolerance", "0.05", "--feature-angle", "40", "--reach", "2.5")
    assert run.returncode == 0, run.stderr
    assert Mesh.Mesh(str(out)).CountFacets > 0


def test_wrapper_script_two_seeds(inputs, tmp_path):
    out = tmp_path / "wrapped.stl"
    run = meshround("round", inputs / "box.stl", out, "--seed", SEED, "--seed", "37,0,40", "--radius", 4,
                    via_wrapper=True)
    assert run.returncode == 0, run.stderr
    assert "2 chain(s) rounded" in run.stdout and out.exists()


@pytest.mark.parametrize("case, args, status, message", [
    ("missing input", ["missing.stl", "o.stl", "--seed", SEED, "--radius", 5], 1, "no such file"),
    ("garbage input", ["garbage.stl", "o.stl", "--seed", SEED, "--radius", 5], 1, "no facets"),
    ("empty input", ["empty.stl", "o.stl", "--seed", SEED, "--radius", 5], 1, "no facets"),
    ("unknown input format", ["box.xyz", "o.stl", "--seed", SEED, "--radius", 5], 2, "unknown mesh format"),
    ("input format read-only by name", ["box.3mf", "o.stl", "--seed", SEED, "--radius", 5], 2,
     "unknown mesh format"),
    ("input without extension", ["box", "o.stl", "--seed", SEED, "--radius", 5], 2, "no file extension"),
    ("unknown output format", ["box.stl", "o.foo", "--seed", SEED, "--radius", 5], 2, "unknown mesh format"),
    ("bad seed", ["box.stl", "o.stl", "--seed", "37,60", "--radius", 5], 2, "X,Y,Z"),
    ("seed not a number", ["box.stl", "o.stl", "--seed", "a,b,c", "--radius", 5], 2, "not a number"),
    ("infinite seed", ["box.stl", "o.stl", "--seed", "37,60,inf", "--radius", 5], 2, "finite"),
    ("no seed", ["box.stl", "o.stl", "--radius", 5], 2, "--seed"),
    ("radius not a number", ["box.stl", "o.stl", "--seed", SEED, "--radius", "5mm"], 2, "not a number"),
    ("negative radius", ["box.stl", "o.stl", "--seed", SEED, "--radius", -5], 2, "must be a positive number"),
    ("zero radius", ["box.stl", "o.stl", "--seed", SEED, "--radius", 0], 2, "must be a positive number"),
    ("nan radius", ["box.stl", "o.stl", "--seed", SEED, "--radius", "nan"], 2, "finite"),
    ("no radius", ["box.stl", "o.stl", "--seed", SEED], 2, "--radius"),
    ("both radii", ["box.stl", "o.stl", "--seed", SEED, "--radius", 5, "--radius-at", "0,60,40:3"], 2,
     "not allowed"),
    ("bad control point", ["box.stl", "o.stl", "--seed", SEED, "--radius-at", "0,60,40"], 2, "X,Y,Z:R"),
    ("bad control radius", ["box.stl", "o.stl", "--seed", SEED, "--radius-at", "0,60,40:-3"], 2, "radii must be positive"),
    ("reach below 1", ["box.stl", "o.stl", "--seed", SEED, "--radius", 5, "--reach", 0.5], 2,
     "the reach factor must be at least 1"),
    ("negative tolerance", ["box.stl", "o.stl", "--seed", SEED, "--radius", 5, "--tolerance", -1], 2, ">= 0"),
    ("bad angle", ["box.stl", "o.stl", "--seed", SEED, "--radius", 5, "--feature-angle", 200], 2, "180"),
    ("angle not a number", ["box.stl", "o.stl", "--seed", SEED, "--radius", 5, "--feature-angle", "x"], 2,
     "not a number"),
    ("no chain found", ["box.stl", "o.stl", "--seed", "50,30,20", "--radius", 5], 1, "no sharp edge"),
    ("no edge that sharp", ["box.stl", "o.stl", "--seed", SEED, "--radius", 5, "--feature-angle", 120], 1,
     "no sharp edge"),
    ("radius too large", ["box.stl", "o.stl", "--seed", SEED, "--radius", 50], 1, "too large"),
    ("control point off the chain", ["box.stl", "o.stl", "--seed", SEED, "--radius-at", "37,60,40:3",
                                     "--radius-at", "500,60,40:6"], 1, "from the chain"),
    ("output folder missing", ["box.stl", "nofolder/o.stl", "--seed", SEED, "--radius", 5], 1,
     "cannot write"),
])
def test_errors(inputs, tmp_path, case, args, status, message):
    args = [inputs / a if i == 0 else a for i, a in enumerate(args)]
    args[1] = tmp_path / args[1]
    report = tmp_path / "report.json"
    run = meshround("round", *args, "--report", report)
    assert run.returncode == status, (case, run.stdout, run.stderr)
    assert message in run.stderr, run.stderr
    assert not os.path.exists(args[1]) and not report.exists()
    if os.path.isdir(tmp_path):
        assert os.listdir(tmp_path) == []  # not even a temporary file


def test_report_folder_missing_leaves_no_output(inputs, tmp_path):
    out = tmp_path / "o.stl"
    run = meshround("round", inputs / "box.stl", out, "--seed", SEED, "--radius", 5,
                    "--report", tmp_path / "nofolder" / "r.json")
    assert run.returncode == 1 and "cannot write" in run.stderr
    assert os.listdir(tmp_path) == []  # neither the mesh nor a temporary file


def test_usage_without_command():
    run = meshround()
    assert run.returncode == 2 and "usage" in run.stderr


@pytest.mark.parametrize("ext", cli.READ_EXTENSIONS)
def test_every_listed_format_reads_back(tmp_path, box, ext):
    """What the CLI accepts by extension is what FreeCAD's Mesh module really reads and writes."""
    path = str(tmp_path / f"box.{ext}")
    box.write(path)
    assert Mesh.Mesh(path).CountFacets == box.CountFacets


@pytest.mark.parametrize("ext", cli.WRITE_EXTENSIONS[len(cli.READ_EXTENSIONS):])
def test_every_listed_write_only_format_writes(tmp_path, box, ext):
    path = tmp_path / f"box.{ext}"
    box.write(str(path))
    assert path.stat().st_size > 0


@pytest.mark.parametrize("ext", ["off", "bms", "smf", "nas", "ast"])
def test_round_other_input_formats(inputs, tmp_path, box, ext):
    source = tmp_path / f"box.{ext}"
    box.write(str(source))
    out = tmp_path / "rounded.x3d"  # a write-only format
    run = meshround("round", source, out, "--seed", SEED, "--radius", 5)
    assert run.returncode == 0, run.stderr
    assert out.stat().st_size > 0


def test_demo_script_missing_is_a_clear_error(monkeypatch, tmp_path, capsys):
    monkeypatch.setattr(cli, "DEMO_SCRIPTS", (str(tmp_path / "nowhere" / "srail_demo.py"),))
    assert cli.main(["demo", "--out", str(tmp_path / "demo")]) == 1
    assert "srail_demo.py is missing" in capsys.readouterr().err
    assert not (tmp_path / "demo").exists()


def test_demo_finds_the_installed_copy(monkeypatch, tmp_path):
    """Installed (tools/setup.sh), the demo's files sit in the workbench folder, not in a source tree."""
    installed = tmp_path / "resources" / "srail_demo.py"
    installed.parent.mkdir()
    installed.write_text("")
    monkeypatch.setattr(cli, "DEMO_SCRIPTS", (str(tmp_path / "no_tree" / "srail_demo.py"), str(installed)))
    assert cli.demo_script() == str(installed)


def test_demo_runs(tmp_path):
    """`meshround demo`: both shoulders rounded twice, every output written (about 15 s: FreeCAD renders)."""
    out = tmp_path / "demo"
    run = meshround("demo", "--out", out)
    assert run.returncode == 0, run.stderr
    names = ["srail_die.stl", "srail_rounded_constant.stl", "srail_rounded_constant.obj",
             "srail_rounded_variable.stl", "srail_rounded_variable.obj", "srail_rounding.FCStd",
             "srail_report.json", "srail_before_after.png"]
    assert sorted(os.listdir(out)) == sorted(names)
    report = json.loads((out / "srail_report.json").read_text())
    assert report["constant"]["report"]["chains"] == 2
    assert report["variable"]["report"]["chains"] == 2
    assert len(report["constant"]["report"]["per_chain"]) == len(report["variable"]["report"]["per_chain"]) == 2
    rounded = Mesh.Mesh(str(out / "srail_rounded_constant.stl"))
    assert rounded.CountFacets > report["facets_in"] and rounded.isSolid()
    assert (out / "srail_before_after.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
