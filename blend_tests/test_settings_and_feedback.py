"""Settings in plain words with tooltips, the presets that ship, and what a long job tells while it runs."""
import sys
import time

import bpy
import pytest

from helpers import import_file


def settings_rna():
    return sys.modules["vesselmesh"].blender.properties.VesselMeshSettings.bl_rna.properties


def test_every_setting_has_a_plain_label_and_a_tooltip_that_says_what_it_changes():
    jargon = ("α", "β", "Tube Departure", "Uniform Levels", "Bidirectional", "Inward Only", "Separate")
    for prop in settings_rna():
        if prop.identifier == "rna_type":
            continue
        assert prop.description, prop.identifier
        assert not any(word in prop.name for word in jargon), prop.name
        if prop.type == "ENUM":
            for item in prop.enum_items:
                assert item.description and not any(word == item.name for word in jargon), (prop.identifier, item)
    assert settings_rna()["levels"].name == "Smoothness" and settings_rna()["smooth"].name == "Smooth Tracing"


@pytest.mark.parametrize("preset, expected", [
    ("quick", {"levels": 0, "curvature": True}),
    ("teaching", {"levels": 1, "color_measure": "k2", "curvature": True}),
    ("print", {"method": "uniform", "curvature": False, "caps": "flat", "crossings": "separate"})])
def test_shipped_presets_fill_in_the_import_and_a_script_can_still_change_one_setting(project_data, preset, expected):
    centerline, surface = import_file(project_data / "bifurcation.swc", preset=preset)
    settings = centerline.vesselmesh.settings
    assert {key: getattr(settings, key) for key in expected} == expected
    assert bool(surface.vesselmesh.color_map) == expected["curvature"]
    centerline, _ = import_file(project_data / "bifurcation.swc", preset=preset, levels=2)
    assert centerline.vesselmesh.settings.levels == 2


def test_a_preset_applies_to_the_active_centerline_for_the_next_regeneration(project_data):
    centerline, surface = import_file(project_data / "bifurcation.swc")
    bpy.context.view_layer.objects.active = surface
    assert bpy.ops.vesselmesh.apply_preset(preset="print") == {"FINISHED"}
    assert (centerline.vesselmesh.settings.method, centerline.vesselmesh.settings.curvature) == ("uniform", False)
    presets = sys.modules["vesselmesh"].core.presets.PRESETS
    assert set(presets) == {"quick", "teaching", "print"}
    assert all(p.label and p.description for p in presets.values())


def test_background_mode_prints_a_line_for_each_stage(project_data, capsys):
    import_file(project_data / "bifurcation.swc")
    out = capsys.readouterr().out
    lines = [line for line in out.splitlines() if line.startswith("VesselMesh: ")]
    assert any(line.startswith("VesselMesh: reading ") and "bifurcation.swc" in line for line in lines)
    assert any("points" in line and "edges" in line for line in lines)
    assert any(line.startswith("VesselMesh: surface: ") and "triangles" in line and "subdivide" in line
               for line in lines)
    assert any("curvature" in line for line in lines) and any("Blender's mesh" in line for line in lines)


def test_a_long_job_says_which_stage_it_is_in_and_prints_while_it_waits(project_data, capsys, monkeypatch):
    """A job whose graph takes a while: the stage stays at reading, and the runner prints a line while it
    waits (every HEARTBEAT seconds, made short here)."""
    vesselmesh = sys.modules["vesselmesh"]
    meshing = vesselmesh.core.meshing
    data = meshing.read_centerline(project_data / "bifurcation.swc")

    def slow():
        time.sleep(0.8)
        return meshing.centerline_graph(**data)

    job = meshing.MeshJob(slow, {"levels": 1}, ("k2", "auto", 2.0))
    assert job.stage() == (0, "reading the centerline")
    assert not job.wait(0.1)
    assert job.wait(30.0) and job.stage()[0] == 3
    lines = job.messages()
    assert any("points" in line for line in lines) and any(line.startswith("surface: ") for line in lines)
    assert job.messages() == []  # each line once
    job.close()

    monkeypatch.setattr(vesselmesh.blender.operators, "HEARTBEAT", 0.3)
    original = meshing.centerline_graph

    def slow_graph(*args, **kwargs):
        time.sleep(0.8)
        return original(*args, **kwargs)

    monkeypatch.setattr(meshing, "centerline_graph", slow_graph)
    import_file(project_data / "bifurcation.swc")
    out = capsys.readouterr().out
    assert "VesselMesh: reading the centerline, " in out and "s so far" in out


def test_the_import_dialog_shows_the_presets_and_the_settings_in_plain_words():
    rna = bpy.ops.import_scene.vesselmesh.get_rna_type().properties
    assert rna["preset"].enum_items.keys() == ["none", "quick", "teaching", "print"]
    assert rna["scale"].description.startswith("Multiplies the file's coordinates")
    assert all(rna[name].description for name in ("levels", "smooth", "fit", "color_measure"))
