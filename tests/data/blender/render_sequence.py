"""Render a short sequence of a moving sphere with Blender (Cycles, CPU) as
one multi-layer EXR per frame, 0000.exr ... 0003.exr, small enough to
commit (64x48, half floats): a style that reads Blender's frames through
`npr render --inputs 'DIR/{frame:04}.exr' --frames 0-3` runs over them
(tests/gpu/blender_sequence.rs; issue 47). The files are numbered from 0,
npr's first frame: a path-dependent style replays its frames from 0, so a
sequence numbered from 1 (Blender's default) would need a frame 0.

    PATH=/usr/bin:/bin blender -b --factory-startup -P render_sequence.py -- OUT_DIR

The scene is render_passes.py's (one sphere over a ground plane, a sun);
the sphere moves 0.4 m along x per frame. Samples, seed and pixel filter
are fixed, so re-running gives the same pixels.
"""

import math
import os
import sys

import bpy
import mathutils

WIDTH, HEIGHT = 64, 48
FRAMES = 4
CAMERA = (0.0, 1.6, 5.0)
TARGET = (0.0, 0.5, 0.0)
FOV_Y_DEG = 40.0
NEAR, FAR = 0.1, 50.0
RADIUS = 0.5
START_X, STEP_X = -0.6, 0.4


def to_blender(p):
    x, y, z = p
    return (x, -z, y)


def main():
    out_dir = sys.argv[sys.argv.index("--") + 1]
    os.makedirs(out_dir, exist_ok=True)
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
    scene.render.image_settings.color_depth = "16"
    scene.render.image_settings.exr_codec = "ZIP"
    layer = scene.view_layers[0]
    layer.name = "ViewLayer"
    layer.use_pass_z = True

    world = bpy.data.worlds.new("world")
    world.color = (0.05, 0.05, 0.05)
    scene.world = world

    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=RADIUS)
    sphere = bpy.context.active_object
    sphere.name = "ball"
    bpy.ops.object.shade_smooth()
    bpy.ops.mesh.primitive_plane_add(size=6.0, location=(0.0, 0.0, 0.0))

    bpy.ops.object.light_add(type="SUN", location=(0.0, 0.0, 5.0))
    sun = bpy.context.active_object
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(40.0), math.radians(20.0), 0.0)

    bpy.ops.object.camera_add(location=to_blender(CAMERA))
    cam = bpy.context.active_object
    cam.data.sensor_fit = "VERTICAL"
    cam.data.angle_y = math.radians(FOV_Y_DEG)
    cam.data.clip_start, cam.data.clip_end = NEAR, FAR
    direction = mathutils.Vector(to_blender(TARGET)) - mathutils.Vector(to_blender(CAMERA))
    cam.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam

    for frame in range(FRAMES):
        x = START_X + STEP_X * frame
        sphere.location = to_blender((x, RADIUS, 0.0))
        scene.render.filepath = os.path.join(out_dir, f"{frame:04}.exr")
        bpy.ops.render.render(write_still=True)


main()
