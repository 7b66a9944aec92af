"""Bad input: the operator reports what and where, returns CANCELLED, and the scene stays as it was."""
import bpy
import pytest


def scene_state():
    return (sorted(o.name for o in bpy.data.objects), sorted(m.name for m in bpy.data.meshes),
            sorted(m.name for m in bpy.data.materials))


@pytest.fixture
def cube():
    bpy.ops.mesh.primitive_cube_add()
    return bpy.context.active_object


def test_a_bad_file_reports_the_file_and_line_and_leaves_the_scene_unchanged(tmp_path, cube):
    bad = tmp_path / "broken.swc"
    bad.write_text("1 1 0 0 0 1 -1\n2 1 0 0 1 1 7\n")
    before = scene_state()
    # bpy.ops turns an operator's ERROR report into a RuntimeError carrying the report's text.
    with pytest.raises(RuntimeError, match=r"broken\.swc: line 2"):
        bpy.ops.import_scene.vesselmesh(filepath=str(bad))
    assert scene_state() == before
    assert bpy.context.active_object == cube


def test_a_missing_file_is_reported_and_changes_nothing(tmp_path, cube):
    before = scene_state()
    with pytest.raises(RuntimeError, match="nowhere.vtk"):
        bpy.ops.import_scene.vesselmesh(filepath=str(tmp_path / "nowhere.vtk"))
    assert scene_state() == before


def test_a_file_with_a_non_positive_radius_is_reported(tmp_path):
    bad = tmp_path / "flat.swc"
    bad.write_text("1 1 0 0 0 1 -1\n2 1 0 0 1 0 1\n")
    with pytest.raises(RuntimeError, match="flat.swc"):
        bpy.ops.import_scene.vesselmesh(filepath=str(bad))
    assert len(bpy.data.objects) == 0


def test_generating_from_a_mesh_without_edges_is_reported(cube):
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.delete(type="EDGE")
    bpy.ops.object.mode_set(mode="OBJECT")
    before = scene_state()
    with pytest.raises(RuntimeError, match="has no edges"):
        bpy.ops.vesselmesh.generate()
    assert scene_state() == before


def test_blender_keeps_working_after_errors(tmp_path, project_data):
    bad = tmp_path / "broken.vtp"
    bad.write_text("<VTKFile type='PolyData'><PolyData><Piece NumberOfPoints='2'")
    with pytest.raises(RuntimeError, match="broken.vtp"):
        bpy.ops.import_scene.vesselmesh(filepath=str(bad))
    assert bpy.ops.import_scene.vesselmesh(filepath=str(project_data / "bifurcation.swc")) == {"FINISHED"}
