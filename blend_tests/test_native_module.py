"""The native module loads and works inside Blender's own Python."""
import bpy
import numpy as np
import pytest

import vesselmesh_core as vm


def test_module_reads_a_centerline_inside_blender(project_data):
    data = vm.read(str(project_data / "bifurcation.swc"))
    assert data["points"].shape == (10, 3)
    assert data["edges"].shape == (9, 2)
    assert bpy.app.version >= (3, 4, 0)


def test_arrays_from_the_module_build_a_blender_mesh(project_data):
    graph = vm.Graph.read(str(project_data / "ring_with_tail.vtk"))
    mesh = bpy.data.meshes.new("centerline")
    mesh.vertices.add(len(graph.points))
    mesh.vertices.foreach_set("co", graph.points.astype(np.float32).ravel())
    mesh.edges.add(len(graph.edges))
    mesh.edges.foreach_set("vertices", graph.edges.astype(np.int32).ravel())
    mesh.update()
    assert not mesh.validate()
    assert len(mesh.edges) == 6
    assert graph.loops == 1


def test_bad_input_raises_a_python_error_not_a_crash(tmp_path):
    bad = tmp_path / "broken.swc"
    bad.write_text("1 1 0 0 0 1 -1\n2 1 0 0 1 1 7\n")
    with pytest.raises(vm.InputError, match="broken.swc: line 2"):
        vm.read(str(bad))
    assert bpy.context.scene is not None  # Blender is still running
