"""The add-on installs from build/vesselmesh.zip the way a user installs it, and carries what it needs."""
import os
import re
import subprocess
import sys
import tomllib
import zipfile

import addon_utils
import bpy

import vesselmesh_core as vm


def test_addon_is_enabled_from_the_zip_with_its_own_native_module():
    assert addon_utils.check("vesselmesh") == (True, True)
    addons = bpy.utils.user_resource("SCRIPTS", path="addons")
    assert os.path.commonpath([vm.__file__, addons]) == addons


def test_zip_has_one_top_level_folder_with_bl_info_manifest_and_native_module(addon_zip):
    with zipfile.ZipFile(addon_zip) as archive:
        names = archive.namelist()
        manifest = tomllib.loads(archive.read("vesselmesh/blender_manifest.toml").decode())
    assert {name.split("/")[0] for name in names} == {"vesselmesh"}
    assert "vesselmesh/__init__.py" in names
    assert any(re.fullmatch(r"vesselmesh/_native/vesselmesh_core\..*\.so", name) for name in names)
    assert manifest["id"] == "vesselmesh" and manifest["type"] == "add-on"
    assert manifest["license"] == ["SPDX:GPL-3.0-or-later"] and "vesselmesh/LICENSE" in names


def test_native_module_needs_only_libraries_every_linux_has():
    needed = re.findall(r"^\s*(\S+) =>", subprocess.run(["ldd", vm.__file__], capture_output=True, text=True,
                                                               check=True).stdout, re.MULTILINE)
    assert needed and set(needed) <= {"libz.so.1", "libstdc++.so.6", "libm.so.6", "libgcc_s.so.1", "libc.so.6"}, needed


def test_addon_and_manifest_carry_the_projects_version(project_root, addon_zip):
    project = re.search(r"project\(VesselMesh VERSION ([0-9.]+)", (project_root / "CMakeLists.txt").read_text()).group(1)
    with zipfile.ZipFile(addon_zip) as archive:
        manifest = tomllib.loads(archive.read("vesselmesh/blender_manifest.toml").decode())
    assert manifest["version"] == project
    assert ".".join(map(str, sys.modules["vesselmesh"].bl_info["version"])) == project


def test_file_import_menu_offers_the_importer():
    operators = sys.modules["vesselmesh"].blender.operators
    assert operators.menu_import in bpy.types.TOPBAR_MT_file_import._dyn_ui_initialize()
    assert bpy.ops.import_scene.vesselmesh.get_rna_type().name == "Import Vessel Centerline"


def test_operators_that_change_the_scene_are_undoable():
    for op in (bpy.ops.import_scene.vesselmesh, bpy.ops.vesselmesh.generate, bpy.ops.vesselmesh.legend):
        assert "UNDO" in op.bl_options
