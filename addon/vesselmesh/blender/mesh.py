"""The only place that reads and writes Blender mesh data (foreach_get/foreach_set on numpy arrays)."""
import bpy
import numpy as np

from .. import compat

COLOR_ATTRIBUTE = "curvature_color"


def write_surface(mesh, vertices, faces, list_edges):
    """Replaces the geometry of mesh (keeping its name, materials and users) by a smooth-shaded triangle
    surface: vertices (V,3) float32 and faces (F,3) int32, C-contiguous; list_edges() returns their edges as
    vesselmesh_core.edges gives them (edges (E,2), corner_edges (F,3) int32). Handing Blender the edges
    spares it hashing them (calc_edges), the largest part of building a big mesh; list_edges() is called once
    the vertices and faces are written, so that a worker can list them meanwhile."""
    mesh.clear_geometry()
    mesh.vertices.add(len(vertices))
    mesh.loops.add(faces.size)
    mesh.polygons.add(len(faces))
    compat.set_positions(mesh, vertices.ravel())
    compat.set_faces(mesh, faces)
    edges, corner_edges = list_edges()
    mesh.edges.add(len(edges))
    compat.set_edges(mesh, edges, corner_edges)
    compat.shade_smooth(mesh)
    mesh.update()


def write_centerline(mesh, points, edges, radius=None, edge_radius=None):
    """A mesh of edges with a FLOAT attribute `radius` on its points, or on its edges when the file gave
    one radius per edge."""
    mesh.vertices.add(len(points))
    compat.set_positions(mesh, np.ascontiguousarray(points, dtype=np.float32).ravel())
    mesh.edges.add(len(edges))
    compat.set_indices(mesh.edges, bpy.types.MeshEdge, "vertices", np.ascontiguousarray(edges, dtype=np.int32))
    mesh.update()
    if radius is not None:
        set_float_attribute(mesh, "radius", radius, "POINT")
    elif edge_radius is not None:
        set_float_attribute(mesh, "radius", edge_radius, "EDGE")


def read_centerline(obj, depsgraph):
    """points (N,3), edges (E,2) and radius (N,) or edge_radius (E,) (None when absent) of an edge mesh
    object as the scene shows it (edit-mode changes and modifiers included), in its local coordinates."""
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        edges = np.empty(2 * len(mesh.edges), dtype=np.int32)
        mesh.edges.foreach_get("vertices", edges)
        radius = mesh.attributes.get("radius")
        domain = radius.domain if radius is not None and radius.data_type == "FLOAT" else None
        return {"points": compat.positions(mesh), "edges": edges.reshape(-1, 2),
                "radius": float_attribute(mesh, "radius") if domain == "POINT" else None,
                "edge_radius": float_attribute(mesh, "radius") if domain == "EDGE" else None}
    finally:
        evaluated.to_mesh_clear()


def set_float_attribute(mesh, name, values, domain="POINT"):
    attribute = mesh.attributes.get(name)
    if attribute is not None:
        mesh.attributes.remove(attribute)
    mesh.attributes.new(name, "FLOAT", domain).data.foreach_set("value", np.ascontiguousarray(values, np.float32))


def float_attribute(mesh, name):
    """The values of a FLOAT attribute as a float64 array, or None when the mesh has no such attribute."""
    attribute = mesh.attributes.get(name)
    if attribute is None or attribute.data_type != "FLOAT":
        return None
    values = np.empty(len(attribute.data), dtype=np.float32)
    attribute.data.foreach_get("value", values)
    return values.astype(np.float64)


def set_point_colors(mesh, rgba, name=COLOR_ATTRIBUTE):
    """A FLOAT_COLOR point attribute from (V,4) scene-linear RGBA, made the one shown and rendered."""
    attribute = mesh.color_attributes.get(name)
    if attribute is not None:
        mesh.color_attributes.remove(attribute)
    mesh.color_attributes.new(name, "FLOAT_COLOR", "POINT").data.foreach_set(
        "color", np.ascontiguousarray(rgba, np.float32).ravel())
    compat.show_color_attribute(mesh, name)


def triangles(mesh):
    """(V,3) vertices and (F,3) faces of a triangle mesh (what write_surface wrote)."""
    faces = np.empty(len(mesh.loops), dtype=np.int32)
    mesh.loops.foreach_get("vertex_index", faces)
    return compat.positions(mesh), faces.reshape(-1, 3)


def point_colors(mesh, name=COLOR_ATTRIBUTE):
    """(V,4) float32 scene-linear RGBA of a FLOAT_COLOR point attribute, or None."""
    attribute = mesh.color_attributes.get(name)
    if attribute is None or attribute.domain != "POINT":
        return None
    rgba = np.empty(4 * len(attribute.data), dtype=np.float32)
    attribute.data.foreach_get("color", rgba)
    return rgba.reshape(-1, 4)
