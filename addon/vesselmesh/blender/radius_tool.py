"""The radius tool: scale the radius of the selected centerline points by dragging, as the Skin
modifier's Ctrl+A does, with circles showing the new radii while it runs."""
import bmesh
import bpy
import numpy as np
from bpy.props import FloatProperty
from mathutils import Vector

from ..core import centerline as centerline_arrays
from .operators import centerline_of

RADIUS = "radius"


def _layer(bm, domain):
    layers = (bm.verts if domain == "POINT" else bm.edges).layers.float
    return layers.get(RADIUS) or layers.new(RADIUS)


def radius_domain(mesh):
    """Where the centerline keeps its radii: 'EDGE' for a radius per edge, else 'POINT'."""
    attribute = mesh.attributes.get(RADIUS)
    return "EDGE" if attribute is not None and attribute.domain == "EDGE" else "POINT"


class RadiusState:
    """The selected items' radii when the tool started (missing ones filled in from their neighbours, as
    meshing fills them), so that every change is that start times a factor, and Esc restores them."""

    def __init__(self, obj, default_radius):
        self.obj = obj
        self.domain = radius_domain(obj.data)
        bm = bmesh.from_edit_mesh(obj.data)
        layer = _layer(bm, self.domain)
        items = bm.verts if self.domain == "POINT" else bm.edges
        items.ensure_lookup_table()
        bm.verts.ensure_lookup_table()
        radius = np.array([item[layer] for item in items])
        points = np.array([v.co[:] for v in bm.verts]).reshape(-1, 3)
        edges = np.array([[e.verts[0].index, e.verts[1].index] for e in bm.edges], dtype=np.int64).reshape(-1, 2)
        fill = centerline_arrays.fill_point_radii if self.domain == "POINT" else centerline_arrays.fill_edge_radii
        self.filled = fill(points, edges, radius, default_radius) if len(radius) else radius
        self.original = radius
        self.selected = np.array([item.select for item in items], dtype=bool)
        if self.domain == "POINT":
            self.centres = points[self.selected]
        else:
            self.centres = np.array([(e.verts[0].co + e.verts[1].co)[:] for e in bm.edges]).reshape(-1, 3)[
                self.selected] / 2
        self.factor = 1.0

    def apply(self, factor):
        """Sets the selected radii to their start times factor (the others as they were)."""
        self.factor = factor
        values = np.where(self.selected, centerline_arrays.scaled_radii(self.filled, self.selected, factor),
                          self.original)
        self._write(values)

    def restore(self):
        self._write(self.original)

    def current(self):
        return centerline_arrays.scaled_radii(self.filled, self.selected, self.factor)[self.selected]

    def _write(self, values):
        """Writes the selected items' radii (the others never change), each mouse move."""
        mesh = self.obj.data
        bm = bmesh.from_edit_mesh(mesh)
        layer = _layer(bm, self.domain)
        items = bm.verts if self.domain == "POINT" else bm.edges
        items.ensure_lookup_table()
        for index in np.flatnonzero(self.selected).tolist():
            items[index][layer] = float(values[index])
        bmesh.update_edit_mesh(mesh, loop_triangles=False, destructive=False)


def _draw_circles(op, context):
    """Circles of the new radii around the selected points, facing the view."""
    import gpu
    from gpu_extras.batch import batch_for_shader

    state, rv3d = op._state, context.region_data
    if state is None or rv3d is None or not len(state.centres):
        return
    matrix = state.obj.matrix_world
    scale = sum(matrix.to_scale()) / 3.0
    view = rv3d.view_rotation
    right, up = view @ Vector((1, 0, 0)), view @ Vector((0, 1, 0))
    angles = np.linspace(0.0, 2.0 * np.pi, 33)
    ring = np.outer(np.cos(angles), right) + np.outer(np.sin(angles), up)
    coords = []
    for centre, radius in zip(state.centres, state.current()):
        world = np.array(matrix @ Vector(centre))
        points = world + scale * radius * ring
        coords.extend(np.repeat(points, 2, axis=0)[1:-1].tolist())
    shader = gpu.shader.from_builtin("3D_UNIFORM_COLOR" if bpy.app.version < (4, 0, 0) else "UNIFORM_COLOR")
    batch = batch_for_shader(shader, "LINES", {"pos": coords})
    shader.bind()
    shader.uniform_float("color", (1.0, 0.6, 0.1, 1.0))
    batch.draw(shader)


def status(state):
    values = state.current()
    spread = f"{values.min():.4g}" if values.min() == values.max() else f"{values.min():.4g} to {values.max():.4g}"
    return (f"Radius × {state.factor:.3f}: {len(values)} selected, radius {spread}   "
            "(move the mouse, type a factor; Ctrl snap, Shift precise; click/Enter confirm, Esc/right-click cancel)")


class VESSELMESH_OT_radius(bpy.types.Operator):
    """Scale the radius of the selected centerline points: drag away from them to widen the vessel, towards
    them to narrow it (as the Skin modifier's Ctrl+A). Points without a radius start from their neighbours'.
    Regenerate afterwards to rebuild the surface"""

    bl_idname = "vesselmesh.radius"
    bl_label = "Scale Vessel Radius"
    bl_options = {"REGISTER", "UNDO", "GRAB_CURSOR", "BLOCKING"}

    factor: FloatProperty(name="Factor", default=1.0, min=0.0, soft_max=10.0,
                          description="What the selected radii are multiplied by")

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return (obj is not None and obj.type == "MESH" and obj.mode == "EDIT" and
                (obj.vesselmesh.role == "CENTERLINE" or RADIUS in obj.data.attributes))

    def execute(self, context):
        obj = context.active_object
        state = RadiusState(obj, centerline_of(obj).vesselmesh.settings.default_radius)
        if not state.selected.any():
            self.report({"WARNING"}, "Select the centerline points whose radius to change")
            return {"CANCELLED"}
        state.apply(self.factor)
        return {"FINISHED"}

    def invoke(self, context, event):
        from bpy_extras.view3d_utils import location_3d_to_region_2d

        obj = context.active_object
        self._state = RadiusState(obj, centerline_of(obj).vesselmesh.settings.default_radius)
        if not self._state.selected.any():
            self.report({"WARNING"}, "Select the centerline points whose radius to change")
            return {"CANCELLED"}
        centre = obj.matrix_world @ Vector(self._state.centres.mean(axis=0))
        pivot = location_3d_to_region_2d(context.region, context.region_data, centre) if context.region_data else None
        mouse = (event.mouse_region_x, event.mouse_region_y)
        self._drag = centerline_arrays.RadiusDrag(pivot if pivot is not None else mouse, mouse)
        self._handle = bpy.types.SpaceView3D.draw_handler_add(_draw_circles, (self, context), "WINDOW", "POST_VIEW")
        context.window_manager.modal_handler_add(self)
        context.area.header_text_set(status(self._state))
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type in {"RIGHTMOUSE", "ESC"} and event.value == "PRESS":
            self._state.restore()
            self._end(context)
            return {"CANCELLED"}
        if event.type in {"LEFTMOUSE", "RET", "NUMPAD_ENTER"} and event.value == "PRESS":
            self.factor = self._state.factor
            self._end(context)
            return {"FINISHED"}
        if event.value == "PRESS" and (event.type.startswith("NUMPAD_") or len(event.ascii) == 1 or
                                       event.type == "BACK_SPACE"):
            key = event.ascii or ("BACK_SPACE" if event.type == "BACK_SPACE" else "")
            if key:
                self._drag.type(key)
        elif event.type not in {"MOUSEMOVE", "LEFT_CTRL", "RIGHT_CTRL", "LEFT_SHIFT", "RIGHT_SHIFT"}:
            return {"RUNNING_MODAL"}
        self._state.apply(self._drag.factor((event.mouse_region_x, event.mouse_region_y), event.ctrl, event.shift))
        if context.area is not None:
            context.area.header_text_set(status(self._state))
            context.area.tag_redraw()
        return {"RUNNING_MODAL"}

    def _end(self, context):
        if getattr(self, "_handle", None) is not None:
            bpy.types.SpaceView3D.draw_handler_remove(self._handle, "WINDOW")
            self._handle = None
        if context.area is not None:
            context.area.header_text_set(None)
            context.area.tag_redraw()


def menu_radius(self, context):
    if VESSELMESH_OT_radius.poll(context):
        self.layout.operator(VESSELMESH_OT_radius.bl_idname)


keymaps = []


def register():
    bpy.utils.register_class(VESSELMESH_OT_radius)
    bpy.types.VIEW3D_MT_edit_mesh_vertices.append(menu_radius)
    config = bpy.context.window_manager.keyconfigs.addon
    if config is not None:  # none in background mode
        keymap = config.keymaps.new(name="Mesh", space_type="EMPTY")
        # Ctrl+A as for the Skin modifier's radii: on other meshes this tool's poll fails and Blender's own
        # Ctrl+A (Skin Resize) runs.
        keymaps.append((keymap, keymap.keymap_items.new(VESSELMESH_OT_radius.bl_idname, "A", "PRESS", ctrl=True)))


def unregister():
    for keymap, item in keymaps:
        keymap.keymap_items.remove(item)
    keymaps.clear()
    bpy.types.VIEW3D_MT_edit_mesh_vertices.remove(menu_radius)
    bpy.utils.unregister_class(VESSELMESH_OT_radius)
