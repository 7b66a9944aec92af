"""Undo and redo: an import or a regeneration is one step that Blender's undo takes back whole.

Operators called from Python push an undo step only when asked, as the UI asks: ("EXEC_DEFAULT", True)
does, and Blender then pushes one only for operators that declare UNDO."""
import bpy
import numpy as np

from helpers import arrays, assert_closed_manifold, edit, import_file


def vessel_objects():
    return sorted(o.name for o in bpy.data.objects if o.vesselmesh.role)


def test_undoing_an_import_removes_both_objects_and_redo_restores_them(project_data):
    bpy.ops.ed.undo_push(message="empty scene")
    assert bpy.ops.import_scene.vesselmesh("EXEC_DEFAULT", True, filepath=str(project_data / "bifurcation.swc")) \
        == {"FINISHED"}
    imported = vessel_objects()
    assert imported == ["bifurcation", "bifurcation centerline"]
    vertices, faces = arrays(bpy.data.objects["bifurcation"])

    bpy.ops.ed.undo()
    assert vessel_objects() == []
    bpy.ops.ed.redo()
    assert vessel_objects() == imported
    surface = bpy.data.objects["bifurcation"]  # undo reloads the data: look objects up again
    assert surface.vesselmesh.centerline == bpy.data.objects["bifurcation centerline"]
    assert_closed_manifold(surface)
    again = arrays(surface)
    assert np.array_equal(again[0], vertices) and np.array_equal(again[1], faces)


def test_undoing_a_regeneration_restores_the_previous_surface(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")

    def thicken(bm, radius):
        for v in bm.verts:
            v[radius] *= 1.5

    edit(centerline, thicken)
    bpy.ops.ed.undo_push(message="thicker radii")
    before = arrays(surface)
    bpy.context.view_layer.objects.active = centerline
    assert bpy.ops.vesselmesh.generate("EXEC_DEFAULT", True) == {"FINISHED"}
    assert not np.array_equal(arrays(surface)[0], before[0])

    bpy.ops.ed.undo()
    surface = bpy.data.objects["bifurcation"]
    restored = arrays(surface)
    assert np.array_equal(restored[0], before[0]) and np.array_equal(restored[1], before[1])
    assert_closed_manifold(surface)
