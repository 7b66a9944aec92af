"""What a surface file holds, without bpy: world (or file-unit) coordinates and curvature values that
follow the same change of length."""
import numpy as np

from . import colors

OBJ_MATERIAL = "VesselMesh_curvature"


def transformed(vertices, faces, matrix, values, length_factor=1.0):
    """(vertices, faces, values) of a surface placed by the 4×4 `matrix` and then measured in a unit whose
    lengths are length_factor times the scene's: vertices in float64 (computed in double, so that an object
    far from the origin keeps its shape), and each curvature measure divided by the change of length to
    the power of its dimension (curvature halves where lengths double). The matrix's scale is taken as
    uniform (the cube root of its determinant): curvature means nothing under a stretch."""
    matrix = np.asarray(matrix, dtype=np.float64)
    world = (np.asarray(vertices, dtype=np.float64) @ matrix[:3, :3].T + matrix[:3, 3]) * length_factor
    stretch = abs(float(np.linalg.det(matrix[:3, :3]))) ** (1.0 / 3.0) * length_factor
    out = {}
    for name, v in values.items():
        dimension = colors.MEASURES[name].dimension if name in colors.MEASURES else 0
        out[name] = (np.asarray(v, dtype=np.float64) * stretch ** dimension).astype(np.float32)
    return world, np.ascontiguousarray(faces, dtype=np.int32), out
