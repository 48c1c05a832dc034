"""Demo: round both die shoulders of the S-rail die mesh, once with a constant and once with a variable radius.

    /usr/bin/python3 resources/srail_demo.py [out_dir]        (default: out)

Writes under out_dir:
  srail_die.stl                         the sharp die mesh (the input, a CAE tool mesh)
  srail_rounded_constant.{stl,obj}      both shoulders rounded, r = CONSTANT_RADIUS
  srail_rounded_variable.{stl,obj}      both shoulders rounded, r varying along each shoulder (LAW)
  srail_rounding.FCStd                  the die mesh and two parametric Rounding features of it
  srail_report.json                     the engine's report of each rounding (per_chain: one per shoulder)
  srail_before_after.png                rendered by FreeCAD's GUI (resources/srail_render.py, under xvfb)
"""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
for _p in ("/usr/lib/freecad-python3/lib", os.path.join(HERE, "srail")):
    if _p not in sys.path:
        sys.path.append(_p)
import FreeCAD  # noqa: E402  (it puts the user's Mod folders first on sys.path ...)
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(HERE, "..", "Mod", "MeshRound"))  # ... so this tree's MeshRound goes before

import MeshRound  # noqa: E402
import srail_die  # noqa: E402

ELEMENT_SIZE = 5.0      # mm: the tool mesh's element size
CONSTANT_RADIUS = 5.0   # mm: the benchmark's die radius
LAW = [(0.0, 3.0), (0.5, 8.0), (1.0, 3.0)]  # (fraction along each shoulder, radius mm): widest in the S
RENDER_SCRIPT = os.path.join(HERE, "srail_render.py")
OUTPUTS = ("srail_die.stl", "srail_rounded_constant.stl", "srail_rounded_constant.obj",
           "srail_rounded_variable.stl", "srail_rounded_variable.obj", "srail_rounding.FCStd",
           "srail_report.json", "srail_before_after.png")


def shoulder_polylines(step=0.5):
    """Each die shoulder as an ordered (n, 3) polyline, from the CAD model (x increasing)."""
    solid = srail_die.die_solid()
    edges = srail_die.shoulder_edges(solid)
    out = []
    for seed in srail_die.shoulder_seeds():
        wire = _chain_through(edges, seed)
        pts = np.array([tuple(p) for p in wire.discretize(Distance=step)])
        out.append(pts if pts[0, 0] < pts[-1, 0] else pts[::-1])
    return out


def _chain_through(edges, seed):
    """The tangent chain of `edges` that passes through `seed` (edges sharing vertices with it)."""
    import Part
    chains = [Part.Wire(c) for c in Part.sortEdges(edges)]
    return min(chains, key=lambda w: w.distToShape(Part.Vertex(seed))[0])


def radius_laws(law=LAW, inset=1.0):
    """Per shoulder, [(FreeCAD.Vector, r)]: the law's control points placed along it by arc length.
    (In one call on both shoulders, each control point belongs to the shoulder nearest to it.)"""
    laws = []
    for line in shoulder_polylines():
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(line, axis=0), axis=1))])
        at = [np.clip(fraction * s[-1], inset, s[-1] - inset) for fraction, _ in law]
        laws.append([(FreeCAD.Vector(*(np.interp(a, s, line[:, k]) for k in range(3))), r)
                     for a, (_, r) in zip(at, law)])
    return laws


class DemoError(RuntimeError):
    """The engine refused a rounding of the demo; the message names the shoulder and the radius."""


SHOULDERS = ("shoulder 1 (y = 95 side)", "shoulder 2 (y = 45 side)")


def _describe(radius):
    if isinstance(radius, (int, float)):
        return f"constant r = {radius:g} mm"
    return "variable r = " + " -> ".join(f"{r:g}" for _, r in radius) + " mm"


def round_checked(mesh, seeds, radius, alone):
    """MeshRound.round_edges on both shoulders; a RoundingError becomes a DemoError naming the shoulder
    and its radius: each shoulder is then tried alone (with alone[i], its own radius) to say which one
    the engine refuses."""
    try:
        return MeshRound.round_edges(mesh, seeds, radius)
    except MeshRound.RoundingError as exc:
        failing = []
        for name, seed, own in zip(SHOULDERS, seeds, alone):
            try:
                MeshRound.round_edges(mesh, [seed], own)
            except MeshRound.RoundingError as error:
                failing.append(f"{name}, {_describe(own)}: {error}")
        if not failing:
            failing = [f"both shoulders in one call (each alone works), {_describe(alone[0])}: {exc}"]
        raise DemoError("the engine refused the demo rounding:\n  " + "\n  ".join(failing)) from exc


def write_meshes(out_dir, name, mesh):
    for ext in ("stl", "obj"):
        mesh.write(os.path.join(out_dir, f"{name}.{ext}"))


def write_document(out_dir, mesh, seeds, law):
    """An FCStd with the die mesh and two parametric Rounding features of it, recomputed:
    RoundingConstant and RoundingVariable, each of both shoulders."""
    path = os.path.join(out_dir, "srail_rounding.FCStd")
    doc = FreeCAD.newDocument("SRailDie")
    try:
        base = doc.addObject("Mesh::Feature", "DieMesh")
        base.Mesh = mesh
        MeshRound.make_rounding(base, seeds, CONSTANT_RADIUS, name="RoundingConstant", doc=doc)
        MeshRound.make_rounding(base, seeds, law, name="RoundingVariable", doc=doc)
        doc.recompute()
        broken = [o.Name for o in doc.Objects if "Invalid" in o.State or "Error" in o.State]
        if broken:
            raise DemoError(f"the document's recompute failed for {', '.join(broken)} (FreeCAD's report "
                            "view / console says why)")
        for old in (path, path + "1"):  # saving over a file leaves FreeCAD's backup (.FCStd1) behind
            if os.path.exists(old):
                os.remove(old)
        doc.saveAs(path)
    finally:
        FreeCAD.closeDocument(doc.Name)
    return path


def render(out_dir):
    """The before/after PNG, drawn by FreeCAD's GUI under a virtual X server.  With SRAIL_SMALL=path in
    the environment the macro also writes a half-size copy there (resources/images/ holds one)."""
    png = os.path.join(out_dir, "srail_before_after.png")
    if os.path.exists(png):
        os.remove(png)  # a PNG left from an earlier run must not pass for this one
    env = dict(os.environ, SRAIL_OUT=os.path.abspath(out_dir), QTWEBENGINE_CHROMIUM_FLAGS="--no-sandbox")
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 1600x1200x24", "freecad", RENDER_SCRIPT]
    try:
        run = subprocess.run(cmd, env=env, timeout=300, check=False, capture_output=True, text=True)
        log = run.stdout + run.stderr
    except (OSError, subprocess.TimeoutExpired) as exc:
        log = str(exc)
    if not os.path.exists(png):
        tail = "\n    ".join(log.strip().splitlines()[-8:])
        raise DemoError(f"FreeCAD's render macro wrote no PNG (are freecad and xvfb-run installed?):\n    {tail}")
    return png


def main(out_dir="out"):
    os.makedirs(out_dir, exist_ok=True)
    mesh = srail_die.die_mesh(ELEMENT_SIZE)
    mesh.write(os.path.join(out_dir, "srail_die.stl"))
    seeds = srail_die.shoulder_seeds()
    laws = radius_laws()
    law = laws[0] + laws[1]  # one call: each control point goes to the shoulder nearest to it
    constant = round_checked(mesh, seeds, CONSTANT_RADIUS, [CONSTANT_RADIUS] * 2)
    variable = round_checked(mesh, seeds, law, laws)
    write_meshes(out_dir, "srail_rounded_constant", constant.mesh)
    write_meshes(out_dir, "srail_rounded_variable", variable.mesh)
    report = dict(element_size=ELEMENT_SIZE, facets_in=mesh.CountFacets,
                  constant=dict(radius=CONSTANT_RADIUS, report=constant.report),
                  variable=dict(law=[[dict(point=list(p), radius=r) for p, r in shoulder] for shoulder in laws],
                                report=variable.report))
    with open(os.path.join(out_dir, "srail_report.json"), "w") as f:
        json.dump(report, f, indent=1)
    write_document(out_dir, mesh, seeds, law)
    render(out_dir)
    for name, r in (("constant r = 5 mm", constant.report), ("variable r = 3 -> 8 -> 3 mm", variable.report)):
        print(f"{name}: {r.get('chains')} chain(s), {r.get('facets_in')} -> {r.get('facets_out')} facets, "
              f"max deviation {r.get('max_deviation'):.4f} mm, {r.get('seconds', 0):.2f} s")
    print(f"wrote {os.path.abspath(out_dir)}:")
    for name in OUTPUTS:
        path = os.path.join(out_dir, name)
        print(f"  {name:30s} {os.path.getsize(path) / 1e3:8.0f} kB")
    return report


if __name__ == "__main__":
    try:
        main(sys.argv[1] if len(sys.argv) > 1 else "out")
    except DemoError as error:
        print(f"srail_demo: error: {error}", file=sys.stderr)
        sys.exit(1)
