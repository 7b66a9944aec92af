"""Curvature colours: the maps, their ranges, recolouring, the legend, and a render that shows them."""
import sys

import bpy
import numpy as np
import pytest

from helpers import attribute, import_file


@pytest.fixture
def colors():
    return sys.modules["vesselmesh"].core.colors


def test_signed_measures_get_a_range_centred_on_zero_and_a_diverging_map(colors):
    values = np.array([-0.5, 0.1, 0.2, 0.3, 2.0])
    lo, hi = colors.value_range(values, "mean", percentile=0)
    assert (lo, hi) == (-2.0, 2.0)
    assert colors.colormap_for("mean") == "rdbu" and colors.colormap_for("gaussian") == "rdbu"
    white = colors.map_colors([0.0], lo, hi, "rdbu")[0]
    assert np.allclose(white[:3], colors.srgb_to_linear(0xF7 / 255), atol=1e-6)  # the map's neutral centre


def test_unsigned_measures_get_viridis_over_their_percentile_range(colors):
    values = np.linspace(0.0, 100.0, 1001)
    lo, hi = colors.value_range(values, "rms", percentile=5)
    assert (lo, hi) == pytest.approx((5.0, 95.0))
    assert colors.colormap_for("rms") == "viridis"
    ends = colors.map_colors([lo - 1, hi + 1], lo, hi, "viridis")
    assert np.allclose(ends[0, :3], colors.srgb_to_linear(np.array([0x44, 0x01, 0x54]) / 255))
    assert np.allclose(ends[1, :3], colors.srgb_to_linear(np.array([0xFD, 0xE7, 0x25]) / 255))


def test_surface_colours_follow_the_chosen_measure_and_range(project_data, colors):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    state = surface.vesselmesh
    mean = attribute(surface, "mean")
    assert (state.color_measure, state.color_map) == ("mean", "rdbu")
    assert state.color_low == pytest.approx(-state.color_high)
    assert state.color_high == pytest.approx(np.abs(np.percentile(mean, [2, 98])).max(), rel=1e-6)
    rgba = attribute(surface, "curvature_color")
    assert np.all((rgba >= 0) & (rgba <= 1))
    assert np.allclose(rgba, colors.map_colors(mean, state.color_low, state.color_high, "rdbu"), atol=1e-6)

    centerline.vesselmesh.settings.color_measure = "rms"  # recolours at once, without meshing
    assert (state.color_measure, state.color_map) == ("rms", "viridis")
    rms = attribute(surface, "rms")
    assert np.allclose(attribute(surface, "curvature_color"),
                       colors.map_colors(rms, state.color_low, state.color_high, "viridis"), atol=1e-6)


def test_import_colours_by_the_measure_map_and_range_it_was_given(project_data, colors):
    _, surface = import_file(project_data / "bifurcation.swc", color_measure="rms", colormap="rdbu", percentile=10)
    state = surface.vesselmesh
    rms = attribute(surface, "rms")
    assert (state.color_measure, state.color_map) == ("rms", "rdbu")
    assert (state.color_low, state.color_high) == pytest.approx(tuple(np.percentile(rms, [10, 90])), rel=1e-6)
    assert np.allclose(attribute(surface, "curvature_color"),
                       colors.map_colors(rms, state.color_low, state.color_high, "rdbu"), atol=1e-6)


def test_a_mesh_job_hands_over_its_colours_only_for_the_settings_it_coloured_by(project_data):
    meshing = sys.modules["vesselmesh"].core.meshing
    graph = meshing.centerline_graph(**meshing.read_centerline(project_data / "bifurcation.swc"))
    job = meshing.MeshJob(graph, {}, ("mean", "auto", 2.0))
    name, lo, hi, rgba = job.coloring(("mean", "auto", 2.0))
    assert name == "rdbu" and lo == -hi and rgba.shape == (len(job.surface()[0]), 4)
    assert job.coloring(("rms", "auto", 2.0)) is None  # the settings changed while it ran: colour anew
    assert meshing.MeshJob(graph, {}, None).coloring(("mean", "auto", 2.0)) is None  # no curvature asked for


def test_legend_shows_the_colour_range_in_the_cameras_view(project_data):
    _, surface = import_file(project_data / "bifurcation.swc")
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    bpy.context.scene.collection.objects.link(camera)
    bpy.context.scene.camera = camera
    assert bpy.ops.vesselmesh.legend() == {"FINISHED"}
    legend = surface.vesselmesh.legend
    assert legend.parent == camera
    labels = sorted((child.location.y, child.data.body) for child in legend.children)
    state = surface.vesselmesh
    assert float(labels[0][1]) == pytest.approx(state.color_low, rel=5e-3)  # 3 significant digits
    assert labels[-1][1] == "mean curvature"
    assert "curvature_color" in legend.data.color_attributes

    surface.vesselmesh.centerline.vesselmesh.settings.color_measure = "gaussian"
    assert sorted(child.data.body for child in legend.children)[-1] == "Gaussian curvature"


@pytest.mark.parametrize("engine", ["BLENDER_WORKBENCH", "CYCLES"])
def test_a_render_shows_the_curvature_colours(project_data, tmp_path, engine):
    """Workbench shows the colour attribute; Cycles renders it through the material. Coloured by the
    mean curvature, the convex tubes come out red (not the grey of an uncoloured surface)."""
    _, surface = import_file(project_data / "bifurcation.swc")
    scene = bpy.context.scene
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    camera.location, camera.rotation_euler = (0.0, -30.0, 5.0), (np.pi / 2, 0.0, 0.0)
    light = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    light.rotation_euler = (0.5, 0.0, 0.0)
    scene.collection.objects.link(light)
    scene.render.engine = engine
    scene.render.resolution_x, scene.render.resolution_y = 80, 60
    scene.render.film_transparent = True
    scene.display.shading.color_type = "VERTEX"
    scene.cycles.samples = 4
    scene.cycles.use_denoising = False  # this Blender is built without OpenImageDenoise
    scene.render.filepath = str(tmp_path / "render.png")
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(scene.render.filepath)
    pixels = np.array(image.pixels[:]).reshape(-1, 4)
    covered = pixels[pixels[:, 3] > 0.5]
    assert len(covered) > 0.05 * len(pixels)
    red = covered[:, 0] > covered[:, 2] + 0.1
    assert red.mean() > 0.5
