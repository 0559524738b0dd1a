"""Builds npr's edge-mark test asset (issue 51, decision 0063) and exports it
as GLB with Blender's bundled glTF exporter.

Blender 3.4's exporter writes no Freestyle edge marks (and skips edge-domain
attributes), so this script copies each face corner's outgoing edge's
Freestyle mark into a face-corner float attribute `npr_edge_mark`, which the
exporter writes as `_NPR_EDGE_MARK`. The mesh is triangulated first: a
corner's outgoing edge is then an edge of its glTF triangle. The same copy
works on any mesh: triangulate, then run `copy_marks`.

Run with Debian's blender (3.4) and a system PATH (the exporter needs
Debian's numpy):

    PATH=/usr/bin:/bin blender -b --factory-startup \
        -P tests/data/blender/make_marked.py -- examples/models

It writes `marked_box.glb`: a cube of side 2 cut once along each axis (so
2x2 quads a face, then triangulated), with the rim of its top face (+Z in
Blender, +Y in glTF) and the line across the top at x = 0 marked: 10 edges
of length 1. `marked_box_marks.json` lists the marked edges' end points in
glTF coordinates (Y up), as read back from Blender's marks after the
triangulation: the truth the runner's test compares with.
"""

import json
import os
import sys

import bmesh
import bpy

out_dir = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "."
os.makedirs(out_dir, exist_ok=True)


def copy_marks(mesh):
    """Per face corner, 1.0 where the edge leaving it is marked."""
    attribute = mesh.attributes.new(name="npr_edge_mark", type="FLOAT", domain="CORNER")
    for loop in mesh.loops:
        attribute.data[loop.index].value = 1.0 if mesh.edges[loop.edge_index].use_freestyle_mark else 0.0


def gltf_point(co):
    # The exporter's +Y up: Blender (x, y, z) is glTF (x, z, -y).
    return [co.x, co.z, -co.y]


bpy.ops.wm.read_factory_settings(use_empty=True)
mesh = bpy.data.meshes.new("marked_box")
bm = bmesh.new()
bmesh.ops.create_cube(bm, size=2.0)
bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=1, use_grid_fill=True)
bmesh.ops.triangulate(bm, faces=bm.faces[:])
bm.to_mesh(mesh)
bm.free()

eps = 1e-6
for edge in mesh.edges:
    a, b = (mesh.vertices[v].co for v in edge.vertices)
    on_top = abs(a.z - 1.0) < eps and abs(b.z - 1.0) < eps
    rim = on_top and (
        (abs(a.x) > 1 - eps and abs(b.x) > 1 - eps and abs(a.x - b.x) < eps)
        or (abs(a.y) > 1 - eps and abs(b.y) > 1 - eps and abs(a.y - b.y) < eps)
    )
    across = on_top and abs(a.x) < eps and abs(b.x) < eps
    edge.use_freestyle_mark = rim or across

copy_marks(mesh)
obj = bpy.data.objects.new("marked_box", mesh)
bpy.context.scene.collection.objects.link(obj)

marks = [
    [gltf_point(mesh.vertices[v].co) for v in edge.vertices] for edge in mesh.edges if edge.use_freestyle_mark
]
with open(os.path.join(out_dir, "marked_box_marks.json"), "w") as f:
    json.dump({"marked_edges": marks}, f, indent=1)
    f.write("\n")

bpy.ops.export_scene.gltf(
    filepath=os.path.join(out_dir, "marked_box.glb"),
    export_format="GLB",
    export_yup=True,
    export_apply=False,
    export_normals=True,
    export_texcoords=False,
    export_materials="NONE",
    export_attributes=True,
)
print(f"marked {len(marks)} edges")
