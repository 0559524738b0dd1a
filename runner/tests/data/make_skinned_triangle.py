"""Writes skinned_triangle.gltf: a 3-vertex skinned triangle (joints bone0,
bone1; vertex 1 half on each), one morph target, and clip `wave` (bone1
turning 90° about Z, LINEAR; the morph weight 0 → 1, STEP). Accessors 9
(weights summing to 0.5) and 10 (a rotation output of 3 keys for 2 times)
are unused: the error tests point the file at them. Run: python3 make_skinned_triangle.py
"""
import base64
import json
import math
import struct

buf = b""
views = []
accs = []


def add(data, count, ctype, typ, **kw):
    global buf
    while len(buf) % 4:
        buf += b"\0"
    views.append({"buffer": 0, "byteOffset": len(buf), "byteLength": len(data)})
    buf += data
    a = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": typ}
    a.update(kw)
    accs.append(a)
    return len(accs) - 1


F = 5126
pos = [(0, 0, 0), (1, 0, 0), (0, 2, 0)]
p = add(b"".join(struct.pack("<3f", *v) for v in pos), 3, F, "VEC3", min=[0, 0, 0], max=[1, 2, 0])
n = add(b"".join(struct.pack("<3f", 0, 0, 1) for _ in pos), 3, F, "VEC3")
j = add(bytes([0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0]), 3, 5121, "VEC4")
w = add(b"".join(struct.pack("<4f", *x) for x in [(1, 0, 0, 0), (0.5, 0.5, 0, 0), (1, 0, 0, 0)]), 3, F, "VEC4")
identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
down = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]
ibm = add(struct.pack("<16f", *identity) + struct.pack("<16f", *down), 2, F, "MAT4")
morph = add(b"".join(struct.pack("<3f", *v) for v in [(0, 0, 0.5), (0, 0, 0), (0, 0, 0)]), 3, F, "VEC3",
            min=[0, 0, 0], max=[0, 0, 0.5])
times = add(struct.pack("<2f", 0, 1), 2, F, "SCALAR", min=[0], max=[1])
h = math.radians(45)
rot = add(struct.pack("<8f", 0, 0, 0, 1, 0, 0, math.sin(h), math.cos(h)), 2, F, "VEC4")
wts = add(struct.pack("<2f", 0, 1), 2, F, "SCALAR")
badw = add(b"".join(struct.pack("<4f", *x) for x in [(1, 0, 0, 0), (0.25, 0.25, 0, 0), (1, 0, 0, 0)]), 3, F, "VEC4")
rot3 = add(struct.pack("<12f", 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1), 3, F, "VEC4")
doc = {
    "asset": {"version": "2.0", "generator": "npr tests (runner/tests/data/make_skinned_triangle.py)"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [
        {"name": "root", "children": [1, 3]},
        {"name": "bone0", "children": [2]},
        {"name": "bone1", "translation": [0, 1, 0]},
        {"name": "triangle", "mesh": 0, "skin": 0},
    ],
    "meshes": [{"primitives": [{"attributes": {"POSITION": p, "NORMAL": n, "JOINTS_0": j, "WEIGHTS_0": w},
                                "targets": [{"POSITION": morph}]}], "weights": [0.0]}],
    "skins": [{"joints": [1, 2], "inverseBindMatrices": ibm}],
    "animations": [{
        "name": "wave",
        "samplers": [{"input": times, "output": rot, "interpolation": "LINEAR"},
                     {"input": times, "output": wts, "interpolation": "STEP"}],
        "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}},
                     {"sampler": 1, "target": {"node": 3, "path": "weights"}}],
    }],
    "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
    "bufferViews": views,
    "accessors": accs,
}
open("skinned_triangle.gltf", "w").write(json.dumps(doc, separators=(",", ":")) + "\n")
