"""Teaching Render: a scene set up for a lecture picture of vessel surfaces.

A camera that frames the vessels with a margin and leaves the right of the frame to the legend (so the
two never overlap), three soft lights (key, fill, rim) and a studio world, a background that stands out
from both ends of the colour map, ambient occlusion and soft shadows for depth, a legend in the file's
unit, and render settings for EEVEE, Cycles and Workbench. The geometry of it is core.framing's."""
import bpy
import numpy as np
from mathutils import Matrix, Vector

from .. import compat
from ..core import framing
from . import mesh as mesh_data
from .paint import legend_share, live, new_legend, place_in_camera

CAMERA = "VesselMesh camera"
WORLD = "VesselMesh studio"
LIGHT_PREFIX = "VesselMesh "
# The key light's power over its squared distance (W/m², about what lights a white wall to just below
# white in the Standard view), and the world's light around the vessels.
LIGHT_POWER = 12.0
AMBIENT = 0.08
ENGINES = {"EEVEE": None, "CYCLES": "CYCLES", "WORKBENCH": "BLENDER_WORKBENCH"}


def surfaces_in(scene):
    """The VesselMesh surfaces the scene renders."""
    return [o for o in scene.objects if o.vesselmesh.role == "SURFACE" and o.type == "MESH" and not o.hide_render]


def world_points(surfaces):
    """A sample of the surfaces' vertices in world coordinates."""
    parts = []
    for obj in surfaces:
        local = framing.sample(mesh_data.triangles(obj.data)[0], 60000 // max(len(surfaces), 1))
        matrix = np.array(obj.matrix_world)
        parts.append(local @ matrix[:3, :3].T + matrix[:3, 3])
    return np.concatenate(parts)


def _camera(scene):
    camera = bpy.data.objects.get(CAMERA)
    if camera is None or camera.type != "CAMERA":
        camera = bpy.data.objects.new(CAMERA, bpy.data.cameras.new(CAMERA))
    if scene.collection not in camera.users_collection and not any(c in scene.collection.children_recursive
                                                                      for c in camera.users_collection):
        scene.collection.objects.link(camera)
    scene.camera = camera
    camera.data.type = "PERSP"
    camera.data.lens = 50.0
    camera.data.sensor_fit = "AUTO"
    camera.data.shift_x = camera.data.shift_y = 0.0
    return camera


def _light(scene, name, position, target, power, size):
    full = LIGHT_PREFIX + name
    obj = bpy.data.objects.get(full)
    if obj is None or obj.type != "LIGHT":
        obj = bpy.data.objects.new(full, bpy.data.lights.new(full, "AREA"))
        scene.collection.objects.link(obj)
    light = obj.data
    light.type = "AREA"
    light.shape = "DISK"
    light.size = size
    light.energy = power
    light.color = (1.0, 0.97, 0.93) if name == "key" else (0.93, 0.96, 1.0)
    if hasattr(light, "use_contact_shadow"):
        light.use_contact_shadow = True
    obj.location = Vector(position)
    obj.rotation_euler = (Vector(target) - Vector(position)).to_track_quat("-Z", "Y").to_euler()
    return obj


def _world(scene, background, ambient=None):
    ambient = AMBIENT if ambient is None else ambient
    """A world that the camera sees as `background` and that lights the vessels softly from every side."""
    world = bpy.data.worlds.get(WORLD) or bpy.data.worlds.new(WORLD)
    scene.world = world
    world.color = background  # Workbench's background
    if not world.use_nodes:
        world.use_nodes = True
    tree = world.node_tree
    tree.nodes.clear()
    output = tree.nodes.new("ShaderNodeOutputWorld")
    light_path = tree.nodes.new("ShaderNodeLightPath")
    seen = tree.nodes.new("ShaderNodeBackground")
    lighting = tree.nodes.new("ShaderNodeBackground")
    mix = tree.nodes.new("ShaderNodeMixShader")
    seen.inputs["Color"].default_value = (*background, 1.0)
    lighting.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    lighting.inputs["Strength"].default_value = ambient
    tree.links.new(lighting.outputs[0], mix.inputs[1])
    tree.links.new(seen.outputs[0], mix.inputs[2])
    tree.links.new(light_path.outputs["Is Camera Ray"], mix.inputs[0])
    tree.links.new(mix.outputs[0], output.inputs["Surface"])
    return world


def _render_settings(scene, engine, size, samples):
    if engine == "EEVEE":
        compat.set_eevee(scene)
    else:
        scene.render.engine = ENGINES[engine]
    scene.view_settings.view_transform = "Standard"  # the colour map's colours as they are
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.render.film_transparent = False
    # EEVEE: ambient occlusion (depth where vessels meet and pass behind one another), soft shadows.
    compat.set_present(scene.eevee, use_gtao=True, gtao_distance=0.15 * size, gtao_factor=1.2,
                       use_soft_shadows=True, shadow_cube_size="2048", taa_render_samples=samples, use_bloom=False)
    cycles = scene.cycles
    cycles.samples = samples
    cycles.use_adaptive_sampling = True
    cycles.max_bounces, cycles.diffuse_bounces, cycles.glossy_bounces = 4, 2, 2
    cycles.transmission_bounces = cycles.volume_bounces = cycles.transparent_max_bounces = 0
    cycles.use_denoising = _has_denoiser()
    shading = scene.display.shading
    shading.light = "STUDIO"
    if "paint.sl" in bpy.context.preferences.studio_lights:  # brighter than Default: colours read true
        shading.studio_light = "paint.sl"
    shading.color_type = "VERTEX"  # Workbench shows the colour attribute (surface and legend)
    shading.show_cavity = True  # Workbench's ambient occlusion
    shading.cavity_type = "BOTH"
    shading.show_shadows = True
    shading.shadow_intensity = 0.35
    shading.show_object_outline = True
    scene.display.render_aa = "8"
    scene.display.light_direction = (-0.45, 0.35, 0.82)


def _has_denoiser():
    try:
        import _cycles
        return bool(_cycles.with_openimagedenoise)
    except (ImportError, AttributeError):
        return False


def set_up(context, surfaces=None, engine="EEVEE", background="auto", samples=64, legend=True, margin=0.05):
    """Sets the scene up for a teaching picture of `surfaces` (default: every VesselMesh surface it
    renders) and returns {"camera", "legend", "lights", "world", "region"}; region is the part of the
    frame, in tangent units of the camera's view, the vessels are fitted into. Rerunning it replaces what
    it made before. The scene's resolution is kept (the framing follows its aspect)."""
    scene = context.scene
    surfaces = surfaces or surfaces_in(scene)
    if not surfaces:
        raise RuntimeError("no vessel surface to render: import a centerline first")
    context.view_layer.update()
    points = world_points(surfaces)
    low, high = points.min(axis=0), points.max(axis=0)
    size = float(np.linalg.norm(high - low))
    coloured = [s for s in surfaces if s.vesselmesh.color_map]
    back = framing.background_for(coloured[0].vesselmesh.color_map if coloured else "viridis", background)

    camera = _camera(scene)
    legend_obj = None
    if legend and coloured:
        legend_obj = new_legend(context, coloured[0], back)
    for surface in surfaces:  # legends of the other surfaces would stand in the picture
        other = live(surface.vesselmesh.legend)
        if other is not None and other != legend_obj and legend_obj is not None:
            other.hide_render = True
    frame = [Vector(c) for c in camera.data.view_frame(scene=scene)]
    frame = [c / -c.z for c in frame]  # tangent units
    x0, x1 = min(c.x for c in frame), max(c.x for c in frame)
    y0, y1 = min(c.y for c in frame), max(c.y for c in frame)
    share = legend_share(legend_obj, scene, camera) if legend_obj is not None else 0.0
    width, height = x1 - x0, y1 - y0
    region = (x0 + margin * width, x1 - (share + margin * (0.5 if share else 1.0)) * width,
              y0 + margin * height, y1 - margin * height)

    right_axis, up_axis, forward = framing.view_axes(points)
    location, distance = framing.fit(points, right_axis, up_axis, forward, region)
    camera.matrix_world = Matrix((right_axis, up_axis, -forward)).transposed().to_4x4()
    camera.location = Vector(location)
    camera.data.clip_start = max(1e-6, 0.02 * distance)
    camera.data.clip_end = 10.0 * (distance + size)
    if legend_obj is not None:
        place_in_camera(legend_obj, scene, camera)

    target = points.mean(axis=0)
    lights = []
    for name, position, share_of_power in framing.lights(location, target, right_axis, up_axis, forward, size):
        reach = float(np.linalg.norm(position - target))
        lights.append(_light(scene, name, position, target, LIGHT_POWER * share_of_power * reach ** 2, 0.5 * size))
    world = _world(scene, back)
    _render_settings(scene, engine, size, samples)
    return {"camera": camera, "legend": legend_obj, "lights": lights, "world": world, "region": region,
            "background": back}
