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

import os
import sys

import bpy

# The shared set-up lives beside this script (cycles_scene.py).
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycles_scene import add_sun_and_camera, cycles_scene, to_blender  # noqa: E402

WIDTH, HEIGHT = 64, 48
FRAMES = 4
CAMERA = (0.0, 1.6, 5.0)
TARGET = (0.0, 0.5, 0.0)
FOV_Y_DEG = 40.0
NEAR, FAR = 0.1, 50.0
RADIUS = 0.5
START_X, STEP_X = -0.6, 0.4


def main():
    out_dir = sys.argv[sys.argv.index("--") + 1]
    os.makedirs(out_dir, exist_ok=True)
    scene, _ = cycles_scene(WIDTH, HEIGHT, 16)

    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=RADIUS)
    sphere = bpy.context.active_object
    sphere.name = "ball"
    bpy.ops.object.shade_smooth()
    bpy.ops.mesh.primitive_plane_add(size=6.0, location=(0.0, 0.0, 0.0))

    add_sun_and_camera(scene, CAMERA, TARGET, FOV_Y_DEG, NEAR, FAR)

    for frame in range(FRAMES):
        x = START_X + STEP_X * frame
        sphere.location = to_blender((x, RADIUS, 0.0))
        scene.render.filepath = os.path.join(out_dir, f"{frame:04}.exr")
        bpy.ops.render.render(write_still=True)


main()
