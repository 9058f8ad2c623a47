// The glTF Sample Viewer target (`ibl bake --target gltf-sample-viewer`), shaded by the Sample
// Viewer's own published shaders.
//
// @khronosgroup/gltf-viewer 1.1 filters a panorama itself (its iblSampler) and has no way in for a
// prefiltered set, so this page does the loading the viewer used to do for glTF-Sample-Environments
// folders (ggx/specular.ktx2, lambertian/diffuse.ktx2, a GGX LUT) and hands the textures to the
// viewer's own GLSL:
//   - the shader sources are taken at run time from the package's bundle
//     (node_modules/@khronosgroup/gltf-viewer/dist/gltf-viewer.module.js: the string literals the
//     viewer registers with `shaderSources.set(...)`: primitive.vert, pbr.frag and the files it
//     includes: ibl.glsl with getDiffuseLight, getSpecularSample, getIBLGGXFresnel and
//     getIBLRadianceGGX, textures.glsl with u_MipCount / u_EnvRotation / the samplers, ...);
//     nothing of them is copied into this repository;
//   - includes are resolved and the program is compiled the way the viewer's ShaderCache does it
//     ("#version 300 es", one "#define" per permutation define, then the expanded source), with the
//     defines the viewer uses for an opaque metallic-roughness primitive with normals, lit by the
//     IBL alone, rendered linearly (LINEAR_OUTPUT, as its transmission pass does): tone mapping is
//     left out, and this page encodes sRGB itself (the viewer's own toneMap() would apply
//     pow(1/2.2), not the sRGB curve);
//   - the cube maps are read with ktx-parse (an independent KTX2 reader; not the viewer's libktx)
//     and uploaded face by face, level by level, as KTX2 stores them (faces +X, -X, +Y, -Y, +Z,
//     -Z, row 0 first: texel row 0 at t = 0), which is what libktx's glUpload does;
//   - uniforms as the viewer sets them (gltf-viewer.module.js, applyEnvironmentMap /
//     drawEnvironmentMap): u_MipCount = the specular chain's level count (its lod =
//     roughness * (u_MipCount - 1)), u_EnvIntensity = scale, u_EnvRotation = rotateY(deg)
//     (gl-matrix) taken to a mat3. The viewer's UI default is environmentRotation = 90 ("front
//     face +Z"); this page uses 0 (the files' own axes) unless `envRotation=DEG` is given.
//
// The sphere is a tessellated unit sphere through the viewer's primitive.vert; the camera is
// orthographic. The viewer's pbr.frag takes the view vector as normalize(u_Camera - v_Position)
// (a point camera even for orthographic views), so u_Camera is put 1e6 units away along the view
// axis: the view vector is then the orthographic one to ~1e-6.
//
// set=own (optional): the viewer's own pipeline instead of ibl's files: its
// ResourceLoader.loadEnvironment(hdr) filters the panorama (iblSampler: 256^2 cube, 1024 GGX
// samples per texel, its own LUT) and the same shaders shade with it. Slow without a GPU (minutes
// under SwiftShader).
//
// Contract (tests/engines/run.mjs): ?set=ibl|own&bake=URL&hdr=URL&roughness=R&metallic=M
// &base=R,G,B&size=N&scale=K&view=front|side[&envRotation=DEG][&ext=JSON][&backdrop=1]; draws into <canvas id="c">, then
// window.iblDone = {ok, notes|error}.

import { read as readKtx2 } from '/engines/node_modules/ktx-parse/dist/index.mjs';
import { params, sphereMesh, backdropMesh, BACKDROP } from './common.mjs';

const VIEWER_BUNDLE = '/engines/node_modules/@khronosgroup/gltf-viewer/dist/gltf-viewer.module.js';

const VK_FORMAT_R16G16B16A16_SFLOAT = 97;
const VK_FORMAT_R32G32B32A32_SFLOAT = 109;

function fail(message) {
  throw new Error(message);
}

async function fetchOk(url) {
  const res = await fetch(url);
  if (!res.ok) fail(`${url}: HTTP ${res.status}`);
  return res;
}

// ---------------------------------------------------------------------------------------------
// The viewer's shader sources, from its bundle.

// The JavaScript string literal that starts at `start` (a double quote), decoded.
function stringLiteralAt(text, start) {
  if (text[start] !== '"') fail('internal: not at a string literal');
  let end = start + 1;
  while (end < text.length && text[end] !== '"') end += text[end] === '\\' ? 2 : 1;
  if (end >= text.length) fail('unterminated string literal in the viewer bundle');
  // The bundle's shader strings use only JSON-compatible escapes (\n, \", \\).
  return JSON.parse(text.slice(start, end + 1));
}

function viewerShaderSources(bundle) {
  // The ShaderCache's map: shaderSources.set("pbr.frag", pbrShader); ... (the renderer's, which is
  // the first such block; the iblSampler's own block comes later and is not needed).
  const sets = [...bundle.matchAll(/shaderSources\.set\("([^"]+)",\s*([A-Za-z_$][\w$]*)\);/g)];
  if (sets.length === 0) fail(`no shaderSources.set(...) in ${VIEWER_BUNDLE}`);
  const sources = new Map();
  for (const [, name, variable] of sets) {
    if (sources.has(name)) continue;
    const decl = `var ${variable} = "`;
    const at = bundle.indexOf(decl);
    if (at < 0) fail(`${VIEWER_BUNDLE}: the source of ${name} (var ${variable}) is not a string literal`);
    sources.set(name, stringLiteralAt(bundle, at + decl.length - 1));
  }
  for (const needed of ['primitive.vert', 'pbr.frag', 'ibl.glsl', 'textures.glsl', 'functions.glsl', 'brdf.glsl', 'material_info.glsl', 'tonemapping.glsl']) {
    if (!sources.has(needed)) fail(`${VIEWER_BUNDLE}: no shader source ${needed}`);
  }
  // Resolve includes exactly as the viewer's ShaderCache constructor does.
  for (const [key, original] of sources) {
    let src = original;
    let changed = false;
    for (const [includeName, includeSource] of sources) {
      const pattern = '#include <' + includeName + '>';
      if (src.includes(pattern)) {
        src = src.replace(pattern, () => includeSource);
        while (src.includes(pattern)) src = src.replace(pattern, '');
        changed = true;
      }
    }
    if (changed) sources.set(key, src);
  }
  // The debug-output defines the viewer always passes (pushFragParameterDefines).
  const debugDefines = [...new Set([...bundle.matchAll(/shaderDefine:\s*"(DEBUG_[A-Z0-9_]+)"/g)].map((m) => m[1]))];
  if (!debugDefines.includes('DEBUG_NONE')) fail(`${VIEWER_BUNDLE}: no DEBUG_NONE shader define`);
  return { sources, debugDefines };
}

// The pieces of the viewer's GLSL this test is about; checked so that a package whose shaders
// changed fails loudly instead of being measured as something else.
function checkViewerGlsl(sources) {
  const ibl = sources.get('ibl.glsl');
  const pbr = sources.get('pbr.frag');
  const expect = [
    [ibl, 'float lod=roughness*float(u_MipCount-1);'],
    [ibl, 'textureLod(u_GGXEnvSampler,u_EnvRotation*reflection,lod)'],
    [ibl, 'texture(u_LambertianEnvSampler,u_EnvRotation*n)'],
    [ibl, 'textureSample.rgb*=u_EnvIntensity;'],
    [ibl, 'vec2 f_ab=texture(u_GGXLUT,brdfSamplePoint).rg;'],
    [pbr, 'f_specular_metal=getIBLRadianceGGX(n,v,materialInfo.perceptualRoughness);'],
    [pbr, 'f_dielectric_brdf_ibl=mix(f_diffuse,f_specular_dielectric,f_dielectric_fresnel_ibl);'],
    [pbr, 'color=mix(f_dielectric_brdf_ibl,f_metal_brdf_ibl,materialInfo.metallic);'],
  ];
  for (const [src, piece] of expect) {
    if (!src.includes(piece)) fail(`the viewer's shaders no longer contain "${piece}"`);
  }
}

// ---------------------------------------------------------------------------------------------
// WebGL helpers.

function compile(gl, type, source, name) {
  const s = gl.createShader(type);
  gl.shaderSource(s, source);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) fail(`${name}: ${gl.getShaderInfoLog(s)}`);
  return s;
}

function link(gl, vs, fs, name) {
  const p = gl.createProgram();
  gl.attachShader(p, vs);
  gl.attachShader(p, fs);
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) fail(`${name}: ${gl.getProgramInfoLog(p)}`);
  return p;
}

// The material extensions this page hands the viewer's shaders: glTF extension -> the define the
// viewer's gltfMaterial adds for it, and the uniforms it sets from the extension's factors
// (gltf-viewer.module.js, gltfMaterial.parseTextureInfoExtensions / updateTextureTransforms and its
// "u_*" properties; defaults as the extensions' specifications give them).
const EXTENSIONS = {
  KHR_materials_ior: { define: 'MATERIAL_IOR', uniforms: (e, gl, loc) => gl.uniform1f(loc('u_Ior'), e.ior ?? 1.5) },
  KHR_materials_specular: {
    define: 'MATERIAL_SPECULAR',
    uniforms: (e, gl, loc) => {
      gl.uniform1f(loc('u_KHR_materials_specular_specularFactor'), e.specularFactor ?? 1);
      gl.uniform3fv(loc('u_KHR_materials_specular_specularColorFactor'), e.specularColorFactor ?? [1, 1, 1]);
    },
  },
  KHR_materials_clearcoat: {
    define: 'MATERIAL_CLEARCOAT',
    uniforms: (e, gl, loc) => {
      gl.uniform1f(loc('u_ClearcoatFactor'), e.clearcoatFactor ?? 0);
      gl.uniform1f(loc('u_ClearcoatRoughnessFactor'), e.clearcoatRoughnessFactor ?? 0);
    },
  },
  KHR_materials_iridescence: {
    define: 'MATERIAL_IRIDESCENCE',
    uniforms: (e, gl, loc) => {
      gl.uniform1f(loc('u_IridescenceFactor'), e.iridescenceFactor ?? 0);
      gl.uniform1f(loc('u_IridescenceIor'), e.iridescenceIor ?? 1.3);
      // Without a thickness texture the film is iridescenceThicknessMaximum thick.
      gl.uniform1f(loc('u_IridescenceThicknessMaximum'), e.iridescenceThicknessMaximum ?? 400);
    },
  },
  KHR_materials_transmission: {
    define: 'MATERIAL_TRANSMISSION',
    frame: true,
    uniforms: (e, gl, loc) => gl.uniform1f(loc('u_TransmissionFactor'), e.transmissionFactor ?? 0),
  },
  KHR_materials_volume: {
    define: 'MATERIAL_VOLUME',
    uniforms: (e, gl, loc) => {
      gl.uniform1f(loc('u_ThicknessFactor'), e.thicknessFactor ?? 0);
      // The viewer's applyVolumeAttenuation takes a distance of 0 (its default) as none absorbed.
      gl.uniform1f(loc('u_AttenuationDistance'), e.attenuationDistance ?? 0);
      gl.uniform3fv(loc('u_AttenuationColor'), e.attenuationColor ?? [1, 1, 1]);
    },
  },
  KHR_materials_anisotropy: {
    define: 'MATERIAL_ANISOTROPY',
    tangents: true,
    uniforms: (e, gl, loc) => {
      const rotation = e.anisotropyRotation ?? 0;
      gl.uniform3f(loc('u_Anisotropy'), Math.cos(rotation), Math.sin(rotation), e.anisotropyStrength ?? 0);
    },
  },
};

function materialExtensions(ext) {
  const used = Object.keys(ext ?? {});
  for (const name of used) if (!EXTENSIONS[name]) fail(`ext: ${name} is not one this page hands the viewer (${Object.keys(EXTENSIONS).join(', ')})`);
  return used.map((name) => ({ name, ...EXTENSIONS[name], factors: ext[name] }));
}

function viewerProgram(gl, sources, debugDefines, extensions) {
  // Defines as the viewer builds them for this primitive and material (gltf-viewer.module.js:
  // gltfPrimitive defines HAS_<ATTRIBUTE>_<TYPE>, gltfMaterial ALPHAMODE_*,
  // MATERIAL_METALLICROUGHNESS and one MATERIAL_* per extension, renderer: LINEAR_OUTPUT for a
  // linear pass, USE_IBL, DEBUG_*).
  const vertDefines = ['HAS_NORMAL_VEC3 1', 'HAS_POSITION_VEC3 1', ...(extensions.some((x) => x.tangents) ? ['HAS_TANGENT_VEC4 1'] : [])];
  const fragDefines = [
    'ALPHAMODE_OPAQUE 0', 'ALPHAMODE_MASK 1', 'ALPHAMODE_BLEND 2', 'ALPHAMODE ALPHAMODE_OPAQUE',
    'MATERIAL_METALLICROUGHNESS 1',
    ...extensions.map((x) => `${x.define} 1`),
    ...vertDefines,
    'LINEAR_OUTPUT 1',
    'USE_IBL 1',
    ...debugDefines.map((d, i) => `${d} ${i}`),
    'DEBUG DEBUG_NONE',
  ];
  const header = (defines) => '#version 300 es\n' + defines.map((d) => `#define ${d}\n`).join('');
  const vs = compile(gl, gl.VERTEX_SHADER, header(vertDefines) + sources.get('primitive.vert'), 'primitive.vert');
  const fs = compile(gl, gl.FRAGMENT_SHADER, header(fragDefines) + sources.get('pbr.frag'), 'pbr.frag');
  return link(gl, vs, fs, 'primitive.vert + pbr.frag');
}

function encodeProgram(gl) {
  const vs = compile(gl, gl.VERTEX_SHADER, `#version 300 es
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}`, 'encode.vert');
  // The exact sRGB curve (IEC 61966-2-1), as ibl's PNG writer uses.
  const fs = compile(gl, gl.FRAGMENT_SHADER, `#version 300 es
precision highp float;
uniform highp sampler2D u_Linear;
out vec4 o;
float enc(float c) {
  c = clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}
void main() {
  vec3 c = texelFetch(u_Linear, ivec2(gl_FragCoord.xy), 0).rgb;
  o = vec4(enc(c.r), enc(c.g), enc(c.b), 1.0);
}`, 'encode.frag');
  return link(gl, vs, fs, 'encode');
}

// A KTX2 cube map with all its levels, as libktx's glUpload would upload it.
function uploadKtx2Cube(gl, buffer, name) {
  const c = readKtx2(new Uint8Array(buffer));
  if (c.faceCount !== 6) fail(`${name}: ${c.faceCount} faces, not a cube map`);
  if (c.layerCount > 1 || c.pixelDepth > 1) fail(`${name}: an array or 3D texture`);
  if (c.pixelWidth !== c.pixelHeight) fail(`${name}: faces ${c.pixelWidth}x${c.pixelHeight} are not square`);
  if (c.supercompressionScheme !== 0) {
    fail(`${name}: supercompression scheme ${c.supercompressionScheme} (ibl writes none; this page has no zstd/zlib decoder)`);
  }
  let internalFormat, type, bytesPerTexel, View;
  if (c.vkFormat === VK_FORMAT_R16G16B16A16_SFLOAT) {
    internalFormat = gl.RGBA16F; type = gl.HALF_FLOAT; bytesPerTexel = 8; View = Uint16Array;
  } else if (c.vkFormat === VK_FORMAT_R32G32B32A32_SFLOAT) {
    if (!gl.getExtension('OES_texture_float_linear')) fail(`${name}: RGBA32F is not filterable here (no OES_texture_float_linear)`);
    internalFormat = gl.RGBA32F; type = gl.FLOAT; bytesPerTexel = 16; View = Float32Array;
  } else {
    fail(`${name}: vkFormat ${c.vkFormat}; expected RGBA16F (97) or RGBA32F (109)`);
  }
  const levels = Math.max(1, c.levelCount);
  if (c.levels.length !== levels) fail(`${name}: ${c.levels.length} levels read, ${levels} declared`);
  const tex = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_CUBE_MAP, tex);
  gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
  gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
  gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
  gl.texStorage2D(gl.TEXTURE_CUBE_MAP, levels, internalFormat, c.pixelWidth, c.pixelHeight);
  for (let m = 0; m < levels; m++) {
    const w = Math.max(1, c.pixelWidth >> m);
    const faceBytes = w * w * bytesPerTexel;
    const data = c.levels[m].levelData;
    if (data.byteLength !== 6 * faceBytes) fail(`${name}: level ${m} holds ${data.byteLength} bytes, expected ${6 * faceBytes}`);
    for (let f = 0; f < 6; f++) {
      // Copy: the level's bytes need not be aligned for a typed view.
      const bytes = data.slice(f * faceBytes, (f + 1) * faceBytes);
      const texels = new View(bytes.buffer, bytes.byteOffset, faceBytes / View.BYTES_PER_ELEMENT);
      gl.texSubImage2D(gl.TEXTURE_CUBE_MAP_POSITIVE_X + f, m, 0, 0, w, w, gl.RGBA, type, texels);
    }
  }
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_BASE_LEVEL, 0);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_MAX_LEVEL, levels - 1);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  // The viewer's samplers: specular LINEAR_MIPMAP_LINEAR, diffuse LINEAR (one level).
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_MIN_FILTER, levels > 1 ? gl.LINEAR_MIPMAP_LINEAR : gl.LINEAR);
  return { tex, levels, size: c.pixelWidth, format: c.vkFormat === VK_FORMAT_R16G16B16A16_SFLOAT ? 'RGBA16F' : 'RGBA32F' };
}

async function uploadLut(gl, url) {
  const blob = await (await fetchOk(url)).blob();
  // 8-bit values with no transfer curve: no color-space conversion, no premultiplication.
  const bitmap = await createImageBitmap(blob, { colorSpaceConversion: 'none', premultiplyAlpha: 'none' });
  const tex = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, tex);
  gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
  gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
  gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, bitmap);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
  return { tex, width: bitmap.width, height: bitmap.height };
}

// A unit UV sphere, triangles counter-clockwise seen from outside (the viewer draws with
// frontFace CCW and flips the normal of back faces in getNormalInfo).
// Column-major 4x4 matrices.
function lookAt(eye, up) {
  const norm = (v) => { const l = Math.hypot(...v); return v.map((x) => x / l); };
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const z = norm(eye); // camera looks along -z, at the origin
  const x = norm(cross(up, z));
  const y = cross(z, x);
  return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
}

function ortho(l, r, b, t, n, f) {
  return [2 / (r - l), 0, 0, 0, 0, 2 / (t - b), 0, 0, 0, 0, -2 / (f - n), 0, -(r + l) / (r - l), -(t + b) / (t - b), -(f + n) / (f - n), 1];
}

function mul(a, b) {
  const o = new Array(16).fill(0);
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) for (let k = 0; k < 4; k++) o[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
  return o;
}

// gl-matrix's rotateY(identity, rad) then mat3.fromMat4, as the viewer builds u_EnvRotation.
function envRotation(deg) {
  const rad = (deg / 180.0) * Math.PI;
  const s = Math.sin(rad), c = Math.cos(rad);
  return [c, 0, -s, 0, 1, 0, s, 0, c];
}


// set=ibl: ibl's gltf-sample-viewer target files, read with ktx-parse.
async function iblSet(gl, p) {
  const dir = `${p.bake.replace(/\/+$/, '')}/gltf-sample-viewer`;
  const [specBuf, diffBuf] = await Promise.all([
    fetchOk(`${dir}/ggx/specular.ktx2`).then((r) => r.arrayBuffer()),
    fetchOk(`${dir}/lambertian/diffuse.ktx2`).then((r) => r.arrayBuffer()),
  ]);
  const specular = uploadKtx2Cube(gl, specBuf, 'ggx/specular.ktx2');
  const diffuse = uploadKtx2Cube(gl, diffBuf, 'lambertian/diffuse.ktx2');
  const lut = await uploadLut(gl, `${dir}/lut_ggx.png`);
  const textures = {
    u_LambertianEnvSampler: [gl.TEXTURE_CUBE_MAP, diffuse.tex],
    u_GGXEnvSampler: [gl.TEXTURE_CUBE_MAP, specular.tex],
    u_GGXLUT: [gl.TEXTURE_2D, lut.tex],
  };
  return {
    // The viewer's u_MipCount is the specular chain's level count.
    mipCount: specular.levels,
    intensityScale: 1,
    bind(name, location, unit) {
      const [target, tex] = textures[name];
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(target, tex);
      gl.uniform1i(location, unit);
    },
    notes: `set=ibl: ${dir}: ggx/specular.ktx2 ${specular.size}^2 ${specular.format} ${specular.levels} levels, ` +
      `lambertian/diffuse.ktx2 ${diffuse.size}^2 ${diffuse.format}, lut_ggx.png ${lut.width}x${lut.height} (ktx-parse, uploaded as stored)`,
  };
}

// set=own: the viewer's own pipeline: ResourceLoader.loadEnvironment(hdr) (its HDR reader, its
// iblSampler: panorama to cube, GGX and Lambertian filtering, its GGX LUT), bound with the
// viewer's own webGl.setTexture. (ResourceLoader is built directly: createResourceLoader() would
// also start its KTX and Draco decoders, which need globals this page does not load.)
async function viewerOwn(gl, p) {
  const { GltfView, ResourceLoader } = await import(VIEWER_BUNDLE);
  const view = new GltfView(gl);
  const loader = new ResourceLoader(view);
  // The sheen LUT the loader always fetches (unused here: no sheen): a 1x1 PNG of our own.
  const c = new OffscreenCanvas(1, 1);
  c.getContext('2d').fillRect(0, 0, 1, 1);
  const sheenUrl = URL.createObjectURL(await c.convertToBlob({ type: 'image/png' }));
  const environment = await loader.loadEnvironment(p.hdr, { lut_sheen_E_file: sheenUrl });
  if (!environment) fail(`the viewer could not load ${p.hdr}`);
  const infos = {
    u_LambertianEnvSampler: environment.diffuseEnvMap,
    u_GGXEnvSampler: environment.specularEnvMap,
    u_GGXLUT: environment.lut,
  };
  return {
    mipCount: environment.mipCount,
    // drawEnvironmentMap / applyEnvironmentMap: u_EnvIntensity = iblIntensity * iblIntensityScale.
    intensityScale: environment.iblIntensityScale,
    bind(name, location, unit) {
      if (!view.renderer.webGl.setTexture(location, environment, infos[name], unit)) fail(`the viewer could not bind ${name}`);
    },
    notes: `set=own: the viewer's ResourceLoader.loadEnvironment(${p.hdr}) and iblSampler; iblIntensityScale ${environment.iblIntensityScale}`,
  };
}

const nextFrame = () => new Promise((resolve) => requestAnimationFrame(() => resolve()));

async function main() {
  const p = params();
  const canvas = document.getElementById('c');
  canvas.width = p.size;
  canvas.height = p.size;
  canvas.style.width = `${p.size}px`;
  canvas.style.height = `${p.size}px`;
  const gl = canvas.getContext('webgl2', { antialias: false, alpha: false, depth: false, preserveDrawingBuffer: true, premultipliedAlpha: false });
  if (!gl) fail('no WebGL2 context');
  if (!gl.getExtension('EXT_color_buffer_float')) fail('no EXT_color_buffer_float (needed for the linear pass)');

  const bundle = await fetchOk(VIEWER_BUNDLE).then((r) => r.text());
  const version = (bundle.match(/\* Version: ([^\s]+)/) || [])[1] ?? 'unknown';
  const { sources, debugDefines } = viewerShaderSources(bundle);
  checkViewerGlsl(sources);

  // The environment first: the viewer's own filtering (set=own) changes GL state freely.
  const env = p.set === 'ibl' ? await iblSet(gl, p) : await viewerOwn(gl, p);

  const extensions = materialExtensions(p.ext);
  const program = viewerProgram(gl, sources, debugDefines, extensions);
  // backdrop=1: the backdrop's stripes, opaque glTF dielectrics (their own permutation).
  const opaqueProgram = p.backdrop ? viewerProgram(gl, sources, debugDefines, []) : null;
  const encode = encodeProgram(gl);
  const transmission = extensions.some((x) => x.frame);

  // Geometry: a vertex array per program and mesh.
  function vertexArray(prog, mesh, tangents) {
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    const attributes = [['a_position', mesh.positions, 3], ['a_normal', mesh.normals, 3]];
    if (tangents) attributes.push(['a_tangent', mesh.tangents, 4]);
    for (const [attr, data, size] of attributes) {
      const l = gl.getAttribLocation(prog, attr);
      if (l < 0) fail(`the viewer's primitive.vert has no attribute ${attr}`);
      gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
      gl.enableVertexAttribArray(l);
      gl.vertexAttribPointer(l, size, gl.FLOAT, false, 0, 0);
    }
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, gl.createBuffer());
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, mesh.indices, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    return { vao, count: mesh.indices.length };
  }
  const sphere = sphereMesh(512);
  sphere.normals = sphere.positions;  // unit sphere: normal = position

  // Uniforms, as the viewer sets them per draw (gltf-viewer.module.js, drawPrimitive).
  const eyeDir = p.view === 'side' ? [1, 0, 0] : [0, 0, 1];
  const eye = eyeDir.map((x) => 10 * x);
  const viewMatrix = lookAt(eye, [0, 1, 0]);
  const projMatrix = ortho(-1.1, 1.1, -1.1, 1.1, 0.1, 100);
  const viewProj = mul(projMatrix, viewMatrix);
  const identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  const FRAME = 1024;  // the viewer's opaqueFramebufferWidth and Height
  const frameUnit = 3;
  const others = new Set();
  function setUniforms(prog, material, exts) {
    gl.useProgram(prog);
    const set = new Set();
    const loc = (name) => {
      const l = gl.getUniformLocation(prog, name);
      if (l === null) fail(`the viewer's shaders have no active uniform ${name}`);
      set.add(name);
      return l;
    };
    gl.uniformMatrix4fv(loc('u_ViewProjectionMatrix'), false, viewProj);
    gl.uniformMatrix4fv(loc('u_ModelMatrix'), false, identity);
    gl.uniformMatrix4fv(loc('u_NormalMatrix'), false, identity);
    gl.uniform3fv(loc('u_Camera'), eyeDir.map((x) => 1e6 * x));
    gl.uniform4f(loc('u_BaseColorFactor'), material.base[0], material.base[1], material.base[2], 1);
    gl.uniform1f(loc('u_MetallicFactor'), material.metallic);
    gl.uniform1f(loc('u_RoughnessFactor'), material.roughness);
    gl.uniform3f(loc('u_EmissiveFactor'), 0, 0, 0);
    gl.uniform1i(loc('u_MipCount'), env.mipCount);
    gl.uniform1f(loc('u_EnvIntensity'), p.scale * env.intensityScale);
    gl.uniformMatrix3fv(loc('u_EnvRotation'), false, envRotation(p.envRotation));
    for (const x of exts) x.uniforms(x.factors, gl, loc);
    ['u_LambertianEnvSampler', 'u_GGXEnvSampler', 'u_GGXLUT'].forEach((name, unit) => env.bind(name, loc(name), unit));
    if (exts.some((x) => x.frame)) {
      // The opaque frame, its size and the matrices its lookup projects with.
      gl.uniform1i(loc('u_TransmissionFramebufferSampler'), frameUnit);
      gl.uniform2i(loc('u_TransmissionFramebufferSize'), FRAME, FRAME);
      gl.uniformMatrix4fv(loc('u_ViewMatrix'), false, viewMatrix);
      gl.uniformMatrix4fv(loc('u_ProjectionMatrix'), false, projMatrix);
    }
    // Every other active uniform keeps its default (0); a sampler among them would be an error.
    const nUniforms = gl.getProgramParameter(prog, gl.ACTIVE_UNIFORMS);
    for (let i = 0; i < nUniforms; i++) {
      const info = gl.getActiveUniform(prog, i);
      const name = info.name.replace(/\[0\]$/, '');
      if (set.has(name)) continue;
      if ([gl.SAMPLER_2D, gl.SAMPLER_CUBE, gl.SAMPLER_3D, gl.SAMPLER_2D_ARRAY].includes(info.type)) fail(`unexpected active sampler ${name}`);
      others.add(name);
    }
  }
  const drawables = [];
  if (opaqueProgram) {
    for (const b of backdropMesh()) {
      drawables.push({ prog: opaqueProgram, ...vertexArray(opaqueProgram, b, false), material: { base: b.color, metallic: 0, roughness: BACKDROP.roughness }, exts: [], opaque: true });
    }
  }
  drawables.push({ prog: program, ...vertexArray(program, sphere, extensions.some((x) => x.tangents)), material: p, exts: extensions, opaque: !transmission });
  const draw = (d) => {
    setUniforms(d.prog, d.material, d.exts);
    gl.bindVertexArray(d.vao);
    gl.drawElements(gl.TRIANGLES, d.count, gl.UNSIGNED_INT, 0);
    gl.bindVertexArray(null);
  };
  const state = () => {
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
    gl.frontFace(gl.CCW);
    gl.enable(gl.CULL_FACE);
    gl.cullFace(gl.BACK);
    gl.disable(gl.BLEND);
    gl.disable(gl.SCISSOR_TEST);
    gl.colorMask(true, true, true, true);
    gl.depthMask(true);
    gl.clearColor(0, 0, 0, 1);
    gl.clearDepth(1);
  };

  // Pass 0, where the sphere transmits: the viewer's transmission pass. The opaque drawables,
  // linear, into a 1024^2 RGBA8 frame whose mipmaps the transmissive material reads
  // (getTransmissionSample: lod = log2(1024) * applyIorToRoughness(roughness, ior)). The viewer
  // draws them multisampled and blits; here they are drawn once, without multisampling.
  if (transmission) {
    const frameTex = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0 + frameUnit);
    gl.bindTexture(gl.TEXTURE_2D, frameTex);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, FRAME, FRAME, 0, gl.RGBA, gl.UNSIGNED_BYTE, null);
    const frameDepth = gl.createRenderbuffer();
    gl.bindRenderbuffer(gl.RENDERBUFFER, frameDepth);
    gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT16, FRAME, FRAME);
    const frameFbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, frameFbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, frameTex, 0);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, frameDepth);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) fail('the opaque frame is incomplete');
    gl.viewport(0, 0, FRAME, FRAME);
    state();
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    for (const d of drawables) if (d.opaque) draw(d);
    gl.activeTexture(gl.TEXTURE0 + frameUnit);
    gl.bindTexture(gl.TEXTURE_2D, frameTex);
    gl.generateMipmap(gl.TEXTURE_2D);
  }

  // Pass 1: the viewer's shading, linear, into a float target: the opaque drawables, then the
  // transmissive one.
  const target = gl.createTexture();
  gl.activeTexture(gl.TEXTURE0 + frameUnit + 1); // a unit of its own: keep the programs' bindings
  gl.bindTexture(gl.TEXTURE_2D, target);
  gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, p.size, p.size);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  const depth = gl.createRenderbuffer();
  gl.bindRenderbuffer(gl.RENDERBUFFER, depth);
  gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, p.size, p.size);
  const fbo = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0);
  gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, depth);
  if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) fail('the RGBA32F framebuffer is incomplete');

  gl.viewport(0, 0, p.size, p.size);
  state();
  gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
  for (const d of drawables) if (d.opaque) draw(d);
  for (const d of drawables) if (!d.opaque) draw(d);
  // Pass 2: sRGB-encode into the canvas.
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  gl.disable(gl.DEPTH_TEST);
  gl.disable(gl.CULL_FACE);
  gl.useProgram(encode);
  gl.activeTexture(gl.TEXTURE0);
  gl.bindTexture(gl.TEXTURE_2D, target);
  gl.uniform1i(gl.getUniformLocation(encode, 'u_Linear'), 0);
  gl.clear(gl.COLOR_BUFFER_BIT);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  const err = gl.getError();
  if (err !== gl.NO_ERROR) fail(`WebGL error 0x${err.toString(16)}`);

  await nextFrame();
  await nextFrame();
  await nextFrame();

  return [
    `@khronosgroup/gltf-viewer ${version}: primitive.vert + pbr.frag (ibl.glsl, textures.glsl, ...) from its bundle, LINEAR_OUTPUT, USE_IBL`,
    env.notes,
    `u_MipCount ${env.mipCount} (lod = roughness*${env.mipCount - 1})`,
    `u_EnvRotation rotateY(${p.envRotation} deg) (viewer UI default 90), u_EnvIntensity ${p.scale}, u_Camera 1e6 along the view axis`,
    `material extensions: ${extensions.map((x) => `${x.name} (${x.define})`).join(', ') || 'none'}`,
    `uniforms left at 0: ${[...others].join(' ') || 'none'}`,
  ].join('; ');
}

main().then(
  (notes) => { window.iblDone = { ok: true, notes }; },
  (e) => { window.iblDone = { ok: false, error: String(e && e.stack ? e.stack : e) }; },
);
