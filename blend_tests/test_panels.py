"""The sidebar panels and the import dialog draw without errors and offer what the guide says. Background
mode draws no UI, so a stand-in layout records the calls and checks every property and operator named."""
import sys
import types

import bpy
import pytest

from helpers import import_file


class Layout:
    """Records layout calls; prop() and operator() check that what they name exists."""

    def __init__(self, calls):
        self.calls = calls
        self.use_property_split = False

    def _child(self, *args, **kwargs):
        return Layout(self.calls)

    row = column = box = split = _child

    def prop(self, data, name, **kwargs):
        assert name in data.bl_rna.properties, (data, name)
        self.calls.append(("prop", name))

    def operator(self, idname, **kwargs):
        category, name = idname.split(".")
        assert hasattr(getattr(bpy.ops, category), name), idname
        self.calls.append(("operator", idname))
        return types.SimpleNamespace()

    def menu(self, idname, **kwargs):
        assert hasattr(bpy.types, idname), idname
        self.calls.append(("menu", idname))

    def label(self, text="", **kwargs):
        self.calls.append(("label", text))


def draw(panel, context):
    calls = []
    panel.draw(types.SimpleNamespace(layout=Layout(calls), pair=panel.pair), context)
    return calls


@pytest.fixture
def panels():
    return sys.modules["vesselmesh"].blender.panel


def test_the_sidebar_offers_presets_regenerate_settings_teaching_render_export_and_colours(project_data, panels):
    import_file(project_data / "bifurcation.swc", scale=0.001)
    context = bpy.context
    calls = draw(panels.VIEW3D_PT_vesselmesh, context)
    assert ("menu", "VESSELMESH_MT_presets") in calls and ("operator", "vesselmesh.generate") in calls
    assert ("operator", "vesselmesh.teaching_render") in calls and ("operator", "export_mesh.vesselmesh") in calls
    assert {("prop", name) for name in ("levels", "smooth", "fit", "crossings")} <= set(calls)
    colours = draw(panels.VIEW3D_PT_vesselmesh_colors, context)
    assert ("prop", "color_measure") in colours and ("operator", "vesselmesh.legend") in colours
    assert any(kind == "label" and text.endswith("1/mm") for kind, text in colours)  # the range in the file's unit
    stats = draw(panels.VIEW3D_PT_vesselmesh_stats, context)
    assert ("operator", "vesselmesh.check") in stats
    assert ("label", "Checked: closed, genus 0, no crossing") in stats  # the core's check of its own surface


def test_the_statistics_name_a_loop_the_surface_closed_and_why(project_data, panels):
    import_file(project_data / "extreme" / "fat_loop_round_a_thin_branch.vtk")
    labels = [text for kind, text in draw(panels.VIEW3D_PT_vesselmesh_stats, bpy.context) if kind == "label"]
    assert any(text.startswith("Loops closed inside a joint: 1, the first from (") for text in labels), labels
    assert "    the joint patch's hull does not close round its hole" in labels


def test_in_edit_mode_the_sidebar_offers_the_radius_tool(project_data, panels):
    centerline, _ = import_file(project_data / "bifurcation.swc")
    bpy.context.view_layer.objects.active = centerline
    bpy.ops.object.mode_set(mode="EDIT")
    assert ("operator", "vesselmesh.radius") in draw(panels.VIEW3D_PT_vesselmesh, bpy.context)


def test_the_import_dialog_draws_every_setting_and_the_preset():
    operators = sys.modules["vesselmesh"].blender.operators
    calls = []
    properties = bpy.ops.import_scene.vesselmesh.get_rna_type()

    class Settings:  # the operator's defaults, as the dialog starts
        bl_rna = properties

    for prop in properties.properties:
        if prop.identifier != "rna_type":
            setattr(Settings, prop.identifier, getattr(prop, "default", None))
    Settings.method, Settings.curvature = "curvature", True
    stand_in = Settings()
    stand_in.layout = Layout(calls)
    operators.IMPORT_SCENE_OT_vesselmesh.draw(stand_in, bpy.context)
    names = {name for kind, name in calls if kind == "prop"}
    assert {"preset", "scale", "levels", "smooth", "curvature", "fit", "crossings", "caps", "default_radius", "method",
            "uniform_levels", "threshold", "measure", "alpha", "beta", "sampling", "color_measure", "colormap",
            "percentile"} <= names
