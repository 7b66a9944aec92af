"""File > Import: every format gives an editable centerline object and a closed, coloured surface."""
import json
import sys

import bpy
import numpy as np
import pytest

import vesselmesh_core as vm
from helpers import arrays, assert_closed_manifold, attribute, import_file, topology

FILES = ["bifurcation.swc", "ring_with_tail.vtk", "y_vertices.csv", "two_lines.vtp"]


@pytest.mark.parametrize("name", FILES)
def test_each_format_imports_as_a_centerline_and_a_closed_surface(project_data, name):
    centerline, surface = import_file(project_data / name)
    data = vm.read(str(project_data / name))
    assert len(centerline.data.vertices) == len(data["points"])
    assert len(centerline.data.edges) == len(data["edges"])
    assert len(centerline.data.polygons) == 0
    radius = centerline.data.attributes["radius"]
    assert radius.data_type == "FLOAT"
    assert radius.domain == ("POINT" if data["radius"] is not None else "EDGE")
    assert_closed_manifold(surface)
    assert centerline.vesselmesh.surface == surface and surface.vesselmesh.centerline == centerline
    assert centerline.vesselmesh.source == str(project_data / name)
    assert bpy.context.active_object == surface


def test_surface_has_the_curvature_attributes_and_an_active_colour_attribute(project_data):
    _, surface = import_file(project_data / "bifurcation.swc")
    mesh = surface.data
    for name in ("k1", "k2", "mean", "gaussian", "rms"):
        attr = mesh.attributes[name]
        assert (attr.data_type, attr.domain) == ("FLOAT", "POINT")
        assert np.all(np.isfinite(attribute(surface, name)))
    color = mesh.color_attributes["curvature_color"]
    assert (color.data_type, color.domain) == ("FLOAT_COLOR", "POINT")
    assert mesh.color_attributes.active_color.name == "curvature_color"
    assert mesh.color_attributes.render_color_index == mesh.color_attributes.active_color_index
    assert mesh.materials[0].name == "VesselMesh curvature"


def test_import_options_are_stored_on_the_centerline_and_used(project_data):
    _, coarse = import_file(project_data / "bifurcation.swc", levels=0, caps="open", curvature=False)
    centerline, fine = import_file(project_data / "bifurcation.swc", levels=2, method="uniform", caps="open")
    settings = centerline.vesselmesh.settings
    assert (settings.levels, settings.method, settings.caps) == (2, "uniform", "open")
    assert len(fine.data.polygons) == 16 * len(coarse.data.polygons)  # uniform Loop: 4 triangles per triangle
    assert topology(fine)["boundary_edges"] > 0  # open ends
    assert "mean" not in coarse.data.attributes and "curvature_color" not in coarse.data.color_attributes


def test_scale_multiplies_coordinates_and_radii(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    small_centerline, small_surface = import_file(project_data / "bifurcation.swc", scale=0.001)
    assert np.allclose(_points(small_centerline), 0.001 * _points(centerline), rtol=1e-6)
    assert np.allclose(attribute(small_centerline, "radius"), 0.001 * attribute(centerline, "radius"), rtol=1e-6)
    assert np.allclose(small_surface.dimensions, 0.001 * surface.dimensions, rtol=1e-3)


def _points(obj):
    points = np.empty(3 * len(obj.data.vertices), dtype=np.float32)
    obj.data.vertices.foreach_get("co", points)
    return points.reshape(-1, 3)


@pytest.mark.parametrize("file, setting, default, other, counted", [
    ("bifurcation.swc", "fit", "onto", "none", "fitted_vertices"),
    ("crossing.swc", "crossings", "separate", "keep", "separated_points")])
def test_setting_reaches_the_core_and_is_kept_for_regeneration(project_data, file, setting, default, other, counted):
    centerline, surface = import_file(project_data / file)
    assert getattr(centerline.vesselmesh.settings, setting) == default
    assert json.loads(surface.vesselmesh.stats)[counted] > 0
    centerline, surface = import_file(project_data / file, **{setting: other})
    assert getattr(centerline.vesselmesh.settings, setting) == other
    assert json.loads(surface.vesselmesh.stats)[counted] == 0


def test_default_settings_are_the_cores_defaults(project_data):
    """The import operator with its defaults builds what vesselmesh_core.mesh builds with its own."""
    meshing = sys.modules["vesselmesh"].core.meshing
    _, surface = import_file(project_data / "bifurcation.swc")
    expected = vm.mesh(meshing.centerline_graph(**meshing.read_centerline(project_data / "bifurcation.swc")))
    vertices, faces = arrays(surface)
    np.testing.assert_array_equal(faces, expected["faces"])
    np.testing.assert_allclose(vertices, expected["vertices"], rtol=0, atol=1e-6)


def test_check_surface_stores_the_checkers_report_on_the_surface(project_data):
    _, surface = import_file(project_data / "bifurcation.swc")
    assert bpy.ops.vesselmesh.check() == {"FINISHED"}
    report = json.loads(surface.vesselmesh.stats)["check"]
    assert report["closed_manifold"] and report["topology"]["genus"] == 0
    assert report["intersections"]["pairs"] == 0
    assert report["fidelity"]["abs_relative_error"]["p95"] < 0.08
    assert report["fidelity"]["area_off_tubes"] < 0.01
    assert report["input_overlaps"] == []


def test_check_surface_measures_it_against_the_vessels_as_moved_apart(project_data):
    """The surface follows the crossing vessels moved apart, and the check measures it against them: the
    moves are no error (against the file's tubes, 16 % of crossing.swc's surface lies off them)."""
    _, surface = import_file(project_data / "crossing.swc")
    assert bpy.ops.vesselmesh.check() == {"FINISHED"}
    fidelity = json.loads(surface.vesselmesh.stats)["check"]["fidelity"]
    assert fidelity["area_off_tubes"] < 0.01
    assert fidelity["abs_relative_error"]["p95"] < 0.05


def test_check_surface_says_where_the_centerlines_tubes_overlap(tmp_path):
    """A vessel that turns back across its own start, three times thinner there: kept as it is, the surface's
    crossings are where the tubes overlap, and the report says where; moved apart, the surface crosses
    nowhere, and the report still says where the centerline's tubes overlap."""
    path = tmp_path / "crosses_itself.swc"
    path.write_text("1 1 0 0 0 1 -1\n2 1 10 0 0 1 1\n3 1 20 0 0 1 2\n4 1 0 10 0 1 1\n5 1 10 10 0.3 0.3 4\n"
                    "6 1 10 -10 0.3 0.3 5\n")
    for crossings in ("keep", "separate"):
        _, surface = import_file(path, crossings=crossings)
        assert bpy.ops.vesselmesh.check() == {"FINISHED"}
        report = json.loads(surface.vesselmesh.stats)["check"]
        pairs = report["intersections"]["pairs"]
        assert pairs > 0 if crossings == "keep" else pairs == 0
        assert report["intersections"]["pairs_in_overlapping_tubes"] == pairs
        [overlap] = report["input_overlaps"]
        assert np.allclose(overlap["at"], [10, 0, 0.15], atol=0.1)
        assert overlap["crossing_pairs"] == overlap["edge_pairs"] > 0
