"""Teaching Render: the vessels framed beside the legend, lit, on a background that stands out from the
colour map; checked by geometry, then by the pixels of small renders in every engine."""
import sys

import bpy
import numpy as np
import pytest
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

from helpers import arrays, import_file


@pytest.fixture
def framing():
    return sys.modules["vesselmesh"].core.framing


def set_up(project_data, engine="WORKBENCH", size=(160, 100), samples=4, **options):
    _, surface = import_file(project_data / "bifurcation.swc", scale=0.001, **options)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    assert bpy.ops.vesselmesh.teaching_render(engine=engine, samples=samples) == {"FINISHED"}
    bpy.context.view_layer.update()
    return scene, surface


def projected(scene, obj, points):
    """(x, y) of points of obj in the camera's frame, 0 to 1 from the lower left."""
    matrix = obj.matrix_world
    return np.array([world_to_camera_view(scene, scene.camera, matrix @ Vector(p))[:2] for p in points])


def test_vessels_fill_the_frame_left_of_the_legend_with_a_margin(project_data):
    scene, surface = set_up(project_data)
    vertices = projected(scene, surface, arrays(surface)[0])
    legend = surface.vesselmesh.legend
    corners = np.concatenate([projected(scene, part, [Vector(c) for c in part.bound_box])
                              for part in [legend, *legend.children]])
    assert legend.parent == scene.camera
    assert vertices.min() > 0.03 and vertices[:, 1].max() < 0.97  # a margin on every side
    assert vertices[:, 0].max() < corners[:, 0].min()  # the legend never overlaps the vessels
    assert corners[:, 0].max() < 0.99 and corners[:, 1].min() > 0.0 and corners[:, 1].max() < 1.0
    spread = vertices.max(axis=0) - vertices.min(axis=0)
    assert spread[0] > 0.5 * corners[:, 0].min() or spread[1] > 0.85  # the vessels fill their part


def test_three_soft_lights_a_studio_world_and_depth_cues_in_every_engine(project_data):
    scene, _ = set_up(project_data, engine="EEVEE")
    lights = sorted(o.name for o in scene.objects if o.type == "LIGHT")
    assert lights == ["VesselMesh fill", "VesselMesh key", "VesselMesh rim"]
    assert all(bpy.data.objects[name].data.type == "AREA" for name in lights)
    assert scene.world.name == "VesselMesh studio"
    assert scene.eevee.use_gtao and scene.eevee.use_soft_shadows  # EEVEE: ambient occlusion, soft shadows
    assert scene.display.shading.show_cavity and scene.display.shading.show_shadows  # Workbench
    assert scene.view_settings.view_transform == "Standard"
    assert scene.render.engine in {"BLENDER_EEVEE", "BLENDER_EEVEE_NEXT"}
    assert bpy.ops.vesselmesh.teaching_render(engine="CYCLES") == {"FINISHED"}
    assert scene.render.engine == "CYCLES" and not scene.cycles.use_denoising  # no OpenImageDenoise here
    assert sorted(o.name for o in scene.objects if o.type == "LIGHT") == lights  # set up again, not twice


def test_the_background_stands_out_from_both_ends_of_the_map(framing):
    colors = sys.modules["vesselmesh"].core.colors
    for name in colors.COLORMAPS:
        background = framing.background_for(name)
        assert min(abs(colors.lightness(background) - end) for end in colors.map_lightness(name)) > 30


def test_the_view_looks_broadside_at_a_flat_network_and_keeps_z_up_for_a_tree(framing):
    rng = np.random.default_rng(3)
    flat = np.c_[rng.uniform(-10, 10, (500, 2)), rng.uniform(-0.2, 0.2, 500)]  # a network in the xy plane
    right, up, forward = framing.view_axes(flat)
    assert forward[2] < -0.9  # looking down on it
    tree = np.c_[rng.uniform(-5, 5, 500), rng.uniform(-1, 1, 500), rng.uniform(0, 20, 500)]  # tall in z
    right, up, forward = framing.view_axes(tree)
    assert up[2] > 0.9 and abs(forward[1]) > 0.8  # z stays up; seen across its thin side


def _pixels(scene, path):
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(str(path))
    width, height = image.size
    pixels = np.array(image.pixels[:]).reshape(height, width, 4)[::-1, :, :3]  # top row first
    bpy.data.images.remove(image)
    return pixels


@pytest.mark.parametrize("engine", ["WORKBENCH", "CYCLES", "EEVEE"])
def test_the_render_shows_vessels_and_a_legible_legend_on_the_background(project_data, tmp_path, engine):
    scene, surface = set_up(project_data, engine=engine, size=(240, 150), samples=4, color_measure="mean")
    pixels = _pixels(scene, tmp_path / f"{engine}.png")
    height, width, _ = pixels.shape
    colors = sys.modules["vesselmesh"].core.colors
    background = colors.linear_to_srgb(np.array(scene.world.color))
    corner = pixels[:5, :5].reshape(-1, 3)
    assert np.allclose(corner, background, atol=0.03)  # the corners show the background
    legend = surface.vesselmesh.legend
    strip = pixels[:, int(0.8 * width):]
    off = np.abs(strip - background).max(axis=2) > 0.1
    assert off.mean() > 0.02  # the legend stands in its strip
    # Its bar shows the map's yellow end (viridis), and dark labels stand out from the grey.
    yellow = (strip[:, :, 0] > 0.6) & (strip[:, :, 1] > 0.6) & (strip[:, :, 2] < 0.35)
    purple = (strip[:, :, 2] > strip[:, :, 1] + 0.1) & (strip.max(axis=2) < 0.45)
    assert yellow.sum() >= 2 and purple.sum() >= 2
    ink = (strip.max(axis=2) < background.max() - 0.2) & (np.ptp(strip, axis=2) < 0.05)  # grey, darker
    assert ink.sum() >= 10
    vessels = pixels[:, : int(0.7 * width)]
    covered = np.abs(vessels - background).max(axis=2) > 0.08
    assert covered.mean() > 0.05
    assert legend.parent == scene.camera
