"""Curvature colours: which map, over which range, legends in the file's unit, recolouring, and renders."""
import sys

import bpy
import numpy as np
import pytest

from helpers import attribute, import_file


@pytest.fixture
def colors():
    return sys.modules["vesselmesh"].core.colors


@pytest.fixture
def legend():
    return sys.modules["vesselmesh"].core.legend


def test_values_of_one_sign_with_a_few_saddles_get_the_sequential_map_over_their_whole_range(colors):
    """Mean curvature of a tree: 1.4 % negative. A diverging map would spend its blue half on them."""
    rng = np.random.default_rng(1)
    values = np.concatenate([rng.uniform(0.2, 4.0, 986), rng.uniform(-0.3, 0.0, 14)])
    coloring = colors.color_by(values)
    assert coloring.map == "viridis"
    assert (coloring.lo, coloring.hi) == pytest.approx(tuple(np.percentile(values, [2, 98])))
    t = colors.normalize(values, coloring.lo, coloring.hi, coloring.map)
    assert t.min() == 0.0 and t.max() == 1.0 and 0.3 < np.median(t) < 0.7  # the whole ramp is used


def test_values_of_both_signs_get_the_diverging_map_each_half_over_its_own_side(colors):
    rng = np.random.default_rng(2)
    values = np.concatenate([rng.uniform(-1.0, 0.0, 300), rng.uniform(0.0, 4.0, 700)])
    coloring = colors.color_by(values)
    assert coloring.map == "rdbu" and coloring.lo < 0 < coloring.hi
    assert coloring.lo == pytest.approx(np.percentile(values, 2)) and coloring.hi == pytest.approx(
        np.percentile(values, 98))
    t = colors.normalize([coloring.lo, 0.0, coloring.hi, coloring.lo / 2, coloring.hi / 2], coloring.lo, coloring.hi,
                         "rdbu")
    assert t == pytest.approx([0.0, 0.5, 1.0, 0.25, 0.75])  # both halves span their own side
    white = colors.map_colors([0.0], coloring.lo, coloring.hi, "rdbu")[0]
    assert np.allclose(white[:3], colors.srgb_to_linear(0xF7 / 255), atol=1e-6)  # zero at the neutral centre
    assert np.allclose(colors.value_at(t, coloring.lo, coloring.hi, "rdbu"),
                       [coloring.lo, 0.0, coloring.hi, coloring.lo / 2, coloring.hi / 2])


def test_a_chosen_map_is_kept_and_the_sequential_ends_are_viridis(colors):
    values = np.linspace(0.0, 100.0, 1001)
    coloring = colors.color_by(values, "viridis", percentile=5)
    assert (coloring.lo, coloring.hi) == pytest.approx((5.0, 95.0))
    ends = colors.map_colors([coloring.lo - 1, coloring.hi + 1], coloring.lo, coloring.hi, "viridis")
    assert np.allclose(ends[0, :3], colors.srgb_to_linear(np.array([0x44, 0x01, 0x54]) / 255))
    assert np.allclose(ends[1, :3], colors.srgb_to_linear(np.array([0xFD, 0xE7, 0x25]) / 255))
    assert colors.color_by(values, "rdbu").map == "rdbu"


def test_legend_ticks_are_round_values_in_the_files_unit_without_exponents(legend):
    # 2,390 per metre in a file in millimetres imported at 0.001: 2.39 per millimetre.
    assert legend.file_unit(0.001) == "mm" and legend.file_unit(1e-6) == "µm" and legend.file_unit(1.0) == "m"
    assert legend.file_unit(0.5) is None and legend.file_unit(0.001, metres_per_scene_unit=0.0) is None
    lo, hi = legend.in_file_unit([120.0, 2390.0], -1, 0.001)
    assert (lo, hi) == pytest.approx((0.12, 2.39))
    assert legend.in_file_unit([4e6], -2, 0.001)[0] == pytest.approx(4.0)  # Gaussian: per mm²
    labels = [text for _, text in legend.ticks(lo, hi, "viridis")]
    assert labels == ["0.5", "1.0", "1.5", "2.0"]
    for lo, hi in ((2.1e3, 8.7e4), (3.3e-5, 9.1e-4), (-0.004, 0.013)):
        marks = legend.ticks(lo, hi, "rdbu" if lo < 0 else "viridis")
        assert len(marks) >= 3
        for position, text in marks:
            assert "e" not in text and 0.0 <= position <= 1.0
            assert lo - 1e-12 <= float(text) <= hi + 1e-12
    marks = dict((text, position) for position, text in legend.ticks(-0.6, 3.2, "rdbu"))
    assert marks["0"] == pytest.approx(0.5)  # zero at the diverging bar's centre
    # Each side of a diverging bar its own round step and decimals.
    assert [text for _, text in legend.ticks(-0.11, 0.05, "rdbu")] == ["-0.10", "-0.05", "0", "0.02", "0.04"]
    assert legend.title_lines("k2", "mm") == ["Saddles and bulges", "k2 in 1/mm"]
    assert legend.title_lines("gaussian", None)[1] == "K in 1/file unit²"


def test_surface_colours_follow_the_chosen_measure_and_range(project_data, colors):
    centerline, surface = import_file(project_data / "bifurcation.swc", color_measure="mean")
    state = surface.vesselmesh
    mean = attribute(surface, "mean")
    assert state.color_measure == "mean"
    expected = colors.color_by(mean.astype(np.float64))
    assert (state.color_map, state.color_low, state.color_high) == (expected.map, pytest.approx(expected.lo),
                                                                     pytest.approx(expected.hi))
    rgba = attribute(surface, "curvature_color")
    assert np.all((rgba >= 0) & (rgba <= 1))
    assert np.allclose(rgba, colors.map_colors(mean, state.color_low, state.color_high, state.color_map), atol=1e-6)

    centerline.vesselmesh.settings.color_measure = "rms"  # recolours at once, without meshing
    assert (state.color_measure, state.color_map) == ("rms", "viridis")
    rms = attribute(surface, "rms")
    assert np.allclose(attribute(surface, "curvature_color"),
                       colors.map_colors(rms, state.color_low, state.color_high, "viridis"), atol=1e-6)


def test_the_default_colours_show_the_smaller_curvature_which_is_zero_along_straight_vessels(project_data):
    _, surface = import_file(project_data / "bifurcation.swc")
    assert surface.vesselmesh.color_measure == "k2"
    k2, k1 = attribute(surface, "k2"), attribute(surface, "k1")
    trunk = np.abs(np.median(k2)) < 0.1 * np.median(k1)  # a tube: k1 ~ 1/r, k2 ~ 0
    assert trunk


@pytest.mark.parametrize("scale", [0.001, 1.0])
def test_shape_is_mean_curvature_times_radius_a_half_along_a_vessel_whatever_its_size(project_data, scale):
    _, surface = import_file(project_data / "bifurcation.swc", scale=scale, color_measure="shape")
    shape, mean = attribute(surface, "shape"), attribute(surface, "mean")
    assert surface.vesselmesh.color_measure == "shape"
    assert abs(np.median(shape) - 0.5) < 0.05  # the same number in metres and in millimetres
    radius = shape / mean
    assert 0.55 * scale * 0.99 < np.median(radius) < 1.0 * scale * 1.01  # the file's radii, in scene units


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
    data = meshing.read_centerline(project_data / "bifurcation.swc")
    job = meshing.MeshJob(lambda: meshing.centerline_graph(**data), {}, ("mean", "auto", 2.0))
    name, lo, hi, rgba = job.coloring(("mean", "auto", 2.0))
    assert name == "viridis" and lo < hi and rgba.shape == (len(job.surface()[0]), 4)
    assert job.coloring(("rms", "auto", 2.0)) is None  # the settings changed while it ran: colour anew
    no_curvature = meshing.MeshJob(lambda: meshing.centerline_graph(**data), {}, None)
    assert no_curvature.coloring(("mean", "auto", 2.0)) is None
    job.close()
    no_curvature.close()


def test_legend_shows_the_range_in_the_files_unit_at_the_right_of_the_cameras_view(project_data, legend):
    _, surface = import_file(project_data / "bifurcation.swc", scale=0.001, color_measure="mean")
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    bpy.context.scene.collection.objects.link(camera)
    bpy.context.scene.camera = camera
    assert bpy.ops.vesselmesh.legend() == {"FINISHED"}
    obj = surface.vesselmesh.legend
    assert obj.parent == camera and obj.location.x > 0  # right of the view's centre
    state = surface.vesselmesh
    assert state.color_high > 1000  # per metre: the file is in millimetres
    low, high = obj["values"]
    assert (low, high) == pytest.approx((0.001 * state.color_low, 0.001 * state.color_high))
    labels = [child for child in obj.children]
    assert all(child.type == "MESH" and "curvature_color" in child.data.color_attributes for child in labels)
    assert "curvature_color" in obj.data.color_attributes
    assert obj.data.materials[0].name == "VesselMesh legend"

    before = len(obj.children)
    surface.vesselmesh.centerline.vesselmesh.settings.color_measure = "gaussian"  # the legend follows
    assert surface.vesselmesh.legend["values"][1] == pytest.approx(1e-6 * state.color_high)
    assert len(surface.vesselmesh.legend.children) > 0 and before > 0


@pytest.mark.parametrize("engine", ["BLENDER_WORKBENCH", "CYCLES"])
def test_a_render_shows_the_curvature_colours(project_data, tmp_path, engine):
    """Workbench shows the colour attribute; Cycles renders it through the material. Coloured by the mean
    curvature on viridis, the tubes come out coloured (not the grey of an uncoloured surface)."""
    import_file(project_data / "bifurcation.swc", color_measure="mean")
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
    colourful = covered[:, :3].max(axis=1) - covered[:, :3].min(axis=1) > 0.1
    assert colourful.mean() > 0.5
