"""CAD cases for the accuracy tests: a sharp Part solid, the chain of its edges to round, and the exact answer.

The exact answer is OCCT's own BRepFilletAPI_MakeFillet on the CAD solid (Part.Shape.makeFillet, or the
Part::Fillet feature for per-edge radii) -- code nobody on this project wrote.  The inputs given to
MeshRound are meshes of the sharp solid (`Case.mesh(variant)`).

Variable radius.  OCCT's "linear" law r1 -> r2 (Add(R1, R2, E)) is not linear: the radii become stations
of a clamped cubic spline along the spine (zero end slopes, the spine extended past its ends).  So a
variable case does not guess the law: it measures the radius the reference really has, on sections
normal to the chain every ~r_max/2 (`measured_law`), and hands those as control points to MeshRound.
Part exposes per-edge (r1, r2) only, no (parameter, radius) pairs; a 3-point law along a multi-edge chain
is built from per-edge stations (the junction radii interpolated by arc length), which OCCT turns into one
smooth law along the whole chain.

Mesh precision.  Mesh.Mesh stores float32 points, so a mesh handed to MeshRound is already what an STL
round trip would give (the test checks this); no STL round trip is made.
"""
import fcntl
import functools
import hashlib
import math
import os
import sys

for _p in ("/usr/lib/freecad-python3/lib", "/usr/lib/freecad/lib"):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402
import Mesh  # noqa: E402,F401  (for the tests)
import MeshPart  # noqa: E402
import Part  # noqa: E402
import numpy as np  # noqa: E402

V = FreeCAD.Vector
TOL = 1e-7  # mm: "on" for CAD coordinates built here

_MESHES = {}  # (the solid's digest, mesher options) -> its mesh, for mesh_of
# What the tests make slowly and deterministically -- meshes of the CAD solids (a fine mesh of the pocket block
# takes the mesher over a minute) and the yardstick's exact samples of OCCT's fillets -- kept on disk between
# the two test workers and between runs: the suite's files share many solids.
TEST_STORE = os.environ.get("MESHROUND_TEST_STORE") or os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "test-store")


def shape_digest(shape):
    """A Part shape known by its vertices, faces, edges, volume and area (to 1e-6 mm)."""
    geometry = sorted((round(v.X, 6), round(v.Y, 6), round(v.Z, 6)) for v in shape.Vertexes)
    return geometry + [(len(shape.Faces), len(shape.Edges), round(shape.Volume, 6), round(shape.Area, 6))]


def kept_on_disk(what, make):
    """The arrays `make()` returns (a dict name -> numpy array), made once for `what` (any repr-able key, with
    the FreeCAD version added): kept in TEST_STORE, where the other worker and later runs find them (a lock
    per key: two workers asking at once make them once)."""
    key = hashlib.sha1(repr((what, FreeCAD.Version()[:3])).encode()).hexdigest()
    os.makedirs(TEST_STORE, exist_ok=True)
    path = os.path.join(TEST_STORE, key + ".npz")
    with open(path + ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not os.path.exists(path):
            np.savez(path + ".tmp.npz", **make())
            os.replace(path + ".tmp.npz", path)
        with np.load(path) as stored:
            return {name: stored[name] for name in stored.files}


def mesh_of(shape, **options):
    """MeshPart.meshFromShape(Shape=shape, **options), each solid meshed once (kept_on_disk).  Every mesh is
    rebuilt from its points and facets in the mesher's order, so a mesh read back is the one made.  A copy is
    returned (a test may change its mesh)."""
    what = ("mesh", shape_digest(shape), sorted(options.items()))
    if repr(what) not in _MESHES:
        def make():
            points, facets = MeshPart.meshFromShape(Shape=shape, **options).Topology
            return dict(points=np.array([[p.x, p.y, p.z] for p in points]).reshape(-1, 3),
                        facets=np.array(facets, dtype=np.int64).reshape(-1, 3))
        stored = kept_on_disk(what, make)
        mesh = Mesh.Mesh()
        mesh.addFacets(([V(*p) for p in stored["points"].tolist()], [tuple(f) for f in stored["facets"].tolist()]))
        _MESHES[repr(what)] = mesh
    return _MESHES[repr(what)].copy()


# Mesh variants of the sharp solid; MaxLength is relative to the case's largest radius.
MESH_VARIANTS = {
    "fine": dict(MaxLength=0.4),    # several elements across the round
    "coarse": dict(MaxLength=2.5),  # elements larger than the round itself
    # a CAD export tessellation: few long thin triangles, chordal error r/250 on curved faces
    "cad": dict(LinearDeflection=0.004, AngularDeflection=0.2, Relative=False),
}


# ------------------------------------------------------------------------------------------- the solids
def edge_middle(e):
    """The point halfway along an edge's parameter range (where a user picks it)."""
    return e.valueAt(0.5 * (e.FirstParameter + e.LastParameter))


def edges_where(shape, test, samples=5):
    """Edges of `shape` all of whose sample points (ends included) satisfy test(point)."""
    def sample(e):
        u0, u1 = e.FirstParameter, e.LastParameter
        return [e.valueAt(u0 + (u1 - u0) * k / (samples - 1)) for k in range(samples)]
    return [e for e in shape.Edges if all(test(p) for p in sample(e))]


def extruded_profile(yz_points, length):
    """A prism: the closed polygon yz_points (in the x = 0 plane) extruded along +x."""
    pts = [V(0, y, z) for y, z in yz_points]
    return Part.Face(Part.makePolygon(pts + pts[:1])).extrude(V(length, 0, 0))


def box():
    """Convex 90 degree edge: the top back edge of a 60 x 40 x 30 box."""
    s = Part.makeBox(60, 40, 30)
    return s, edges_where(s, lambda p: abs(p.y - 40) < TOL and abs(p.z - 30) < TOL)


def lchannel():
    """Concave 90 degree edge: the inner edge of an L-section (flange 40 x 8, web 35 x 8), 60 long."""
    s = extruded_profile([(0, 0), (40, 0), (40, 8), (8, 8), (8, 35), (0, 35)], 60)
    return s, edges_where(s, lambda p: abs(p.y - 8) < TOL and abs(p.z - 8) < TOL)


def tilted(builder, z_deg=25.0, x_deg=17.5):
    """The solid of `builder`, turned about z then x: no face on an axis plane, so its float32 mesh
    vertices lie off their faces' planes, as on a real part wherever it sits."""
    def build():
        solid, chain = builder()
        turn = FreeCAD.Matrix()
        turn.rotateZ(math.radians(z_deg))
        turn.rotateX(math.radians(x_deg))
        turned = solid.transformGeometry(turn)
        mids = [turn.multiply(edge_middle(e)) for e in chain]
        return turned, [e for e in turned.Edges if any(e.distToShape(Part.Vertex(m))[0] < TOL for m in mids)]
    return build


def acute_ridge():
    """Convex 45 degree edge: a flat top meeting a wall undercut beneath it.  The contacts lie 2.4 r from
    the edge, so the round fills most of the reach."""
    s = extruded_profile([(0, 0), (60, 0), (60, 8), (3, 8), (25, 30), (0, 30)], 60)
    return s, edges_where(s, lambda p: abs(p.y - 25) < TOL and abs(p.z - 30) < TOL)


def vee_groove():
    """Concave 60 degree edge: a floor met by a wall that leans over it (a V-groove's side).  The wall is
    off the axes, so its float32 mesh vertices lie off the exact plane, as in any exported mesh."""
    s = extruded_profile([(0, 0), (70, 0), (70, 10), (30, 10), (30 + 30 / math.tan(math.radians(60)), 40), (0, 40)], 60)
    return s, edges_where(s, lambda p: abs(p.y - 30) < TOL and abs(p.z - 10) < TOL)


DRAFT_DEG = 10.0


def draft_shoulder():
    """A die shoulder: binder flat z = 30 meeting a wall drafted 10 degrees (the solid's angle is 100
    degrees), the wall running down to a floor at z = 8."""
    foot = 25 + 22 * math.tan(math.radians(DRAFT_DEG))
    s = extruded_profile([(0, 0), (50, 0), (50, 8), (foot, 8), (25, 30), (0, 30)], 60)
    return s, edges_where(s, lambda p: abs(p.y - 25) < TOL and abs(p.z - 30) < TOL)


POCKET_R = 25.0


def pocket_rim():
    """A closed loop: the top rim of a 25 mm radius, 10 deep circular pocket in a 62 x 62 x 20 block."""
    block = Part.makeBox(62, 62, 20)
    s = block.cut(Part.makeCylinder(POCKET_R, 11, V(31, 31, 10))).removeSplitter()
    return s, edges_where(s, lambda p: abs(p.z - 20) < TOL and abs(math.hypot(p.x - 31, p.y - 31) - POCKET_R) < 1e-6)


def pocket_block(draft_deg=0.0):
    """A 80 x 60 x 30 block with a 40 x 30, 12 deep rectangular pocket, its walls drafted by draft_deg."""
    block = Part.makeBox(80, 60, 30)
    top = Part.makePolygon([V(20, 15, 30.01), V(60, 15, 30.01), V(60, 45, 30.01), V(20, 45, 30.01), V(20, 15, 30.01)])
    if draft_deg == 0:
        tool = Part.Face(top).extrude(V(0, 0, -12.01))
    else:
        d = 12.01 * math.tan(math.radians(draft_deg))
        bottom = Part.makePolygon([V(20 + d, 15 + d, 18), V(60 - d, 15 + d, 18), V(60 - d, 45 - d, 18), V(20 + d, 45 - d, 18),
                                   V(20 + d, 15 + d, 18)])
        tool = Part.makeLoft([bottom, top], True)
    return block.cut(tool).removeSplitter()


def pocket_edge(draft_deg=0.0):
    """One rim edge of a rectangular pocket: at both ends it runs into the next wall (a concave neighbour),
    while the top face goes on around the corner."""
    def build():
        s = pocket_block(draft_deg)
        return s, edges_where(s, lambda p: abs(p.y - 15) < 0.01 and abs(p.z - 30) < TOL and 19 < p.x < 61)
    return build


def pocket_rim_square(draft_deg=0.0):
    """The whole rim of a rectangular pocket: four edges, each meeting the next at a corner where the
    pocket's wall edge stays sharp (OCCT mitres the rounds there)."""
    def build():
        s = pocket_block(draft_deg)
        return s, edges_where(s, lambda p: abs(p.z - 30) < TOL and 19 < p.x < 61 and 14 < p.y < 46)
    return build


def pocket_rim_walls(draft_deg=0.0):
    """The rim of a rectangular pocket and the pocket's four wall corners: at each rim corner two convex
    rounds meet a concave one; OCCT rounds the wall corner and rolls the rim on around its top (a torus
    where the walls are square)."""
    def build():
        s = pocket_block(draft_deg)
        inside = edges_where(s, lambda p: 19 < p.x < 61 and 14 < p.y < 46 and p.z > 17.9)
        return s, [e for e in inside if max(v.Point.z for v in e.Vertexes) > 18.5]
    return build


def pocket_rim_round_walls(wall_radius=6.0):
    """The rim of a rectangular pocket whose four wall corners are rounded (OCCT, wall_radius): one smooth
    chain all around, straight along the walls and arcs around their corners (a rim round on it rolls on
    around each wall corner as a torus)."""
    def build():
        s = pocket_block()
        vertical = [e for e in edges_where(s, lambda p: 19 < p.x < 61 and 14 < p.y < 46 and 17.9 < p.z < 30.1)
                    if abs(e.Vertexes[0].Point.z - e.Vertexes[1].Point.z) > 5]
        s = s.makeFillet(wall_radius, vertical).removeSplitter()
        return s, edges_where(s, lambda p: abs(p.z - 30) < TOL and 19 < p.x < 61 and 14 < p.y < 46)
    return build


def pocket_all(draft_deg=0.0):
    """Every edge of a rectangular pocket: the rim, the wall corners and the floor (at the floor's corners
    three concave rounds meet in a sphere)."""
    def build():
        s = pocket_block(draft_deg)
        return s, edges_where(s, lambda p: 19 < p.x < 61 and 14 < p.y < 46 and p.z > 17.9)
    return build


def box_oblique_end():
    """A box edge ending at an end face at 45 degrees to it (a convex end): the top back edge of a 60 x 40
    x 30 box whose right end is cut off along x + y = 100."""
    s = Part.makeBox(60, 40, 30).cut(Part.makeBox(60, 60, 40, V(60, -10, -5), V(0, 0, 1))
                                     .rotated(V(60, 40, 0), V(0, 0, 1), 45)).removeSplitter()
    return s, edges_where(s, lambda p: abs(p.y - 40) < TOL and abs(p.z - 30) < TOL)


def open_sheet(crop_deg=None):
    """A shoulder running off the mesh's edge: the top and back faces of a 60 x 40 x 30 box only (an open
    shell, as a die's working surface is), their shared edge rounded. With `crop_deg` = (top, back), the
    sheet's end at x = 60 is cut by a plane through the chain's end slanted across it: in plan, the top face's
    end edge turns back by `top` degrees from square (an acute corner of that face); in elevation, the back
    face's end edge leans out by `back` degrees (an obtuse corner: that face runs on past the end). OCCT ends
    the round on that plane (an ellipse)."""
    def build():
        box = Part.makeBox(60 if crop_deg is None else 100, 40, 30)
        shell = Part.makeShell([f for f in box.Faces if abs(f.CenterOfMass.z - 30) < TOL or abs(f.CenterOfMass.y - 40) < TOL])
        if crop_deg is not None:
            shell = cropped(shell, V(60, 40, 30), crop_deg)
        return shell, edges_where(shell, lambda p: abs(p.y - 40) < TOL and abs(p.z - 30) < TOL)
    return build


def cropped(shell, corner, crop_deg):
    """The part of `shell` (a top face, normal +z, and a back face, normal +y, meeting along x at `corner`)
    before the plane through `corner` slanted by crop_deg = (top, back) degrees from square to x: the top
    face's cut edge turns back in plan (acute), the back face's leans out in elevation (obtuse)."""
    top, back = (math.tan(math.radians(a)) for a in crop_deg)
    beyond = Part.makeBox(4000, 4000, 4000, V(-2000, -2000, 0))
    beyond.Placement = FreeCAD.Placement(corner, FreeCAD.Rotation(V(0, 0, 1), V(1, -top, back).normalize()))
    return shell.cut(beyond).Shells[0]


def open_prism(builder):
    """A prism case with its two end faces (x = its least and largest x) taken off: a tube open at both ends,
    the chain running off the mesh's edge at each (a concave one for the L-section's inner edge)."""
    def build():
        solid, chain = builder()
        box = solid.BoundBox
        shell = Part.makeShell([f for f in solid.Faces if not (abs(f.BoundBox.XMax - f.BoundBox.XMin) < TOL and
                                                                 f.BoundBox.XMin in (box.XMin, box.XMax))])
        at = [(e.Vertexes[0].Point, e.Vertexes[-1].Point) for e in chain]
        return shell, [e for e in shell.Edges if any((e.Vertexes[0].Point - a).Length < TOL and (e.Vertexes[-1].Point - b).Length < TOL
                                                    for a, b in at)]
    return build


def box_corner():
    """A box corner with its three edges rounded: equal radii meet in a patch of the rolling ball (the
    three edges at (100, 60, 40) of a 100 x 60 x 40 box, each running its whole length)."""
    s = Part.makeBox(100, 60, 40)
    at = V(100, 60, 40)
    return s, [e for e in s.Edges if any((v.Point - at).Length < TOL for v in e.Vertexes)]


def box_top_corner():
    """Two convex rounds meeting at a box corner whose third (vertical) edge stays sharp: the top edges at
    (100, 60, 40) of a 100 x 60 x 40 box (OCCT mitres the rounds: they meet along one curve in the plane
    bisecting the two edges)."""
    s = Part.makeBox(100, 60, 40)
    at = V(100, 60, 40)
    return s, [e for e in s.Edges if any((v.Point - at).Length < TOL for v in e.Vertexes) and abs(e.Vertexes[0].Point.z - e.Vertexes[1].Point.z) < TOL]


def l_bracket(side):
    """A shoulder running into a wall at 45 degrees in plan: an 80 x 60 x 10 flange with a 12 thick, 40
    high wall standing on it at 45 degrees to the flange's front top edge, which the wall cuts in two. The
    chain is the front top edge on one side of the wall: side 0 meets the wall face at 45 degrees (the
    wall leans over the round's end), side 1 at 135 degrees."""
    def build():
        wall = Part.makeBox(12, 120, 40, V(0, -60, 0))
        wall.rotate(V(0, 0, 0), V(0, 0, 1), -45)
        wall.translate(V(50, 0, 0))
        s = Part.makeBox(80, 60, 10).fuse(wall.common(Part.makeBox(80, 60, 40))).removeSplitter()
        front = sorted(edges_where(s, lambda p: abs(p.y) < TOL and abs(p.z - 10) < TOL), key=lambda e: e.BoundBox.XMin)
        return s, [front[side]]
    return build


def pyramid():
    """Every edge of a square pyramid (base 60 x 60, height 30): four rounds meet at the apex, three at
    each base corner. OCCT's fillet makes no valid solid of it (it does not blend four rounds at a
    vertex); the reference is the solid offset inwards by r and back out with round joins, which is the
    rolling ball's answer when every edge of a convex solid is rounded with one radius."""
    pts = [V(0, 0, 0), V(60, 0, 0), V(60, 60, 0), V(0, 60, 0)]
    apex = V(30, 30, 30)
    faces = [Part.Face(Part.makePolygon(pts + pts[:1]))]
    faces += [Part.Face(Part.makePolygon([pts[i], pts[(i + 1) % 4], apex, pts[i]])) for i in range(4)]
    s = Part.Solid(Part.Shell(faces))
    return s, list(s.Edges)


pyramid.offset_reference = True


def s_outline():
    """Plan view S: line, convex arc R20, concave arc R30, line -- tangent throughout, from (0,60) to (120,10)."""
    return Part.Wire([
        Part.LineSegment(V(0, 60, 0), V(30, 60, 0)).toShape(),
        Part.ArcOfCircle(Part.Circle(V(30, 40, 0), V(0, 0, 1), 20), 0, math.pi / 2).toShape(),
        Part.ArcOfCircle(Part.Circle(V(80, 40, 0), V(0, 0, 1), 30), math.pi, 1.5 * math.pi).toShape(),
        Part.LineSegment(V(80, 10, 0), V(120, 10, 0)).toShape(),
    ])


def s_plate():
    """An S-shaped chain: a 20 thick plate whose back outline is the S; the chain is its top edge along the S."""
    s_wire = s_outline()
    rest = Part.makePolygon([V(120, 10, 0), V(120, -20, 0), V(0, -20, 0), V(0, 60, 0)])
    outline = Part.Wire(Part.__sortEdges__(s_wire.Edges + rest.Edges))
    s = Part.Face(outline).extrude(V(0, 0, 20))
    on_s = lambda p: abs(p.z - 20) < TOL and s_wire.distToShape(Part.Vertex(V(p.x, p.y, 0)))[0] < 1e-6  # noqa: E731
    return s, edges_where(s, on_s)


# ------------------------------------------------------------------------------------------ chain geometry
def ordered_chain(edges):
    """The chain's edges in order, each with a flag: True when it runs backwards (end -> start) in the chain."""
    left = list(edges)
    out = [(left.pop(0), False)]
    while left:
        tail = out[-1][0].valueAt(out[-1][0].LastParameter if not out[-1][1] else out[-1][0].FirstParameter)
        for e in left:
            if (e.valueAt(e.FirstParameter) - tail).Length < 1e-6:
                out.append((e, False))
            elif (e.valueAt(e.LastParameter) - tail).Length < 1e-6:
                out.append((e, True))
            else:
                continue
            left.remove(e)
            break
        else:
            raise ValueError("the chain's edges are not connected")
    return out


def chain_points(edges, step):
    """(n, 3) points along the chain, in order, at most `step` apart (ends included)."""
    pts = []
    for e, backwards in ordered_chain(edges):
        n = max(2, int(math.ceil(e.Length / step)) + 1)
        u = np.linspace(e.FirstParameter, e.LastParameter, n)
        seg = [tuple(e.valueAt(x)) for x in (u[::-1] if backwards else u)]
        pts += seg if not pts else seg[1:]
    return np.array(pts)


def arc_length(points):
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))])


def is_closed(edges):
    p = chain_points(edges, 1e9)
    return bool(np.linalg.norm(p[0] - p[-1]) < 1e-6)


# ---------------------------------------------------------------------------------------- fillet faces
def fillet_faces(reference, sharp):
    """Faces of the filleted solid that are not on the sharp solid's skin: the rounds themselves.
    A face is tested at the centroid of its largest tessellation triangle, projected onto the face."""
    out, skin = [], Part.Compound(sharp.Faces)  # faces, not the solid: a point inside is not "on"
    for f in reference.Faces:
        pts, tris = f.tessellate(0.05)
        P = np.array([tuple(p) for p in pts])
        T = np.array(tris)
        area = np.linalg.norm(np.cross(P[T[:, 1]] - P[T[:, 0]], P[T[:, 2]] - P[T[:, 0]]), axis=1)
        c = V(*P[T[area.argmax()]].mean(axis=0))
        p = f.valueAt(*f.Surface.parameter(c))
        if skin.distToShape(Part.Vertex(p))[0] > 1e-5:
            out.append(f)
    if not out:
        raise RuntimeError("the reference fillet made no face: the case is broken")
    return out


def section_radius(rounds, point, tangent):
    """Radius of the round's cross-section in the plane through `point` normal to `tangent` (circle
    through three points of the section arc)."""
    sec = rounds.section(Part.Plane(point, tangent).toShape())
    arc = max(sec.Edges, key=lambda e: e.Length)
    u0, u1 = arc.FirstParameter, arc.LastParameter
    a, b, c = (np.array(tuple(arc.valueAt(u0 + (u1 - u0) * k))) for k in (0.1, 0.5, 0.9))
    return float(np.linalg.norm(b - a) * np.linalg.norm(c - a) * np.linalg.norm(c - b)
                 / (2 * np.linalg.norm(np.cross(b - a, c - a))))


# ------------------------------------------------------------------------------------------------ cases
class Case:
    """One rounding task.  `law`: None for a constant radius, else [(fraction of chain length, r)] stations
    handed to OCCT; `radius` is what MeshRound gets (a float, or [(FreeCAD.Vector, r)] control points):
    for a law, OCCT's own radius measured along the chain, or with controls="ends" just the law's first
    and last radius at the chain's ends (a start -> end law, as a user gives it)."""

    def __init__(self, name, builder, radius, law=None, controls="measured", edge_radius=None):
        self.name = name
        self.builder = builder
        self.solid, self.chain = builder()
        self.law = law
        # edge_radius(edge) -> r, or (r at the edge's first parameter, r at its last): each edge's own radius
        # (a network: MeshRound gets a control point at each edge's middle, or at its two ends for a law;
        # OCCT each edge's radius or start -> end law).
        self.edge_radius = None if edge_radius is None else (lambda e: _pair(edge_radius(e)))
        if edge_radius is not None:
            radius = max(max(self.edge_radius(e)) for e in self.chain)
        self.r_max = radius if law is None else max(r for _, r in law)
        self.tolerance = self.r_max / 100
        try:
            self.points = chain_points(self.chain, 0.02 * self.r_max)  # the chain, densely, in order
            self.network = False
        except ValueError:  # edges meeting at a vertex, not one chain: each edge is a chain of its own
            self.points = np.concatenate([chain_points([e], 0.02 * self.r_max) for e in self.chain])
            self.network = True
        self.closed = not self.network and is_closed(self.chain)
        self.reference = self._occt_fillet(radius)
        self.rounds = fillet_faces(self.reference, self.solid)
        if edge_radius is not None:
            self.radius = []
            for e in self.chain:
                r0, r1 = self.edge_radius(e)
                self.radius += ([(edge_middle(e), r0)] if r0 == r1 else
                                [(e.valueAt(e.FirstParameter), r0), (e.valueAt(e.LastParameter), r1)])
        elif law is None:
            self.radius = radius
        elif controls == "ends":
            self.radius = [(V(*self.points[0]), law[0][1]), (V(*self.points[-1]), law[-1][1])]
        else:
            self.radius = self.measured_law()
        self._meshes = {}

    @property
    def seed(self):
        """A point on the chain, a third of the way along (away from chain ends and edge joints)."""
        return V(*self.points[len(self.points) // 3])

    @property
    def seeds(self):
        """What a user picks: one point, or where the chain's edges meet at corners (a turn sharper
        than the feature angle), the middle of every edge: each is a chain of its own, rounded together."""
        if self.network or (len(self.chain) > 1 and self.corners):
            return [edge_middle(e) for e in self.chain]
        return [self.seed]

    @property
    def corners(self):
        """True when consecutive edges of the chain meet at an angle (not tangent), or edges meet at a vertex."""
        if self.network:
            return True
        ordered = ordered_chain(self.chain)
        for (a, ra), (b, rb) in zip(ordered, ordered[1:] + (ordered[:1] if self.closed else [])):
            ta = a.tangentAt(a.FirstParameter if ra else a.LastParameter) * (-1 if ra else 1)
            tb = b.tangentAt(b.LastParameter if rb else b.FirstParameter) * (-1 if rb else 1)
            if ta.getAngle(tb) > math.radians(30):
                return True
        return False

    def _occt_fillet(self, radius):
        if getattr(self.builder, "offset_reference", False):  # every edge of a convex solid, one radius
            return self.solid.makeOffsetShape(-radius, 1e-7, join=0).makeOffsetShape(radius, 1e-7, join=0)
        if self.edge_radius is not None:
            return part_fillet_feature(self.solid, [(self._index(e), *self.edge_radius(e)) for e in self.chain])
        if self.law is None:
            return self.solid.makeFillet(radius, self.chain)
        return part_fillet_feature(self.solid, self._edge_stations())

    def _edge_stations(self):
        """(edge index, r at the edge's first parameter, r at its last) from the chain-fraction law."""
        s_of, r_of = np.array([s for s, _ in self.law]), np.array([r for _, r in self.law])
        total, done, out = sum(e.Length for e in self.chain), 0.0, []
        for e, backwards in ordered_chain(self.chain):
            r0, r1 = np.interp([done / total, (done + e.Length) / total], s_of, r_of)
            out.append((self._index(e), *((r1, r0) if backwards else (r0, r1))))
            done += e.Length
        return out

    def _index(self, edge):
        return next(i for i, e in enumerate(self.solid.Edges, 1) if e.isSame(edge))

    def measured_law(self, spacing=None, inset=0.3):
        """[(point, r)]: the reference's own radius on sections normal to the chain, every ~r_max/2."""
        P, s = self.points, arc_length(self.points)
        spacing = spacing or 0.5 * self.r_max
        at = np.linspace(inset, s[-1] - inset, max(3, int(s[-1] / spacing) + 1))
        rounds = Part.Compound(self.rounds)
        out = []
        for x in at:
            i = min(np.searchsorted(s, x), len(P) - 1)
            p = np.array([np.interp(x, s, P[:, k]) for k in range(3)])
            t = P[i] - P[i - 1]
            out.append((V(*p), section_radius(rounds, V(*p), V(*t))))
        return out

    def mesh(self, variant):
        """The sharp solid meshed as `variant` (see MESH_VARIANTS)."""
        if variant not in self._meshes:
            kw = dict(MESH_VARIANTS[variant])
            if "MaxLength" in kw:
                kw["MaxLength"] *= self.r_max
            self._meshes[variant] = mesh_of(self.solid, **kw)
        return self._meshes[variant]

    def __repr__(self):
        return f"Case({self.name})"


def _pair(r):
    return (float(r), float(r)) if np.isscalar(r) else (float(r[0]), float(r[1]))


def part_fillet_feature(solid, stations):
    """OCCT fillet with per-edge radii (r1 at each edge's first parameter), through a Part::Fillet feature in
    a scratch document: Part.Shape.makeFillet takes one (r1, r2) for all edges."""
    doc = FreeCAD.newDocument("meshround_reference")
    try:
        base = doc.addObject("Part::Feature", "Sharp")
        base.Shape = solid
        fillet = doc.addObject("Part::Fillet", "Fillet")
        fillet.Base = base
        fillet.Edges = [(i, float(r0), float(r1)) for i, r0, r1 in stations]
        doc.recompute()
        if not fillet.Shape.isValid() or fillet.Shape.isNull():
            raise RuntimeError("OCCT could not fillet the case")
        return fillet.Shape.copy()
    finally:
        FreeCAD.closeDocument(doc.Name)


# name -> (builder, radius, law); law: [(fraction of the chain's length, radius)] or None
SPECS = {
    "box": (box, 5.0, None),
    "box_tilted": (tilted(box), 5.0, None),
    "lchannel": (lchannel, 4.0, None),
    "acute_ridge": (acute_ridge, 4.0, None),
    "vee_groove": (vee_groove, 4.0, None),
    "draft_shoulder": (draft_shoulder, 5.0, None),
    "pocket_rim": (pocket_rim, 3.0, None),
    "s_chain": (s_plate, 4.0, None),
    "pocket_edge": (pocket_edge(), 2.0, None),
    "pocket_edge_draft": (pocket_edge(10.0), 2.0, None),
    "box_oblique_end": (box_oblique_end, 4.0, None),
    "l_bracket_45": (l_bracket(0), 2.0, None),
    "l_bracket_135": (l_bracket(1), 2.0, None),
    "pocket_rim_square": (pocket_rim_square(), 2.0, None),
    "pocket_rim_draft": (pocket_rim_square(10.0), 2.0, None),
    "pocket_rim_walls": (pocket_rim_walls(), 2.0, None),
    "pocket_rim_walls_draft": (pocket_rim_walls(10.0), 2.0, None),
    "open_sheet": (open_sheet(), 5.0, None),
    "open_sheet_slanted": (open_sheet((30.0, 20.0)), 5.0, None),
    "lchannel_open": (open_prism(lchannel), 4.0, None),
    "box_corner": (box_corner, 5.0, None),
    "box_top_corner": (box_top_corner, 5.0, None),
    "pyramid": (pyramid, 4.0, None),
    "box_var": (box, None, [(0.0, 2.0), (1.0, 8.0)]),
    "lchannel_var": (lchannel, None, [(0.0, 2.0), (1.0, 6.0)]),
    "s_chain_var3": (s_plate, None, [(0.0, 2.5), (0.5, 5.0), (1.0, 3.0)]),
    "box_ends": (box, None, [(0.0, 2.0), (1.0, 8.0)], "ends"),
    "lchannel_ends": (lchannel, None, [(0.0, 6.0), (1.0, 2.0)], "ends"),
}
CONSTANT = [n for n, spec in SPECS.items() if spec[2] is None]
VARIABLE = [n for n, spec in SPECS.items() if spec[2] is not None]


@functools.lru_cache(maxsize=None)
def case(name):
    return Case(name, *SPECS[name])
