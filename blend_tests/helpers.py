"""Small helpers shared by the add-on tests."""
import bmesh
import bpy
import numpy as np

import vesselmesh_core as vm


def import_file(path, **options):
    """Runs the import operator; returns (centerline, surface)."""
    assert bpy.ops.import_scene.vesselmesh(filepath=str(path), **options) == {"FINISHED"}
    surface = bpy.context.active_object
    return surface.vesselmesh.centerline, surface


def arrays(obj):
    """(V,3) vertices and (F,3) faces of a triangle mesh object."""
    mesh = obj.data
    vertices = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    mesh.vertices.foreach_get("co", vertices)
    faces = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", faces)
    return vertices.reshape(-1, 3).astype(np.float64), faces.reshape(-1, 3)


def topology(obj):
    """What vesselmesh_core.check says about the surface's topology."""
    return vm.check(*arrays(obj))["topology"]


def assert_closed_manifold(obj):
    t = topology(obj)
    assert t["boundary_edges"] == 0 and t["non_manifold_edges"] == 0, t
    assert len(obj.data.polygons) > 0
    assert len(obj.data.edges) == t["edges"]  # Blender's edges are the surface's, each once
    assert not obj.data.validate(verbose=True)  # edges, corners and faces agree (validate fixes and says so)


def attribute(obj, name):
    attr = obj.data.attributes[name]
    width = 4 if attr.data_type == "FLOAT_COLOR" else 1
    values = np.empty(width * len(attr.data), dtype=np.float32)
    attr.data.foreach_get("color" if width == 4 else "value", values)
    return values.reshape(-1, 4) if width == 4 else values


def edit(centerline, change):
    """Applies change(bm, radius_layer) to the centerline's mesh through bmesh."""
    bm = bmesh.new()
    bm.from_mesh(centerline.data)
    bm.verts.ensure_lookup_table()
    change(bm, bm.verts.layers.float["radius"])
    bm.to_mesh(centerline.data)
    bm.free()
