"""Puts the built module on the path: $VESSELMESH_PYTHON_PATH, else build/python."""
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, os.environ.get("VESSELMESH_PYTHON_PATH", str(ROOT / "build" / "python")))
