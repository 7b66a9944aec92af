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
    for op in (bpy.ops.import_scene.vesselmesh, bpy.ops.vesselmesh.generate, bpy.ops.vesselmesh.legend,
               bpy.ops.vesselmesh.radius, bpy.ops.vesselmesh.teaching_render, bpy.ops.vesselmesh.apply_preset):
        assert "UNDO" in op.bl_options


def test_file_export_menu_offers_the_exporter():
    export = sys.modules["vesselmesh"].blender.export
    assert export.menu_export in bpy.types.TOPBAR_MT_file_export._dyn_ui_initialize()


# What Blender 4.2's extension manifest schema 1.0.0 accepts (docs.blender.org, "Extensions › Getting
# Started › Manifest"; Blender validates these when it builds or installs an extension).
ADDON_TAGS = {"3D View", "Add Curve", "Add Mesh", "Animation", "Bake", "Camera", "Compositing", "Development",
              "Game Engine", "Geometry Nodes", "Grease Pencil", "Import-Export", "Lighting", "Material", "Modeling",
              "Mesh", "Node", "Object", "Paint", "Pipeline", "Physics", "Render", "Rigging", "Scene", "Sculpt",
              "Sequencer", "System", "Text Editor", "Tracking", "User Interface", "UV"}
PLATFORMS = {"windows-x64", "windows-arm64", "macos-x64", "macos-arm64", "linux-x64"}
PERMISSIONS = {"files", "network", "clipboard", "camera", "microphone"}


def check_manifest(manifest):
    required = {"schema_version", "id", "version", "name", "tagline", "maintainer", "type", "blender_version_min",
                "license"}
    assert required <= set(manifest), required - set(manifest)
    assert manifest["schema_version"] == "1.0.0" and manifest["type"] == "add-on"
    assert re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", manifest["id"])
    assert re.fullmatch(r"\d+\.\d+\.\d+", manifest["version"])
    assert len(manifest["tagline"]) <= 64 and manifest["tagline"][-1] not in ".,;:!?"
    major, minor, patch = map(int, manifest["blender_version_min"].split("."))
    assert (major, minor, patch) >= (4, 2, 0)
    assert all(value.startswith("SPDX:") for value in manifest["license"])
    assert set(manifest["tags"]) <= ADDON_TAGS
    assert set(manifest["platforms"]) <= PLATFORMS
    for key, reason in manifest.get("permissions", {}).items():
        assert key in PERMISSIONS and 0 < len(reason) <= 64 and reason[-1] not in ".,;:!?"


def extension_package(addon_zip):
    packages = list(addon_zip.parent.glob("vesselmesh-*.zip"))
    assert len(packages) == 1, packages
    return packages[0]


def test_build_writes_an_extension_package_for_blender_4_2_laid_out_as_blender_builds_them(addon_zip, project_root):
    package = extension_package(addon_zip)
    with zipfile.ZipFile(package) as archive:
        names = set(archive.namelist())
        manifest = tomllib.loads(archive.read("blender_manifest.toml").decode())
    check_manifest(manifest)
    project = re.search(r"project\(VesselMesh VERSION ([0-9.]+)", (project_root / "CMakeLists.txt").read_text()).group(1)
    [platform] = manifest["platforms"]
    assert package.name == f"vesselmesh-{project}-{platform.replace('-', '_')}.zip"  # as --split-platforms names it
    assert manifest["version"] == project and manifest["id"] == "vesselmesh"
    assert {"__init__.py", "LICENSE", "blender_manifest.toml", "core/colors.py", "blender/operators.py"} <= names
    assert not any(n.endswith((".in", ".pyc")) or "__pycache__" in n for n in names)
    with zipfile.ZipFile(addon_zip) as legacy:  # the same files as the add-on zip, one folder up
        assert {n[len("vesselmesh/"):] for n in legacy.namelist() if n != "vesselmesh/"} == names


def test_the_extensions_native_module_is_built_for_the_python_and_platform_it_names(addon_zip):
    with zipfile.ZipFile(extension_package(addon_zip)) as archive:
        manifest = tomllib.loads(archive.read("blender_manifest.toml").decode())
        [native] = [n for n in archive.namelist() if n.startswith("_native/") and n.endswith((".so", ".pyd"))]
    tag = f"cpython-{sys.version_info.major}{sys.version_info.minor}"
    assert tag in native  # the Python of this Blender (4.2 to 5.0 run 3.11, 5.1 and later 3.13)
    machine = {"x86_64": "x64", "aarch64": "arm64", "arm64": "arm64"}[os.uname().machine]
    assert manifest["platforms"] == [f"linux-{machine}"] and native.endswith(f"{os.uname().machine}-linux-gnu.so")


def test_the_add_on_zips_manifest_passes_the_same_checks(addon_zip):
    with zipfile.ZipFile(addon_zip) as archive:
        check_manifest(tomllib.loads(archive.read("vesselmesh/blender_manifest.toml").decode()))
