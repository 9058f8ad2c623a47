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
- Glass (`--glass IOR`, bench/cycles_transmission.sh; `--geometry mesh`, as a point's sphere has
  no inside): a Glass BSDF, white, GGX or Multiscatter GGX, its exact dielectric Fresnel (glTF's:
  Schlick's); `--attenuation-color R,G,B --attenuation-distance D` adds a Volume Absorption of the
  same coefficient as KHR_materials_volume's, -ln(c) / D. Transmission bounces as --bounces.
- Light paths. Only the environment, seen through the sphere's reflection: max bounces 1
  (camera -> sphere -> environment; the sphere is convex, it never sees itself), caustics on
  (irrelevant), no clamping, Filter Glossy 0, no denoising, no adaptive sampling, no light tree
  (Blender 3.4 has none). Camera rays that miss are transparent (black RGB, alpha 0), as ibl's
  `--background 0,0,0`; statistics should use the pixels the sphere covers fully.
- Pixel filter. Box, 1 pixel wide: uniform positions in the pixel, as ibl's.
- Output. Linear RGBA float EXR (view transform Standard; EXR output is not tone mapped).

`--scene room` renders a glTF scene lit by an ibl lights file instead (bench/cycles.sh's room:
data/scenes/room.gltf and data/scenes/room_lights.json, `ibl render --env none`):

    blender -b --factory-startup -P bench/cycles_scene.py -- --scene room --gltf ROOM.gltf \
        --lights LIGHTS.json --look-from X,Y,Z --look-at X,Y,Z -o OUT.exr [--bounces B ...]

- Geometry and materials. Blender's bundled glTF importer (+Y up to +Z up, as above); any
  KHR_lights_punctual lights it brings are deleted (ibl cannot leave a glTF's lights out, so
  bench/cycles.sh gives both renderers a copy of the glTF without them). `--diffuse lambert`
  (default; ibl `--diffuse lambert`): each dielectric material's Principled BSDF (metallic 0)
  gets a black base color (its diffuse lobe off; with Specular Tint 0 its specular lobe, F0 0.04,
  does not depend on the base color) plus a Diffuse BSDF of roughness 0 (Lambert) of the base
  color: ibl's sum of Lambert and GGX, the diffuse not weighted by 1 - F either. Metals (metallic
  1) keep the Principled BSDF (no diffuse lobe). `--diffuse principled` keeps the importer's
  Principled BSDF (Burley's diffuse with retro-reflection, not ibl's renormalized Disney).
  Distribution GGX (single scattering: ibl `--multiscatter off`). Left: Cycles 3.4's separable
  Smith G1 G1 (ibl: height-correlated) and its dielectric Fresnel curve at IOR 1.5 (ibl: Schlick).
- Lights. Each rect of the lights file becomes an area light (rectangle, size width x height,
  emitting along the file's `direction`; one-sided like ibl's). Cycles 3.4 gives an area light of
  P watts the radiance P / (4 A) (measured: a 2 m^2 light of 10 W seen by the camera is 1.25),
  so P = 4 A L with L = lumens / (pi A) (ibl: nits, the renderer's units) or the nits given.
  Color: `kelvin` as ibl's blackbodyColor (Planck against the Wyman-Sloan-Shirley CIE fit, 360 to
  830 nm, to linear Rec.709, luminance 1), or `color`; Blender takes the color over its largest
  component and the power times it. Visible to the camera (as ibl's emitters; with a transparent
  film its pixels have alpha 0, so the statistics leave them out). Only rect lights are
  converted; any other type is an error. Light threshold 0 (no probabilistic light
  termination), no world light (ibl `--env none`).
- Camera. ibl's --look-from/--look-at/--up +Y, vertical field of view --fov.
- Light paths. max bounces B with diffuse and glossy B (ibl `--bounces B`: B bounces after the
  first surface), transparent 0 (a path ends on a light it meets, as ibl's), no clamping, Filter
  Glossy 0, no denoising or adaptive sampling, box filter 1 px.
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
    p.add_argument("--scene", choices=["sphere", "room"], default="sphere",
                   help="sphere: ibl's built-in sphere under --env; room: --gltf lit by --lights")
    p.add_argument("--env", help="equirectangular environment (EXR/HDR; --scene sphere)")
    p.add_argument("--gltf", help="--scene room: the glTF file")
    p.add_argument("--lights", help="--scene room: an ibl lights file (rect lights)")
    p.add_argument("--look-from", default="0,1.5,10.0556", help="--scene room: ibl X,Y,Z")
    p.add_argument("--look-at", default="0,1.5,0", help="--scene room: ibl X,Y,Z")
    p.add_argument("--diffuse", choices=["lambert", "principled"], default="lambert",
                   help="--scene room: Lambert diffuse (ibl --diffuse lambert) or Principled's")
    p.add_argument("-o", "--output", required=True, help="output EXR")
    p.add_argument("--size", default="256x256", help="WxH")
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--roughness", type=float, default=0.5)
    p.add_argument("--dielectric-f0", type=float, default=None,
                   help="--scene sphere: a black dielectric of this F0 (Principled BSDF, "
                   "Specular = F0 / 0.08, Specular Tint 0) instead of the white metal")
    p.add_argument("--multiscatter", action="store_true",
                   help="with --dielectric-f0 or --glass: Cycles' multiple-scattering GGX")
    p.add_argument("--glass", type=float, default=None, metavar="IOR",
                   help="--scene sphere: a solid glass sphere of this index (Glass BSDF, white, "
                   "--geometry mesh) instead of the white metal")
    p.add_argument("--attenuation-color", default=None, metavar="R,G,B",
                   help="with --glass: KHR_materials_volume's attenuation color, kept after "
                   "--attenuation-distance inside (a Volume Absorption shader)")
    p.add_argument("--attenuation-distance", type=float, default=1.0)
    p.add_argument("--fov", type=float, default=40.0, help="vertical field of view, degrees")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--bounces", type=int, default=None,
                   help="max bounces (default: 1 for the sphere, 4 for the room)")
    p.add_argument("--geometry", choices=["points", "mesh"], default="points")
    p.add_argument("--env-rotate-z", type=float, default=0.0,
                   help="degrees about Blender's +Z (ibl's +Y); 0 is ibl's convention")
    p.add_argument("--env-mirror", action="store_true",
                   help="mirror the map (a control for the orientation check)")
    p.add_argument("--clamp-negative", choices=["lookup", "texel", "off"], default="lookup",
                   help="negative radiance of the map to 0 (ibl zeroes texels): after the "
                   "bilinear lookup (default), in the texels, or not at all")
    a = p.parse_args(argv)
    if a.bounces is None:
        a.bounces = 1 if a.scene == "sphere" else 4
    if a.scene == "sphere" and not a.env:
        p.error("--scene sphere needs --env")
    if a.glass is not None and a.geometry != "mesh":
        p.error("--glass needs --geometry mesh (a point's sphere has no inside for the volume)")
    if a.scene == "room" and not (a.gltf and a.lights):
        p.error("--scene room needs --gltf and --lights")
    return a


def clear_scene():
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights,
                 bpy.data.worlds, bpy.data.node_groups):
        for b in list(coll):
            coll.remove(b)


def node_material(name):
    """A new material of nodes: the material, its node tree (empty) and its Cycles output node."""
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nt = m.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.target = "CYCLES"
    return m, nt, out


def make_material(roughness):
    m, nt, out = node_material("metal")
    g = nt.nodes.new("ShaderNodeBsdfGlossy")
    g.distribution = "GGX"
    g.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    g.inputs["Roughness"].default_value = roughness
    nt.links.new(g.outputs["BSDF"], out.inputs["Surface"])
    return m


def make_dielectric(f0, roughness, multiscatter):
    """A black dielectric whose specular lobe has F0 `f0`: Cycles 3.4's Principled BSDF takes F0 =
    0.08 x Specular (KHR_materials_specular's conversion table names the same)."""
    m, nt, out = node_material("dielectric")
    b = nt.nodes.new("ShaderNodeBsdfPrincipled")
    b.distribution = "MULTI_GGX" if multiscatter else "GGX"
    b.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    b.inputs["Metallic"].default_value = 0.0
    b.inputs["Specular"].default_value = f0 / 0.08
    b.inputs["Specular Tint"].default_value = 0.0
    b.inputs["Roughness"].default_value = roughness
    b.inputs["Sheen"].default_value = 0.0
    b.inputs["Clearcoat"].default_value = 0.0
    nt.links.new(b.outputs["BSDF"], out.inputs["Surface"])
    return m


def make_glass(ior, roughness, multiscatter, attenuation_color, attenuation_distance):
    """A solid glass sphere of index `ior`: Cycles 3.4's Glass BSDF (reflection and refraction by
    its exact dielectric Fresnel; KHR_materials_volume's are Schlick's), white. An attenuation
    color c after a distance d is KHR_materials_volume's sigma = -ln(c) / d per channel; Cycles'
    Volume Absorption takes sigma = (1 - color) density, so density 1 and color 1 + ln(c) / d."""
    m, nt, out = node_material("glass")
    g = nt.nodes.new("ShaderNodeBsdfGlass")
    g.distribution = "MULTI_GGX" if multiscatter else "GGX"
    g.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    g.inputs["Roughness"].default_value = roughness
    g.inputs["IOR"].default_value = ior
    nt.links.new(g.outputs["BSDF"], out.inputs["Surface"])
    if attenuation_color:
        c = [float(v) for v in attenuation_color.split(",")]
        color = [1.0 + math.log(v) / attenuation_distance for v in c]
        if min(color) < 0.0:
            raise SystemExit("cycles_scene.py: --attenuation-color too dark for --attenuation-distance "
                             "(Volume Absorption's color would be below 0)")
        a = nt.nodes.new("ShaderNodeVolumeAbsorption")
        a.inputs["Color"].default_value = (*color, 1.0)
        a.inputs["Density"].default_value = 1.0
        nt.links.new(a.outputs["Volume"], out.inputs["Volume"])
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


def new_camera(t):
    """A perspective camera of vertical half-angle tangent t, linked to the scene."""
    cam = bpy.data.cameras.new("camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"
    cam.sensor_height = 24.0
    cam.lens = 0.5 * cam.sensor_height / t
    cam.clip_start = 0.01
    cam.clip_end = 1000.0
    obj = bpy.data.objects.new("camera", cam)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def make_camera(fov_deg):
    t = math.tan(0.5 * math.radians(fov_deg))
    distance = 1.1 * (1.0 / t) + 1.0  # ibl's framing of the bounds [-1, 1]^3 (apps/scene_options.cpp)
    obj = new_camera(t)
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
    c.diffuse_bounces = a.bounces if a.scene == "room" else 0
    if a.scene == "room":
        c.light_sampling_threshold = 0.0  # no probabilistic termination of light samples
    # A glass sphere's light goes in and out through refractions and reflections inside.
    c.transmission_bounces = a.bounces if a.glass is not None else 0
    c.volume_bounces = 0
    c.transparent_max_bounces = 0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.use_auto_tile = False
    s.view_layers[0].cycles.denoising_store_passes = False
    s.view_layers[0].use_pass_combined = True


# --- The room: a glTF scene lit by an ibl lights file -------------------------------------------

def ibl_point(text):
    """An ibl point or vector "X,Y,Z" (+Y up) in Blender's axes (+Z up): (x, -z, y)."""
    x, y, z = (float(v) for v in text.split(","))
    return (x, -z, y)


def blackbody_color(kelvin):
    """ibl's blackbodyColor (src/math/color.cpp): linear Rec.709 of luminance 1."""
    def lobe(lam, mu, s1, s2):
        t = (lam - mu) / (s1 if lam < mu else s2)
        return math.exp(-0.5 * t * t)
    xyz = [0.0, 0.0, 0.0]
    for nm in range(360, 831):
        lam = float(nm)
        planck = 1.0 / (lam ** 5 * math.expm1(1.438777e7 / (lam * kelvin)))
        cmf = (1.056 * lobe(lam, 599.8, 37.9, 31.0) + 0.362 * lobe(lam, 442.0, 16.0, 26.7)
               - 0.065 * lobe(lam, 501.1, 20.4, 26.2),
               0.821 * lobe(lam, 568.8, 46.9, 40.5) + 0.286 * lobe(lam, 530.9, 16.3, 31.1),
               1.217 * lobe(lam, 437.0, 11.8, 36.0) + 0.681 * lobe(lam, 459.0, 26.0, 13.8))
        for i in range(3):
            xyz[i] += planck * cmf[i]
    x, y, z = (v / xyz[1] for v in xyz)
    rgb = (3.2404542 * x - 1.5371385 * y - 0.4985314 * z,
           -0.9692660 * x + 1.8760108 * y + 0.0415560 * z,
           0.0556434 * x - 0.2040259 * y + 1.0572252 * z)
    lum = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]
    return tuple(c / lum for c in rgb)


def import_room(path, diffuse):
    import numpy  # the importer needs it (Debian: python3-numpy)
    if "bool" not in numpy.__dict__:
        numpy.bool = bool  # Blender 3.4's importer uses np.bool, gone since NumPy 1.24
    bpy.ops.import_scene.gltf(filepath=path)
    for o in list(bpy.data.objects):
        if o.type in ("LIGHT", "CAMERA"):
            print(f"cycles_room_removed: {o.type.lower()} {o.name}")
            bpy.data.objects.remove(o, do_unlink=True)
    for m in bpy.data.materials:
        if not m.use_nodes:
            continue
        nt = m.node_tree
        for node in list(nt.nodes):
            if node.type != "BSDF_PRINCIPLED":
                continue
            node.distribution = "GGX"
            node.inputs["Specular Tint"].default_value = 0.0
            if diffuse != "lambert":
                continue
            metallic = node.inputs["Metallic"]
            if metallic.is_linked or metallic.default_value not in (0.0, 1.0):
                print(f"cycles_room_warning: {m.name}: metallic not 0 or 1, Principled's diffuse kept")
                continue
            if metallic.default_value == 1.0:
                continue  # a metal: no diffuse lobe
            base = node.inputs["Base Color"]
            lam = nt.nodes.new("ShaderNodeBsdfDiffuse")
            lam.inputs["Roughness"].default_value = 0.0  # Lambert
            if base.is_linked:
                nt.links.new(base.links[0].from_socket, lam.inputs["Color"])
                nt.links.remove(base.links[0])
            else:
                lam.inputs["Color"].default_value = base.default_value
            base.default_value = (0.0, 0.0, 0.0, 1.0)
            out_links = list(node.outputs["BSDF"].links)
            add = nt.nodes.new("ShaderNodeAddShader")
            nt.links.new(node.outputs["BSDF"], add.inputs[0])
            nt.links.new(lam.outputs["BSDF"], add.inputs[1])
            for link in out_links:
                to = link.to_socket
                nt.links.remove(link)
                nt.links.new(add.outputs["Shader"], to)
            print(f"cycles_room_material: {m.name}: Lambert {tuple(round(c, 4) for c in lam.inputs['Color'].default_value[:3])}"
                  f" + GGX (F0 0.04), roughness {node.inputs['Roughness'].default_value:.3f}")


def add_rect_lights(path):
    import json
    from mathutils import Matrix, Vector
    with open(path) as f:
        lights = json.load(f)["lights"]
    for k, l in enumerate(lights):
        if l.get("type") != "rect":
            sys.exit(f"cycles_scene.py: {path}: light {k}: only rect lights are converted")
        w, h = float(l["width"]), float(l["height"])
        area = w * h
        unit = l.get("unit", "nit")
        if unit == "lm":
            radiance = float(l["intensity"]) / (area * math.pi)  # one-sided: L = phi / (A pi)
        elif unit == "nit":
            radiance = float(l["intensity"])
        else:
            sys.exit(f"cycles_scene.py: {path}: light {k}: unit {unit}")
        color = blackbody_color(float(l["kelvin"])) if "kelvin" in l else tuple(l.get("color", (1, 1, 1)))
        peak = max(color)
        light = bpy.data.lights.new(f"rect{k}", "AREA")
        light.shape = "RECTANGLE"
        light.size, light.size_y = w, h
        light.color = tuple(c / peak for c in color)
        light.energy = 4.0 * area * radiance * peak  # Cycles 3.4: radiance P / (4 A)
        if hasattr(light, "spread"):
            light.spread = math.pi  # a Lambertian emitter
        light.use_shadow = True
        obj = bpy.data.objects.new(f"rect{k}", light)
        bpy.context.scene.collection.objects.link(obj)
        d = Vector(ibl_point(",".join(str(v) for v in l["direction"]))).normalized()
        up = Vector(ibl_point(",".join(str(v) for v in l["up"])))
        up = (up - up.dot(d) * d).normalized()
        z = -d  # the area light emits along its local -Z
        y = up  # size_y (height) along up
        x = y.cross(z)  # size (width) along up x direction, up to its sign
        rot = Matrix((x, y, z)).transposed()
        obj.matrix_world = Matrix.Translation(Vector(ibl_point(",".join(str(v) for v in l["position"])))) @ rot.to_4x4()
        for attr in ("visible_camera", "visible_diffuse", "visible_glossy", "visible_transmission"):
            setattr(obj, attr, True)
        print(f"cycles_room_light: rect {w} x {h} m, radiance {radiance:.3f} nit x color "
              f"{tuple(round(c, 5) for c in color)}, Blender power {light.energy:.2f} W, "
              f"color {tuple(round(c, 5) for c in light.color)}")


def make_room_camera(look_from, look_at, fov_deg):
    from mathutils import Vector
    t = math.tan(0.5 * math.radians(fov_deg))
    obj = new_camera(t)
    frm, at = Vector(ibl_point(look_from)), Vector(ibl_point(look_at))
    obj.location = frm
    # the camera looks along its -Z with its +Y up; ibl's up is +Y (Blender +Z)
    obj.rotation_euler = (at - frm).to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.camera = obj


def make_black_world():
    w = bpy.data.worlds.new("none")
    bpy.context.scene.world = w
    w.use_nodes = True
    w.node_tree.nodes["Background"].inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    w.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    w.cycles.sampling_method = "NONE"


def main_room(a):
    clear_scene()
    s = bpy.context.scene
    s.render.engine = "CYCLES"
    import_room(a.gltf, a.diffuse)
    add_rect_lights(a.lights)
    make_room_camera(a.look_from, a.look_at, a.fov)
    make_black_world()
    setup_render(a)
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    seconds = time.perf_counter() - t0
    bpy.data.images["Render Result"].save_render(filepath=bpy.path.abspath(a.output), scene=s)
    print(f"cycles_render_seconds: {seconds:.4f}")


def main():
    a = parse_args()
    if a.scene == "room":
        main_room(a)
        return
    clear_scene()
    s = bpy.context.scene
    s.render.engine = "CYCLES"
    if a.glass is not None:
        material = make_glass(a.glass, a.roughness, a.multiscatter, a.attenuation_color,
                              a.attenuation_distance)
    elif a.dielectric_f0 is not None:
        material = make_dielectric(a.dielectric_f0, a.roughness, a.multiscatter)
    else:
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
