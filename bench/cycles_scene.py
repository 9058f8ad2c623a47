"""Blender Cycles (CPU) rendering of the scene of

    ibl render sphere --env ENV --metallic 1 --roughness R --base-color 1,1,1 \
        --multiscatter off --mode reference --size WxH --spp N --tonemap none \
        --background 0,0,0 --seed S -o OUT.exr

so that the reference renderer's efficiency (noise per second) can be measured against Cycles'
(bench/cycles.sh). Run it as

    blender -b --factory-startup -P bench/cycles_scene.py -- --env ENV -o OUT.exr [options]

It prints `cycles_render_seconds: T`: the time of the render alone (scene sync, which includes
loading the environment and building its importance map, plus path tracing), without Blender's
start, the scene setup or the EXR write.

The scene, and how it matches ibl's:

- Axes. ibl's world is +Y up, Blender's +Z up. A point (x, y, z) of ibl is (x, -z, y) here (the
  glTF importer's conversion, a rotation, so nothing is mirrored).
- Environment. ibl's equirect convention (docs/conventions.md): u = 0.5 + atan2(z, x)/2pi,
  v = acos(y)/pi, image center toward +X. Cycles' Environment Texture maps a Blender direction
  D to u = 0.5 - atan2(D.y, D.x)/2pi, v = 0.5 + asin(D.z)/pi (v from the image's bottom row).
  With D = (x, -z, y): u = 0.5 + atan2(z, x)/2pi and the top row is straight up, so the two
  conventions agree with no rotation (Mapping node: identity). bench/cycles.sh verifies this on
  a mirror sphere against ibl, with a 90-degree rotation and a mirrored map as controls
  (--env-rotate-z, --env-mirror). The map is read as linear Rec.709 (Blender's scene linear, the
  same primaries as ibl), bilinearly filtered, negative components set to 0 after
  the lookup (ibl zeroes texels before filtering; park.exr has a blue texel of -1876 next to
  one of 11800, so blue differs near it; --clamp-negative texel zeroes the texels instead).
  Differences left: ibl lights with the 256^2 source cube `ibl bake` resamples the equirect
  into, Cycles with the equirect itself; Cycles' background importance map has its own
  resolution ('AUTOMATIC').
- Sphere. ibl's built-in `sphere` is an analytic unit sphere at the origin (an Embree sphere
  point). The default `--geometry points` here is the same: one point of radius 1 made by
  Geometry Nodes, which Cycles renders as an analytic sphere with exact normals. `--geometry
  mesh` uses an ico sphere (subdivisions 7, 163842 vertices, smooth shading) instead: its
  silhouette is within 1e-4 of the sphere and its normals are interpolated.
- Camera. ibl frames the sphere's bounds from +Z: distance 1.1 * 1/tan(fov/2) + 1 from the
  center (4.0222 for fov 40), vertical field of view 40 degrees, up +Y: here the camera at
  (0, -d, 0) looking along +Y, up +Z, sensor fit vertical.
- Material. A Glossy BSDF, GGX (not Multiscatter GGX: single scattering like ibl's
  `--multiscatter off`), white, roughness R (perceptual; Cycles squares it, alpha = R^2, as
  ibl). A white metal has Fresnel 1 in both (ibl's Schlick with F0 = f90 = 1). Cycles 3.4's
  GGX uses the separable Smith masking-shadowing G1(v) G1(l); ibl's the height-correlated
  form, which is slightly brighter at r = 0.5 (a known few-percent difference in brightness).
- Light paths. Only the environment, seen through the sphere's reflection: max bounces 1
  (camera -> sphere -> environment; the sphere is convex, it never sees itself), caustics on
  (irrelevant), no clamping, Filter Glossy 0, no denoising, no adaptive sampling, no light tree
  (Blender 3.4 has none). Camera rays that miss are transparent (black RGB, alpha 0), as ibl's
  `--background 0,0,0`; statistics should use the pixels the sphere covers fully.
- Pixel filter. Box, 1 pixel wide: uniform positions in the pixel, as ibl's.
- Output. Linear RGBA float EXR (view transform Standard; EXR output is not tone mapped).
"""

import argparse
import math
import sys
import time
from array import array

import bpy


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles_scene.py", description=__doc__.split("\n")[0])
    p.add_argument("--env", required=True, help="equirectangular environment (EXR/HDR)")
    p.add_argument("-o", "--output", required=True, help="output EXR")
    p.add_argument("--size", default="256x256", help="WxH")
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--roughness", type=float, default=0.5)
    p.add_argument("--fov", type=float, default=40.0, help="vertical field of view, degrees")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--bounces", type=int, default=1)
    p.add_argument("--geometry", choices=["points", "mesh"], default="points")
    p.add_argument("--env-rotate-z", type=float, default=0.0,
                   help="degrees about Blender's +Z (ibl's +Y); 0 is ibl's convention")
    p.add_argument("--env-mirror", action="store_true",
                   help="mirror the map (a control for the orientation check)")
    p.add_argument("--clamp-negative", choices=["lookup", "texel", "off"], default="lookup",
                   help="negative radiance of the map to 0 (ibl zeroes texels): after the "
                   "bilinear lookup (default), in the texels, or not at all")
    return p.parse_args(argv)


def clear_scene():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights,
                 bpy.data.worlds, bpy.data.node_groups):
        for b in list(coll):
            coll.remove(b)


def make_material(roughness):
    m = bpy.data.materials.new("metal")
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    g = nt.nodes.new("ShaderNodeBsdfGlossy")
    g.distribution = "GGX"
    g.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    g.inputs["Roughness"].default_value = roughness
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.target = "CYCLES"
    nt.links.new(g.outputs["BSDF"], out.inputs["Surface"])
    return m


def make_sphere(kind, material):
    scene = bpy.context.scene
    if kind == "mesh":
        bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=7, radius=1.0, location=(0, 0, 0))
        obj = bpy.context.active_object
        for poly in obj.data.polygons:
            poly.use_smooth = True
        obj.data.materials.append(material)
        return obj
    # One point of radius 1 at the origin: Cycles renders point clouds as analytic spheres.
    mesh = bpy.data.meshes.new("anchor")
    obj = bpy.data.objects.new("sphere", mesh)
    scene.collection.objects.link(obj)
    tree = bpy.data.node_groups.new("sphere_points", "GeometryNodeTree")
    tree.outputs.new("NodeSocketGeometry", "Geometry")
    pts = tree.nodes.new("GeometryNodePoints")
    pts.inputs["Count"].default_value = 1
    pts.inputs["Position"].default_value = (0.0, 0.0, 0.0)
    pts.inputs["Radius"].default_value = 1.0
    setm = tree.nodes.new("GeometryNodeSetMaterial")
    setm.inputs["Material"].default_value = material
    out = tree.nodes.new("NodeGroupOutput")
    tree.links.new(pts.outputs["Geometry"], setm.inputs["Geometry"])
    tree.links.new(setm.outputs["Geometry"], out.inputs[0])
    mod = obj.modifiers.new("points", "NODES")
    mod.node_group = tree
    obj.data.materials.append(material)
    return obj


def make_world(env, rotate_z, mirror, clamp_negative):
    w = bpy.data.worlds.new("env")
    bpy.context.scene.world = w
    w.use_nodes = True
    nt = w.node_tree
    nt.nodes.clear()
    coord = nt.nodes.new("ShaderNodeTexCoord")
    mapping = nt.nodes.new("ShaderNodeMapping")
    mapping.vector_type = "POINT"
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(rotate_z))
    if mirror:
        mapping.inputs["Scale"].default_value = (1.0, -1.0, 1.0)
    tex = nt.nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(env, check_existing=True)
    tex.image.colorspace_settings.name = "Linear"
    tex.interpolation = "Linear"
    tex.projection = "EQUIRECTANGULAR"
    bg = nt.nodes.new("ShaderNodeBackground")
    bg.inputs["Strength"].default_value = 1.0
    out = nt.nodes.new("ShaderNodeOutputWorld")
    out.target = "CYCLES"
    nt.links.new(coord.outputs["Generated"], mapping.inputs["Vector"])
    nt.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    color = tex.outputs["Color"]
    if clamp_negative == "texel":
        # ibl reads negative components as 0 texel by texel, before any filtering (park.exr
        # has a blue texel of -1876 next to 11800). Cycles renders the in-memory pixels; but
        # measured, this also darkens R and G by 2.5 % (unexplained), so it is not the default.
        img = tex.image
        px = array("f", bytes(4 * img.channels * img.size[0] * img.size[1]))
        img.pixels.foreach_get(px)
        negative = sum(1 for i, v in enumerate(px) if v < 0.0 and i % 4 != 3)
        img.pixels.foreach_set(array("f", (v if v > 0.0 else 0.0 for v in px)))
        img.update()
        print(f"cycles_env_negative_components_zeroed: {negative}")
    elif clamp_negative == "lookup":
        mx = nt.nodes.new("ShaderNodeVectorMath")  # max(0) after the bilinear lookup
        mx.operation = "MAXIMUM"
        mx.inputs[1].default_value = (0.0, 0.0, 0.0)
        nt.links.new(color, mx.inputs[0])
        color = mx.outputs["Vector"]
    nt.links.new(color, bg.inputs["Color"])
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    w.cycles.sampling_method = "AUTOMATIC"  # background importance map (Cycles' default)


def make_camera(fov_deg):
    t = math.tan(0.5 * math.radians(fov_deg))
    distance = 1.1 * (1.0 / t) + 1.0  # ibl's framing of the bounds [-1, 1]^3 (apps/scene_options.cpp)
    cam = bpy.data.cameras.new("camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"
    cam.sensor_height = 24.0
    cam.lens = 0.5 * cam.sensor_height / t
    cam.clip_start = 0.01
    cam.clip_end = 1000.0
    obj = bpy.data.objects.new("camera", cam)
    bpy.context.scene.collection.objects.link(obj)
    obj.location = (0.0, -distance, 0.0)           # ibl (0, 0, d)
    obj.rotation_euler = (math.radians(90.0), 0.0, 0.0)  # looks along +Y (ibl -Z), up +Z (ibl +Y)
    bpy.context.scene.camera = obj
    return distance


def setup_render(a):
    s = bpy.context.scene
    w, h = (int(v) for v in a.size.lower().split("x"))
    r = s.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = w, h, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.film_transparent = True
    r.threads_mode = "FIXED"
    r.threads = a.threads
    r.use_persistent_data = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_mode = "RGBA"
    r.image_settings.color_depth = "32"
    r.image_settings.exr_codec = "ZIP"
    s.view_settings.view_transform = "Standard"
    s.view_settings.look = "None"
    s.view_settings.exposure = 0.0
    s.view_settings.gamma = 1.0
    c = s.cycles
    c.device = "CPU"
    c.samples = a.spp
    c.seed = a.seed
    c.use_animated_seed = False
    c.use_adaptive_sampling = False
    c.use_denoising = False
    if hasattr(c, "use_preview_denoising"):
        c.use_preview_denoising = False
    if hasattr(c, "use_light_tree"):
        c.use_light_tree = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.max_bounces = a.bounces
    c.glossy_bounces = a.bounces
    c.diffuse_bounces = 0
    c.transmission_bounces = 0
    c.volume_bounces = 0
    c.transparent_max_bounces = 0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.use_auto_tile = False
    s.view_layers[0].cycles.denoising_store_passes = False
    s.view_layers[0].use_pass_combined = True


def main():
    a = parse_args()
    clear_scene()
    s = bpy.context.scene
    s.render.engine = "CYCLES"
    material = make_material(a.roughness)
    make_sphere(a.geometry, material)
    make_world(a.env, a.env_rotate_z, a.env_mirror, a.clamp_negative)
    distance = make_camera(a.fov)
    setup_render(a)
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    seconds = time.perf_counter() - t0
    bpy.data.images["Render Result"].save_render(filepath=bpy.path.abspath(a.output), scene=s)
    print(f"cycles_camera_distance: {distance:.5f}")
    print(f"cycles_render_seconds: {seconds:.4f}")


main()
