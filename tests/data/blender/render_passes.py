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

import os
import sys

import bpy

# The shared set-up lives beside this script (cycles_scene.py).
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_scene import add_sun_and_camera, cycles_scene, to_blender  # noqa: E402

WIDTH, HEIGHT = 160, 120
# In npr's axes (y up).
CAMERA = (0.0, 1.6, 5.0)
TARGET = (0.0, 0.5, 0.0)
FOV_Y_DEG = 40.0
NEAR, FAR = 0.1, 50.0
SPHERES = [("left", (-0.9, 0.6, 0.0), 0.6), ("right", (0.8, 0.45, 0.6), 0.45)]
PLANE = ("ground", 6.0)


def main():
    argv = sys.argv[sys.argv.index("--") + 1 :]
    exr_out, toml_out = argv[0], argv[1]
    scene, layer = cycles_scene(WIDTH, HEIGHT, 32)
    layer.use_pass_normal = True
    layer.use_pass_object_index = True
    layer.use_pass_vector = True

    for i, (name, centre, radius) in enumerate(SPHERES):
        bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=radius, location=to_blender(centre))
        obj = bpy.context.active_object
        obj.name = name
        obj.pass_index = i + 1
        bpy.ops.object.shade_smooth()
    bpy.ops.mesh.primitive_plane_add(size=PLANE[1], location=(0.0, 0.0, 0.0))
    bpy.context.active_object.name = PLANE[0]
    bpy.context.active_object.pass_index = len(SPHERES) + 1

    add_sun_and_camera(scene, CAMERA, TARGET, FOV_Y_DEG, NEAR, FAR)

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
