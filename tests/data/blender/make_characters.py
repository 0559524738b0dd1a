"""Builds npr's skinned and morphing test characters and exports them as GLB
with Blender's bundled glTF exporter (issue 48).

Run with Debian's blender (3.4) and a system PATH, so that Blender's Python
finds Debian's numpy (the exporter needs it):

    PATH=/usr/bin:/bin blender -b --factory-startup \
        -P tests/data/blender/make_characters.py -- examples/models

It writes `arm.glb` (a two-bone chain skinning a subdivided cylinder, clip
`bend`) and `blob.glb` (a sphere with two shape keys, clip `pulse`). The
geometry is small on purpose (tens of KB): these are test assets.
"""

import math
import os
import sys

import bpy

out_dir = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "."
os.makedirs(out_dir, exist_ok=True)


def clear():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.fps = 24
    scene.frame_start = 1
    scene.frame_end = 25


def export(name):
    bpy.ops.export_scene.gltf(
        filepath=os.path.join(out_dir, name),
        export_format="GLB",
        export_animations=True,
        export_skins=True,
        export_morph=True,
        export_morph_normal=True,
        export_morph_tangent=False,
        export_materials="NONE",
        export_yup=True,
        export_apply=False,
        export_texcoords=True,
        export_normals=True,
    )


def make_arm():
    """An open tube of radius 0.25 from z = 0 to z = 2 (Blender's Z up: the
    exporter turns it to +Y), bones `upper` (z 0..1) and `lower` (z 1..2),
    weights blending linearly over z in [0.8, 1.2]."""
    clear()
    # An open tube: 12 segments by 17 rings (z = 0, 0.125, ..., 2), built
    # from data so that the vertex count stays small.
    segments, rings = 12, 17
    verts = [
        (0.25 * math.cos(2 * math.pi * s / segments), 0.25 * math.sin(2 * math.pi * s / segments), 2.0 * r / (rings - 1))
        for r in range(rings)
        for s in range(segments)
    ]
    faces = [
        (r * segments + s, r * segments + (s + 1) % segments, (r + 1) * segments + (s + 1) % segments, (r + 1) * segments + s)
        for r in range(rings - 1)
        for s in range(segments)
    ]
    data = bpy.data.meshes.new("arm")
    data.from_pydata(verts, [], faces)
    # Cylindrical UVs (u around, v along), so that styles reading `uv`
    # run on it; the seam at u = 0/1 splits 17 vertices in the export.
    uv_layer = data.uv_layers.new(name="UVMap")
    for poly in data.polygons:
        us = [(data.loops[i].vertex_index % segments) / segments for i in poly.loop_indices]
        for i, u in zip(poly.loop_indices, us):
            vertex = data.loops[i].vertex_index
            if u == 0.0 and max(us) > 0.5:
                u = 1.0
            uv_layer.data[i].uv = (u, (vertex // segments) / (rings - 1))
    data.update()
    arm = bpy.data.objects.new("arm", data)
    bpy.context.collection.objects.link(arm)
    bpy.context.view_layer.objects.active = arm
    arm.select_set(True)
    bpy.ops.object.shade_smooth()

    bpy.ops.object.armature_add(enter_editmode=True, location=(0, 0, 0))
    rig = bpy.context.object
    rig.name = "rig"
    bones = rig.data.edit_bones
    upper = bones[0]
    upper.name = "upper"
    upper.head = (0, 0, 0)
    upper.tail = (0, 0, 1)
    lower = bones.new("lower")
    lower.head = (0, 0, 1)
    lower.tail = (0, 0, 2)
    lower.parent = upper
    lower.use_connect = True
    bpy.ops.object.mode_set(mode="OBJECT")

    g_upper = arm.vertex_groups.new(name="upper")
    g_lower = arm.vertex_groups.new(name="lower")
    for v in arm.data.vertices:
        w = min(1.0, max(0.0, (v.co.z - 0.8) / 0.4))
        if w < 1.0:
            g_upper.add([v.index], 1.0 - w, "REPLACE")
        if w > 0.0:
            g_lower.add([v.index], w, "REPLACE")
    arm.parent = rig
    modifier = arm.modifiers.new("skin", "ARMATURE")
    modifier.object = rig

    rig.animation_data_create()
    action = bpy.data.actions.new("bend")
    rig.animation_data.action = action
    pose_upper = rig.pose.bones["upper"]
    pose_lower = rig.pose.bones["lower"]
    for bone in (pose_upper, pose_lower):
        bone.rotation_mode = "XYZ"
    for frame, up, low in ((1, 0.0, 0.0), (13, 20.0, 70.0), (25, 0.0, 0.0)):
        pose_upper.rotation_euler = (math.radians(up), 0, 0)
        pose_lower.rotation_euler = (math.radians(low), 0, 0)
        pose_upper.keyframe_insert("rotation_euler", frame=frame)
        pose_lower.keyframe_insert("rotation_euler", frame=frame)
    export("arm.glb")


def make_blob():
    """A UV sphere of radius 1 with shape keys `inflate` (every vertex
    pushed out 30 %) and `stretch` (y doubled above the equator), the first
    at a default value of 0.25; clip `pulse` animates both."""
    clear()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=16, ring_count=8, radius=1.0)
    blob = bpy.context.object
    blob.name = "blob"
    bpy.ops.object.shade_smooth()
    blob.shape_key_add(name="Basis")
    inflate = blob.shape_key_add(name="inflate")
    for point in inflate.data:
        point.co = point.co * 1.3
    stretch = blob.shape_key_add(name="stretch")
    for point in stretch.data:
        if point.co.z > 0:
            point.co.z *= 2.0
    inflate.value = 0.25
    stretch.value = 0.0
    keys = blob.data.shape_keys
    keys.animation_data_create()
    action = bpy.data.actions.new("pulse")
    keys.animation_data.action = action
    for frame, a, b in ((1, 0.25, 0.0), (13, 1.0, 0.5), (25, 0.25, 0.0)):
        inflate.value = a
        stretch.value = b
        inflate.keyframe_insert("value", frame=frame)
        stretch.keyframe_insert("value", frame=frame)
    inflate.value = 0.25
    stretch.value = 0.0
    export("blob.glb")


make_arm()
make_blob()
