"""The `meshround` command line, run as a user would: a subprocess of Debian's Python."""
import json
import os
import subprocess

import pytest

import Mesh

from conftest import MOD_DIR, box_mesh

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
    ("unknown input format", ["box.xyz", "o.stl", "--seed", SEED, "--radius", 5], 2, "unknown mesh format"),
    ("unknown output format", ["box.stl", "o.foo", "--seed", SEED, "--radius", 5], 2, "unknown mesh format"),
    ("bad seed", ["box.stl", "o.stl", "--seed", "37,60", "--radius", 5], 2, "X,Y,Z"),
    ("seed not a number", ["box.stl", "o.stl", "--seed", "a,b,c", "--radius", 5], 2, "not a number"),
    ("no seed", ["box.stl", "o.stl", "--radius", 5], 2, "--seed"),
    ("negative radius", ["box.stl", "o.stl", "--seed", SEED, "--radius", -5], 2, "must be > 0"),
    ("nan radius", ["box.stl", "o.stl", "--seed", SEED, "--radius", "nan"], 2, "finite"),
    ("no radius", ["box.stl", "o.stl", "--seed", SEED], 2, "--radius"),
    ("both radii", ["box.stl", "o.stl", "--seed", SEED, "--radius", 5, "--radius-at", "0,60,40:3"], 2,
     "not allowed"),
    ("bad control point", ["box.stl", "o.stl", "--seed", SEED, "--radius-at", "0,60,40"], 2, "X,Y,Z:R"),
    ("bad angle", ["box.stl", "o.stl", "--seed", SEED, "--radius", 5, "--feature-angle", 200], 2, "180"),
    ("no chain found", ["box.stl", "o.stl", "--seed", "50,30,20", "--radius", 5], 1, "sharp edge"),
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


def test_demo_reports_a_missing_script_clearly_or_runs(tmp_path):
    from MeshRound import cli
    run = meshround("demo", "--out", tmp_path / "demo")
    if os.path.isfile(cli.DEMO_SCRIPT):
        assert run.returncode == 0, run.stderr
    else:
        assert run.returncode == 1 and "srail_demo.py" in run.stderr
