"""Regenerate: the surface follows edits of its centerline and stays a closed manifold; the surface
object keeps its identity; a centerline drawn in Blender works too."""
import bmesh
import bpy
import numpy as np

import vesselmesh_core as vm
from helpers import arrays, assert_closed_manifold, attribute, edit, import_file, topology


def regenerate(obj):
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.vesselmesh.generate() == {"FINISHED"}
    return obj.vesselmesh.surface if obj.vesselmesh.role == "CENTERLINE" else obj


def graph_of(centerline):
    points = np.array([v.co[:] for v in centerline.data.vertices])
    edges = np.array([e.vertices[:] for e in centerline.data.edges])
    return vm.Graph(points, edges, radius=attribute(centerline, "radius").astype(np.float64))


def test_unedited_centerline_regenerates_the_same_surface(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    before = arrays(surface)
    regenerate(centerline)
    after = arrays(surface)
    assert np.array_equal(before[1], after[1]) and np.array_equal(before[0], after[0])


def test_moving_a_point_in_edit_mode_moves_the_surface(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    assert arrays(surface)[0][:, 0].max() < 4.0
    surface.select_set(False)
    bpy.context.view_layer.objects.active = centerline
    bpy.ops.object.mode_set(mode="EDIT")
    bm = bmesh.from_edit_mesh(centerline.data)
    bm.verts.ensure_lookup_table()
    bm.verts[6].co = (5.0, 0.0, 12.0)  # the right branch's tip, from (3, 0, 10.5)
    bmesh.update_edit_mesh(centerline.data)
    regenerate(centerline)
    bpy.ops.object.mode_set(mode="OBJECT")
    vertices = arrays(surface)[0]
    assert 5.0 < vertices[:, 0].max() < 5.0 + 2 * 0.65
    assert 12.0 <= vertices[:, 2].max() < 12.0 + 2 * 0.65
    assert_closed_manifold(surface)


def test_changing_radii_changes_the_surface_to_match(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    volume = vm.check(*arrays(surface))["topology"]["signed_volume"]

    def thicken_left_branch(bm, radius):
        for i in (7, 8, 9):
            bm.verts[i][radius] *= 1.5

    edit(centerline, thicken_left_branch)
    regenerate(centerline)
    assert_closed_manifold(surface)
    assert vm.check(*arrays(surface))["topology"]["signed_volume"] > 1.1 * volume
    error = vm.radius_error(*arrays(surface), graph_of(centerline))
    assert np.nanmedian(np.abs(error)) < 0.05  # the surface follows the new radii


def test_deleting_a_branch_removes_it_from_the_surface(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    triangles = len(surface.data.polygons)
    edit(centerline, lambda bm, radius: bmesh.ops.delete(bm, geom=[bm.verts[i] for i in (7, 8, 9)], context="VERTS"))
    regenerate(centerline)
    assert_closed_manifold(surface)
    assert topology(surface)["components"] == 1
    assert len(surface.data.polygons) < triangles
    assert arrays(surface)[0][:, 0].min() > -1.5  # the left branch reached x = -3


def test_adding_a_branch_adds_it_to_the_surface(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")

    def add_branch(bm, radius):
        joint = bm.verts[3]  # (0, 0, 6)
        tip = bm.verts.new((0.0, 4.0, 7.0))
        tip[radius] = 0.5
        bm.edges.new((joint, tip))

    edit(centerline, add_branch)
    regenerate(centerline)
    assert_closed_manifold(surface)
    t = topology(surface)
    assert (t["components"], t["genus"]) == (1, 0)
    assert 3.5 < arrays(surface)[0][:, 1].max() < 4.0 + 0.5  # it reached y = 1 before


def test_regenerating_keeps_the_surface_objects_name_transform_materials_and_modifiers(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc", levels=1)
    surface.name = "artery"
    surface.location = (1.0, 2.0, 3.0)
    material = bpy.data.materials.new("wall")
    surface.data.materials[0] = material
    surface.modifiers.new("smooth", "SMOOTH")
    triangles = len(surface.data.polygons)
    centerline.vesselmesh.settings.levels = 2
    assert regenerate(surface) is surface  # from the surface selected, too
    assert len(surface.data.polygons) > triangles
    assert surface.name == "artery" and tuple(surface.location) == (1.0, 2.0, 3.0)
    assert surface.data.materials[:] == [material]
    assert [m.name for m in surface.modifiers] == ["smooth"]
    assert len(bpy.data.objects) == 2


def test_a_centerline_drawn_in_blender_without_radii_gets_the_default_radius():
    mesh = bpy.data.meshes.new("drawn")
    mesh.from_pydata([(0, 0, 0), (0, 0, 1), (0.5, 0, 2)], [(0, 1), (1, 2)], [])
    drawn = bpy.data.objects.new("drawn", mesh)
    bpy.context.scene.collection.objects.link(drawn)
    drawn.vesselmesh.settings.default_radius = 0.2
    surface = regenerate(drawn)
    assert surface.name == "drawn surface" and drawn.vesselmesh.role == "CENTERLINE"
    assert_closed_manifold(surface)
    vertices = arrays(surface)[0]
    near_middle = vertices[np.abs(vertices[:, 2] - 0.5) < 0.05]
    assert np.allclose(np.hypot(near_middle[:, 0], near_middle[:, 1]), 0.2, rtol=0.05)
