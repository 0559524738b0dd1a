"""Builds npr's skinned and morphing test characters and exports them as GLB
with Blender's bundled glTF exporter (issue 48).

Run with Debian's blender (3.4) and a system PATH, so that Blender's Python
finds Debian's numpy (the exporter needs it):

    PATH=/usr/bin:/bin blender -b --factory-startup \
        -P tests/data/blender/make_characters.py -- examples/models

It writes `arm.glb` (a two-bone chain skinning a subdivided cylinder, clip
`bend`), `blob.glb` (a sphere with two shape keys, clip `pulse`) and
`walker.glb` (a figure of eight bones with a textured material, clip `walk`,
one second looping). The geometry is small on purpose (tens of KB): these
are test assets.
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


def export(name, materials="NONE"):
    bpy.ops.export_scene.gltf(
        filepath=os.path.join(out_dir, name),
        export_format="GLB",
        export_animations=True,
        export_skins=True,
        export_morph=True,
        export_morph_normal=True,
        export_morph_tangent=False,
        export_materials=materials,
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


# The walker's parts: (name, bottom, top, radius, x, bones, v-row of the
# texture). Each part is a closed capsule along Blender's z (the exporter
# turns it to +Y); `bones` is one bone (rigid) or two blended linearly over
# z in [knee - 0.06, knee + 0.06] (the knee or the waist).
WALKER_PARTS = (
    ("torso", 0.85, 1.55, 0.20, 0.0, ("hips", "spine", 1.12)),
    ("head", 1.58, 1.90, 0.14, 0.0, ("spine",)),
    ("leg.L", 0.0, 0.95, 0.085, 0.11, ("thigh.L", "shin.L", 0.50)),
    ("leg.R", 0.0, 0.95, 0.085, -0.11, ("thigh.R", "shin.R", 0.50)),
    ("arm.L", 0.85, 1.50, 0.06, 0.28, ("arm.L",)),
    ("arm.R", 0.85, 1.50, 0.06, -0.28, ("arm.R",)),
)

# The walker's texture: one 8-texel-high band per part (its base colour),
# with a 4-texel checker of a lighter shade in it, so that the pattern is
# visible and its position on the surface can be checked through the UVs.
WALKER_COLOURS = (
    (0.80, 0.25, 0.20),  # torso: red shirt
    (0.95, 0.80, 0.65),  # head: skin
    (0.20, 0.30, 0.70),  # legs: blue trousers
    (0.20, 0.30, 0.70),
    (0.95, 0.80, 0.65),  # arms: skin
    (0.95, 0.80, 0.65),
)
TEXTURE_SIZE = 48


def walker_texture():
    image = bpy.data.images.new("walker_colour", TEXTURE_SIZE, TEXTURE_SIZE, alpha=False)
    pixels = []
    for y in range(TEXTURE_SIZE):
        band = min(len(WALKER_COLOURS) - 1, y // 8)
        for x in range(TEXTURE_SIZE):
            light = ((x // 4) + (y // 4)) % 2
            r, g, b = WALKER_COLOURS[band]
            k = 1.0 if light == 0 else 0.6
            pixels.extend((r * k, g * k, b * k, 1.0))
    image.pixels = pixels
    image.filepath_raw = "//walker_colour.png"
    image.file_format = "PNG"
    image.pack()
    return image


def walker_material():
    material = bpy.data.materials.new("walker")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    bsdf = nodes["Principled BSDF"]
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = walker_texture()
    texture.interpolation = "Closest"
    material.node_tree.links.new(texture.outputs["Color"], bsdf.inputs["Base Color"])
    bsdf.inputs["Metallic"].default_value = 0.25
    bsdf.inputs["Roughness"].default_value = 0.6
    bsdf.inputs["Emission"].default_value = (0.05, 0.02, 0.0, 1.0)
    bsdf.inputs["Emission Strength"].default_value = 1.0
    return material


def make_walker():
    """A figure 1.9 high standing on z = 0, bones hips (root, the pelvis),
    spine, thigh/shin per leg and one bone per arm; clip `walk` (one
    second, looping: its last key equals its first). Each part's UVs map u
    around and v along the part into its band of the texture."""
    clear()
    # Keys from frame 0, so that the clip's times run 0..1 s exactly.
    bpy.context.scene.frame_start = 0
    bpy.context.scene.frame_end = 24
    segments, rings = 12, 10
    verts, faces, loops_uv, owners = [], [], [], []
    for k, (name, z0, z1, radius, x, bones) in enumerate(WALKER_PARTS):
        base = len(verts)
        v_low, v_high = (k * 8 + 0.5) / TEXTURE_SIZE, (k * 8 + 7.5) / TEXTURE_SIZE
        # Pole, rings (radius r sin(pi t)), pole: a closed, manifold capsule.
        verts.append((x, 0.0, z0))
        for r in range(1, rings):
            t = r / rings
            ring_radius = radius * math.sin(math.pi * t) ** 0.5
            z = z0 + (z1 - z0) * t
            for s in range(segments):
                a = 2 * math.pi * s / segments
                verts.append((x + ring_radius * math.cos(a), ring_radius * math.sin(a), z))
        verts.append((x, 0.0, z1))
        top = len(verts) - 1
        ring = lambda r, s: base + 1 + (r - 1) * segments + s % segments
        v_of = lambda r: v_low + (v_high - v_low) * r / rings
        for s in range(segments):
            faces.append((base, ring(1, s + 1), ring(1, s)))
            loops_uv.append([((s + 0.5) / segments, v_of(0)), ((s + 1) / segments, v_of(1)), (s / segments, v_of(1))])
        for r in range(1, rings - 1):
            for s in range(segments):
                faces.append((ring(r, s), ring(r, s + 1), ring(r + 1, s + 1), ring(r + 1, s)))
                loops_uv.append([
                    (s / segments, v_of(r)), ((s + 1) / segments, v_of(r)),
                    ((s + 1) / segments, v_of(r + 1)), (s / segments, v_of(r + 1)),
                ])
        for s in range(segments):
            faces.append((ring(rings - 1, s), ring(rings - 1, s + 1), top))
            loops_uv.append([(s / segments, v_of(rings - 1)), ((s + 1) / segments, v_of(rings - 1)), ((s + 0.5) / segments, v_of(rings))])
        owners.append((base, len(verts), bones))

    data = bpy.data.meshes.new("walker")
    data.from_pydata(verts, [], faces)
    uv_layer = data.uv_layers.new(name="UVMap")
    for poly, uvs in zip(data.polygons, loops_uv):
        for i, uv in zip(poly.loop_indices, uvs):
            uv_layer.data[i].uv = uv
    data.update()
    data.materials.append(walker_material())
    walker = bpy.data.objects.new("walker", data)
    bpy.context.collection.objects.link(walker)
    bpy.context.view_layer.objects.active = walker
    walker.select_set(True)
    bpy.ops.object.shade_smooth()

    bpy.ops.object.armature_add(enter_editmode=True, location=(0, 0, 0))
    rig = bpy.context.object
    rig.name = "rig"
    bones = rig.data.edit_bones
    hips = bones[0]
    hips.name = "hips"
    hips.head, hips.tail = (0, 0, 0.95), (0, 0, 1.12)

    def bone(name, head, tail, parent, connect=False):
        b = bones.new(name)
        b.head, b.tail = head, tail
        b.parent = parent
        b.use_connect = connect
        return b

    spine = bone("spine", (0, 0, 1.12), (0, 0, 1.6), hips, True)
    for side, x in (("L", 0.11), ("R", -0.11)):
        thigh = bone(f"thigh.{side}", (x, 0, 0.95), (x, 0, 0.50), hips)
        bone(f"shin.{side}", (x, 0, 0.50), (x, 0, 0.02), thigh, True)
    for side, x in (("L", 0.28), ("R", -0.28)):
        bone(f"arm.{side}", (x, 0, 1.50), (x, 0, 0.88), spine)
    bpy.ops.object.mode_set(mode="OBJECT")

    groups = {}
    for base, end, owner in owners:
        for index in range(base, end):
            z = walker.data.vertices[index].co.z
            if len(owner) == 1:
                weights = {owner[0]: 1.0}
            else:
                lower_bone, upper_bone, joint = owner
                # Legs: the thigh is above the knee; the torso: the spine is above the waist.
                above, below = (lower_bone, upper_bone) if lower_bone.startswith("thigh") else (upper_bone, lower_bone)
                w = min(1.0, max(0.0, (z - (joint - 0.06)) / 0.12))
                weights = {above: w, below: 1.0 - w}
            for name, w in weights.items():
                if w > 0.0:
                    if name not in groups:
                        groups[name] = walker.vertex_groups.new(name=name)
                    groups[name].add([index], w, "REPLACE")
    walker.parent = rig
    modifier = walker.modifiers.new("skin", "ARMATURE")
    modifier.object = rig

    rig.animation_data_create()
    rig.animation_data.action = bpy.data.actions.new("walk")
    pose = rig.pose.bones
    for b in pose:
        b.rotation_mode = "XYZ"
    # One stride a second: legs swing +-28 degrees about x, the knee bends
    # on the forward swing, arms swing opposite the legs, the hips bob.
    for frame in range(0, 25, 2):
        phase = 2 * math.pi * frame / 24
        swing = math.sin(phase)
        for side, sign in (("L", 1.0), ("R", -1.0)):
            pose[f"thigh.{side}"].rotation_euler = (math.radians(28 * sign * swing), 0, 0)
            knee = max(0.0, math.sin(phase + sign * math.pi / 2 + math.pi / 2))
            pose[f"shin.{side}"].rotation_euler = (math.radians(-40 * knee), 0, 0)
            pose[f"arm.{side}"].rotation_euler = (math.radians(-22 * sign * swing), 0, 0)
        pose["hips"].location = (0, 0.03 * math.cos(2 * phase), 0)
        for b in pose:
            b.keyframe_insert("rotation_euler", frame=frame)
        pose["hips"].keyframe_insert("location", frame=frame)
    export("walker.glb", materials="EXPORT")


make_arm()
make_blob()
make_walker()
