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


def lost_loop_comments(lost_loops, matrix, length_factor=1.0):
    """The comment lines naming each loop the surface closed inside a joint patch (its statistics'
    lost_loops: the ends of the loop's branch through the patch, in the surface's own coordinates, and
    why), its ends placed as `transformed` places the vertices: the lines `vesselmesh mesh` writes, which
    `vesselmesh check --centerline` reads back and prints."""
    matrix = np.asarray(matrix, dtype=np.float64)

    def point(p):
        x, y, z = (np.asarray(p, dtype=np.float64) @ matrix[:3, :3].T + matrix[:3, 3]) * length_factor
        return f"({x:.6g}, {y:.6g}, {z:.6g})"

    return [f"lost loop: the loop through the branch from {point(loop['joints'][0])} to {point(loop['joints'][1])} "
            f"closed inside a joint patch: {loop['why']}" for loop in lost_loops]
