"""The parametric "Rounding" feature: a Mesh::FeaturePython whose mesh is its Base mesh, rounded.

    obj = MeshRound.make_rounding(base, seeds, radius)   # then doc.recompute()

Properties (group "Rounding"):
  Base             App::PropertyLink        any Mesh feature, another Rounding included (roundings chain)
  Seeds            App::PropertyVectorList  each selects the sharp edge nearest to it and its whole chain
  Radius           App::PropertyLength      constant radius; takes expressions (e.g. Spreadsheet.r)
  RadiusLaw        App::PropertyVectorList  variable radius: control points on the chain ...
  RadiusLawRadii   App::PropertyFloatList   ... and their radii in mm (same length). A non-empty law wins
                                            over Radius.
  Tolerance        App::PropertyLength      chordal tolerance, 0 = largest radius / 100
  FeatureAngle     App::PropertyAngle       an edge is sharp when its facets turn by at least this
  Reach            App::PropertyFloat       facets within Reach * r of a chain are re-meshed
  ElementAngle     App::PropertyAngle       band elements: at most this angle of the profile each, 0 = off
  ElementLength    App::PropertyLength      band elements: length along the round, 0 = the input's own
  MaxAspectRatio   App::PropertyFloat       band elements: longest / shortest side at most, 0 = built-in
  Surfaces         App::PropertyLink        (read-only) the "RoundingSurfaces" Part::Feature child whose
                                            Shape is the compound of the rolling-ball faces (STEP export)
  Operation        App::PropertyEnumeration "Round sharp edges" (round_edges; the default, and what files
                                            saved before it had) or "Change radius of existing round"
                                            (change_radius: each seed on an existing round, which is made
                                            again at Radius; Radius 0 sharpens it)
  Statistics       App::PropertyMap         (read-only output) the engine's report of the last recompute
  FoundRadius      App::PropertyFloatList   (read-only output) change radius: the radius each round had (mm)

execute() never touches Base; on failure it raises, FreeCAD marks the feature invalid and prints why
(a change of radius's refusal with its code first, e.g. "not_a_round: ...").
The class path MeshRound.objects.rounding.Rounding is stored in .FCStd files: keep it stable.
"""
import FreeCAD

from .. import api, inputs, reround
from ..errors import RoundingError
from ..progress import busy
from . import surfaces as surfaces_feature

TYPE = "Mesh::FeaturePython"
GROUP = "Rounding"
ROUND, CHANGE_RADIUS = OPERATIONS = ["Round sharp edges", "Change radius of existing round"]

# (type, name, tooltip, default); added only when missing, so files from older versions keep loading.
PROPERTIES = [
    ("App::PropertyLink", "Base", "The mesh feature to round (never modified)", None),
    ("App::PropertyVectorList", "Seeds", "Points near the sharp edges to round: each selects the "
     "nearest sharp edge and its whole chain", None),
    ("App::PropertyLength", "Radius", "Rolling ball radius (ignored when a radius law is given)", 5.0),
    ("App::PropertyVectorList", "RadiusLaw", "Variable radius: control points on the chain", None),
    ("App::PropertyFloatList", "RadiusLawRadii", "Variable radius: radius in mm at each control point",
     None),
    ("App::PropertyLength", "Tolerance", "Chordal tolerance of the new facets; 0 = radius / 100", 0.0),
    ("App::PropertyAngle", "FeatureAngle", "An edge is sharp when its facets turn by at least this", 30.0),
    ("App::PropertyFloat", "Reach", "Facets within Reach x radius of a chain are re-meshed", 3.0),
    ("App::PropertyAngle", "ElementAngle", "Band elements: at most this angle of the round's profile per element "
     "across it (e.g. 10); 0 = the chordal tolerance alone", 0.0),
    ("App::PropertyLength", "ElementLength", "Band elements: element length along the round; 0 = the input's "
     "own next to the edge", 0.0),
    ("App::PropertyFloat", "MaxAspectRatio", "Band elements: largest longest/shortest side of the round's "
     "elements (>= 1); 0 = the built-in bound", 0.0),
    ("App::PropertyLink", "Surfaces", "Part feature showing the rolling-ball surfaces", None),
    ("App::PropertyEnumeration", "Operation", "Round sharp edges, or change the radius of existing rounds "
     "(each seed on a round; Radius 0 sharpens it)", OPERATIONS),
    ("App::PropertyMap", "Statistics", "Report of the last recompute", None),
    ("App::PropertyFloatList", "FoundRadius", "Change radius: the radius each picked round had (mm)", None),
]
# Set by the feature itself, shown read-only; Statistics and FoundRadius are outputs (writing them does not
# touch).
PROPERTY_STATUS = {"Surfaces": ["ReadOnly"], "Statistics": ["Output", "ReadOnly"],
                   "FoundRadius": ["Output", "ReadOnly"]}
# The engine each Operation runs: both take (mesh, seeds, radius, tolerance=, feature_angle=, reach=, cancel=,
# band=) and return a RoundingResult.
ENGINES = {ROUND: api.round_edges, CHANGE_RADIUS: reround.change_radius}


class Rounding:
    """Proxy of the Rounding feature."""

    def __init__(self, obj):
        obj.Proxy = self
        self.ensure_properties(obj)

    @staticmethod
    def ensure_properties(obj):
        for type_name, name, tooltip, default in PROPERTIES:
            if name in obj.PropertiesList:
                continue
            obj.addProperty(type_name, name, GROUP, tooltip)
            if default is not None:
                setattr(obj, name, default)
            if name in PROPERTY_STATUS:
                obj.setPropertyStatus(name, PROPERTY_STATUS[name])

    def onDocumentRestored(self, obj):
        self.ensure_properties(obj)
        if "RadiusLawPoints" in obj.PropertiesList:  # its name in files saved before 0.1.0
            obj.RadiusLaw = obj.RadiusLawPoints
            obj.removeProperty("RadiusLawPoints")

    def execute(self, obj):
        base = obj.Base
        check_base(base)
        with busy(f"{_doing(obj)} of {base.Label} (Esc cancels)") as token:
            try:
                result = engine(obj)(base.Mesh, list(obj.Seeds), radius_argument(obj),
                                     tolerance=obj.Tolerance.Value or None, feature_angle=obj.FeatureAngle.Value,
                                     reach=obj.Reach, cancel=token, band=band_argument(obj))
            except RoundingError as exc:
                raise _refusal(obj, exc) from None
        obj.Mesh = result.mesh
        surfaces_feature.update_surfaces(obj, result.surfaces)
        obj.Statistics = statistics(result.report)
        obj.FoundRadius = result.report.get("found_radius", [])
        note = api.quality_note(result.report)
        if note:  # in the report view, where a recompute's warnings go
            FreeCAD.Console.PrintWarning(f"{obj.Label}: {note}\n")

    # No state of its own: everything lives in the properties.
    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__  # the names FreeCAD >= 0.21 looks for


def engine(obj):
    """The engine function obj's Operation runs (api.round_edges or reround.change_radius)."""
    return ENGINES[getattr(obj, "Operation", ROUND)]


def _doing(obj):
    return "Changing the radius" if engine(obj) is reround.change_radius else "Rounding edges"


def _refusal(obj, exc):
    """The error a refusal leaves the feature with: change radius names the code first (reround.named);
    round_edges' message as it is."""
    return reround.named(exc) if engine(obj) is reround.change_radius else exc


def statistics(report):
    """The report's scalars as strings (details stay in the API), the band's quality, and per round that
    change radius found: its radius, law ("constant" or min-max) and strip facets."""
    values = {key: str(value) for key, value in report.items() if not isinstance(value, (dict, list))}
    values.update({f"band_{key}": str(value) for key, value in report["band_quality"].items()})
    for number, strip in enumerate(report.get("strips", []), 1):
        law = "constant" if strip["constant"] else f"{strip['radius_min']:.4g} to {strip['radius_max']:.4g} mm"
        values[f"strip{number}_found_radius"] = f"{strip['found_radius']:.4g} mm ({law})"
        values[f"strip{number}_facets"] = str(strip["strip_facets"])
    return values


def check_base(base):
    """RoundingError unless base is a Mesh feature with facets."""
    if base is None:
        raise RoundingError("Rounding has no Base: link it to a mesh feature")
    if not base.isDerivedFrom("Mesh::Feature"):
        raise RoundingError(f"Base '{base.Label}' is a {base.TypeId}, not a mesh feature")
    if base.Mesh.CountFacets == 0:
        raise RoundingError(f"Base '{base.Label}' has an empty mesh")


def radius_argument(obj):
    """The radius to hand to api.round_edges: the law's (point, r) pairs if it has any, else Radius."""
    points, radii = list(obj.RadiusLaw), list(obj.RadiusLawRadii)
    if len(points) != len(radii):
        raise RoundingError(f"RadiusLaw has {len(points)} points but RadiusLawRadii has {len(radii)} "
                            "radii: they must pair up")
    if points:
        return list(zip(points, radii))
    return obj.Radius.Value


def band_argument(obj):
    """The band element controls of the feature, as round_edges' band argument."""
    return dict(max_element_angle=obj.ElementAngle.Value, element_length=obj.ElementLength.Value,
                max_aspect_ratio=obj.MaxAspectRatio)


def make_rounding(base, seeds, radius, tolerance=0, feature_angle=30, reach=3, name="Rounding",
                  doc=None, operation=ROUND):
    """Add a Rounding of mesh feature `base` (and its "RoundingSurfaces" child) to doc; no recompute.

    radius: mm, or a list of (point, radius) control points for a variable radius.  operation: ROUND
    (seeds next to sharp edges) or CHANGE_RADIUS (seeds on existing rounds; radius 0 sharpens them).  The
    arguments are checked here (RoundingError); whether the seeds find an edge or a round shows at recompute.
    """
    check_base(base)
    if operation not in OPERATIONS:
        raise RoundingError(f"operation must be one of {OPERATIONS}, got {operation!r}")
    seed_vectors = [FreeCAD.Vector(*p) for p in inputs.seed_array(seeds).tolist()]
    sharpen = operation == CHANGE_RADIUS and reround.sharpen_only(radius)
    largest_radius, law = (0.0, None) if sharpen else inputs.radius_and_law(radius)
    tolerance = inputs.tolerance_value(tolerance)
    feature_angle = inputs.feature_angle_value(feature_angle)
    reach = inputs.reach_value(reach)

    doc = doc or base.Document
    if doc.Name != base.Document.Name:  # App::PropertyLink cannot point into another document
        raise RoundingError(f"Base '{base.Label}' is in document '{base.Document.Name}', "
                            f"not in '{doc.Name}'")
    obj = doc.addObject(TYPE, name)
    Rounding(obj)
    obj.Base = base
    obj.Operation = operation
    obj.Seeds = seed_vectors
    obj.Radius = largest_radius
    if law is not None:
        obj.RadiusLaw = [FreeCAD.Vector(*row[:3]) for row in law.tolist()]
        obj.RadiusLawRadii = law[:, 3].tolist()
    obj.Tolerance = tolerance
    obj.FeatureAngle = feature_angle
    obj.Reach = reach
    surfaces_feature.make_surfaces(obj)
    if FreeCAD.GuiUp:
        from ..viewproviders.rounding import ViewProviderRounding
        ViewProviderRounding(obj.ViewObject)
        base.ViewObject.Visibility = False
    return obj
