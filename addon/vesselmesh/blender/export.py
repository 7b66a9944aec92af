"""File > Export > Vessel surface: the surface with what the add-on computed for it.

PLY (vertex colours and the curvature values as float properties), OBJ (colours and a material) and STL
are written by the core (vesselmesh_core.write_mesh: positions kept exact where float would not be); glTF
binary by Blender's exporter, with the colours and the curvature values as custom attributes."""
import json
import os

import bpy
import numpy as np
from bpy.props import BoolProperty, EnumProperty, StringProperty
from bpy_extras.io_utils import ExportHelper

from .. import compat
from ..core import colors, exporting
from ..core.native import core
from . import mesh as mesh_data
from .operators import say, surface_of

FORMATS = {"PLY": ".ply", "OBJ": ".obj", "STL": ".stl", "GLB": ".glb"}


def placement(surface, units="SCENE"):
    """(matrix, length factor) from the surface's coordinates to the file's: world, and with units 'FILE'
    in the centerline file's lengths (the import's scale undone)."""
    centerline = surface.vesselmesh.centerline
    scale = centerline.vesselmesh.scale if units == "FILE" and centerline is not None else 1.0
    return np.array(surface.matrix_world, dtype=np.float64), 1.0 / scale


def surface_arrays(surface, units="SCENE"):
    """What a file of the surface holds: world vertices (V,3) float64, faces (F,3), the curvature values
    {name: (V,)} and the colours (V,4) scene-linear, or None. With units 'FILE', lengths are those of the
    centerline's file (the import's scale undone) and curvature values follow."""
    vertices, faces = mesh_data.triangles(surface.data)
    values = {name: mesh_data.float_attribute(surface.data, name) for name in colors.MEASURES}
    values = {name: v for name, v in values.items() if v is not None}
    rgba = mesh_data.point_colors(surface.data)
    matrix, length_factor = placement(surface, units)
    return exporting.transformed(vertices, faces, matrix, values, length_factor) + (rgba,)


def write(surface, path, fmt=None, units="SCENE", with_colors=True, with_curvature=True):
    """Writes the surface to path in the format its extension names (or fmt). Raises RuntimeError or
    ValueError with the reason (an STL that float would spoil, a folder that does not exist)."""
    fmt = fmt or next((k for k, ext in FORMATS.items() if path.lower().endswith(ext)), None)
    if fmt is None:
        raise ValueError(f"{path}: unknown extension; expected {', '.join(FORMATS.values())}")
    if fmt == "GLB":
        return _write_gltf(surface, path, with_colors, with_curvature)
    vertices, faces, values, rgba = surface_arrays(surface, units)
    srgb = colors.linear_to_srgb8(rgba)[:, :3] if with_colors and rgba is not None else None
    # The loops the surface closed, named as `vesselmesh mesh` names them, for `vesselmesh check` (STL has no
    # comments).
    lost = json.loads(surface.vesselmesh.stats or "{}").get("lost_loops", [])
    comments = exporting.lost_loop_comments(lost, *placement(surface, units)) if fmt != "STL" else []
    core().write_mesh(path, vertices, faces, properties=values if with_curvature and fmt == "PLY" else None,
                      colors=srgb if fmt != "STL" else None,
                      material=exporting.OBJ_MATERIAL if fmt == "OBJ" else "", comments=comments)
    return path


def _write_gltf(surface, path, with_colors, with_curvature):
    context = bpy.context
    selected, active = list(context.selected_objects), context.view_layer.objects.active
    for obj in selected:
        obj.select_set(False)
    surface.select_set(True)
    context.view_layer.objects.active = surface
    try:
        bpy.ops.export_scene.gltf(filepath=path, export_format="GLB", use_selection=True,
                                  export_attributes=with_curvature, export_apply=True,
                                  **compat.gltf_color_options(with_colors))
    finally:
        surface.select_set(False)
        for obj in selected:
            obj.select_set(True)
        context.view_layer.objects.active = active
    return path


class EXPORT_MESH_OT_vesselmesh(bpy.types.Operator, ExportHelper):
    """Export the vessel surface with its curvature colours (PLY, OBJ, glTF) and values (PLY, glTF)"""

    bl_idname = "export_mesh.vesselmesh"
    bl_label = "Export Vessel Surface"
    bl_options = {"REGISTER"}

    filename_ext = ".ply"
    filter_glob: StringProperty(default="*.ply;*.obj;*.stl;*.glb", options={"HIDDEN"})
    file_format: EnumProperty(
        name="Format", default="PLY",
        items=[("PLY", "PLY", "Colours and the curvature values per vertex (MeshLab, ParaView, Blender)"),
               ("OBJ", "OBJ", "Colours per vertex and a material (most 3D programs)"),
               ("STL", "STL", "The shape only, for 3D printing"),
               ("GLB", "glTF binary", "Colours and the curvature values, for the web and game engines")])
    units: EnumProperty(
        name="Units", default="SCENE",
        items=[("SCENE", "Scene", "Lengths as the scene has them (after the import's scale)"),
               ("FILE", "Centerline File", "Lengths in the unit of the file the centerline came from (the "
                                           "import's scale undone): millimetres for a file in millimetres, as "
                                           "3D printing expects")])
    colors: BoolProperty(name="Colours", default=True, description="Write the curvature colours per vertex")
    curvature: BoolProperty(name="Curvature Values", default=True,
                            description="Write k1, k2, mean, Gaussian and RMS curvature per vertex (PLY, glTF)")

    def check(self, context):
        ext = FORMATS[self.file_format]
        if not self.filepath.lower().endswith(ext):
            self.filepath = os.path.splitext(self.filepath)[0] + ext
            return True
        return False

    @classmethod
    def poll(cls, context):
        surface = surface_of(context.active_object)
        return surface is not None and surface.vesselmesh.role == "SURFACE"

    def invoke(self, context, event):
        surface = surface_of(context.active_object)
        self.filepath = bpy.path.ensure_ext(bpy.path.clean_name(surface.name), FORMATS[self.file_format])
        return ExportHelper.invoke(self, context, event)

    def execute(self, context):
        surface = surface_of(context.active_object)
        path = bpy.path.abspath(self.filepath)
        try:
            write(surface, path, self.file_format, self.units, self.colors, self.curvature)
        except (ValueError, RuntimeError) as error:
            self.report({"ERROR"}, f"{surface.name}: {error}")
            return {"CANCELLED"}
        say(f"wrote {path}")
        self.report({"INFO"}, f"{surface.name}: wrote {path}")
        return {"FINISHED"}


def menu_export(self, context):
    self.layout.operator(EXPORT_MESH_OT_vesselmesh.bl_idname, text="Vessel surface (.ply .obj .stl .glb)")


def register():
    bpy.utils.register_class(EXPORT_MESH_OT_vesselmesh)
    bpy.types.TOPBAR_MT_file_export.append(menu_export)


def unregister():
    bpy.types.TOPBAR_MT_file_export.remove(menu_export)
    bpy.utils.unregister_class(EXPORT_MESH_OT_vesselmesh)
