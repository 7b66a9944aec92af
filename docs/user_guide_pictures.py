"""Render the pictures of docs/user_guide.md with the add-on itself (Workbench engine).

    blender -b --factory-startup --python-exit-code 1 --python docs/user_guide_pictures.py -- \\
        build/vesselmesh.zip docs/images

Installs the add-on from the zip into a temporary user profile and writes (640 x 400 PNGs):

    guide_import.png      bifurcation.swc: the centerline object and the surface the importer made
    guide_regenerate.png  before and after editing the centerline (a branch moved, one added)
    guide_methods.png     uniform and curvature-adaptive subdivision at level 2, wireframe over solid
    guide_colors.png      mean curvature (diverging map) and RMS curvature (viridis), with legends
"""
import os
import sys
import tempfile

import bmesh
import bpy
import numpy as np
from mathutils import Matrix, Vector

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIFURCATION = os.path.join(REPO, "native", "tests", "data", "bifurcation.swc")


def setup(zip_path):
    profile = tempfile.mkdtemp(prefix="vesselmesh-guide-")
    os.environ["BLENDER_USER_SCRIPTS"] = profile
    bpy.ops.preferences.addon_install(filepath=zip_path)
    bpy.ops.preferences.addon_enable(module="vesselmesh")


def new_scene():
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x, scene.render.resolution_y = 640, 400
    scene.render.image_settings.compression = 100
    scene.render.dither_intensity = 0  # flat areas without noise keep the PNGs small
    scene.view_settings.view_transform = "Standard"
    scene.display.render_aa = "8"
    shading = scene.display.shading
    shading.light, shading.color_type, shading.show_object_outline = "STUDIO", "OBJECT", True
    scene.world = bpy.data.worlds.new("background")
    scene.world.color = (0.92, 0.92, 0.92)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    return scene


def import_bifurcation(x, **options):
    bpy.ops.import_scene.vesselmesh(filepath=BIFURCATION, **options)
    surface = bpy.context.active_object
    for obj in (surface, surface.vesselmesh.centerline):
        obj.location.x += x
    surface.color = (0.88, 0.40, 0.32, 1.0)
    return surface.vesselmesh.centerline, surface


def centerline_tube(centerline):
    """The edges of a centerline object drawn as a thin dark tube (edge meshes do not render)."""
    curve = bpy.data.curves.new(centerline.name + " line", "CURVE")
    curve.dimensions, curve.bevel_depth = "3D", 0.06
    for a, b in (e.vertices for e in centerline.data.edges):
        spline = curve.splines.new("POLY")
        spline.points.add(1)
        for point, index in zip(spline.points, (a, b)):
            point.co = (*centerline.data.vertices[index].co, 1.0)
    obj = bpy.data.objects.new(curve.name, curve)
    obj.location = centerline.location
    obj.color = (0.1, 0.1, 0.12, 1.0)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def wireframe(surface):
    wire = bpy.data.objects.new(surface.name + " wire", surface.data)
    wire.location = surface.location
    bpy.context.scene.collection.objects.link(wire)
    modifier = wire.modifiers.new("wire", "WIREFRAME")
    modifier.thickness, modifier.use_even_offset = 0.02, False
    wire.color = (0.12, 0.09, 0.09, 1.0)


def aim(scene, margin=1.1):
    """Looks at everything rendered from the front and a little above, just fitting it."""
    bpy.context.view_layer.update()  # world matrices of the objects moved since
    coords = np.concatenate([[o.matrix_world @ Vector(c) for c in o.bound_box] for o in scene.objects
                             if o.type in {"MESH", "CURVE", "FONT"} and not o.hide_render])
    forward = Vector((0.0, 1.0, -0.3)).normalized()
    right = forward.cross(Vector((0.0, 0.0, 1.0))).normalized()
    scene.camera.matrix_world = Matrix((right, right.cross(forward), -forward)).transposed().to_4x4()
    centre = (coords.min(axis=0) + coords.max(axis=0)) / 2
    location, _ = scene.camera.camera_fit_coords(bpy.context.evaluated_depsgraph_get(),
                                                 (centre + margin * (coords - centre)).ravel())
    scene.camera.location = location


def render(scene, path):
    aim(scene)
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    print(f"wrote {path}: {os.path.getsize(path) // 1024} KiB")


def picture_import(out):
    scene = new_scene()
    centerline, surface = import_bifurcation(0.0)
    centerline_tube(centerline)
    surface.location.x += 8.0  # beside its centerline
    render(scene, out)


def picture_regenerate(out):
    scene = new_scene()
    import_bifurcation(-5.0, curvature=False)
    centerline, after = import_bifurcation(5.0, curvature=False)
    bm = bmesh.new()
    bm.from_mesh(centerline.data)
    bm.verts.ensure_lookup_table()
    radius = bm.verts.layers.float["radius"]
    bm.verts[6].co = (4.0, 0.0, 9.5)  # the right branch's tip bends outwards
    trunk = bm.verts[1]  # (0, 0, 2)
    tip = bm.verts.new((-3.5, 0.0, 4.0))  # a new branch off the trunk
    tip[radius] = 0.45
    bm.edges.new((trunk, tip))
    bm.to_mesh(centerline.data)
    bm.free()
    bpy.context.view_layer.objects.active = centerline
    bpy.ops.vesselmesh.generate()
    render(scene, out)


def picture_methods(out):
    scene = new_scene()
    for x, method in ((-5.0, "uniform"), (5.0, "curvature")):
        _, surface = import_bifurcation(x, method=method, curvature=False)
        wireframe(surface)
    render(scene, out)


def picture_colors(out):
    scene = new_scene()
    scene.display.shading.color_type = "VERTEX"
    camera, scene.camera = scene.camera, None  # without a camera each legend stands beside its surface
    for x, measure in ((-9.0, "mean"), (4.0, "rms")):
        import_bifurcation(x, color_measure=measure)
        bpy.ops.vesselmesh.legend()
    scene.camera = camera
    render(scene, out)


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2:
        print(__doc__)
        sys.exit(2)
    zip_path, out_dir = (os.path.abspath(a) for a in args)
    os.makedirs(out_dir, exist_ok=True)
    setup(zip_path)
    picture_import(os.path.join(out_dir, "guide_import.png"))
    picture_regenerate(os.path.join(out_dir, "guide_regenerate.png"))
    picture_methods(os.path.join(out_dir, "guide_methods.png"))
    picture_colors(os.path.join(out_dir, "guide_colors.png"))


main()
