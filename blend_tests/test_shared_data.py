"""Real centerlines through the import operator: closed manifold surfaces with curvature attributes.
These use ../shared/data and skip when it is absent."""
import numpy as np
import pytest

import vesselmesh_core as vm
from helpers import arrays, assert_closed_manifold, attribute, import_file

FILES = ["brava-bg0003/BG0003_ColorCoded.CNG.swc", "human-brain-arteries/arteries_smooth.vtk"]


@pytest.mark.parametrize("name", FILES)
def test_real_network_imports_as_a_closed_manifold_with_curvature(shared_data, name):
    centerline, surface = import_file(shared_data / name)
    assert_closed_manifold(surface)
    assert vm.check(*arrays(surface))["topology"]["components"] == vm.Graph.read(str(shared_data / name)).components
    for measure in ("k1", "k2", "mean", "gaussian", "rms"):
        assert np.all(np.isfinite(attribute(surface, measure)))
    assert np.all(attribute(surface, "k1") >= attribute(surface, "k2"))
    state = surface.vesselmesh
    assert state.color_low < 0 < state.color_high
