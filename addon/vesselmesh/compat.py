"""Everything that differs between the Blender versions the add-on supports (3.4 onwards), detected by
feature rather than by version number. Only the 3.4 branches run on Debian 12's Blender; the others
follow the API changes of 3.5 (positions), 3.6 (corner vertices, read-only loop_total), 4.1 (smooth
shading) and 4.2 (the EEVEE engine's name)."""
import bpy
import numpy as np


def set_positions(mesh, coords):
    """Vertex positions from a flat float32 array (3 per vertex)."""
    position = mesh.attributes.get("position")  # 3.5+: positions are a generic attribute
    if position is not None:
        position.data.foreach_set("vector", coords)
    else:
        mesh.vertices.foreach_set("co", coords)


def positions(mesh):
    """(V,3) float64 vertex positions."""
    coords = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    position = mesh.attributes.get("position")
    if position is not None:
        position.data.foreach_get("vector", coords)
    else:
        mesh.vertices.foreach_get("co", coords)
    return coords.reshape(-1, 3).astype(np.float64)


def set_indices(collection, item_type, name, values):
    """collection.foreach_set(name, values) for an int property of item_type (int32 values). Blender copies
    the array in one go only when its type is the property's own: uint32 where the property is unsigned
    (3.4's mesh elements), else it converts item by item, twenty times slower."""
    unsigned = item_type.bl_rna.properties[name].subtype == "UNSIGNED"
    collection.foreach_set(name, values.ravel().view(np.uint32) if unsigned else values.ravel())


def set_faces(mesh, faces):
    """The corners and faces of a mesh whose loops and polygons were just added: faces (F,3) int32."""
    corner_vert = mesh.attributes.get(".corner_vert")  # 3.6+
    if corner_vert is not None:
        corner_vert.data.foreach_set("value", faces.ravel())
    else:
        set_indices(mesh.loops, bpy.types.MeshLoop, "vertex_index", faces)
    set_indices(mesh.polygons, bpy.types.MeshPolygon, "loop_start", np.arange(0, faces.size, 3, dtype=np.int32))
    if not bpy.types.MeshPolygon.bl_rna.properties["loop_total"].is_readonly:  # derived from loop_start in 3.6+
        set_indices(mesh.polygons, bpy.types.MeshPolygon, "loop_total", np.full(len(faces), 3, dtype=np.int32))


def set_edges(mesh, edges, corner_edges):
    """The edges of a mesh whose edges were just added, and the edge of each corner: edges (E,2) and
    corner_edges (F,3) (the edge from each corner to the next), int32."""
    set_indices(mesh.edges, bpy.types.MeshEdge, "vertices", edges)
    corner_edge = mesh.attributes.get(".corner_edge")  # 3.6+
    if corner_edge is not None:
        corner_edge.data.foreach_set("value", corner_edges.ravel())
    else:
        set_indices(mesh.loops, bpy.types.MeshLoop, "edge_index", corner_edges)


def shade_smooth(mesh):
    if hasattr(mesh, "shade_smooth"):  # 4.1+
        mesh.shade_smooth()
    else:
        mesh.polygons.foreach_set("use_smooth", np.ones(len(mesh.polygons), dtype=bool))


def show_color_attribute(mesh, name):
    """Makes a colour attribute the one the viewport shows and renders use."""
    attributes = mesh.color_attributes
    attributes.active_color = attributes[name]
    attributes.render_color_index = attributes.active_color_index


def set_eevee(scene):
    """Selects EEVEE, named BLENDER_EEVEE_NEXT in 4.2 to 4.5."""
    for engine in ("BLENDER_EEVEE_NEXT", "BLENDER_EEVEE"):
        try:
            scene.render.engine = engine
            return
        except TypeError:
            continue
    raise RuntimeError("this Blender has no EEVEE engine")


def node_material(name):
    """A new material with a node tree (use_nodes is implied and deprecated from 5.0)."""
    material = bpy.data.materials.new(name)
    if not material.use_nodes:
        material.use_nodes = True
    return material


def set_present(struct, **values):
    """Sets the settings a struct has and skips the others (EEVEE's settings changed in 4.2: soft shadows,
    shadow cube size and bloom went, ambient occlusion moved)."""
    for name, value in values.items():
        if name in struct.bl_rna.properties and not struct.bl_rna.properties[name].is_readonly:
            setattr(struct, name, value)


def gltf_color_options(colors):
    """The glTF exporter's keyword for writing the active colour attribute (COLOR_0): export_colors up to
    4.1, export_vertex_color from 4.2."""
    properties = bpy.ops.export_scene.gltf.get_rna_type().properties
    if "export_vertex_color" in properties:
        return {"export_vertex_color": "ACTIVE" if colors else "NONE"}
    return {"export_colors": colors}
