"""Editing as Blender users expect: the surface follows its centerline object, new points take their
neighbours' radius, the radius tool scales selected radii (and undoes), and jagged tracings smooth out."""
import sys
import types

import bmesh
import bpy
import numpy as np
import pytest
from mathutils import Matrix

import vesselmesh_core as vm
from helpers import arrays, assert_closed_manifold, attribute, import_file


@pytest.fixture
def centerline_arrays():
    return sys.modules["vesselmesh"].core.centerline


def world_bounds(obj):
    vertices, _ = arrays(obj)
    matrix = np.array(obj.matrix_world)
    world = vertices @ matrix[:3, :3].T + matrix[:3, 3]
    return world.min(axis=0), world.max(axis=0)


def regenerate(obj):
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.vesselmesh.generate() == {"FINISHED"}


def test_the_surface_is_the_centerlines_child_and_follows_it_before_and_after_regenerating(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    assert surface.parent == centerline
    low, high = world_bounds(surface)
    centerline.matrix_world = Matrix.Translation((10.0, -4.0, 2.0)) @ Matrix.Scale(2.0, 4)
    bpy.context.view_layer.update()
    moved = world_bounds(surface)
    np.testing.assert_allclose(moved[0], 2 * low + (10, -4, 2), atol=1e-5)
    regenerate(centerline)  # rebuilt in the centerline's own coordinates: still where the centerline is
    bpy.context.view_layer.update()
    again = world_bounds(surface)
    np.testing.assert_allclose(again[0], moved[0], atol=1e-4)
    np.testing.assert_allclose(again[1], moved[1], atol=1e-4)


def test_a_surface_without_parent_is_put_onto_its_centerline_when_regenerated(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    surface.parent = None  # as an older version left it
    centerline.location = (5.0, 0.0, 0.0)
    regenerate(centerline)
    bpy.context.view_layer.update()
    assert surface.parent == centerline
    assert world_bounds(surface)[0][0] > 5.0 - 3.0 - 1.0  # the left branch reaches x = -3 from the centerline


def test_new_points_take_their_neighbours_radius(centerline_arrays):
    points = np.array([[0.0, 0, 0], [0, 0, 1], [0, 0, 2], [0, 0, 3], [1, 0, 3], [2, 0, 3]])
    edges = np.array([[0, 1], [1, 2], [2, 3], [3, 4], [4, 5]])
    radius = np.array([1.0, 0.0, 2.0, 2.0, 0.0, 0.0])  # a point inserted mid-edge, a new two-point tip
    filled = centerline_arrays.fill_point_radii(points, edges, radius, default=0.1)
    np.testing.assert_allclose(filled, [1.0, 1.5, 2.0, 2.0, 2.0, 2.0])
    alone = centerline_arrays.fill_point_radii(points[:2], edges[:1], np.zeros(2), default=0.25)
    np.testing.assert_allclose(alone, [0.25, 0.25])  # no radius anywhere around: the default
    edge_radius = centerline_arrays.fill_edge_radii(points, edges, np.array([1.0, 0.0, 3.0, 3.0, 3.0]), 0.1)
    assert edge_radius[1] == pytest.approx(2.0)


def test_a_point_drawn_in_a_millimetre_import_gets_a_vessels_radius_not_a_default_blob(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc", scale=0.001)
    assert centerline.vesselmesh.settings.default_radius == pytest.approx(0.0007, rel=0.2)  # the file's median

    def add_tip(bm):
        radius = bm.verts.layers.float["radius"]
        joint = bm.verts[3]
        tip = bm.verts.new((0.0, 0.004, 0.007))  # drawn: radius 0
        bm.edges.new((joint, tip))
        assert tip[radius] == 0.0

    edit_mesh(centerline, add_tip)
    regenerate(centerline)
    assert_closed_manifold(surface)
    vertices = arrays(surface)[0]
    tip = vertices[vertices[:, 1] > 0.0035]
    assert len(tip) and np.ptp(tip[:, 0]) < 4 * 0.0009  # a vessel as thick as its neighbour, not 0.2 wide


def edit_mesh(obj, change):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bm.verts.ensure_lookup_table()
    change(bm)
    bm.to_mesh(obj.data)
    bm.free()


def enter_edit_mode(centerline, selected):
    bpy.context.view_layer.objects.active = centerline
    centerline.select_set(True)
    bpy.ops.object.mode_set(mode="EDIT")
    bm = bmesh.from_edit_mesh(centerline.data)
    bm.verts.ensure_lookup_table()
    for v in bm.verts:
        v.select_set(v.index in selected)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(centerline.data)


def test_the_radius_tool_scales_the_selected_radii_and_the_regenerated_surface_follows(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    before = attribute(centerline, "radius").copy()
    volume = vm.check(*arrays(surface))["topology"]["signed_volume"]
    enter_edit_mode(centerline, {7, 8, 9})  # the left branch
    assert bpy.ops.vesselmesh.radius(factor=1.5) == {"FINISHED"}
    bpy.ops.object.mode_set(mode="OBJECT")
    after = attribute(centerline, "radius")
    np.testing.assert_allclose(after[[7, 8, 9]], 1.5 * before[[7, 8, 9]], rtol=1e-6)
    np.testing.assert_array_equal(after[:7], before[:7])
    regenerate(centerline)
    assert_closed_manifold(surface)
    assert vm.check(*arrays(surface))["topology"]["signed_volume"] > 1.1 * volume  # the left branch is thicker


def test_the_radius_tool_drags_like_blenders_scale_tools_and_cancel_restores(project_data):
    """The modal steps with a stand-in for the operator and its events (background mode has no window)."""
    radius_tool = sys.modules["vesselmesh"].blender.radius_tool
    centerline, _ = import_file(project_data / "bifurcation.swc")
    before = attribute(centerline, "radius").copy()
    enter_edit_mode(centerline, {4, 5, 6})
    op = types.SimpleNamespace(factor=1.0, _handle=None)
    op._state = radius_tool.RadiusState(centerline, 0.1)
    op._drag = sys.modules["vesselmesh"].core.centerline.RadiusDrag((100, 100), (150, 100))
    op._end = lambda context: None

    def event(kind, x=150, y=100, value="NOTHING", ctrl=False, shift=False, ascii=""):
        return types.SimpleNamespace(type=kind, value=value, mouse_region_x=x, mouse_region_y=y, ctrl=ctrl,
                                     shift=shift, ascii=ascii)

    modal = radius_tool.VESSELMESH_OT_radius.modal
    context = bpy.context
    assert modal(op, context, event("MOUSEMOVE", x=200)) == {"RUNNING_MODAL"}  # twice as far: twice the radius
    np.testing.assert_allclose(np.array(op._state.current()), 2 * before[[4, 5, 6]], rtol=1e-6)
    modal(op, context, event("MOUSEMOVE", x=173, ctrl=True))  # Ctrl snaps to tenths: 1.5
    assert op._state.factor == pytest.approx(1.5)
    modal(op, context, event("THREE", value="PRESS", ascii="3"))  # a typed factor wins
    assert op._state.factor == pytest.approx(3.0)
    assert modal(op, context, event("ESC", value="PRESS")) == {"CANCELLED"}
    bpy.ops.object.mode_set(mode="OBJECT")
    np.testing.assert_array_equal(attribute(centerline, "radius"), before)

    enter_edit_mode(centerline, {4, 5, 6})
    op._state = radius_tool.RadiusState(centerline, 0.1)
    op._drag = sys.modules["vesselmesh"].core.centerline.RadiusDrag((100, 100), (150, 100))
    modal(op, context, event("MOUSEMOVE", x=125))
    assert modal(op, context, event("LEFTMOUSE", value="PRESS")) == {"FINISHED"} and op.factor == pytest.approx(0.5)
    bpy.ops.object.mode_set(mode="OBJECT")
    np.testing.assert_allclose(attribute(centerline, "radius")[[4, 5, 6]], 0.5 * before[[4, 5, 6]], rtol=1e-6)


def test_the_radius_tool_is_undone_by_one_undo(project_data):
    centerline, _ = import_file(project_data / "bifurcation.swc")
    before = attribute(centerline, "radius").copy()
    enter_edit_mode(centerline, {1, 2})
    bpy.ops.ed.undo_push(message="selected")
    assert bpy.ops.vesselmesh.radius("EXEC_DEFAULT", True, factor=2.0) == {"FINISHED"}
    bpy.ops.ed.undo()
    bpy.ops.object.mode_set(mode="OBJECT")
    centerline = bpy.data.objects["bifurcation centerline"]
    np.testing.assert_array_equal(attribute(centerline, "radius"), before)


def test_the_radius_tool_only_runs_on_centerlines_in_edit_mode(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    bpy.context.view_layer.objects.active = centerline
    assert not bpy.ops.vesselmesh.radius.poll()  # object mode
    bpy.ops.mesh.primitive_cube_add()
    bpy.ops.object.mode_set(mode="EDIT")
    assert not bpy.ops.vesselmesh.radius.poll()  # a mesh that is no centerline: Ctrl+A stays Skin Resize


def test_smoothing_irons_out_a_zigzag_tracing_and_keeps_forks_and_ends(centerline_arrays):
    x = np.linspace(0.0, 20.0, 41)
    points = np.c_[x, 0.3 * (-1) ** np.arange(41), np.zeros(41)]  # a zig-zag along x
    points = np.r_[points, [[10.0, 5.0, 0.0]]]  # a branch from the middle point
    edges = np.r_[np.c_[np.arange(40), np.arange(1, 41)], [[20, 41]]]
    smoothed, _ = centerline_arrays.smooth(points, edges, None, iterations=5)
    assert np.abs(smoothed[5:16, 1]).max() < 0.1 * 0.3
    for fixed in (0, 20, 40, 41):  # ends and the fork stay
        np.testing.assert_array_equal(smoothed[fixed], points[fixed])
    assert smoothed[:, 0].max() == pytest.approx(20.0) and np.ptp(smoothed[1:40, 0]) > 18  # no shrinking


def test_smooth_tracing_setting_smooths_the_surface_but_not_the_centerline_object(project_data, tmp_path):
    path = tmp_path / "jagged.swc"
    lines = [f"{i + 1} 3 {0.4 * (-1) ** i:.2f} 0 {i:.1f} 0.5 {i if i else -1}" for i in range(30)]
    path.write_text("\n".join(lines) + "\n")
    centerline, jagged = import_file(path)
    _, smooth = import_file(path, smooth=5)
    def middle_width(surface):
        vertices = arrays(surface)[0]
        return np.ptp(vertices[(vertices[:, 2] > 5) & (vertices[:, 2] < 25), 0])

    assert middle_width(smooth) < 0.8 * middle_width(jagged)
    assert_closed_manifold(smooth)
    points = np.array([v.co[:] for v in centerline.data.vertices])
    assert np.abs(points[:, 0]).max() == pytest.approx(0.4)  # the tracing itself stays as it was
