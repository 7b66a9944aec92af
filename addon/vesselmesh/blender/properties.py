"""The settings stored on centerline objects (and offered by the import operator), and what each
VesselMesh object remembers: its role, its partner, the last run's statistics, its colour range."""
import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty, StringProperty

from ..core.meshing import MESH_OPTIONS


def _recolor(self, context):
    """Colour settings apply at once: recolouring reads the stored curvature, no meshing needed."""
    from .paint import paint

    owner = getattr(self, "id_data", None)  # None for the import operator's own copy of the settings
    surface = owner.vesselmesh.surface if isinstance(owner, bpy.types.Object) else None
    if surface is not None:
        paint(surface)


class MeshSettings:
    """The meshing and colour settings, shared by the import operator and the centerline objects."""

    method: EnumProperty(
        name="Method", default="curvature",
        items=[("curvature", "Curvature", "Refine only where the surface bends (the paper's adaptive Loop subdivision)"),
               ("uniform", "Uniform", "Refine every triangle at every level"),
               ("dihedral", "Dihedral", "Refine where neighbouring triangles meet at a sharp angle")])
    levels: IntProperty(name="Levels", default=2, min=0, max=4, description="Loop subdivision levels")
    uniform_levels: IntProperty(name="Uniform Levels", default=1, min=0, max=4,
                                description="The first levels split every triangle, whatever the method")
    threshold: FloatProperty(name="Threshold", default=0.7, min=0.0, max=1.0,
                             description="Curvature method: triangles whose vertices all rank below this "
                                         "(equalised curvature, 0 to 1) stay as they are")
    measure: EnumProperty(
        name="Measure", default="tube-departure", description="The curvature that the curvature method ranks",
        items=[("tube-departure", "Tube Departure",
                "min(|k1|, |k2|) / max(|k1|, |k2|): how far the surface departs from a tube, the same for vessels "
                "of every size"),
               ("rms", "RMS", "sqrt((k1² + k2²)/2)"), ("gaussian", "Gaussian", "k1·k2 (signed)"),
               ("abs-gaussian", "|Gaussian|", "|k1·k2|"), ("mean", "Mean", "(k1 + k2)/2 (signed)"),
               ("abs-mean", "|Mean|", "|k1 + k2|/2")])
    angle: FloatProperty(name="Angle", default=160.0, min=0.0, max=180.0,
                         description="Dihedral method: refine where neighbouring triangles meet at less than "
                                     "this angle (degrees)")
    sampling: EnumProperty(
        name="Sampling", default="bidirectional",
        items=[("bidirectional", "Bidirectional", "Sections placed from both ends of each branch towards its middle"),
               ("unidirectional", "Unidirectional", "Sections placed from the start of each branch")])
    alpha: FloatProperty(name="Spacing α", default=1.0, min=0.05, soft_max=4.0,
                         description="Section spacing, in diameters on straight parts")
    beta: FloatProperty(name="Bend β", default=4.0, min=0.0, soft_max=20.0,
                        description="How much sections crowd where the centerline bends")
    crossings: EnumProperty(
        name="Crossings", default="separate",
        description="Vessels whose tubes cross away from any joint, or pass close by another vessel's joint "
                    "(a tracing put them too close)",
        items=[("separate", "Separate", "Move them apart, each by the same share of its own radius: a surface "
                                        "that does not cross itself"),
               ("keep", "Keep", "Leave the centerline as it is: the surfaces cross where the tubes do")])
    fit: EnumProperty(
        name="Fit", default="onto", description="Bring the smooth surface onto the centerline's tubes",
        items=[("onto", "Onto Tubes", "Every vertex within 3 % of the radius the file gives: crotches and bends "
                                      "as the centerline has them"),
               ("inward", "Inward Only", "Only where the smooth surface lies outside the tubes (webbed crotches, "
                                         "filled bends); elsewhere it keeps its rounder shape"),
               ("none", "None", "The smooth Loop surface as it is")])
    caps: EnumProperty(name="Caps", default="flat",
                       items=[("flat", "Flat", "Close the vessel ends"), ("open", "Open", "Leave the ends open")])
    default_radius: FloatProperty(name="Default Radius", default=0.1, min=1e-9, soft_max=10.0, subtype="DISTANCE",
                                  description="The radius of centerline points that have none (drawn in Blender)")
    curvature: BoolProperty(name="Curvature", default=True,
                            description="Compute per-vertex curvature (k1, k2, mean, Gaussian, RMS) and colour "
                                        "the surface by it")
    color_measure: EnumProperty(
        name="Colour By", default="mean", update=_recolor,
        items=[("mean", "Mean", "Mean curvature (signed: saddles are negative)"),
               ("gaussian", "Gaussian", "Gaussian curvature (signed)"), ("rms", "RMS", "RMS curvature"),
               ("k1", "k1", "Largest principal curvature"), ("k2", "k2", "Smallest principal curvature")])
    colormap: EnumProperty(
        name="Colour Map", default="auto", update=_recolor,
        items=[("auto", "Automatic", "Diverging, centred on zero, for signed measures; viridis for RMS"),
               ("viridis", "Viridis", "Perceptually uniform, dark to bright"),
               ("rdbu", "Blue-Red", "Diverging: blue, white, red")])
    percentile: FloatProperty(name="Clip %", default=2.0, min=0.0, max=25.0, update=_recolor,
                              description="The colour range spans this percentile to its complement")


SETTINGS = (*MESH_OPTIONS, "default_radius", "curvature", "color_measure", "colormap", "percentile")


def copy_settings(source, target):
    for name in SETTINGS:
        setattr(target, name, getattr(source, name))


def mesh_options(settings):
    """The keyword arguments of vesselmesh_core.mesh for these settings."""
    return {name: getattr(settings, name) for name in MESH_OPTIONS}


def color_options(settings):
    """What colors.color_by takes besides the values: the measure, colour map and percentile; None when
    the settings ask for no curvature."""
    return (settings.color_measure, settings.colormap, settings.percentile) if settings.curvature else None


class VesselMeshSettings(MeshSettings, bpy.types.PropertyGroup):
    pass


class VesselMeshObject(bpy.types.PropertyGroup):
    """Object.vesselmesh."""

    role: EnumProperty(name="Role", default="NONE",
                       items=[("NONE", "None", ""), ("CENTERLINE", "Centerline", ""), ("SURFACE", "Surface", "")])
    source: StringProperty(name="Source", subtype="FILE_PATH", description="The file the centerline came from")
    settings: PointerProperty(type=VesselMeshSettings)
    surface: PointerProperty(type=bpy.types.Object, name="Surface", description="The surface made from this centerline")
    centerline: PointerProperty(type=bpy.types.Object, name="Centerline",
                                description="The centerline this surface is made from")
    legend: PointerProperty(type=bpy.types.Object, name="Legend")
    stats: StringProperty(name="Statistics", description="The last run's figures, as JSON")
    color_measure: StringProperty()
    color_map: StringProperty()
    color_low: FloatProperty()
    color_high: FloatProperty()


classes = (VesselMeshSettings, VesselMeshObject)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Object.vesselmesh = PointerProperty(type=VesselMeshObject)


def unregister():
    del bpy.types.Object.vesselmesh
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
