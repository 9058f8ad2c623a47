#!/usr/bin/env python3
"""Writes data/scenes/room.gltf: a 5 x 3 x 5 m room open on one side (walls facing inward), a
table, a sphere and a box on the floor, with two KHR_lights_punctual lights (a spot and a point).
The shadow study's interior (docs/lights.md); area lights come from data/scenes/room_lights.json.
Run from the repository root: python3 tools/make_room_scene.py"""
import base64, json, math, struct

positions, normals, indices = [], [], []
meshes = []  # (first index, count, material)


def quad(c, u, v, n, material):
    base = len(positions)
    for p in (c, [c[i] + u[i] for i in range(3)], [c[i] + u[i] + v[i] for i in range(3)],
              [c[i] + v[i] for i in range(3)]):
        positions.append(p)
        normals.append(n)
    cross = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    tri = [0, 1, 2, 0, 2, 3] if sum(cross[i] * n[i] for i in range(3)) > 0 else [0, 2, 1, 0, 3, 2]
    first = len(indices)
    indices.extend(base + t for t in tri)
    meshes.append((first, 6, material))


def box(center, half, material):
    for axis in range(3):
        for sign in (-1, 1):
            a, b = (axis + 1) % 3, (axis + 2) % 3
            c = [center[i] - half[i] for i in range(3)]
            c[axis] = center[axis] + sign * half[axis]
            u = [0, 0, 0]; v = [0, 0, 0]; n = [0, 0, 0]
            u[a] = 2 * half[a]; v[b] = 2 * half[b]; n[axis] = sign
            quad(c, u, v, n, material)


def sphere(center, r, material, rings=24, segments=48):
    base = len(positions)
    for i in range(rings + 1):
        t = math.pi * i / rings
        for j in range(segments + 1):
            p = 2 * math.pi * j / segments
            n = [math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p)]
            positions.append([center[k] + r * n[k] for k in range(3)])
            normals.append(n)
    first = len(indices)
    for i in range(rings):
        for j in range(segments):
            a = base + i * (segments + 1) + j
            b = a + segments + 1
            indices.extend([a, a + 1, b, a + 1, b + 1, b])
    meshes.append((first, len(indices) - first, material))


W, H, D = 5.0, 3.0, 5.0
quad([-W / 2, 0, -D / 2], [W, 0, 0], [0, 0, D], [0, 1, 0], 0)        # floor
quad([-W / 2, H, -D / 2], [W, 0, 0], [0, 0, D], [0, -1, 0], 1)       # ceiling
quad([-W / 2, 0, -D / 2], [W, 0, 0], [0, H, 0], [0, 0, 1], 1)        # back wall
quad([-W / 2, 0, -D / 2], [0, 0, D], [0, H, 0], [1, 0, 0], 1)        # left wall
quad([W / 2, 0, -D / 2], [0, 0, D], [0, H, 0], [-1, 0, 0], 1)        # right wall
box([0.6, 0.72, -0.6], [0.8, 0.04, 0.5], 2)                          # table top
for x in (-0.15, 1.35):
    for z in (-1.0, -0.2):
        box([x, 0.35, z], [0.04, 0.35, 0.04], 2)                     # legs
sphere([-1.2, 0.45, 0.3], 0.45, 3)
box([1.4, 0.3, 1.0], [0.3, 0.3, 0.3], 2)

buf = b"".join(struct.pack("<3f", *p) for p in positions)
nrm_off = len(buf)
buf += b"".join(struct.pack("<3f", *n) for n in normals)
idx_off = len(buf)
buf += b"".join(struct.pack("<I", i) for i in indices)
lo = [min(p[i] for p in positions) for i in range(3)]
hi = [max(p[i] for p in positions) for i in range(3)]
accessors = [
    {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3", "min": lo, "max": hi},
    {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
]
gltf_meshes = []
for first, count, material in meshes:
    accessors.append({"bufferView": 2, "byteOffset": 4 * first, "componentType": 5125,
                      "count": count, "type": "SCALAR"})
    gltf_meshes.append({"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1},
                                        "indices": len(accessors) - 1, "material": material}]})
materials = [
    {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.45, 0.35, 1], "metallicFactor": 0, "roughnessFactor": 0.6}},
    {"name": "walls", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.78, 1], "metallicFactor": 0, "roughnessFactor": 0.9}},
    {"name": "wood", "pbrMetallicRoughness": {"baseColorFactor": [0.4, 0.25, 0.15, 1], "metallicFactor": 0, "roughnessFactor": 0.5}},
    {"name": "metal", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1], "metallicFactor": 1, "roughnessFactor": 0.3}},
]
nodes = [{"mesh": i} for i in range(len(gltf_meshes))]
# KHR_lights_punctual: lights shine along the node's -Z; a spot over the table, a point light.
def look_down(tilt_x):
    s, c = math.sin(-math.pi / 4 + tilt_x), math.cos(-math.pi / 4 + tilt_x)
    return [math.sin(-math.pi / 4), 0, 0, math.cos(-math.pi / 4)]
nodes.append({"name": "spot", "translation": [0.6, 2.9, -0.6], "rotation": [-0.7071068, 0, 0, 0.7071068],
              "extensions": {"KHR_lights_punctual": {"light": 0}}})
nodes.append({"name": "lamp", "translation": [-1.6, 2.2, 1.6], "extensions": {"KHR_lights_punctual": {"light": 1}}})
doc = {
    "asset": {"version": "2.0", "generator": "ibl tools/make_room_scene.py"},
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "name": "spot", "color": [1.0, 0.85, 0.7], "intensity": 600,
         "spot": {"innerConeAngle": 0.35, "outerConeAngle": 0.6}},
        {"type": "point", "name": "lamp", "color": [1.0, 0.9, 0.8], "intensity": 150, "range": 8}]}},
    "scene": 0,
    "scenes": [{"nodes": list(range(len(nodes)))}],
    "nodes": nodes,
    "meshes": gltf_meshes,
    "materials": materials,
    "accessors": accessors,
    "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": nrm_off, "target": 34962},
        {"buffer": 0, "byteOffset": nrm_off, "byteLength": idx_off - nrm_off, "target": 34962},
        {"buffer": 0, "byteOffset": idx_off, "byteLength": len(buf) - idx_off, "target": 34963},
    ],
    "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
}
with open("data/scenes/room.gltf", "w") as f:
    json.dump(doc, f, separators=(",", ":"))
