"""File > Import, Regenerate, Check and Legend."""
import json
import os
import time

import bpy
from bpy_extras.io_utils import ImportHelper
from bpy.props import FloatProperty, StringProperty

from ..core import meshing
from ..core.native import core
from . import mesh as mesh_data
from .paint import add_legend, curvature_material, paint
from .properties import MeshSettings, color_options, copy_settings, mesh_options


class MeshJobRunner:
    """Runs a meshing job: from the UI as a modal operator (progress in the status bar, Esc cancels and
    leaves the scene as it was), from scripts and in background mode synchronously (Blender's timers
    and progress do not run there). `finish(context, job)` puts the result into the scene."""

    def run(self, context, job):
        self._job, self._started = job, time.perf_counter()
        if not self.options.is_invoke or bpy.app.background or context.window is None:
            return self._finish(context)
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        wm.progress_begin(0, 2)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC":
            self._job.cancel()
            self._stop(context)
            self.report({"WARNING"}, "Meshing cancelled; nothing changed")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}  # the view stays navigable while the core works
        if self._job.done():
            self._stop(context)
            return self._finish(context)
        step = "curvature" if self._job.surface_done() else "meshing"
        context.window_manager.progress_update(1 if self._job.surface_done() else 0)
        context.workspace.status_text_set(
            f"VesselMesh: {step}, {time.perf_counter() - self._started:.1f} s (Esc to cancel)")
        return {"RUNNING_MODAL"}

    def _stop(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)

    def _finish(self, context):
        try:
            surface = self.finish(context, self._job)
            # Blender's first evaluation of the new surface copies it whole: done here, while the job still
            # holds freed memory (MeshJob), it reuses the pages the core let go of.
            context.view_layer.update()
        except (ValueError, RuntimeError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        finally:
            self._job.close()
        stats = json.loads(surface.vesselmesh.stats)
        self.report({"INFO"}, f"{surface.name}: {stats['triangles']:,} triangles in {stats['wall_seconds']:.2f} s "
                              f"(core {stats['seconds']:.2f} s)")
        return {"FINISHED"}


def build_surface(job, surface, started):
    """Writes the job's surface and curvature into the surface object's mesh, and its figures."""
    mesh_data.write_surface(surface.data, *job.surface(), job.edges)
    for name, values in job.curvature().items():  # waits for the curvature run, which ran meanwhile
        mesh_data.set_float_attribute(surface.data, name, values)
    stats = job.stats()
    stats["wall_seconds"] = time.perf_counter() - started
    surface.vesselmesh.stats = json.dumps(stats)
    coloring = job.coloring(color_options(surface.vesselmesh.centerline.vesselmesh.settings))
    if paint(surface, coloring) and not surface.data.materials:
        surface.data.materials.append(curvature_material())


def link_pair(centerline, surface):
    centerline.vesselmesh.role, surface.vesselmesh.role = "CENTERLINE", "SURFACE"
    centerline.vesselmesh.surface, surface.vesselmesh.centerline = surface, centerline


def new_surface(centerline, name):
    """A surface object for the centerline, with its transform (not yet in any collection)."""
    surface = bpy.data.objects.new(name, bpy.data.meshes.new(name))
    surface.matrix_world = centerline.matrix_world
    link_pair(centerline, surface)
    return surface


def select_only(context, obj):
    for other in context.selected_objects:
        other.select_set(False)
    obj.select_set(True)
    context.view_layer.objects.active = obj


class IMPORT_SCENE_OT_vesselmesh(MeshSettings, MeshJobRunner, bpy.types.Operator, ImportHelper):
    """Import a vessel centerline and build its surface"""

    bl_idname = "import_scene.vesselmesh"
    bl_label = "Import Vessel Centerline"
    bl_options = {"REGISTER", "UNDO", "PRESET"}

    filter_glob: StringProperty(default="*.swc;*.vtk;*.vtp;*.csv", options={"HIDDEN"})
    scale: FloatProperty(name="Scale", default=1.0, min=1e-9, soft_min=1e-6, soft_max=1e3,
                         description="Multiplies the file's coordinates and radii (0.001: millimetres to metres)")

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(self, "scale")
        draw_settings(layout, self)
        if self.curvature:
            draw_colors(layout, self)

    def execute(self, context):
        try:
            self._data = meshing.read_centerline(self.filepath, self.scale)
            graph = meshing.centerline_graph(**self._data, default_radius=self.default_radius)
        except (ValueError, RuntimeError) as error:  # InputError names the file and the line
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        return self.run(context, meshing.MeshJob(graph, mesh_options(self), color_options(self)))

    def finish(self, context, job):
        # The scene changes only once the surface exists: a failed or cancelled run leaves it as it was.
        name = os.path.splitext(os.path.basename(self.filepath))[0]
        centerline = bpy.data.objects.new(name + " centerline", bpy.data.meshes.new(name + " centerline"))
        mesh_data.write_centerline(centerline.data, **self._data)
        centerline.vesselmesh.source = self.filepath
        copy_settings(self, centerline.vesselmesh.settings)
        surface = new_surface(centerline, name)
        try:
            build_surface(job, surface, self._started)
        except (ValueError, RuntimeError):
            for obj in (surface, centerline):
                data = obj.data
                bpy.data.objects.remove(obj)
                bpy.data.meshes.remove(data)
            raise
        for obj in (centerline, surface):
            context.collection.objects.link(obj)
        select_only(context, surface)
        return surface


def centerline_of(obj):
    """The centerline an object belongs to: its own centerline for a surface, else the object itself."""
    if obj is not None and obj.vesselmesh.role == "SURFACE":
        return obj.vesselmesh.centerline
    return obj


def live(obj):
    """obj, unless it is None or was deleted (kept alive only by a pointer)."""
    return obj if obj is not None and obj.users_collection else None


class VESSELMESH_OT_generate(MeshJobRunner, bpy.types.Operator):
    """Rebuild the vessel surface from its (edited) centerline, or build one from a mesh of edges with a
    `radius` attribute. The surface keeps its name, transform, materials and modifiers"""

    bl_idname = "vesselmesh.generate"
    bl_label = "Regenerate Surface"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        centerline = live(centerline_of(context.active_object))
        return centerline is not None and centerline.type == "MESH"

    def execute(self, context):
        centerline = centerline_of(context.active_object)
        settings = centerline.vesselmesh.settings
        surface = live(centerline.vesselmesh.surface)
        if surface is not None and surface.mode == "EDIT":
            self.report({"ERROR"}, f"{surface.name} is in edit mode: leave it to regenerate the surface")
            return {"CANCELLED"}
        data = mesh_data.read_centerline(centerline, context.evaluated_depsgraph_get())
        if not len(data["edges"]):
            self.report({"ERROR"}, f"{centerline.name} has no edges to build a vessel along")
            return {"CANCELLED"}
        try:
            graph = meshing.centerline_graph(**data, default_radius=settings.default_radius)
        except (ValueError, RuntimeError) as error:
            self.report({"ERROR"}, f"{centerline.name}: {error}")
            return {"CANCELLED"}
        self._centerline = centerline
        return self.run(context, meshing.MeshJob(graph, mesh_options(settings), color_options(settings)))

    def finish(self, context, job):
        centerline = self._centerline
        surface = live(centerline.vesselmesh.surface)
        if surface is None:
            surface = new_surface(centerline, centerline.name + " surface")
            for collection in centerline.users_collection:
                collection.objects.link(surface)
        link_pair(centerline, surface)
        build_surface(job, surface, self._started)
        return surface


class VESSELMESH_OT_check(bpy.types.Operator):
    """Check the surface: closed, manifold, self-intersections, and how closely it follows the radii"""

    bl_idname = "vesselmesh.check"
    bl_label = "Check Surface"

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and live(obj.vesselmesh.surface if obj.vesselmesh.role == "CENTERLINE" else obj) \
            is not None and live(centerline_of(obj)) is not None

    def execute(self, context):
        centerline = centerline_of(context.active_object)
        surface = centerline.vesselmesh.surface
        settings = centerline.vesselmesh.settings
        graph = meshing.centerline_graph(**mesh_data.read_centerline(centerline, context.evaluated_depsgraph_get()),
                                         default_radius=settings.default_radius)
        report = core().check(*mesh_data.triangles(surface.data), graph)
        # Where the centerline's own tubes overlap, the surface cannot follow both: say where.
        report["input_overlaps"] = graph.summary()["overlaps"]
        places = len(report["input_overlaps"])
        stats = json.loads(surface.vesselmesh.stats or "{}")
        stats["check"] = report
        surface.vesselmesh.stats = json.dumps(stats)
        topology, crossing = report["topology"], report["intersections"]
        level = "INFO" if report["closed_manifold"] else "WARNING"
        self.report({level}, f"{surface.name}: {'closed manifold' if report['closed_manifold'] else 'NOT closed'}, "
                             f"genus {topology['genus']}, {crossing['pairs']} crossing triangle pairs "
                             f"({crossing['pairs_in_overlapping_tubes']} where the centerline's tubes overlap, "
                             f"at {places} place{'' if places == 1 else 's'}), "
                             f"radius error median {report['fidelity']['abs_relative_error']['median']:.1%}, "
                             f"{report['fidelity']['area_off_tubes']:.1%} of its area off the tubes, "
                             f"the furthest face {report['fidelity']['largest_centroid_offset']['relative']:.2f} "
                             f"radii off them, the longest edge {report['fidelity']['longest_edge']['relative']:.1f} "
                             f"radii")
        return {"FINISHED"}


class VESSELMESH_OT_legend(bpy.types.Operator):
    """Add a colour bar with values for the surface's curvature colours (in the camera's view when the scene
    has a camera)"""

    bl_idname = "vesselmesh.legend"
    bl_label = "Add Legend"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        surface = live(obj.vesselmesh.surface if obj is not None and obj.vesselmesh.role == "CENTERLINE" else obj)
        return surface is not None and bool(surface.vesselmesh.color_map)

    def execute(self, context):
        obj = context.active_object
        surface = obj.vesselmesh.surface if obj.vesselmesh.role == "CENTERLINE" else obj
        legend = live(surface.vesselmesh.legend)
        if legend is not None:
            bpy.data.objects.remove(legend)
        add_legend(context, surface)
        return {"FINISHED"}


def draw_settings(layout, settings):
    """The meshing and colour settings, for the import dialog and the sidebar."""
    col = layout.column()
    col.prop(settings, "method")
    col.prop(settings, "levels")
    if settings.method != "uniform":
        col.prop(settings, "uniform_levels")
    if settings.method == "curvature":
        col.prop(settings, "threshold")
        col.prop(settings, "measure")
    elif settings.method == "dihedral":
        col.prop(settings, "angle")
    col = layout.column()
    col.prop(settings, "sampling")
    col.prop(settings, "alpha")
    col.prop(settings, "beta")
    col.prop(settings, "caps")
    col.prop(settings, "crossings")
    col.prop(settings, "fit")
    col.prop(settings, "default_radius")
    col.prop(settings, "curvature")


def draw_colors(layout, settings):
    col = layout.column()
    col.prop(settings, "color_measure")
    col.prop(settings, "colormap")
    col.prop(settings, "percentile")


def menu_import(self, context):
    self.layout.operator(IMPORT_SCENE_OT_vesselmesh.bl_idname, text="Vessel centerline (.swc .vtk .vtp .csv)")


classes = (IMPORT_SCENE_OT_vesselmesh, VESSELMESH_OT_generate, VESSELMESH_OT_check, VESSELMESH_OT_legend)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.TOPBAR_MT_file_import.append(menu_import)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(menu_import)
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
