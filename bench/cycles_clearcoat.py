# KHR_materials_clearcoat against Blender Cycles 3.4 (docs/materials.md, "Clear coat"): a black
# sphere with no specular of its own (Principled BSDF: base color 0, specular 0) under clearcoat
# 1 at roughness R, in a white world of radiance 1, seen head-on through a 0.02-wide orthographic
# view (8 x 8 pixels, 1024 samples, no denoising). ibl's coat reflects 0.04 E(1, R) there
# (ClearcoatRender.CoatReflectsItsWeightedGgxLobe); Cycles' reflects a quarter of it.
# Usage: blender -b --python bench/cycles_clearcoat.py -- R OUTPUT.exr
import bpy, sys
argv = sys.argv[sys.argv.index("--") + 1:]
rough = float(argv[0]); out = argv[1]
bpy.ops.wm.read_factory_settings(use_empty=True)
s = bpy.context.scene
s.render.engine = 'CYCLES'; s.cycles.samples = 1024; s.cycles.device = 'CPU'
s.render.resolution_x = s.render.resolution_y = 8
s.render.image_settings.file_format = 'OPEN_EXR'
s.view_settings.view_transform = 'Standard'
s.cycles.use_denoising = False
s.render.threads_mode = 'FIXED'; s.render.threads = 1
w = bpy.data.worlds.new("w"); s.world = w; w.use_nodes = True
w.node_tree.nodes["Background"].inputs[0].default_value = (1, 1, 1, 1)
bpy.ops.mesh.primitive_uv_sphere_add(segments=256, ring_count=128, radius=1)
bpy.ops.object.shade_smooth()
o = bpy.context.active_object
m = bpy.data.materials.new("m"); m.use_nodes = True; o.data.materials.append(m)
b = m.node_tree.nodes["Principled BSDF"]
b.inputs["Base Color"].default_value = (0, 0, 0, 1)
b.inputs["Specular"].default_value = 0.0
b.inputs["Clearcoat"].default_value = 1.0
b.inputs["Clearcoat Roughness"].default_value = rough
cam = bpy.data.cameras.new("c"); cam.type = 'ORTHO'; cam.ortho_scale = 0.02
c = bpy.data.objects.new("c", cam); s.collection.objects.link(c); s.camera = c
c.location = (0, 0, 5)
s.render.filepath = out
bpy.ops.render.render(write_still=True)
