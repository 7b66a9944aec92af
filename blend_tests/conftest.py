"""Fixtures for the tests that run inside Blender (see run.py).

The add-on is installed the way a user installs it, from the build's zip into a temporary user profile,
before any test module is imported: so `import vesselmesh_core` in the tests gets the add-on's own
copy of the native module. The zip is found next to $VESSELMESH_PYTHON_PATH (build/python by default):
build/vesselmesh.zip.
"""
import os
import sys
import tempfile
from pathlib import Path

import bpy
import pytest

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("VESSELMESH_PYTHON_PATH", ROOT / "build" / "python")).resolve().parent
PROFILE = tempfile.TemporaryDirectory(prefix="vesselmesh-profile-")
os.environ["BLENDER_USER_SCRIPTS"] = os.path.join(PROFILE.name, "scripts")
os.environ["BLENDER_USER_CONFIG"] = os.path.join(PROFILE.name, "config")
bpy.ops.preferences.addon_install(filepath=str(BUILD / "vesselmesh.zip"))
bpy.ops.preferences.addon_enable(module="vesselmesh")
sys.modules["vesselmesh"].core.native.core()  # the add-on's native module, loaded once for every test


@pytest.fixture(autouse=True)
def empty_scene():
    """Every test starts from an empty factory scene, with the add-on still enabled (unlike
    read_factory_settings, read_homefile keeps the preferences)."""
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    yield


@pytest.fixture
def addon_zip():
    """The zip the add-on was installed from."""
    return BUILD / "vesselmesh.zip"
