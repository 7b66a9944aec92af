"""The "Vessel" tab of the 3D view's sidebar."""
import json

import bpy

from .operators import centerline_of, draw_colors, draw_settings, live
from .radius_tool import VESSELMESH_OT_radius


class VesselPanel:
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "Vessel"

    @staticmethod
    def pair(context):
        """(centerline, surface) of the active object; either may be None."""
        centerline = live(centerline_of(context.active_object))
        if centerline is None or centerline.type != "MESH":
            return None, None
        return centerline, live(centerline.vesselmesh.surface)


class VIEW3D_PT_vesselmesh(VesselPanel, bpy.types.Panel):
    bl_label = "Vessel Surface"

    def draw(self, context):
        layout = self.layout
        centerline, surface = self.pair(context)
        if centerline is None:
            layout.label(text="Select a centerline (a mesh of edges) or a vessel surface")
            layout.operator("import_scene.vesselmesh", icon="IMPORT")
            return
        layout.label(text=centerline.name, icon="OUTLINER_OB_MESH")
        if centerline.vesselmesh.source:
            layout.label(text=bpy.path.basename(centerline.vesselmesh.source), icon="FILE")
        row = layout.row()
        row.menu("VESSELMESH_MT_presets", icon="PRESET")
        row.operator("vesselmesh.generate", text="Regenerate" if surface else "Generate", icon="FILE_REFRESH")
        if VESSELMESH_OT_radius.poll(context):
            layout.operator(VESSELMESH_OT_radius.bl_idname, icon="FULLSCREEN_ENTER")
        layout.use_property_split = True
        draw_settings(layout, centerline.vesselmesh.settings)
        if surface is not None:
            row = layout.row()
            row.operator("vesselmesh.teaching_render", icon="RENDER_STILL")
            row.operator("export_mesh.vesselmesh", text="Export", icon="EXPORT")


class VIEW3D_PT_vesselmesh_colors(VesselPanel, bpy.types.Panel):
    bl_label = "Curvature Colours"
    bl_parent_id = "VIEW3D_PT_vesselmesh"

    @classmethod
    def poll(cls, context):
        return cls.pair(context)[1] is not None

    def draw(self, context):
        layout = self.layout
        centerline, surface = self.pair(context)
        layout.use_property_split = True
        draw_colors(layout, centerline.vesselmesh.settings)
        state = surface.vesselmesh
        if state.color_map:
            from ..core import colors, legend
            from .paint import unit_of

            measure = colors.MEASURES.get(state.color_measure)
            if measure is not None:
                unit, scale = unit_of(surface, context.scene)
                lo, hi = legend.in_file_unit([state.color_low, state.color_high], measure.dimension, scale)
                label = legend.unit_label(measure.dimension, unit)
                layout.label(text=f"{lo:.3g} to {hi:.3g} {label}")
            layout.operator("vesselmesh.legend", icon="COLOR")
        else:
            layout.label(text="Regenerate with Curvature on to colour the surface")


class VIEW3D_PT_vesselmesh_stats(VesselPanel, bpy.types.Panel):
    bl_label = "Last Run"
    bl_parent_id = "VIEW3D_PT_vesselmesh"

    @classmethod
    def poll(cls, context):
        surface = cls.pair(context)[1]
        return surface is not None and bool(surface.vesselmesh.stats)

    def draw(self, context):
        layout = self.layout
        stats = json.loads(self.pair(context)[1].vesselmesh.stats)
        col = layout.column(align=True)
        col.label(text=f"{stats['triangles']:,} triangles, {stats['vertices']:,} vertices")
        col.label(text=f"{stats['wall_seconds']:.2f} s in all, core {stats['seconds']:.2f} s")
        for stage in stats["stages"]:
            col.label(text=f"    {stage['stage']}: {stage['seconds']:.3f} s, {stage['faces']:,} faces")
        verified = stats.get("verified")
        if verified:
            col.label(text=f"Fails its own check: {verified['problem']}" if verified["problem"] else
                      f"Checked: closed, genus {verified['genus']}"
                      + ("" if verified["crossing_pairs"] else
                         ", no crossing" if verified["crossings_checked"] else
                         # .get: the statistics of a surface made before the check near joints lack it
                         ", no crossing near its joints" if verified.get("crossings_checked_near_joints") else
                         ""))
        lost = stats.get("lost_loops")
        if lost:
            ends = [", ".join(f"{c:.4g}" for c in joint) for joint in lost[0]["joints"]]
            col.label(text=f"Loops closed inside a joint: {len(lost)}, the first from ({ends[0]}) to ({ends[1]}):")
            col.label(text=f"    {lost[0]['why']}")
        if stats.get("hidden_terminals"):
            col.label(text=f"Twigs wholly inside other vessels left out: {stats['hidden_terminals']:,}")
        if stats.get("separated_points"):
            col.label(text=f"Crossing vessels moved apart: {stats['separated_points']:,} points, "
                           f"up to {stats['largest_separation']:.1f} radii")
        check = stats.get("check")
        col = layout.column(align=True)
        if check:
            error = check["fidelity"]["abs_relative_error"]
            col.label(text=("Closed manifold" if check["closed_manifold"] else "Not a closed manifold")
                      + f", genus {check['topology']['genus']}")
            col.label(text=f"{check['intersections']['pairs']} crossing triangle pairs")
            overlaps = check.get("input_overlaps", [])
            if overlaps:
                crossing = sum(o.get("crossing_pairs", 0) > 0 for o in overlaps)
                col.label(text=f"Centerline's tubes overlap at {len(overlaps)} place{'' if len(overlaps) == 1 else 's'}"
                               + (f", crossing at {crossing}" if crossing else ""))
            col.label(text=f"Radius error: median {error['median']:.1%}, 95% {error['p95']:.1%}")
            between = check["fidelity"].get("centroid_error")
            if between:
                col.label(text=f"Between the vertices: median {between['median']:.1%}, 95% {between['p95']:.1%}, "
                               f"99% {between['p99']:.1%}")
            col.label(text=f"Area off the tubes: {check['fidelity']['area_off_tubes']:.1%}")
            furthest, longest = check["fidelity"].get("largest_centroid_offset"), check["fidelity"].get("longest_edge")
            if furthest and longest:
                col.label(text=f"Furthest face {furthest['relative']:.2f} radii off, "
                               f"longest edge {longest['relative']:.1f} radii")
            missing = check["fidelity"].get("missing_axis")
            if missing and missing["relative"] > 0:
                col.label(text=f"Centerline with no surface round it: {missing['relative']:.1f} radii")
        layout.operator("vesselmesh.check", icon="CHECKMARK")


classes = (VIEW3D_PT_vesselmesh, VIEW3D_PT_vesselmesh_colors, VIEW3D_PT_vesselmesh_stats)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
