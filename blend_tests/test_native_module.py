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


def arena_decay():
    """Each created jemalloc arena's (dirty, muzzy) decay times in ms, read through Blender's allocator."""
    import ctypes
    mallctl = ctypes.CDLL(None).mallctl
    count = ctypes.c_uint()
    mallctl(b"arenas.narenas", ctypes.byref(count), ctypes.byref(ctypes.c_size_t(4)), None, 0)
    decay = {}
    for arena in range(count.value):
        values = []
        for kind in ("dirty", "muzzy"):
            value = ctypes.c_ssize_t()
            size = ctypes.c_size_t(ctypes.sizeof(value))
            if mallctl(f"arena.{arena}.{kind}_decay_ms".encode(), ctypes.byref(value), ctypes.byref(size), None, 0):
                break
            values.append(value.value)
        if len(values) == 2:
            decay[arena] = tuple(values)
    return decay


def test_a_held_allocator_keeps_freed_pages_until_the_last_hold_is_released():
    assert vm.FreedMemoryHold.supported  # Blender allocates with jemalloc
    vm.mesh(vm.Graph(np.array([[0.0, 0, 0], [0, 0, 9]]), np.array([[0, 1]]), radius=np.ones(2)), levels=1)
    before = arena_decay()
    assert any(value != (-1, -1) for value in before.values())  # a huge-block arena purges at once
    outer = vm.FreedMemoryHold()
    with vm.FreedMemoryHold():
        assert set(arena_decay()[arena] for arena in before) == {(-1, -1)}
    assert set(arena_decay()[arena] for arena in before) == {(-1, -1)}  # the outer hold still holds
    outer.release()
    outer.release()  # a second release does nothing
    assert {arena: arena_decay()[arena] for arena in before} == before
