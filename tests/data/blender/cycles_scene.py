"""What render_passes.py and render_sequence.py share: npr's axes in
Blender's, a factory-fresh Cycles scene that renders the same pixels on
every run into a multi-layer EXR, its world, sun and camera.

Blender is Z-up and npr Y-up: npr's (x, y, z) is Blender's (x, -z, y), the
rotation `NormalConvention::WorldZUp` undoes for normals. npr's `fov` is the
vertical field of view, so the camera fits its sensor vertically. Every
pixel is sampled at its centre (a pixel filter 0.01 px wide), as a
rasterizer does, so that depth and normals are not blended across edges.
"""

import math

import bpy
import mathutils


def to_blender(p):
    x, y, z = p
    return (x, -z, y)


def cycles_scene(width, height, exr_bits):
    """An empty Cycles scene (CPU, 4 samples, fixed seed, no denoising,
    adaptive sampling or motion blur) writing `exr_bits`-bit multi-layer
    EXRs, with a dark world; returns the scene and its view layer, which
    writes depth."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 4
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.seed = 0
    scene.cycles.filter_width = 0.01
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.use_motion_blur = False
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    scene.render.image_settings.color_depth = str(exr_bits)
    scene.render.image_settings.exr_codec = "ZIP"
    layer = scene.view_layers[0]
    layer.name = "ViewLayer"
    layer.use_pass_z = True

    world = bpy.data.worlds.new("world")
    world.color = (0.05, 0.05, 0.05)
    scene.world = world
    return scene, layer


def add_sun_and_camera(scene, camera, target, fov_y_deg, near, far):
    """The sun both scenes are lit by, and a camera at `camera` looking at
    `target` (npr's axes): its -Z towards the target, its +Y up."""
    bpy.ops.object.light_add(type="SUN", location=(0.0, 0.0, 5.0))
    sun = bpy.context.active_object
    sun.data.energy = 3.0
    sun.rotation_euler = (math.radians(40.0), math.radians(20.0), 0.0)

    bpy.ops.object.camera_add(location=to_blender(camera))
    cam = bpy.context.active_object
    cam.data.sensor_fit = "VERTICAL"
    cam.data.angle_y = math.radians(fov_y_deg)
    cam.data.clip_start, cam.data.clip_end = near, far
    direction = mathutils.Vector(to_blender(target)) - mathutils.Vector(to_blender(camera))
    cam.rotation_euler = direction.to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam
