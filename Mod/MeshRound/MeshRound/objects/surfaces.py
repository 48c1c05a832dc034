"""The "RoundingSurfaces" child: a Part feature showing a Rounding's rolling-ball faces as a shape.

A Mesh feature cannot carry a Part shape in a way the tree, STEP export or Part tools see, so every
Rounding gets this companion.  It *pulls* the faces from its Rounding's hidden SurfaceShape output in its
own execute(): it depends on the Rounding (Source link), so a recompute runs Rounding first, then this,
and neither touches the other -- no recompute loop.  The Rounding's view provider claims it as a child.
The class path MeshRound.objects.surfaces.RoundingSurfaces is stored in .FCStd files: keep it stable.
"""
import FreeCAD

TYPE = "Part::FeaturePython"


class RoundingSurfaces:
    """Proxy of the RoundingSurfaces feature."""

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        if "Source" not in obj.PropertiesList:
            obj.addProperty("App::PropertyLink", "Source", "Rounding",
                            "The Rounding whose surfaces this shows")
            obj.setPropertyStatus("Source", ["ReadOnly"])

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)

    def execute(self, obj):
        source = obj.Source
        if source is not None and "SurfaceShape" in source.PropertiesList:
            obj.Shape = source.SurfaceShape.copy()

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__


def make_surfaces(rounding):
    """Add the RoundingSurfaces child of `rounding` to its document."""
    doc = rounding.Document
    obj = doc.addObject(TYPE, rounding.Name + "Surfaces")
    RoundingSurfaces(obj)
    obj.Source = rounding
    obj.Label = rounding.Label + "Surfaces"
    if FreeCAD.GuiUp:
        from ..viewproviders.rounding import ViewProviderRoundingSurfaces
        ViewProviderRoundingSurfaces(obj.ViewObject)
    return obj


def surfaces_of(rounding):
    """The RoundingSurfaces features that show `rounding` (normally one)."""
    return [o for o in rounding.InList
            if isinstance(getattr(o, "Proxy", None), RoundingSurfaces) and o.Source == rounding]
