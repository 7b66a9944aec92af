"""Runs pytest inside Blender: blender -b --factory-startup --python-exit-code 1 --python blend_tests/run.py -- ARGS.

Everything after '--' goes to pytest; Blender exits with pytest's status.
"""
import sys

import pytest

args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else ["blend_tests"]
sys.exit(int(pytest.main(args)))
