"""The settings stored on centerline objects (and offered by the import operator), and what each
VesselMesh object remembers: its role, its partner, the last run's statistics, its colour range.

Labels and tooltips say what a setting changes in the picture; the Python names are the core's (they
are what scripts and saved files use)."""
import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty, StringProperty

from ..core import colors
from ..core.meshing import MESH_OPTIONS


def _recolor(self, context):
    """Colour settings apply at once: recolouring reads the stored curvature, no meshing needed."""
    from .paint import paint

    owner = getattr(self, "id_data", None)  # None for the import operator's own copy of the settings
    surface = owner.vesselmesh.surface if isinstance(owner, bpy.types.Object) else None
    if surface is not None:
        paint(surface)


MEASURE_HELP = {
    "k2": "The smaller principal curvature: 0 along straight vessels of every size; negative (blue) where "
          "the wall is saddle-shaped (forks, narrowings, the inside of bends), positive (red) where it bulges "
          "(aneurysms, vessel ends)",
    "mean": "Mean curvature: about 1/(2 × radius) on a straight vessel, so it mostly shows calibre (thin "
            "vessels bright); bends and bulges add to it",
    "gaussian": "Gaussian curvature k1·k2: 0 along straight vessels, positive on bulges and ends, negative on "
                "saddles; its extremes are small, so most of a tree is near the centre of the map",
    "k1": "The larger principal curvature, about 1/radius: shows calibre",
    "rms": "Root mean square of k1 and k2: how strongly the wall curves, whatever the direction (calibre "
           "mostly)",
    "shape": "Mean curvature times the vessel's radius there: 0.5 along a straight vessel of any size; higher "
             "on the outside of bends, on bulges and at ends, lower on the inside of bends, at narrowings and "
             "forks. Shows shape rather than calibre",
}


class MeshSettings:
    """The meshing and colour settings, shared by the import operator and the centerline objects."""

    levels: IntProperty(
        name="Smoothness", default=1, min=0, max=4,
        description="How many times the surface is refined (Loop subdivision levels): 0 is faceted, 1 is smooth "
                    "in a picture, each step up has up to 4 times the triangles")
    method: EnumProperty(
        name="Refine", default="curvature",
        description="Where the refining steps add triangles",
        items=[("curvature", "Where It Bends",
                "Only where the wall curves: straight stretches stay coarse, the same picture with fewer "
                "triangles (the paper's adaptive subdivision)"),
               ("uniform", "Everywhere", "Every triangle at every step: an even mesh, the most triangles"),
               ("dihedral", "At Sharp Edges", "Where neighbouring triangles meet at a sharp angle")])
    uniform_levels: IntProperty(
        name="Even Steps", default=1, min=0, max=4,
        description="The first refining steps split every triangle, whatever Refine says: more gives rounder "
                    "straight vessels")
    threshold: FloatProperty(
        name="Detail Threshold", default=0.72, min=0.0, max=1.0,
        description="Refine Where It Bends: how curved a place must be to get finer triangles (0 to 1, ranked "
                    "over the surface); lower refines more of it")
    measure: EnumProperty(
        name="Bend Measure", default="tube-departure",
        description="Refine Where It Bends: what counts as curved",
        items=[("tube-departure", "Unlike a Tube",
                "How far the wall departs from a straight tube, the same for vessels of every size"),
               ("rms", "Any Curvature", "How strongly the wall curves (thin vessels count most)"),
               ("gaussian", "Gaussian (signed)", "k1·k2"), ("abs-gaussian", "Gaussian (size)", "|k1·k2|"),
               ("mean", "Mean (signed)", "(k1 + k2)/2"), ("abs-mean", "Mean (size)", "|k1 + k2|/2")])
    angle: FloatProperty(
        name="Edge Angle", default=160.0, min=0.0, max=180.0,
        description="Refine At Sharp Edges: refine where neighbouring triangles meet at less than this angle "
                    "(degrees); higher refines more")
    sampling: EnumProperty(
        name="Ring Order", default="bidirectional",
        description="In which order the cross-section rings are placed along each branch",
        items=[("bidirectional", "From Both Ends",
                "From both ends towards the middle: even rings at both joints of a branch"),
               ("unidirectional", "From the Start", "From the start of each branch to its end")])
    alpha: FloatProperty(
        name="Ring Spacing", default=1.0, min=0.05, soft_max=4.0,
        description="Distance between cross-section rings on straight parts, in vessel diameters: smaller "
                    "follows radius changes more closely, with more triangles")
    beta: FloatProperty(
        name="Rings in Bends", default=4.0, min=0.0, soft_max=20.0,
        description="How much closer the rings come where the centerline bends: higher keeps tight bends round")
    crossings: EnumProperty(
        name="Crossing Vessels", default="separate",
        description="Vessels whose tubes cross away from any joint, or pass close by another vessel's joint "
                    "(a tracing put them too close)",
        items=[("separate", "Move Apart",
                "Move them apart, each by the same share of its own radius: a surface that never crosses itself"),
               ("keep", "Leave As Traced", "Leave the centerline as it is: the surfaces cross where the tubes do")])
    fit: EnumProperty(
        name="Match Radii", default="onto",
        description="How closely the smooth surface follows the radii in the file",
        items=[("onto", "Exactly", "Every point within 3 % of the radius: forks and bends as the centerline "
                                   "has them"),
               ("inward", "Trim Bulges Only", "Only where the smooth surface swells past the tubes (webbed "
                                              "forks, filled bends); elsewhere it stays rounder"),
               ("none", "Smooth As Is", "The smooth subdivision surface, a little thinner than the radii")])
    caps: EnumProperty(
        name="Vessel Ends", default="flat", description="The ends of the terminal vessels",
        items=[("flat", "Closed", "Close each end: a watertight surface"),
               ("open", "Open", "Leave the ends open: you can see into the vessels")])
    smooth: IntProperty(
        name="Smooth Tracing", default=0, min=0, soft_max=10, max=50,
        description="Irons out a jagged, zig-zag tracing before the surface is built (rounds of smoothing; "
                    "forks and ends stay put); 0 follows the centerline exactly")
    default_radius: FloatProperty(
        name="Default Radius", default=0.1, min=1e-9, soft_max=10.0, subtype="DISTANCE",
        description="The radius of points that have none and no neighbour with one (a centerline drawn in "
                    "Blender); a new point next to others takes theirs")
    curvature: BoolProperty(
        name="Curvature Colours", default=True,
        description="Work out the curvature of the surface and colour it by it")
    color_measure: EnumProperty(
        name="Colour By", default="k2", update=_recolor,
        description="What the colours show",
        items=[(key, colors.MEASURES[key].title, MEASURE_HELP[key]) for key in colors.MEASURES])
    colormap: EnumProperty(
        name="Colour Map", default="auto", update=_recolor,
        description="The colours the values are painted with",
        items=[("auto", "Automatic",
                "Blue-white-red centred on zero when both signs carry weight, each side spanning its own "
                "range; otherwise one ramp (viridis) over the values"),
               ("viridis", "Viridis", "One ramp, dark purple to yellow: evenly perceived steps"),
               ("rdbu", "Blue-White-Red", "Diverging: blue below zero, white at zero, red above")])
    percentile: FloatProperty(
        name="Ignore Extremes %", default=2.0, min=0.0, max=25.0, update=_recolor,
        description="The colours span the values from this percentile to its complement, so that a few extreme "
                    "points (cap rims, sharp forks) do not wash out the rest")


SETTINGS = (*MESH_OPTIONS, "smooth", "default_radius", "curvature", "color_measure", "colormap", "percentile")


def copy_settings(source, target):
    for name in SETTINGS:
        setattr(target, name, getattr(source, name))


def mesh_options(settings):
    """The keyword arguments of vesselmesh_core.mesh for these settings."""
    return {name: getattr(settings, name) for name in MESH_OPTIONS}


def color_options(settings):
    """The measure, colour map and percentile to colour by; None when the settings ask for no curvature."""
    return (settings.color_measure, settings.colormap, settings.percentile) if settings.curvature else None


class VesselMeshSettings(MeshSettings, bpy.types.PropertyGroup):
    pass


class VesselMeshObject(bpy.types.PropertyGroup):
    """Object.vesselmesh."""

    role: EnumProperty(name="Role", default="NONE",
                       items=[("NONE", "None", ""), ("CENTERLINE", "Centerline", ""), ("SURFACE", "Surface", "")])
    source: StringProperty(name="Source", subtype="FILE_PATH", description="The file the centerline came from")
    scale: FloatProperty(name="Import Scale", default=1.0, min=1e-12,
                         description="The scale the centerline was imported at: scene length = file length × "
                                     "scale (0.001: the file is in millimetres); the legend's unit follows it")
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
