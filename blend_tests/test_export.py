"""File > Export > Vessel surface: each format keeps what the add-on computed, read back from the file."""
import json
import struct
import sys

import bpy
import numpy as np
import pytest

import vesselmesh_core as vm
from helpers import arrays, attribute, import_file


@pytest.fixture
def surface(project_data):
    _, surface = import_file(project_data / "bifurcation.swc", scale=0.001)
    surface.vesselmesh.centerline.location = (0.5, -0.25, 2.0)  # the file holds world coordinates
    bpy.context.view_layer.update()
    return surface


def export(surface, path, **options):
    bpy.context.view_layer.objects.active = surface
    assert bpy.ops.export_mesh.vesselmesh(filepath=str(path), **options) == {"FINISHED"}
    return path


def world_vertices(surface):
    vertices, _ = arrays(surface)
    matrix = np.array(surface.matrix_world)
    return vertices @ matrix[:3, :3].T + matrix[:3, 3]


def srgb8(surface):
    colors = sys.modules["vesselmesh"].core.colors
    return colors.linear_to_srgb8(attribute(surface, "curvature_color"))


def test_ply_holds_colours_and_the_curvature_values(surface, tmp_path):
    path = export(surface, tmp_path / "tree.ply", file_format="PLY")
    read = vm.read_mesh(str(path))
    # Float, as nothing merges or flattens this near the origin; the world coordinates computed in double.
    np.testing.assert_array_equal(read["vertices"], world_vertices(surface).astype(np.float32))
    np.testing.assert_array_equal(read["faces"], arrays(surface)[1])
    for name in ("k1", "k2", "mean", "gaussian", "rms"):
        np.testing.assert_allclose(read["properties"][name], attribute(surface, name), rtol=1e-6)
    rgb = srgb8(surface)
    for channel, name in enumerate(("red", "green", "blue")):
        np.testing.assert_array_equal(read["properties"][name], rgb[:, channel])


def test_blenders_own_ply_importer_reads_the_colours_back(surface, tmp_path):
    path = export(surface, tmp_path / "tree.ply", file_format="PLY")
    bpy.ops.import_mesh.ply(filepath=str(path))
    imported = bpy.context.selected_objects[0]
    assert len(imported.data.vertices) == len(surface.data.vertices)
    layer = imported.data.vertex_colors[0]  # 3.4's PLY importer: byte colours per corner
    corner = np.empty(4 * len(layer.data), dtype=np.float32)
    layer.data.foreach_get("color", corner)
    assert np.ptp(corner.reshape(-1, 4)[:, :3], axis=0).max() > 0.2  # not one flat colour


def test_ply_in_the_files_unit_undoes_the_import_scale_for_lengths_and_curvature(surface, tmp_path):
    path = export(surface, tmp_path / "tree_mm.ply", file_format="PLY", units="FILE")
    read = vm.read_mesh(str(path))
    np.testing.assert_allclose(read["vertices"], 1000 * world_vertices(surface), rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(read["properties"]["mean"], 0.001 * attribute(surface, "mean"), rtol=1e-5)
    np.testing.assert_allclose(read["properties"]["gaussian"], 1e-6 * attribute(surface, "gaussian"), rtol=1e-5)


def test_ply_and_obj_name_the_loops_the_surface_closed_as_the_command_line_does(project_data, tmp_path):
    # A loop of radius 4 filling its own hole at its joint: the surface closes it inside the joint's patch.
    _, surface = import_file(project_data / "extreme" / "fat_loop_round_a_thin_branch.vtk", scale=0.001)
    surface.vesselmesh.centerline.location = (0.5, -0.25, 2.0)
    bpy.context.view_layer.update()
    lost = json.loads(surface.vesselmesh.stats)["lost_loops"]
    assert len(lost) == 1
    matrix = np.array(surface.matrix_world)
    ends = [1000 * (np.array(p) @ matrix[:3, :3].T + matrix[:3, 3]) for p in lost[0]["joints"]]
    for fmt in ("PLY", "OBJ"):
        path = export(surface, tmp_path / f"loop.{fmt.lower()}", file_format=fmt, units="FILE")
        lines = [c for c in vm.read_mesh(str(path))["comments"] if c.startswith("lost loop: ")]
        assert len(lines) == 1, fmt
        assert lines[0].endswith(f"closed inside a joint patch: {lost[0]['why']}"), lines[0]
        # In the file's unit and world place, as its vertices: the ends of the loop's branch through the patch.
        written = [np.array([float(x) for x in part.split(")")[0].split(", ")])
                   for part in lines[0].split("(")[1:3]]
        np.testing.assert_allclose(written, ends, rtol=1e-5, atol=1e-6)
    assert not vm.read_mesh(str(export(surface, tmp_path / "loop.stl", file_format="STL")))["comments"]


def test_obj_holds_colours_and_a_material_that_blenders_importer_reads(surface, tmp_path):
    path = export(surface, tmp_path / "tree.obj", file_format="OBJ")
    read = vm.read_mesh(str(path))
    np.testing.assert_allclose(read["vertices"], world_vertices(surface), rtol=0, atol=1e-7)
    assert (tmp_path / "tree.mtl").read_text().count("newmtl VesselMesh_curvature") == 1
    bpy.ops.wm.obj_import(filepath=str(path), forward_axis="Y", up_axis="Z")
    imported = bpy.context.selected_objects[0]
    assert [m.name for m in imported.data.materials] == ["VesselMesh_curvature"]
    color = imported.data.color_attributes[0]
    rgba = np.empty(4 * len(color.data), dtype=np.float32)
    color.data.foreach_get("color", rgba)
    colors = sys.modules["vesselmesh"].core.colors
    expected = colors.srgb_to_linear(srgb8(surface)[:, :3] / 255.0)
    np.testing.assert_allclose(rgba.reshape(-1, 4)[:, :3], expected, atol=2e-3)


def test_gltf_holds_colours_and_the_curvature_values(surface, tmp_path):
    path = export(surface, tmp_path / "tree.glb", file_format="GLB")
    data = path.read_bytes()
    length, = struct.unpack_from("<I", data, 12)
    document = json.loads(data[20:20 + length])
    attributes = document["meshes"][0]["primitives"][0]["attributes"]
    assert "COLOR_0" in attributes and {"_MEAN", "_K2", "_GAUSSIAN"} <= set(attributes)
    binary = data[20 + length + 8:]

    def accessor(index):
        a = document["accessors"][index]
        view = document["bufferViews"][a["bufferView"]]
        width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[a["type"]]
        dtype = {5126: np.float32, 5123: np.uint16, 5121: np.uint8}[a["componentType"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        return np.frombuffer(binary, dtype=dtype, count=a["count"] * width, offset=start).reshape(a["count"], width)

    mean = accessor(attributes["_MEAN"])[:, 0]
    assert np.isclose(np.median(mean), np.median(attribute(surface, "mean")), rtol=1e-3)
    assert accessor(attributes["COLOR_0"]).shape[1] in (3, 4)


def test_stl_holds_the_shape_and_a_surface_far_from_the_origin_is_refused_naming_ply_and_obj(surface, tmp_path):
    path = export(surface, tmp_path / "tree.stl", file_format="STL", units="FILE")
    read = vm.read_mesh(str(path))
    assert len(read["faces"]) == len(surface.data.polygons)
    surface.vesselmesh.centerline.location = (1e9, 0.0, 0.0)  # float cannot place its triangles there
    bpy.context.view_layer.update()
    with pytest.raises(RuntimeError, match="write PLY or OBJ instead"):
        bpy.ops.export_mesh.vesselmesh(filepath=str(tmp_path / "far.stl"), file_format="STL")
    export(surface, tmp_path / "far.ply", file_format="PLY")  # PLY keeps it, in double
    far = vm.read_mesh(str(tmp_path / "far.ply"))
    np.testing.assert_allclose(far["vertices"], world_vertices(surface), rtol=1e-15)
    assert vm.check(far["vertices"], far["faces"])["topology"]["boundary_edges"] == 0
