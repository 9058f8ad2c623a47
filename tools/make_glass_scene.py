#!/usr/bin/env python3
"""Writes data/scenes/glass.gltf: glass before opaque surfaces (docs/materials.md, "Transmission
and volume"): a solid ball of absorbing glass (KHR_materials_transmission and KHR_materials_volume,
index 1.5) and a thin pane of frosted glass standing on a checkered floor, before a striped wall,
so that what the real-time paths show through the glass (the opaque frame behind it, read at the
refracted exit point) can be measured against the reference."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_scene import Scene, material  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def glass(name, color, roughness, thickness=0.0, attenuation=None):
    m = material(name, color, roughness)
    m["extensions"] = {"KHR_materials_transmission": {"transmissionFactor": 1.0}}
    if thickness > 0:
        volume = {"thicknessFactor": thickness}
        if attenuation:
            volume["attenuationColor"], volume["attenuationDistance"] = attenuation
        m["extensions"]["KHR_materials_volume"] = volume
    return m


def main():
    s = Scene()
    tile = 0.5
    for i in range(8):  # the floor: 8 x 8 tiles of 0.5 m, light and dark
        for j in range(8):
            s.quad([-2 + i * tile, 0, -2 + j * tile], [tile, 0, 0], [0, 0, tile], [0, 1, 0],
                   (i + j) % 2)
    for i in range(8):  # the wall behind: vertical stripes of red, white and blue
        s.quad([-2 + i * tile, 0, -2], [tile, 0, 0], [0, 2, 0], [0, 0, 1], 2 + i % 3)
    s.sphere([-0.6, 0.5, 0.2], 0.5, 5)  # the ball: solid glass, 1 m across
    s.quad([0.3, 0, 0.4], [1.0, 0, 0], [0, 1.0, 0], [0, 0, 1], 6)  # the pane: thin, frosted
    materials = [material("tile light", [0.8, 0.8, 0.8], 0.6),
                 material("tile dark", [0.05, 0.05, 0.05], 0.6),
                 material("stripe red", [0.7, 0.05, 0.05], 0.7),
                 material("stripe white", [0.8, 0.8, 0.8], 0.7),
                 material("stripe blue", [0.05, 0.1, 0.7], 0.7),
                 glass("glass green", [1, 1, 1], 0.0, 1.0, ([0.6, 0.9, 0.7], 1.0)),
                 glass("glass frosted", [0.95, 0.97, 1.0], 0.2)]
    extensions = ["KHR_materials_transmission", "KHR_materials_volume"]
    path = os.path.join(ROOT, "data", "scenes", "glass.gltf")
    s.write(path, "ibl tools/make_glass_scene.py", materials)
    with open(path) as f:
        doc = json.load(f)
    doc["extensionsUsed"] = extensions
    with open(path, "w") as f:
        json.dump(doc, f, separators=(",", ":"))


if __name__ == "__main__":
    main()
