"""The native module vesselmesh_core, shipped in the add-on's _native folder."""
import importlib.machinery
import importlib.util
import sys
from pathlib import Path

NATIVE_DIR = Path(__file__).resolve().parent.parent / "_native"


def core():
    """The vesselmesh_core module, loaded once per process.

    A copy that is already loaded (a script that put build/python on sys.path first) is reused: a
    pybind11 module loaded a second time from another path cannot register its types again.
    """
    module = sys.modules.get("vesselmesh_core")
    if module is None:
        # PathFinder picks the binary whose suffix matches this Python (cpython-311-x86_64-linux-gnu, ...).
        spec = importlib.machinery.PathFinder.find_spec("vesselmesh_core", [str(NATIVE_DIR)])
        if spec is None:
            raise ImportError(f"no vesselmesh_core built for Python {sys.version_info.major}."
                              f"{sys.version_info.minor} in {NATIVE_DIR}")
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        sys.modules["vesselmesh_core"] = module
    return module
