"""write_mesh and read_mesh: surfaces with their curvature values and colours to files, read back."""
import numpy as np
import pytest

import vesselmesh_core as vm


@pytest.fixture(scope="module")
def surface():
    graph = vm.Graph(np.array([[0.0, 0, 0], [0, 0, 6], [2, 0, 10], [-2, 0, 10]]),
                     np.array([[0, 1], [1, 2], [1, 3]]), radius=np.array([1.0, 0.9, 0.6, 0.6]))
    return vm.mesh(graph, levels=1, curvature=True)


def srgb(count):
    return (np.arange(4 * count) % 256).astype(np.uint8).reshape(-1, 4)


def header(path):
    data = path.read_bytes()
    return data[:data.index(b"end_header")].decode()


def test_ply_keeps_positions_faces_curvature_and_colours(tmp_path, surface):
    path = tmp_path / "surface.ply"
    v, f, curvature = surface["vertices"], surface["faces"], surface["curvature"]
    colors = srgb(len(v))[:, :3]
    vm.write_mesh(str(path), v, f, properties=curvature, colors=colors)
    assert "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float k1\n" in header(path)
    read = vm.read_mesh(str(path))
    np.testing.assert_array_equal(read["vertices"], v.astype(np.float32))  # float: nothing merges near the origin
    np.testing.assert_array_equal(read["faces"], f)
    for name, values in curvature.items():
        np.testing.assert_array_equal(read["properties"][name], values)
    for channel, name in enumerate(("red", "green", "blue")):
        np.testing.assert_array_equal(read["properties"][name], colors[:, channel])


def test_comments_are_kept_in_ply_and_obj_and_read_back(tmp_path, surface):
    v, f = surface["vertices"], surface["faces"]
    for name in ("s.ply", "s.obj"):
        vm.write_mesh(str(tmp_path / name), v, f, comments=["lost loop: from (0, 0, 1)", "two\nlines"])
        assert vm.read_mesh(str(tmp_path / name))["comments"] == ["lost loop: from (0, 0, 1)", "two lines"]
    vm.write_mesh(str(tmp_path / "s.stl"), v, f, comments=["nowhere to go"])
    assert vm.read_mesh(str(tmp_path / "s.stl"))["comments"] == []
    vm.write_mesh(str(tmp_path / "plain.ply"), v, f)
    assert vm.read_mesh(str(tmp_path / "plain.ply"))["comments"] == []


def test_a_surface_far_from_the_origin_keeps_its_positions_in_ply_and_obj_and_stl_is_refused(tmp_path, surface):
    v = surface["vertices"] + 1e9
    f = surface["faces"]
    for name in ("far.ply", "far.obj"):
        vm.write_mesh(str(tmp_path / name), v, f)
        read = vm.read_mesh(str(tmp_path / name))
        np.testing.assert_array_equal(read["vertices"], v)
        assert vm.check(read["vertices"], read["faces"])["topology"]["boundary_edges"] == 0
    assert "property double x" in header(tmp_path / "far.ply")
    with pytest.raises(RuntimeError, match="write PLY or OBJ instead"):
        vm.write_mesh(str(tmp_path / "far.stl"), v, f)


def test_obj_carries_colours_and_a_material(tmp_path, surface):
    v, f = surface["vertices"], surface["faces"]
    vm.write_mesh(str(tmp_path / "s.obj"), v, f, colors=srgb(len(v)), material="VesselMesh")
    lines = (tmp_path / "s.obj").read_text().splitlines()
    assert "mtllib s.mtl" in lines and "usemtl VesselMesh" in lines
    first = next(line for line in lines if line.startswith("v "))
    assert len(first.split()) == 7  # v x y z r g b
    assert "newmtl VesselMesh" in (tmp_path / "s.mtl").read_text()
    np.testing.assert_array_equal(vm.read_mesh(str(tmp_path / "s.obj"))["vertices"], v)


def test_bad_arrays_raise_input_errors_and_bad_paths_runtime_errors(tmp_path, surface):
    v, f = surface["vertices"], surface["faces"]
    with pytest.raises(vm.InputError, match="colors"):
        vm.write_mesh(str(tmp_path / "s.ply"), v, f, colors=np.zeros((len(v), 3)))  # floats, not uint8
    with pytest.raises(vm.InputError, match="property 'mean'"):
        vm.write_mesh(str(tmp_path / "s.ply"), v, f, properties={"mean": np.zeros(3)})
    with pytest.raises(RuntimeError, match="unknown mesh extension"):
        vm.write_mesh(str(tmp_path / "s.vtk"), v, f)
    with pytest.raises(RuntimeError, match="cannot open"):
        vm.write_mesh(str(tmp_path / "missing" / "s.ply"), v, f)
    with pytest.raises(vm.InputError, match="s.ply"):
        vm.read_mesh(str(tmp_path / "nowhere" / "s.ply"))
