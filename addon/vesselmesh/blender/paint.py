"""Curvature colours on a surface: the colour attribute, the materials that render it, and the legend.

The legend is geometry: a colour bar and labels turned into meshes, all carrying the colour attribute
and an emission material, so that it reads the same in Workbench (which shows the attribute), EEVEE and
Cycles, whatever the lights."""
import math

import bpy
import numpy as np
from mathutils import Matrix, Vector

from .. import compat
from ..core import colors, legend
from . import mesh as mesh_data

MATERIAL = "VesselMesh curvature"
LEGEND_MATERIAL = "VesselMesh legend"
DARK_TEXT = (0.01, 0.01, 0.01, 1.0)
LIGHT_TEXT = (0.92, 0.92, 0.92, 1.0)

# The legend's layout, in units of the bar's height.
BAR_WIDTH = 0.07
TICK_LENGTH = 0.035
LABEL_GAP = 0.03
LABEL_SIZE = 0.075
TITLE_SIZE = 0.075
TITLE_GAP = 0.07


def paint(surface, coloring=None):
    """Colours the surface by the curvature measure its centerline's settings choose: by `coloring` when
    the caller has it (colors.color_by for those settings), else from the surface's attributes. False
    when there is nothing to colour by (meshed without curvature)."""
    settings = surface.vesselmesh.centerline.vesselmesh.settings
    if coloring is None:
        values = mesh_data.float_attribute(surface.data, settings.color_measure)
        if values is None:
            return False
        coloring = colors.color_by(values, settings.colormap, settings.percentile)
    state = surface.vesselmesh
    state.color_measure = settings.color_measure
    state.color_map, state.color_low, state.color_high, rgba = coloring
    mesh_data.set_point_colors(surface.data, rgba)
    if live(state.legend) is not None:
        update_legend(state.legend, surface)
    return True


def live(obj):
    """obj, unless it is None or was deleted (kept alive only by a pointer)."""
    return obj if obj is not None and obj.users_collection else None


def curvature_material():
    """The shared material that renders the colour attribute in Cycles and EEVEE."""
    material = bpy.data.materials.get(MATERIAL)
    if material is None:
        material = compat.node_material(MATERIAL)
        tree = material.node_tree
        shader = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
        shader.inputs["Roughness"].default_value = 0.4
        color = tree.nodes.new("ShaderNodeVertexColor")
        color.layer_name = mesh_data.COLOR_ATTRIBUTE
        color.location = shader.location - Vector((250, 0))
        tree.links.new(color.outputs["Color"], shader.inputs["Base Color"])
    return material


def legend_material():
    """The legend's material: the colour attribute as emission, so that lights and shadows leave the bar's
    colours and the labels as they are."""
    material = bpy.data.materials.get(LEGEND_MATERIAL)
    if material is None:
        material = compat.node_material(LEGEND_MATERIAL)
        tree = material.node_tree
        for node in list(tree.nodes):
            if node.type != "OUTPUT_MATERIAL":
                tree.nodes.remove(node)
        output = next(n for n in tree.nodes if n.type == "OUTPUT_MATERIAL")
        emission = tree.nodes.new("ShaderNodeEmission")
        color = tree.nodes.new("ShaderNodeVertexColor")
        color.layer_name = mesh_data.COLOR_ATTRIBUTE
        emission.location, color.location = output.location - Vector((220, 0)), output.location - Vector((440, 0))
        tree.links.new(color.outputs["Color"], emission.inputs["Color"])
        tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])
        if hasattr(material, "shadow_method"):  # EEVEE (legacy): casts no shadow
            material.shadow_method = "NONE"
    return material


def unit_of(surface, scene):
    """(name of the file's length unit or None, the import's scale) for the surface's legend."""
    centerline = surface.vesselmesh.centerline
    scale = centerline.vesselmesh.scale if centerline is not None else 1.0
    units = scene.unit_settings
    metres = units.scale_length if units.system == "METRIC" else (0.3048 * units.scale_length
                                                                    if units.system == "IMPERIAL" else 0.0)
    return legend.file_unit(scale, metres), scale


def text_color(background):
    """Dark labels on a light background, light ones on a dark one (L* 50 is the turning point)."""
    return DARK_TEXT if colors.lightness(background) >= 50.0 else LIGHT_TEXT


def new_legend(context, surface, background=None):
    """A legend object for the surface's colours (not yet placed), linked beside the surface; the
    previous one, if any, goes. Labels are dark unless the background given is dark."""
    old = live(surface.vesselmesh.legend)
    if old is not None:
        remove_legend(old)
    obj = bpy.data.objects.new(surface.name + " legend", bpy.data.meshes.new(surface.name + " legend"))
    for collection in surface.users_collection:
        collection.objects.link(obj)
    obj["text_color"] = text_color(background) if background is not None else DARK_TEXT
    surface.vesselmesh.legend = obj
    _quiet(obj)
    update_legend(obj, surface, context.scene)
    return obj


def remove_legend(obj):
    for child in list(obj.children):
        _remove_object(child)
    _remove_object(obj)


def _remove_object(obj):
    data = obj.data
    bpy.data.objects.remove(obj)
    if data is not None and data.users == 0:
        (bpy.data.meshes if isinstance(data, bpy.types.Mesh) else bpy.data.curves).remove(data)


def _quiet(obj):
    """Seen by the camera only: no shadows, reflections or light of its own on the scene."""
    for name in ("visible_shadow", "visible_diffuse", "visible_glossy", "visible_transmission",
                 "visible_volume_scatter"):
        if name in obj.bl_rna.properties:
            setattr(obj, name, False)


def legend_size(obj):
    """(width, height) of the legend in units of its bar's height, labels and title included."""
    return tuple(obj.get("extent", (1.0, 1.0)))


def update_legend(obj, surface, scene=None):
    """Rebuilds the legend's bar, ticks and labels for the surface's current colours, keeping where the
    legend is. Values are shown in the file's unit (from the import's scale), without exponents."""
    scene = scene or bpy.context.scene
    state = surface.vesselmesh
    measure = colors.MEASURES[state.color_measure]
    unit, scale = unit_of(surface, scene)
    lo, hi = legend.in_file_unit([state.color_low, state.color_high], measure.dimension, scale)
    ink = tuple(obj.get("text_color", DARK_TEXT))
    marks = legend.ticks(float(lo), float(hi), state.color_map)

    vertices, quads, rgba = legend.colorbar(state.color_map)
    vertices[:, 0] *= BAR_WIDTH
    parts = [(vertices, quads, rgba)]
    thin = 0.006
    for y, _ in marks:  # a short dark tick beside the bar at each label
        tick = np.array([[BAR_WIDTH, y - thin, 0], [BAR_WIDTH + TICK_LENGTH, y - thin, 0],
                         [BAR_WIDTH + TICK_LENGTH, y + thin, 0], [BAR_WIDTH, y + thin, 0]])
        parts.append((tick, np.array([[0, 1, 2, 3]]), np.tile(ink, (4, 1))))
    bar = obj.data
    bar.clear_geometry()
    _fill(bar, parts)
    if not bar.materials:
        bar.materials.append(legend_material())

    for child in list(obj.children):
        _remove_object(child)
    width = BAR_WIDTH + TICK_LENGTH
    x = BAR_WIDTH + TICK_LENGTH + LABEL_GAP
    for y, text in marks:
        width = max(width, x + _add_text(obj, text, (x, y), LABEL_SIZE, ink, "CENTER"))
    lines = legend.title_lines(state.color_measure, unit)
    top = 1.0 + TITLE_GAP
    for i, line in enumerate(reversed(lines)):
        width = max(width, _add_text(obj, line, (0.0, top + 1.35 * TITLE_SIZE * i), TITLE_SIZE, ink, "BOTTOM"))
    obj["extent"] = (width, top + 1.35 * TITLE_SIZE * len(lines))
    obj["values"] = (float(lo), float(hi))


def _fill(mesh, parts):
    """A mesh of quads from [(vertices, quads, rgba)], with the rgba as its colour attribute."""
    offset, vertices, quads, rgba = 0, [], [], []
    for v, q, c in parts:
        vertices.append(v)
        quads.append(q + offset)
        rgba.append(c)
        offset += len(v)
    mesh.from_pydata(np.concatenate(vertices).tolist(), [], np.concatenate(quads).tolist())  # a few hundred
    mesh_data.set_point_colors(mesh, np.concatenate(rgba))


def _add_text(parent, body, location, size, ink, align_y):
    """A label as a mesh (with the colour attribute, so Workbench shows its colour); returns its width."""
    curve = bpy.data.curves.new("label", "FONT")
    curve.body = body
    curve.size = size
    curve.align_y = align_y
    font = bpy.data.objects.new("label", curve)
    mesh = bpy.data.meshes.new_from_object(font)
    bpy.data.objects.remove(font)
    bpy.data.curves.remove(curve)
    mesh.name = parent.name + " label"
    mesh_data.set_point_colors(mesh, np.tile(ink, (len(mesh.vertices), 1)))
    mesh.materials.append(legend_material())
    text = bpy.data.objects.new(mesh.name, mesh)
    for collection in parent.users_collection:
        collection.objects.link(text)
    text.parent = parent
    text.location = (location[0], location[1], 0.0)
    _quiet(text)
    xs = [v.co.x for v in mesh.vertices]
    return max(xs) if xs else 0.0


def camera_frame(scene, camera, depth):
    """(left, right, bottom, top) of the camera's view at `depth` in front of it, in camera space."""
    frame = [Vector(c) for c in camera.data.view_frame(scene=scene)]
    if camera.data.type != "ORTHO":
        frame = [c * (depth / -c.z) for c in frame]
    xs, ys = [c.x for c in frame], [c.y for c in frame]
    return min(xs), max(xs), min(ys), max(ys)


def legend_share(obj, scene, camera, height=0.5, margin=0.04):
    """The share of the frame's width the legend takes on its right (margins included), when its bar is
    `height` of the frame's height."""
    left, right, bottom, top = camera_frame(scene, camera, 1.0)
    width, _ = legend_size(obj)
    return (width * height * (top - bottom) + 2 * margin * (right - left)) / (right - left)


def place_in_camera(obj, scene, camera, height=0.5, margin=0.04):
    """Parents the legend to the camera, at the right of its view, centred in height, its bar `height`
    of the frame's height, just past the near clip plane (so that it is drawn in front of everything)."""
    depth = 1.5 * camera.data.clip_start
    left, right, bottom, top = camera_frame(scene, camera, depth)
    s = height * (top - bottom)
    width, total = legend_size(obj)
    obj.parent = camera
    obj.matrix_parent_inverse = Matrix.Identity(4)
    obj.location = (right - margin * (right - left) - width * s, bottom + 0.5 * ((top - bottom) - total * s), -depth)
    obj.rotation_euler = (0.0, 0.0, 0.0)
    obj.scale = (s, s, s)


def place_beside(context, obj, surface):
    """Stands the legend upright beside the surface, facing the front view (-y)."""
    obj.parent = None
    context.view_layer.update()  # matrix_world of objects a script has just moved
    low, high = world_bounds(surface)
    size = max(high - low)
    obj.location = (high.x + 0.1 * size, (low.y + high.y) / 2, low.z)
    obj.rotation_euler = (math.pi / 2, 0.0, 0.0)
    obj.scale = (0.6 * size,) * 3


def add_legend(context, surface):
    """A colour bar with tick values and a title for the surface's colours: at the right of the scene
    camera's view when there is a camera (parented to it), else standing beside the surface."""
    obj = new_legend(context, surface)
    camera = context.scene.camera
    if camera is not None and camera.type == "CAMERA":
        place_in_camera(obj, context.scene, camera)
    else:
        place_beside(context, obj, surface)
    return obj


def world_bounds(obj):
    corners = [obj.matrix_world @ Vector(c) for c in obj.bound_box]
    return (Vector([min(c[i] for c in corners) for i in range(3)]),
            Vector([max(c[i] for c in corners) for i in range(3)]))
