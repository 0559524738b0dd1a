"""Render a small analytic scene's passes with Blender (Cycles, CPU) as one
multi-layer EXR, and write the same scene as an npr scene TOML with the same
camera (issue 47: a style over a real renderer's frame).

    PATH=/usr/bin:/bin blender -b --factory-startup -P render_passes.py -- OUT.exr OUT.toml

Blender is Z-up and npr Y-up: npr's (x, y, z) is Blender's (x, -z, y), the
rotation `NormalConvention::WorldZUp` undoes for normals. npr's `fov` is the
vertical field of view, so the camera fits its sensor vertically.

Every pixel is sampled at its centre (a pixel filter 0.01 px wide), as a
rasterizer does, so that depth and normals are not blended across edges.
"""

import math
import sys

import bpy

WIDTH, HEIGHT = 160, 120
# In npr's axes (y up).
CAMERA = (0.0, 1.6, 5.0)
TARGET = (0.0, 0.5, 0.0)
FOV_Y_DEG = 40.0
NEAR, FAR = 0.1, 50.0
SPHERES = [("left", (-0.9, 0.6, 0.0), 0.6), ("right", (0.8, 0.45, 0.6), 0.45)]
PLANE = ("ground", 6.0)


def to_blender(p):
    x, y, z = p
    return (x, -z, y)


def main():
    argv = sys.argv[sys.argv.index("--") + 1 :]
    exr_out, toml_out = argv[0], argv[1]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 4
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.seed = 0
    scene.cycles.filter_width = 0.01
    scene.render.resolution_x, scene.render.resolution_y = WIDTH, HEIGHT
    scene.render.resolution_percentage = 100
    scene.render.use_motion_blur = False
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"
    layer = scene.view_layers[0]
    layer.name = "ViewLayer"
    layer.use_pass_z = True
    layer.use_pass_normal = True
    layer.use_pass_object_index = True
    layer.use_pass_vector = True

    world = bpy.data.worlds.new("world")
    world.color = (0.05, 0.05, 0.05)
    scene.world = world

    for i, (name, centre, radius) in enumerate(SPHERES):
        bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=radius, location=to_blender(centre))
        obj = bpy.context.active_object
        obj.name = name
        obj.pass_index = i + 1
        bpy.ops.object.shade_smooth()
    bpy.ops.mesh.primitive_plane_add(size=PLANE[1], location=(0.0, 0.0, 0.0))
    bpy.context.active_object.name = PLANE[0]
    bpy.context.active_object.pass_index = len(SPHERES) + 1

    bpy.ops.object.light_add(type="SUN", location=(0.0, 0.0, 5.0))
    sun = bpy.context.active_object
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(40.0), math.radians(20.0), 0.0)

    bpy.ops.object.camera_add(location=to_blender(CAMERA))
    cam = bpy.context.active_object
    cam.data.sensor_fit = "VERTICAL"
    cam.data.angle_y = math.radians(FOV_Y_DEG)
    cam.data.clip_start, cam.data.clip_end = NEAR, FAR
    # Look at the target: the camera's -Z towards it, its +Y up.
    import mathutils

    direction = mathutils.Vector(to_blender(TARGET)) - mathutils.Vector(to_blender(CAMERA))
    cam.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam

    scene.render.filepath = exr_out
    bpy.ops.render.render(write_still=True)

    with open(toml_out, "w") as f:
        f.write("# Written by tests/data/blender/render_passes.py: the scene Blender renders\n")
        f.write("# into blender_passes.exr, in npr's axes (y up).\n")
        f.write("[camera]\n")
        f.write(f"position = {list(CAMERA)}\ntarget = {list(TARGET)}\n")
        f.write(f"fov = {FOV_Y_DEG}\nnear = {NEAR}\nfar = {FAR}\n\n")
        for name, centre, radius in SPHERES:
            f.write("[[object]]\n")
            f.write(f'name = "{name}"\n')
            f.write(f'primitive = {{ kind = "sphere", radius = {radius}, segments = 64, rings = 32 }}\n')
            f.write(f"translate = {list(centre)}\n\n")
        f.write("[[object]]\n")
        f.write(f'name = "{PLANE[0]}"\n')
        f.write(f'primitive = {{ kind = "plane", size = {PLANE[1]}, subdivisions = 1 }}\n')


main()
