#!/usr/bin/env python3
"""Writes the irradiance volume's test interiors (docs/probes.md, "Measured against the
reference") into data/scenes/:
  skylight_room.gltf  a closed 4 x 3 x 4 m room (inside x, z in [-2, 2], y in [0, 3]) lit only
                      through a 1.2 m square skylight centered in the ceiling;
  window_room.gltf    the same room with a 1.2 x 1.0 m window (x in [-0.6, 0.6], y in [1, 2]) in
                      the front wall (z = 2) instead of the skylight;
  two_rooms.gltf      two such rooms side by side (inside x in [-4.05, -0.05] and
                      [0.05, 4.05]) sharing a 10 cm wall; only the left one has the window, the
                      right one is closed (any light in it came through a wall: a leak);
  open_scene.gltf     a 12 x 12 m floor with boxes and pillars, no walls.
Walls, floor and ceiling are solid slabs 10 cm thick (boxes, faces outward), so that no light
passes through a zero-thickness quad. The rooms' left wall is red, the right one green, the rest
white; a white box and a rough metal sphere (roughness 0.5, metallic 1) stand on the floor.
Run from the repository root: python3 tools/make_interior_scenes.py"""
import os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_scene import Scene, material

T = 0.1           # slab thickness
H = 3.0           # room height
HALF = 2.0        # half of the room's inside width and depth
HOLE = 0.6        # half of the skylight's side and the window's width
SILL, LINTEL = 1.0, 2.0  # the window's bottom and top
WHITE, RED, GREEN, FLOOR, METAL = range(5)
MATERIALS = [
    material("white", [0.73, 0.73, 0.73], 0.9),       # Cornell box reflectances
    material("red", [0.63, 0.065, 0.05], 0.9),
    material("green", [0.14, 0.45, 0.091], 0.9),
    material("floor", [0.5, 0.5, 0.5], 0.8),
    material("metal", [0.95, 0.93, 0.88], 0.5, metallic=1),
]
GENERATOR = "ibl tools/make_interior_scenes.py"


def holed_slab(s, lo, hi, hole_lo, hole_hi, axes, mat):
    """The slab lo..hi with a rectangular hole hole_lo..hole_hi on the two `axes`: four pieces."""
    a, b = axes
    def piece(a0, a1, b0, b1):
        plo, phi = list(lo), list(hi)
        plo[a], phi[a], plo[b], phi[b] = a0, a1, b0, b1
        s.slab(plo, phi, mat)
    piece(lo[a], hole_lo[a], lo[b], hi[b])
    piece(hole_hi[a], hi[a], lo[b], hi[b])
    piece(hole_lo[a], hole_hi[a], lo[b], hole_lo[b])
    piece(hole_lo[a], hole_hi[a], hole_hi[b], hi[b])


def room(s, x0, x1, skylight=False, window=False, left=RED, right=GREEN, left_wall=True):
    """A room with inside x in [x0, x1], z in [-HALF, HALF], y in [0, H]; walls around it
    (the left one left out when left_wall is False: a neighbour's wall stands there)."""
    cx = (x0 + x1) / 2
    s.slab([x0 - T, -T, -HALF - T], [x1 + T, 0, HALF + T], FLOOR)
    ceiling = ([x0 - T, H, -HALF - T], [x1 + T, H + T, HALF + T])
    if skylight:
        holed_slab(s, *ceiling, [cx - HOLE, 0, -HOLE], [cx + HOLE, 0, HOLE], (0, 2), WHITE)
    else:
        s.slab(*ceiling, WHITE)
    if left_wall:
        s.slab([x0 - T, 0, -HALF - T], [x0, H, HALF + T], left)
    s.slab([x1, 0, -HALF - T], [x1 + T, H, HALF + T], right)
    s.slab([x0, 0, -HALF - T], [x1, H, -HALF], WHITE)   # back wall
    front = ([x0, 0, HALF], [x1, H, HALF + T])
    if window:
        holed_slab(s, *front, [cx - HOLE, SILL, 0], [cx + HOLE, LINTEL, 0], (0, 1), WHITE)
    else:
        s.slab(*front, WHITE)
    s.box([cx + 0.8, 0.4, -0.6], [0.4, 0.4, 0.4], WHITE)
    s.sphere([cx - 0.8, 0.5, 0.4], 0.5, METAL)


def write(s, name):
    path = os.path.join("data", "scenes", name)
    s.write(path, GENERATOR, MATERIALS)
    print(f"{path}: {os.path.getsize(path)} bytes")


def main():
    s = Scene()
    room(s, -HALF, HALF, skylight=True)
    write(s, "skylight_room.gltf")
    s = Scene()
    room(s, -HALF, HALF, window=True)
    write(s, "window_room.gltf")
    s = Scene()
    room(s, -4.05, -0.05, window=True, right=WHITE)     # the lit room; its right wall is shared
    room(s, 0.05, 4.05, left_wall=False, left=WHITE)    # the closed one
    write(s, "two_rooms.gltf")
    s = Scene()
    s.slab([-6, -T, -6], [6, 0, 6], FLOOR)
    for x, z, h in ((-2.5, -2.0, 3.0), (2.5, -2.0, 3.0), (-2.5, 2.0, 3.0), (2.5, 2.0, 3.0)):
        s.box([x, h / 2, z], [0.2, h / 2, 0.2], WHITE)    # pillars
    s.box([0.8, 0.4, -0.6], [0.4, 0.4, 0.4], WHITE)
    s.box([-1.2, 0.6, -1.4], [0.6, 0.6, 0.3], RED)
    s.box([1.6, 0.3, 1.0], [0.3, 0.3, 0.6], GREEN)
    s.sphere([-0.8, 0.5, 0.4], 0.5, METAL)
    write(s, "open_scene.gltf")


if __name__ == "__main__":
    main()
