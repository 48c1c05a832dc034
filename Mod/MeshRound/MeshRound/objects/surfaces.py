"""The "RoundingSurfaces" child of a Rounding: a plain Part::Feature holding the rolling-ball faces.

A Mesh feature cannot carry a Part shape that the tree, STEP export or Part tools see, so each Rounding
owns one of these, linked from its `Surfaces` property and claimed as a child by its view provider.
The Rounding links the child (not the other way round), so deleting a Rounding warns about nothing, and
its view provider deletes the child with it.  The Rounding's execute() writes the child's Shape and then
clears the child's touched flag: the child has nothing to compute itself, so this ends the recompute.
"""
import FreeCAD

from .. import shapes

TYPE = "Part::Feature"
SURFACE_COLOR = (0.95, 0.55, 0.15)  # orange, like the chain highlight of the task panel


def make_surfaces(rounding):
    """Add the RoundingSurfaces child of `rounding` and link it from rounding.Surfaces."""
    obj = rounding.Document.addObject(TYPE, rounding.Name + "Surfaces")
    obj.Label = rounding.Label + "Surfaces"
    rounding.Surfaces = obj
    if FreeCAD.GuiUp:
        obj.ViewObject.ShapeColor = SURFACE_COLOR
        obj.ViewObject.Visibility = False  # it lies on the rounded mesh; shown on demand (Space)
    return obj


def update_surfaces(rounding, faces):
    """Show `faces` in the rounding's child, if it has one (it may have been deleted by the user)."""
    child = rounding.Surfaces
    if child is None:
        return
    child.Shape = shapes.compound(faces)
    child.purgeTouched()  # nothing to recompute in the child: don't leave it marked
