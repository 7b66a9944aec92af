"""Render the pictures of docs/user_guide.md with the add-on itself.

    blender -b --factory-startup --python-exit-code 1 --python docs/user_guide_pictures.py -- \\
        build/vesselmesh.zip docs/images [--only NAME ...]

Installs the add-on from the zip into a temporary user profile and writes PNGs:

    guide_teaching.png    the lecture picture: the built-in synthetic network (as `scripts/dev.sh demo` makes it)
                          through Teaching Render, Cycles, 1280 x 800
    guide_import.png      bifurcation.swc: the centerline object and the surface the importer made (Workbench)
    guide_regenerate.png  before and after editing the centerline (a branch moved, one added) (Workbench)
    guide_radius.png      the radius tool: the left branch's radius scaled by 1.6, regenerated (Cycles)
    guide_smoothing.png   a jagged tracing as traced and with Smooth Tracing 8 (Cycles)
    guide_methods.png     uniform and curvature-adaptive refinement at level 2, wireframe over solid (Workbench)
    guide_colors.png      Saddles and bulges (k2, diverging map) and mean curvature (sequential map) of
                          bifurcation.swc imported at scale 0.001, each through Teaching Render (Cycles)
    guide_closeup.png     a fork of brava-bg0003 close up, Saddles and bulges and Shape, each through Teaching
                          Render (Workbench; skipped when ../shared/data is absent)
"""
import os
import sys
import tempfile
import time

import bmesh
import bpy
import numpy as np
from mathutils import Matrix, Vector

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIFURCATION = os.path.join(REPO, "native", "tests", "data", "bifurcation.swc")
SIZE = (800, 500)


def setup(zip_path):
    profile = tempfile.mkdtemp(prefix="vesselmesh-guide-")
    os.environ["BLENDER_USER_SCRIPTS"] = profile
    bpy.ops.preferences.addon_install(filepath=zip_path)
    bpy.ops.preferences.addon_enable(module="vesselmesh")


def new_scene(size=SIZE):
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.image_settings.compression = 100
    return scene


def workbench(scene, color_type="OBJECT"):
    """The viewport's look, for pictures of the objects themselves."""
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.dither_intensity = 0  # flat areas without noise keep the PNGs small
    scene.view_settings.view_transform = "Standard"
    scene.display.render_aa = "8"
    shading = scene.display.shading
    shading.light, shading.color_type, shading.show_object_outline = "STUDIO", color_type, True
    scene.world = bpy.data.worlds.new("background")
    scene.world.color = (0.92, 0.92, 0.92)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera


def import_bifurcation(x, scale=1.0, **options):
    """bifurcation.swc (millimetres) at `scale`, its centerline moved x file units along x."""
    bpy.ops.import_scene.vesselmesh(filepath=BIFURCATION, scale=scale, **options)
    surface = bpy.context.active_object
    surface.vesselmesh.centerline.location.x += x * scale  # the surface, its child, follows
    surface.color = (0.88, 0.40, 0.32, 1.0)
    return surface.vesselmesh.centerline, surface


def centerline_tube(centerline, depth=0.06):
    """The edges of a centerline object drawn as a thin dark tube (edge meshes do not render)."""
    curve = bpy.data.curves.new(centerline.name + " line", "CURVE")
    curve.dimensions, curve.bevel_depth = "3D", depth
    for a, b in (e.vertices for e in centerline.data.edges):
        spline = curve.splines.new("POLY")
        spline.points.add(1)
        for point, index in zip(spline.points, (a, b)):
            point.co = (*centerline.data.vertices[index].co, 1.0)
    obj = bpy.data.objects.new(curve.name, curve)
    obj.matrix_world = centerline.matrix_world
    obj.color = (0.1, 0.1, 0.12, 1.0)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def wireframe(surface):
    wire = bpy.data.objects.new(surface.name + " wire", surface.data)
    wire.matrix_world = surface.matrix_world
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
    scene.render.filepath = path
    start = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    print(f"wrote {path}: {scene.render.resolution_x} x {scene.render.resolution_y}, {scene.render.engine}, "
          f"{time.perf_counter() - start:.1f} s, {os.path.getsize(path) // 1024} KiB", flush=True)


def teaching(scene, path, engine="CYCLES", samples=128, **options):
    """Teaching Render of every surface in the scene, its legend that of the active one."""
    bpy.ops.vesselmesh.teaching_render(engine=engine, samples=samples, **options)
    render(scene, path)


def write_vtk(path, data):
    """A legacy VTK polydata file of a centerline: one line cell per edge, the radius as point data."""
    points, edges, radius = data["points"], data["edges"], data["radius"]
    with open(path, "w") as f:
        f.write("# vtk DataFile Version 3.0\nsynthetic network\nASCII\nDATASET POLYDATA\n")
        f.write(f"POINTS {len(points)} double\n")
        f.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in points.tolist())
        f.write(f"LINES {len(edges)} {3 * len(edges)}\n")
        f.writelines(f"2 {a} {b}\n" for a, b in edges.tolist())
        f.write(f"POINT_DATA {len(points)}\nSCALARS radius double 1\nLOOKUP_TABLE default\n")
        f.writelines(f"{r!r}\n" for r in radius.tolist())


def picture_teaching(out):
    """The built-in network (`vesselmesh synth --sections 2000 --loops 2 --seed 1`, millimetres)."""
    vm = sys.modules["vesselmesh"].core.native.core()  # the add-on's own vesselmesh_core
    scene = new_scene((1280, 800))
    path = os.path.join(tempfile.mkdtemp(prefix="vesselmesh-guide-"), "network.vtk")
    write_vtk(path, vm.synthesize(sections=2000, loops=2, seed=1))
    bpy.ops.import_scene.vesselmesh(filepath=path, scale=0.001, preset="teaching")
    teaching(scene, out)


def picture_import(out):
    scene = new_scene()
    workbench(scene)
    centerline, surface = import_bifurcation(0.0)
    centerline_tube(centerline)
    surface.parent = None  # beside its centerline
    surface.location.x += 8.0
    aim(scene)
    render(scene, out)


def picture_regenerate(out):
    scene = new_scene()
    workbench(scene)
    import_bifurcation(-5.0, curvature=False)
    centerline, after = import_bifurcation(5.0, curvature=False)
    bm = bmesh.new()
    bm.from_mesh(centerline.data)
    bm.verts.ensure_lookup_table()
    bm.verts[6].co = (4.0, 0.0, 9.5)  # the right branch's tip bends outwards
    trunk = bm.verts[1]  # (0, 0, 2)
    tip = bm.verts.new((-3.5, 0.0, 4.0))  # a new branch off the trunk, thinner than the trunk
    tip[bm.verts.layers.float["radius"]] = 0.45
    bm.edges.new((trunk, tip))
    bm.to_mesh(centerline.data)
    bm.free()
    bpy.context.view_layer.objects.active = centerline
    bpy.ops.vesselmesh.generate()
    aim(scene)
    render(scene, out)


def picture_radius(out):
    scene = new_scene()
    import_bifurcation(-4.0, scale=0.001)
    centerline, surface = import_bifurcation(4.0, scale=0.001)
    bpy.context.view_layer.objects.active = centerline
    bpy.ops.object.mode_set(mode="EDIT")
    bm = bmesh.from_edit_mesh(centerline.data)
    for v in bm.verts:
        v.select_set(v.index in (7, 8, 9))  # the left branch
    bm.select_flush_mode()
    bmesh.update_edit_mesh(centerline.data)
    bpy.ops.vesselmesh.radius(factor=1.6)
    bpy.ops.object.mode_set(mode="OBJECT")
    bpy.ops.vesselmesh.generate()
    bpy.context.view_layer.objects.active = surface
    teaching(scene, out)


def picture_smoothing(out):
    scene = new_scene()
    rng = np.random.default_rng(5)
    folder = tempfile.mkdtemp(prefix="vesselmesh-guide-")
    path = os.path.join(folder, "jagged_tracing.swc")
    with open(path, "w") as f:  # a bent vessel traced on a coarse voxel grid: steps and jitter
        for i in range(60):
            t = i / 59
            x, z = 6 * np.sin(1.4 * t), 14 * t
            x, z = np.round(x / 0.6) * 0.6 + rng.normal(0, 0.08), np.round(z / 0.6) * 0.6
            f.write(f"{i + 1} 3 {x:.3f} {rng.normal(0, 0.08):.3f} {z:.3f} {0.55 + 0.1 * rng.random():.3f} "
                    f"{i if i else -1}\n")
    for x, smooth in ((-5.0, 0), (5.0, 8)):
        bpy.ops.import_scene.vesselmesh(filepath=path, scale=0.001, smooth=smooth, color_measure="k2")
        bpy.context.active_object.vesselmesh.centerline.location.x += 0.001 * x
    teaching(scene, out)


def picture_methods(out):
    scene = new_scene()
    workbench(scene)
    for x, method in ((-5.0, "uniform"), (5.0, "curvature")):
        _, surface = import_bifurcation(x, method=method, curvature=False)
        wireframe(surface)
    aim(scene)
    render(scene, out)


def side_by_side(paths, out):
    """One PNG of pictures of equal height, left to right."""
    images = [bpy.data.images.load(p) for p in paths]
    height = images[0].size[1]
    rows = [np.array(i.pixels[:], dtype=np.float32).reshape(height, i.size[0], 4) for i in images]
    joined = np.concatenate(rows, axis=1)
    image = bpy.data.images.new("joined", joined.shape[1], height, alpha=False)
    image.pixels.foreach_set(joined.ravel())
    image.filepath_raw, image.file_format = out, "PNG"
    image.save()
    for p in paths:
        os.remove(p)
    print(f"wrote {out}: {joined.shape[1]} x {height}, {os.path.getsize(out) // 1024} KiB", flush=True)


def picture_colors(out):
    parts = []
    for measure in ("k2", "mean"):
        scene = new_scene((640, 400))
        bpy.ops.import_scene.vesselmesh(filepath=BIFURCATION, scale=0.001, color_measure=measure)
        parts.append(out[:-4] + f"_{measure}.png")
        teaching(scene, parts[-1])
    side_by_side(parts, out)


def picture_closeup(out):
    """A fork of brava-bg0003 (../shared/data, millimetres) close up: no stripes along the vessels."""
    path = os.path.join(REPO, "..", "shared", "data", "brava-bg0003", "BG0003_ColorCoded.CNG.swc")
    if not os.path.exists(path):
        print(f"skipped {out}: {path} is absent", flush=True)
        return
    vm = sys.modules["vesselmesh"].core.native.core()
    graph = vm.read(path)
    points, radius = graph["points"] * 0.001, graph["radius"] * 0.001
    degree = np.bincount(graph["edges"].ravel(), minlength=len(points))
    forks = np.flatnonzero((degree == 3) & (radius >= np.median(radius)))
    fork = forks[len(forks) // 2]  # a fork of a mid-sized vessel, the same every time
    parts = []
    for measure in ("k2", "shape"):
        scene = new_scene((640, 400))
        bpy.ops.import_scene.vesselmesh(filepath=path, scale=0.001, color_measure=measure)
        bpy.ops.vesselmesh.teaching_render(engine="WORKBENCH", render=False)
        centre, distance = Vector(points[fork]), 12 * float(radius[fork])
        camera = scene.camera
        camera.location = centre + Vector((0.3, -1.0, 0.5)).normalized() * distance
        camera.rotation_euler = (centre - camera.location).to_track_quat("-Z", "Y").to_euler()
        camera.data.clip_start = 0.05 * float(radius[fork])
        # The legend hangs in front of the camera as far as the whole tree was: brought in (and shrunk
        # alike, so that it looks the same) to a quarter of the close-up's distance, in front of the vessels.
        for legend in camera.children:
            shrink = 0.25 * distance / max(abs(legend.location.z), 1e-12)
            legend.location *= shrink
            legend.scale *= shrink
        parts.append(out[:-4] + f"_{measure}.png")
        render(scene, parts[-1])
    side_by_side(parts, out)


PICTURES = {"guide_teaching": picture_teaching, "guide_import": picture_import,
            "guide_regenerate": picture_regenerate, "guide_radius": picture_radius,
            "guide_smoothing": picture_smoothing, "guide_methods": picture_methods,
            "guide_colors": picture_colors, "guide_closeup": picture_closeup}


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    only = args[args.index("--only") + 1:] if "--only" in args else list(PICTURES)
    args = args[:args.index("--only")] if "--only" in args else args
    if len(args) != 2:
        print(__doc__)
        sys.exit(2)
    zip_path, out_dir = (os.path.abspath(a) for a in args)
    os.makedirs(out_dir, exist_ok=True)
    setup(zip_path)
    for name in only:
        PICTURES[name](os.path.join(out_dir, name + ".png"))


main()
