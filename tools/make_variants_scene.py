#!/usr/bin/env python3
"""Writes data/scenes/variants.gltf: a sphere on a box on a floor whose looks are three
KHR_materials_variants variants (docs/scenes.md, "Material variants"): "red" (the file's own
materials: red paint, white box), "gold" (the sphere gold metal, the box dark) and "blue" (the
sphere blue paint; the box keeps its own material)."""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_scene import Scene, material  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def main():
    s = Scene()
    s.slab([-2, -0.05, -2], [2, 0, 2], 0)       # mesh 0: the floor
    s.box([0, 0.3, 0], [0.4, 0.3, 0.4], 1)      # mesh 1: the box
    s.sphere([0, 0.95, 0], 0.35, 2)             # mesh 2: the sphere
    materials = [material("floor", [0.5, 0.5, 0.5], 0.8),
                 material("box white", [0.8, 0.8, 0.8], 0.5),
                 material("paint red", [0.7, 0.05, 0.05], 0.3),
                 material("gold", [1.0, 0.78, 0.34], 0.25, metallic=1),
                 material("box dark", [0.05, 0.05, 0.05], 0.4),
                 material("paint blue", [0.05, 0.1, 0.7], 0.3)]
    variants = {"variants": [{"name": "red"}, {"name": "gold"}, {"name": "blue"}]}
    path = os.path.join(ROOT, "data", "scenes", "variants.gltf")
    s.write(path, "ibl tools/make_variants_scene.py", materials,
            extensions={"KHR_materials_variants": variants})
    with open(path) as f:
        doc = json.load(f)
    # Every mesh is one primitive; the slab and the box are six quads each (meshes 0-5 and 6-11),
    # the sphere mesh 12.
    def map_primitives(meshes, mappings):
        for m in meshes:
            doc["meshes"][m]["primitives"][0]["extensions"] = {
                "KHR_materials_variants": {"mappings": mappings}}
    map_primitives(range(6, 12), [{"material": 4, "variants": [1]}])
    map_primitives([12], [{"material": 3, "variants": [1]}, {"material": 5, "variants": [2]}])
    with open(path, "w") as f:
        json.dump(doc, f, separators=(",", ":"))


if __name__ == "__main__":
    main()
