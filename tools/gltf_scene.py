"""Geometry and glTF writing shared by the scene generators in tools/ (make_room_scene.py,
make_interior_scenes.py): quads, boxes and spheres gathered into one buffer, written as a glTF
file with the buffer embedded (base64)."""
import base64, json, math, struct


class Scene:
    """Triangles with per-vertex normals, grouped into meshes of one material each."""

    def __init__(self):
        self.positions, self.normals, self.indices = [], [], []
        self.meshes = []  # (first index, count, material)

    def quad(self, c, u, v, n, material):
        """The parallelogram c, c + u, c + u + v, c + v, facing n."""
        base = len(self.positions)
        for p in (c, [c[i] + u[i] for i in range(3)], [c[i] + u[i] + v[i] for i in range(3)],
                  [c[i] + v[i] for i in range(3)]):
            self.positions.append(p)
            self.normals.append(n)
        cross = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        tri = [0, 1, 2, 0, 2, 3] if sum(cross[i] * n[i] for i in range(3)) > 0 else [0, 2, 1, 0, 3, 2]
        first = len(self.indices)
        self.indices.extend(base + t for t in tri)
        self.meshes.append((first, 6, material))

    def box(self, center, half, material):
        """An axis-aligned box, faces outward."""
        for axis in range(3):
            for sign in (-1, 1):
                a, b = (axis + 1) % 3, (axis + 2) % 3
                c = [center[i] - half[i] for i in range(3)]
                c[axis] = center[axis] + sign * half[axis]
                u = [0, 0, 0]; v = [0, 0, 0]; n = [0, 0, 0]
                u[a] = 2 * half[a]; v[b] = 2 * half[b]; n[axis] = sign
                self.quad(c, u, v, n, material)

    def slab(self, lo, hi, material):
        """The box between corners lo and hi."""
        self.box([(lo[i] + hi[i]) / 2 for i in range(3)], [(hi[i] - lo[i]) / 2 for i in range(3)],
                 material)

    def sphere(self, center, r, material, rings=24, segments=48):
        base = len(self.positions)
        for i in range(rings + 1):
            t = math.pi * i / rings
            for j in range(segments + 1):
                p = 2 * math.pi * j / segments
                n = [math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p)]
                self.positions.append([center[k] + r * n[k] for k in range(3)])
                self.normals.append(n)
        first = len(self.indices)
        for i in range(rings):
            for j in range(segments):
                a = base + i * (segments + 1) + j
                b = a + segments + 1
                self.indices.extend([a, a + 1, b, a + 1, b + 1, b])
        self.meshes.append((first, len(self.indices) - first, material))

    def write(self, path, generator, materials, extra_nodes=(), extensions=None):
        """Writes the glTF file: one node per mesh, then extra_nodes; extensions: the document's
        extensions (their names go to extensionsUsed)."""
        positions, normals, indices = self.positions, self.normals, self.indices
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
        for first, count, material in self.meshes:
            accessors.append({"bufferView": 2, "byteOffset": 4 * first, "componentType": 5125,
                              "count": count, "type": "SCALAR"})
            gltf_meshes.append({"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1},
                                                "indices": len(accessors) - 1, "material": material}]})
        nodes = [{"mesh": i} for i in range(len(gltf_meshes))] + list(extra_nodes)
        doc = {"asset": {"version": "2.0", "generator": generator}}
        if extensions:
            doc["extensionsUsed"] = list(extensions)
            doc["extensions"] = extensions
        doc.update({
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
        })
        with open(path, "w") as f:
            json.dump(doc, f, separators=(",", ":"))


def material(name, color, roughness, metallic=0):
    """A glTF metallic-roughness material of a linear base color R,G,B."""
    return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(color) + [1],
                                                   "metallicFactor": metallic, "roughnessFactor": roughness}}
