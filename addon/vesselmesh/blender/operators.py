"""File > Import, Regenerate, Check, Legend, Teaching Render and the presets."""
import json
import os
import time

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty
from bpy_extras.io_utils import ImportHelper

from ..core import meshing, presets
from ..core.native import core
from . import mesh as mesh_data
from . import teaching
from .paint import add_legend, curvature_material, live, paint
from .properties import MeshSettings, color_options, copy_settings, mesh_options

HEARTBEAT = 10.0  # seconds between "still working" lines on stdout in background mode


BACKGROUND = bpy.app.background  # read once: say() is called from the meshing job's worker too


def say(line):
    """A line on stdout in background mode, where headless users read what happens (the UI shows it in
    the status bar instead)."""
    if BACKGROUND:
        print(f"VesselMesh: {line}", flush=True)


class MeshJobRunner:
    """Runs a meshing job: from the UI as a modal operator (the status bar names the stage and the time so
    far, the progress bar steps through the stages, Esc cancels and leaves the scene as it was), from
    scripts and in background mode synchronously (Blender's timers and progress do not run there), with
    a line on stdout for each stage and every HEARTBEAT seconds while one lasts. `finish(context, job)`
    puts the result into the scene."""

    def start(self, context, prepare, settings):
        """Starts a job meshing what prepare() gives with these settings; a native module that does not load
        (an add-on built for another Python) is an error report, not a traceback."""
        try:
            job = meshing.MeshJob(prepare, mesh_options(settings), color_options(settings))
        except ImportError as error:
            self.report({"ERROR"}, f"{error}: build the add-on for this Blender (user guide, Install)")
            return {"CANCELLED"}
        return self.run(context, job)

    def run(self, context, job):
        self._job, self._started = job, time.perf_counter()
        if not self.options.is_invoke or bpy.app.background or context.window is None:
            beat = HEARTBEAT
            while not job.wait(0.25):
                self._tell()
                if job.seconds() >= beat:
                    say(f"{job.stage()[1]}, {job.seconds():.0f} s so far")
                    beat += HEARTBEAT
            self._tell()
            return self._finish(context)
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        wm.progress_begin(0, len(job.STAGES))
        return {"RUNNING_MODAL"}

    def _tell(self):
        for line in self._job.messages():
            say(line)

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
        index, stage = self._job.stage()
        context.window_manager.progress_update(index)
        context.workspace.status_text_set(
            f"VesselMesh: {stage} ({index + 1} of {len(self._job.STAGES)}), {self._job.seconds():.1f} s "
            f"(Esc to cancel)")
        return {"RUNNING_MODAL"}

    def _stop(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)

    def _finish(self, context):
        try:
            start = time.perf_counter()
            surface = self.finish(context, self._job)
            # Blender's first evaluation of the new surface copies it whole: done here, while the job still
            # holds freed memory (MeshJob), it reuses the pages the core let go of.
            context.view_layer.update()
            say(f"Blender's mesh filled in {time.perf_counter() - start:.2f} s")
        except (ValueError, RuntimeError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        finally:
            self._job.close()
        stats = json.loads(surface.vesselmesh.stats)
        self.report({"INFO"}, f"{surface.name}: {stats['triangles']:,} triangles in {stats['wall_seconds']:.2f} s "
                              f"(core {stats['seconds']:.2f} s)")
        problem = stats.get("verified", {}).get("problem")
        if problem:
            self.report({"WARNING"}, f"{surface.name} fails its own check: {problem} (Check Surface shows more)")
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
    """Ties a surface to its centerline: each knows the other, and the surface is the centerline's child, so
    that moving, turning or scaling the centerline object carries the surface along. A surface that had no
    parent (made by an older version) is put onto its centerline."""
    centerline.vesselmesh.role, surface.vesselmesh.role = "CENTERLINE", "SURFACE"
    centerline.vesselmesh.surface, surface.vesselmesh.centerline = surface, centerline
    if surface.parent != centerline:
        surface.parent = centerline
        surface.matrix_parent_inverse.identity()
        surface.matrix_basis.identity()


def new_surface(centerline, name):
    """A surface object for the centerline, its child (not yet in any collection)."""
    surface = bpy.data.objects.new(name, bpy.data.meshes.new(name))
    link_pair(centerline, surface)
    return surface


def select_only(context, obj):
    for other in context.selected_objects:
        other.select_set(False)
    obj.select_set(True)
    context.view_layer.objects.active = obj


def _apply_preset(self, context):
    """Choosing a preset fills in the settings at once (in the import dialog, they show)."""
    if self.preset != "none":
        presets.apply(self.preset, self)


PRESET_ITEMS = [("none", "As Below", "Use the settings below as they are")] + [
    (key, p.label, p.description) for key, p in presets.PRESETS.items()]


class PresetChoice:
    """The import's preset. As the last base class, its property comes first in the operator's properties,
    which Blender fills from a script's keywords in that order: the preset is applied first, and the
    settings a script names besides it win."""

    preset: EnumProperty(name="Preset", default="none", items=PRESET_ITEMS, update=_apply_preset,
                         description="Fill in the settings for a purpose")


class IMPORT_SCENE_OT_vesselmesh(MeshSettings, MeshJobRunner, bpy.types.Operator, ImportHelper, PresetChoice):
    """Import a vessel centerline and build its surface"""

    bl_idname = "import_scene.vesselmesh"
    bl_label = "Import Vessel Centerline"
    bl_options = {"REGISTER", "UNDO", "PRESET"}

    filter_glob: StringProperty(default="*.swc;*.vtk;*.vtp;*.csv", options={"HIDDEN"})
    scale: FloatProperty(name="Scale", default=1.0, min=1e-9, soft_min=1e-6, soft_max=1e3,
                         description="Multiplies the file's coordinates and radii: 0.001 for a file in millimetres "
                                     "(the scene is in metres), 1e-6 for micrometres; the legend then shows "
                                     "values per millimetre or micrometre")

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(self, "preset")
        layout.prop(self, "scale")
        draw_settings(layout, self)
        if self.curvature:
            draw_colors(layout, self)

    def execute(self, context):
        path, scale = self.filepath, self.scale
        held = {}
        default_set = self.properties.is_property_set("default_radius")
        default_radius, smooth = self.default_radius, self.smooth

        def prepare():
            say(f"reading {path}")
            data = meshing.read_centerline(path, scale)
            held["data"] = data
            typical = meshing.typical_radius(data)
            held["default_radius"] = default_radius if default_set or typical is None else typical
            return meshing.centerline_graph(**data, default_radius=held["default_radius"], smooth=smooth)

        self._held = held
        return self.start(context, prepare, self)

    def finish(self, context, job):
        job.graph()  # a bad file raises here: the scene changes only once the surface exists
        name = os.path.splitext(os.path.basename(self.filepath))[0]
        centerline = bpy.data.objects.new(name + " centerline", bpy.data.meshes.new(name + " centerline"))
        mesh_data.write_centerline(centerline.data, **self._held["data"])
        centerline.vesselmesh.source = self.filepath
        centerline.vesselmesh.scale = self.scale
        copy_settings(self, centerline.vesselmesh.settings)
        centerline.vesselmesh.settings.default_radius = self._held["default_radius"]
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


class VESSELMESH_OT_generate(MeshJobRunner, bpy.types.Operator):
    """Rebuild the vessel surface from its (edited) centerline, or build one from a mesh of edges with a
    `radius` attribute. The surface keeps its name, materials and modifiers, and follows the centerline
    object wherever it is moved"""

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
        name, default_radius, smooth = centerline.name, settings.default_radius, settings.smooth
        say(f"regenerating {centerline.name}: {len(data['points']):,} points")

        def prepare():
            try:
                return meshing.centerline_graph(**data, default_radius=default_radius, smooth=smooth)
            except (ValueError, RuntimeError) as error:
                raise ValueError(f"{name}: {error}") from error

        self._centerline = centerline
        return self.start(context, prepare, settings)

    def finish(self, context, job):
        job.graph()
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
        try:
            graph = meshing.centerline_graph(**mesh_data.read_centerline(centerline,
                                                                         context.evaluated_depsgraph_get()),
                                             default_radius=settings.default_radius, smooth=settings.smooth)
            # The surface follows the centerline with its crossing vessels moved apart: measured against that.
            tubes = (core().separate(graph) if settings.crossings == "separate" else None) or graph
            report = core().check(*mesh_data.triangles(surface.data), tubes)
        except (ValueError, RuntimeError) as error:
            self.report({"ERROR"}, f"{centerline.name}: {error}")
            return {"CANCELLED"}
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
                             f"radii, {report['fidelity']['missing_axis']['relative']:.1f} radii of centerline with no "
                             f"surface round it")
        return {"FINISHED"}


def surface_of(obj):
    """The surface an object belongs to: its own surface for a centerline, else the object itself."""
    if obj is not None and obj.vesselmesh.role == "CENTERLINE":
        return live(obj.vesselmesh.surface)
    return live(obj)


class VESSELMESH_OT_legend(bpy.types.Operator):
    """Add a colour bar with values for the surface's curvature colours (at the right of the camera's view
    when the scene has a camera, else beside the surface)"""

    bl_idname = "vesselmesh.legend"
    bl_label = "Add Legend"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        surface = surface_of(context.active_object)
        return surface is not None and bool(surface.vesselmesh.color_map)

    def execute(self, context):
        add_legend(context, surface_of(context.active_object))
        return {"FINISHED"}


class VESSELMESH_OT_teaching_render(bpy.types.Operator):
    """Set the scene up for a lecture picture of the vessels: a camera that frames them beside the legend,
    soft studio lights, a background that stands out from the colours, shadows and ambient occlusion.
    Press F12 to render (or tick Render)"""

    bl_idname = "vesselmesh.teaching_render"
    bl_label = "Teaching Render"
    bl_options = {"REGISTER", "UNDO"}

    engine: EnumProperty(
        name="Engine", default="EEVEE",
        items=[("EEVEE", "EEVEE", "Fast on a graphics card; soft shadows and ambient occlusion"),
               ("CYCLES", "Cycles", "Path traced: the most natural light, slower"),
               ("WORKBENCH", "Workbench", "The viewport's look, fastest: outlines, cavity shading")])
    background: EnumProperty(
        name="Background", default="auto",
        items=[("auto", "Automatic", "The grey that stands out most from both ends of the colour map"),
               ("light", "Light", "Near white, as on most slides"), ("mid", "Mid Grey", "Neutral grey"),
               ("dark", "Dark", "Near black, for dark slides")])
    samples: IntProperty(name="Samples", default=64, min=1, soft_max=1024,
                         description="Render samples (EEVEE and Cycles): more is smoother and slower")
    legend: BoolProperty(name="Legend", default=True, description="Show the colour legend beside the vessels")
    render: BoolProperty(name="Render", default=False, description="Render the picture at once")
    filepath: StringProperty(name="Save As", subtype="FILE_PATH", default="",
                             description="With Render: where to save the picture (PNG)")

    @classmethod
    def poll(cls, context):
        return bool(teaching.surfaces_in(context.scene))

    def execute(self, context):
        active = surface_of(context.active_object)
        surfaces = teaching.surfaces_in(context.scene)
        if active in surfaces:  # its legend is the one shown
            surfaces.remove(active)
            surfaces.insert(0, active)
        try:
            teaching.set_up(context, surfaces, self.engine, self.background, self.samples, self.legend)
        except RuntimeError as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        if self.render:
            scene = context.scene
            if self.filepath:
                scene.render.filepath = bpy.path.abspath(self.filepath)
            say(f"rendering {scene.render.resolution_x} x {scene.render.resolution_y} with {scene.render.engine}")
            start = time.perf_counter()
            bpy.ops.render.render(write_still=bool(self.filepath))
            say(f"rendered in {time.perf_counter() - start:.1f} s" +
                (f": {scene.render.filepath}" if self.filepath else ""))
        return {"FINISHED"}


class VESSELMESH_OT_apply_preset(bpy.types.Operator):
    """Fill in the active centerline's settings for a purpose (then press Regenerate)"""

    bl_idname = "vesselmesh.apply_preset"
    bl_label = "Apply Preset"
    bl_options = {"REGISTER", "UNDO"}

    preset: EnumProperty(name="Preset", items=PRESET_ITEMS[1:])

    @classmethod
    def poll(cls, context):
        centerline = live(centerline_of(context.active_object))
        return centerline is not None and centerline.type == "MESH"

    @classmethod
    def description(cls, context, properties):
        return presets.PRESETS[properties.preset].description

    def execute(self, context):
        settings = centerline_of(context.active_object).vesselmesh.settings
        presets.apply(self.preset, settings)
        return {"FINISHED"}


class VESSELMESH_MT_presets(bpy.types.Menu):
    bl_idname = "VESSELMESH_MT_presets"
    bl_label = "Presets"

    def draw(self, context):
        for key, preset in presets.PRESETS.items():
            self.layout.operator(VESSELMESH_OT_apply_preset.bl_idname, text=preset.label).preset = key


def draw_settings(layout, settings):
    """The meshing settings, for the import dialog and the sidebar: the ones that change the picture most
    first, the finer ones below."""
    col = layout.column()
    col.prop(settings, "levels")
    col.prop(settings, "smooth")
    col.prop(settings, "curvature")
    col = layout.column(heading="Shape")
    col.prop(settings, "fit")
    col.prop(settings, "crossings")
    col.prop(settings, "caps")
    col.prop(settings, "default_radius")
    col = layout.column(heading="Triangles")
    col.prop(settings, "method")
    if settings.method != "uniform":
        col.prop(settings, "uniform_levels")
    if settings.method == "curvature":
        col.prop(settings, "threshold")
        col.prop(settings, "measure")
    elif settings.method == "dihedral":
        col.prop(settings, "angle")
    col.prop(settings, "alpha")
    col.prop(settings, "beta")
    col.prop(settings, "sampling")


def draw_colors(layout, settings):
    col = layout.column()
    col.prop(settings, "color_measure")
    col.prop(settings, "colormap")
    col.prop(settings, "percentile")


def menu_import(self, context):
    self.layout.operator(IMPORT_SCENE_OT_vesselmesh.bl_idname, text="Vessel centerline (.swc .vtk .vtp .csv)")


classes = (IMPORT_SCENE_OT_vesselmesh, VESSELMESH_OT_generate, VESSELMESH_OT_check, VESSELMESH_OT_legend,
           VESSELMESH_OT_teaching_render, VESSELMESH_OT_apply_preset, VESSELMESH_MT_presets)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.TOPBAR_MT_file_import.append(menu_import)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(menu_import)
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
