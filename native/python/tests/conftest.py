"""Puts the built module on the path: $VESSELMESH_PYTHON_PATH, else build/python."""
import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, os.environ.get("VESSELMESH_PYTHON_PATH", str(ROOT / "build" / "python")))


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
