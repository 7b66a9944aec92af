"""Fixtures for the tests that run inside Blender (see run.py)."""
import os
import sys
from pathlib import Path

import bpy
import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, os.environ.get("VESSELMESH_PYTHON_PATH", str(ROOT / "build" / "python")))


@pytest.fixture(autouse=True)
def empty_scene():
    """Every test starts from an empty factory scene."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    yield


@pytest.fixture
def project_data():
    """The project's own small inputs."""
    return ROOT / "native" / "tests" / "data"
