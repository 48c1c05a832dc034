"""The S-rail die (after the NUMISHEET '96 S-rail benchmark) as a parametric FreeCAD Part solid.

A block whose top is the binder flat, with an S-shaped channel (the die cavity) cut into it: the channel's
centre line runs straight, bends left through an arc, runs straight at an angle, bends back through an
arc and runs straight again.  The channel walls are drafted and meet the binder in two sharp die-shoulder
edges, one along each side of the S; these are what MeshRound rounds.  See README.md for the dimensions.

    import srail_die
    solid = srail_die.die_solid()            # Part.Solid, mm
    seeds = srail_die.shoulder_seeds()       # [FreeCAD.Vector]: one point on each shoulder
    mesh = srail_die.die_mesh(5.0)           # Mesh.Mesh, a CAE tool mesh with elements about 5 mm
"""
import math
import sys
from dataclasses import dataclass

for _p in ("/usr/lib/freecad-python3/lib", "/usr/lib/freecad/lib"):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402
import MeshPart  # noqa: E402
import Part  # noqa: E402

V = FreeCAD.Vector


@dataclass(frozen=True)
class Dimensions:
    """All in mm and degrees.  The channel runs along +x; its centre line starts at y = start_y."""
    length: float = 360.0           # block, along x
    width: float = 200.0            # block, along y
    height: float = 60.0            # block; the binder flat is its top, z = height
    start_y: float = 70.0           # centre line, first straight
    first_straight: float = 110.0   # length of the first straight
    bend_radius: float = 100.0      # centre-line radius of both bends
    bend_angle: float = 35.0        # each bend turns by this much (left, then back right)
    middle_straight: float = 41.5   # the inclined straight between the bends
    opening: float = 50.0           # channel width at the binder (between the two shoulders)
    depth: float = 37.0             # channel depth (the benchmark's draw depth)
    draft: float = 10.0             # wall draft from the vertical: the shoulders are 100 degree edges


DEFAULT = Dimensions()


def centre_line(d=DEFAULT, overhang=20.0):
    """The channel's centre line in the plane z = 0, lengthened by `overhang` past both block ends."""
    a = math.radians(d.bend_angle)
    p0 = V(-overhang, d.start_y, 0)
    p1 = V(d.first_straight, d.start_y, 0)
    c1 = V(p1.x, p1.y + d.bend_radius, 0)  # left bend: centre on the left
    p2 = c1 + V(d.bend_radius * math.sin(a), -d.bend_radius * math.cos(a), 0)
    p3 = p2 + V(math.cos(a), math.sin(a), 0) * d.middle_straight
    c2 = p3 + V(math.sin(a), -math.cos(a), 0) * d.bend_radius  # right bend: centre on the right
    p4 = V(c2.x, c2.y + d.bend_radius, 0)
    p5 = V(d.length + overhang, p4.y, 0)
    bend = lambda c, s, e: Part.Arc(s, c + (s + e - c * 2).normalize() * d.bend_radius, e)  # noqa: E731
    return Part.Wire([Part.LineSegment(p0, p1).toShape(), bend(c1, p1, p2).toShape(),
                      Part.LineSegment(p2, p3).toShape(), bend(c2, p3, p4).toShape(),
                      Part.LineSegment(p4, p5).toShape()])


def half_width(z, d=DEFAULT):
    """Half the channel's width at height z: the opening at the binder, narrower below by the draft."""
    return 0.5 * d.opening - (d.height - z) * math.tan(math.radians(d.draft))


def channel_outline(z, d=DEFAULT):
    """The closed outline of the channel at height z (the centre line offset to both sides, capped)."""
    w = centre_line(d).makeOffset2D(half_width(z, d), 0, False, False)  # arc joins; a closed "sausage"
    w.translate(V(0, 0, z))
    return w


def die_solid(d=DEFAULT):
    """The sharp die: the block less the drafted S channel (a ruled loft between two offset outlines)."""
    block = Part.makeBox(d.length, d.width, d.height)
    floor = d.height - d.depth
    cavity = Part.makeLoft([channel_outline(floor, d), channel_outline(d.height + 1.0, d)], True, True)
    return block.cut(cavity).removeSplitter()


def shoulder_seeds(d=DEFAULT):
    """One point on each die shoulder (left and right of the channel), on the first straight."""
    x, y = 0.5 * d.first_straight, d.start_y
    return [V(x, y + 0.5 * d.opening, d.height), V(x, y - 0.5 * d.opening, d.height)]


def shoulder_edges(solid, d=DEFAULT):
    """The CAD edges of both shoulders: the edges of the binder flat (z = height) that are not on the
    block's sides."""
    def on_shoulder(e):
        bb = e.BoundBox
        on_side = (bb.XMax < 1e-6 or bb.XMin > d.length - 1e-6 or bb.YMax < 1e-6 or bb.YMin > d.width - 1e-6)
        return bb.ZMin > d.height - 1e-6 and not on_side
    return [e for e in solid.Edges if on_shoulder(e)]


def die_mesh(element_size, d=DEFAULT):
    """The die as a CAE tool mesh: MeshPart's Mefisto mesher with elements of about element_size."""
    return MeshPart.meshFromShape(Shape=die_solid(d), MaxLength=element_size)


if __name__ == "__main__":
    s = die_solid()
    print("valid", s.isValid(), "volume", round(s.Volume), "faces", len(s.Faces), "shoulder edges",
          len(shoulder_edges(s)))
