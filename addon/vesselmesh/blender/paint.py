"""Curvature colours on a surface: the colour attribute, the material that renders it, and the legend."""
import math

import bpy
from mathutils import Matrix, Vector

from .. import compat
from ..core import colors, legend
from . import mesh as mesh_data

MATERIAL = "VesselMesh curvature"
TEXT_MATERIAL = "VesselMesh legend text"


def paint(surface, coloring=None):
    """Colours the surface by the curvature measure its centerline's settings choose: by `coloring` when
    the caller has it (colors.color_by for those settings), else from the surface's attributes. False
    when there is nothing to colour by (meshed without curvature)."""
    settings = surface.vesselmesh.centerline.vesselmesh.settings
    if coloring is None:
        values = mesh_data.float_attribute(surface.data, settings.color_measure)
        if values is None:
            return False
        coloring = colors.color_by(values, settings.color_measure, settings.colormap, settings.percentile)
    state = surface.vesselmesh
    state.color_measure = settings.color_measure
    state.color_map, state.color_low, state.color_high, rgba = coloring
    mesh_data.set_point_colors(surface.data, rgba)
    if state.legend is not None:
        update_legend(state.legend, surface)
    return True


def curvature_material():
    """The shared material that renders the colour attribute in Cycles and EEVEE."""
    material = bpy.data.materials.get(MATERIAL)
    if material is None:
        material = compat.node_material(MATERIAL)
        tree = material.node_tree
        shader = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
        shader.inputs["Roughness"].default_value = 0.45
        color = tree.nodes.new("ShaderNodeVertexColor")
        color.layer_name = mesh_data.COLOR_ATTRIBUTE
        color.location = shader.location - Vector((250, 0))
        tree.links.new(color.outputs["Color"], shader.inputs["Base Color"])
    return material


def _text_material():
    material = bpy.data.materials.get(TEXT_MATERIAL)
    if material is None:
        material = bpy.data.materials.new(TEXT_MATERIAL)
        material.diffuse_color = (0.01, 0.01, 0.01, 1.0)
        if material.node_tree is not None:
            shader = next(n for n in material.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
            shader.inputs["Base Color"].default_value = material.diffuse_color
    return material


def add_legend(context, surface):
    """A colour bar with tick values and a title for the surface's colours: in the lower right of the
    scene camera's view when there is a camera (parented to it), else standing beside the surface."""
    obj = bpy.data.objects.new(surface.name + " legend", bpy.data.meshes.new(surface.name + " legend"))
    for collection in surface.users_collection:
        collection.objects.link(obj)
    surface.vesselmesh.legend = obj
    camera = context.scene.camera
    if camera is not None:
        # The view's frame corners in camera space, moved to a depth just past the near clip plane.
        depth = 1.5 * camera.data.clip_start
        frame = [Vector(c) for c in camera.data.view_frame(scene=context.scene)]
        if camera.data.type != "ORTHO":
            frame = [c * (depth / -c.z) for c in frame]
        xs, ys = [c.x for c in frame], [c.y for c in frame]
        width, height = max(xs) - min(xs), max(ys) - min(ys)
        obj.parent = camera
        obj.matrix_parent_inverse = Matrix.Identity(4)
        obj.location = (max(xs) - 0.22 * width, min(ys) + 0.2 * height, -depth)
        obj.scale = (0.6 * height,) * 3
    else:
        context.view_layer.update()  # matrix_world of objects a script has just moved
        low, high = _world_bounds(surface)
        size = max(high - low)
        obj.location = (high.x + 0.1 * size, (low.y + high.y) / 2, low.z)
        obj.rotation_euler = (math.pi / 2, 0.0, 0.0)  # upright, facing the front view
        obj.scale = (0.6 * size,) * 3
    update_legend(obj, surface)
    return obj


def update_legend(obj, surface):
    """Rebuilds the legend's bar and labels for the surface's current colours (keeping where it is)."""
    state = surface.vesselmesh
    vertices, quads, rgba = legend.colorbar(state.color_map, state.color_low, state.color_high)
    vertices[:, 0] *= 0.08  # a bar 0.08 as wide as it is high, in the legend's unit height
    bar = obj.data
    bar.clear_geometry()
    bar.from_pydata(vertices.tolist(), [], quads.tolist())  # 66 vertices: small enough for from_pydata
    mesh_data.set_point_colors(bar, rgba)
    if not bar.materials:
        bar.materials.append(curvature_material())
    for child in list(obj.children):
        bpy.data.objects.remove(child)
    labels = [(0.12, y, 0.06, text) for y, text in legend.ticks(state.color_low, state.color_high)]
    labels.append((0.0, 1.08, 0.07, legend.TITLES[state.color_measure]))
    for x, y, size, text in labels:
        _add_text(obj, text, (x, y), size)


def _add_text(parent, body, location, size):
    curve = bpy.data.curves.new(parent.name + " label", "FONT")
    curve.body = body
    curve.size = size
    curve.align_y = "CENTER"
    curve.materials.append(_text_material())
    text = bpy.data.objects.new(curve.name, curve)
    for collection in parent.users_collection:
        collection.objects.link(text)
    text.parent = parent
    text.location = (location[0], location[1], 0.0)


def _world_bounds(obj):
    corners = [obj.matrix_world @ Vector(c) for c in obj.bound_box]
    return (Vector([min(c[i] for c in corners) for i in range(3)]),
            Vector([max(c[i] for c in corners) for i in range(3)]))
