"""Fixtures shared by the project's two pytest suites, native/python/tests (the Python module) and
blend_tests (inside Blender): where their inputs are. pytest.ini makes this folder their root."""
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent


@pytest.fixture
def project_root():
    return ROOT


@pytest.fixture
def project_data():
    """The project's own small inputs."""
    return ROOT / "native" / "tests" / "data"


@pytest.fixture
def shared_data():
    """../shared/data, or skip: the shared data sets are not part of the project."""
    path = ROOT.parent / "shared" / "data"
    if not path.is_dir():
        pytest.skip("../shared/data is absent (shared data sets are not part of the project)")
    return path
