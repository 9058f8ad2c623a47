#!/usr/bin/env python3
"""Writes data/scenes/room.gltf: a 5 x 3 x 5 m room open on one side (walls facing inward), a
table, a sphere and a box on the floor, with two KHR_lights_punctual lights (a spot and a point).
The shadow study's interior (docs/lights.md); area lights come from data/scenes/room_lights.json.
Run from the repository root: python3 tools/make_room_scene.py"""
from gltf_scene import Scene, material

s = Scene()
W, H, D = 5.0, 3.0, 5.0
s.quad([-W / 2, 0, -D / 2], [W, 0, 0], [0, 0, D], [0, 1, 0], 0)        # floor
s.quad([-W / 2, H, -D / 2], [W, 0, 0], [0, 0, D], [0, -1, 0], 1)       # ceiling
s.quad([-W / 2, 0, -D / 2], [W, 0, 0], [0, H, 0], [0, 0, 1], 1)        # back wall
s.quad([-W / 2, 0, -D / 2], [0, 0, D], [0, H, 0], [1, 0, 0], 1)        # left wall
s.quad([W / 2, 0, -D / 2], [0, 0, D], [0, H, 0], [-1, 0, 0], 1)        # right wall
s.box([0.6, 0.72, -0.6], [0.8, 0.04, 0.5], 2)                          # table top
for x in (-0.15, 1.35):
    for z in (-1.0, -0.2):
        s.box([x, 0.35, z], [0.04, 0.35, 0.04], 2)                     # legs
s.sphere([-1.2, 0.45, 0.3], 0.45, 3)
s.box([1.4, 0.3, 1.0], [0.3, 0.3, 0.3], 2)

materials = [
    material("floor", [0.55, 0.45, 0.35], 0.6),
    material("walls", [0.8, 0.8, 0.78], 0.9),
    material("wood", [0.4, 0.25, 0.15], 0.5),
    material("metal", [0.9, 0.9, 0.9], 0.3, metallic=1),
]
# KHR_lights_punctual: lights shine along the node's -Z; a spot over the table, a point light.
nodes = [
    {"name": "spot", "translation": [0.6, 2.9, -0.6], "rotation": [-0.7071068, 0, 0, 0.7071068],
     "extensions": {"KHR_lights_punctual": {"light": 0}}},
    {"name": "lamp", "translation": [-1.6, 2.2, 1.6], "extensions": {"KHR_lights_punctual": {"light": 1}}},
]
lights = {"KHR_lights_punctual": {"lights": [
    {"type": "spot", "name": "spot", "color": [1.0, 0.85, 0.7], "intensity": 600,
     "spot": {"innerConeAngle": 0.35, "outerConeAngle": 0.6}},
    {"type": "point", "name": "lamp", "color": [1.0, 0.9, 0.8], "intensity": 150, "range": 8}]}}
s.write("data/scenes/room.gltf", "ibl tools/make_room_scene.py", materials, nodes, lights)
