// Shared by the engine pages (tests/engines/pages/*.html): the URL parameters of the page
// contract (tests/engines/run.mjs), the sphere every page draws, and the sphere as a glTF binary (GLB)
// with one material and its extensions, for engines that take their materials from glTF (Filament's
// gltfio, three.js's GLTFLoader).

// The page's URL parameters, checked: an Error naming the parameter where one is missing or
// malformed. `set`: the default set; `sets`: those the page renders.
export function params({ set = 'ibl', sets = ['ibl', 'own'] } = {}) {
  const q = new URLSearchParams(location.search);
  const bad = (message) => {
    throw new Error(message);
  };
  const num = (name, def) => {
    const s = q.get(name);
    if (s === null || s === '') return def;
    const v = Number(s);
    if (!Number.isFinite(v)) bad(`parameter ${name}=${s} is not a number`);
    return v;
  };
  const base = (q.get('base') ?? '1,1,1').split(',').map(Number);
  if (base.length !== 3 || !base.every(Number.isFinite)) bad(`parameter base=${q.get('base')} is not R,G,B`);
  const p = {
    set: q.get('set') || set,
    bake: q.get('bake'),
    hdr: q.get('hdr'),
    roughness: num('roughness', 0.5),
    metallic: num('metallic', 0),
    base,
    size: Math.round(num('size', 128)),
    scale: num('scale', 1),
    view: q.get('view') || 'front',
    envRotation: num('envRotation', 0),
    ext: null,
    // backdrop=1: the opaque backdrop (BACKDROP) behind the sphere.
    backdrop: q.get('backdrop') === '1',
  };
  // ext: the material's glTF extensions as JSON, e.g. {"KHR_materials_clearcoat":{"clearcoatFactor":1}}.
  const ext = q.get('ext');
  if (ext) {
    try {
      p.ext = JSON.parse(ext);
    } catch {
      bad(`parameter ext=${ext} is not JSON`);
    }
    if (typeof p.ext !== 'object' || p.ext === null || Array.isArray(p.ext)) bad(`parameter ext=${ext} is not an object of glTF material extensions`);
  }
  if (!sets.includes(p.set)) bad(`set=${p.set}: this page renders set=${sets.join(' or ')}`);
  if (p.set === 'ibl' && !p.bake) bad('missing parameter bake');
  if (p.set === 'own' && !p.hdr) bad('missing parameter hdr');
  if (p.view !== 'front' && p.view !== 'side') bad(`view=${p.view}: front or side`);
  if (!(p.size >= 1 && p.size <= 4096)) bad(`size=${p.size} out of range`);
  return p;
}

// Camera position of the contract's views: front on +Z, side on +X; both look at the origin, up +Y.
export function eye(view) {
  return view === 'side' ? [10, 0, 0] : [0, 0, 10];
}

export function done(result) {
  window.iblDone = result;
}

export function fail(e) {
  console.error(e);
  window.iblDone = { ok: false, error: String((e && e.stack) || e) };
}

// Waits for n animation frames (each one presented by the compositor).
export function frames(n) {
  return new Promise((resolve) => {
    const step = () => (n-- <= 0 ? resolve() : requestAnimationFrame(step));
    requestAnimationFrame(step);
  });
}

// A UV sphere of radius 1 (exact normals), `seg` segments around, seg/2 rings: positions (also the
// normals), tangents along the parallels as ibl's built-in spheres have them
// (shared::sphereTangent: (-z, 0, x) normalized, w = 1, what KHR_materials_anisotropy's direction
// follows), texture coordinates and triangle indices (counter-clockwise seen from outside).
export function sphereMesh(seg = 128) {
  const rings = seg / 2;
  const pos = [], tan = [], uv = [], idx = [];
  for (let j = 0; j <= rings; j++) {
    const th = (Math.PI * j) / rings;
    for (let i = 0; i <= seg; i++) {
      const ph = (2 * Math.PI * i) / seg;
      pos.push(Math.sin(th) * Math.cos(ph), Math.cos(th), -Math.sin(th) * Math.sin(ph));
      tan.push(Math.sin(ph), 0, Math.cos(ph), 1);
      uv.push(i / seg, j / rings);
    }
  }
  const row = seg + 1;
  for (let j = 0; j < rings; j++)
    for (let i = 0; i < seg; i++) {
      const a = j * row + i, b = a + row;
      idx.push(a, b, a + 1, a + 1, b, b + 1);
    }
  return { positions: new Float32Array(pos), tangents: new Float32Array(tan), uvs: new Float32Array(uv), indices: new Uint32Array(idx) };
}

// The opaque backdrop of the transmission cases (run.mjs, TRANSMISSION_CASES): a wall of
// vertical stripes facing +Z at z = BACKDROP.z, 2 * BACKDROP.half across, behind the sphere seen
// from the front view; glTF dielectrics of roughness BACKDROP.roughness in two colors (linear).
// What a transmissive sphere shows through it, each engine reads from its own frame of the opaque
// objects drawn first.
export const BACKDROP = { z: -1.5, half: 2, stripes: 8, colors: [[0.8, 0.8, 0.8], [0.1, 0.2, 0.4]], roughness: 1 };

// The backdrop's stripes, one list of quads per color: positions, normals (+Z) and triangle
// indices (counter-clockwise seen from +Z).
export function backdropMesh() {
  const { z, half, stripes } = BACKDROP;
  return BACKDROP.colors.map((color, k) => {
    const pos = [], nrm = [], idx = [];
    for (let s = k; s < stripes; s += 2) {
      const x0 = -half + (2 * half * s) / stripes, x1 = -half + (2 * half * (s + 1)) / stripes;
      const v = pos.length / 3;
      pos.push(x0, -half, z, x1, -half, z, x1, half, z, x0, half, z);
      nrm.push(0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1);
      idx.push(v, v + 1, v + 2, v, v + 2, v + 3);
    }
    return { color, positions: new Float32Array(pos), normals: new Float32Array(nrm), indices: new Uint32Array(idx) };
  });
}

// The sphere as a glTF binary (GLB) with one glTF metallic-roughness material and, where given,
// the material's `extensions` (KHR_materials_*, as the page's `ext` parameter holds them); with
// `backdrop`, the backdrop's stripes too. `matrix` (column-major 4 x 4), where given, is the
// root node's transform: ibl's renders of an engine whose world is turned against ibl's.
export function sphereGlb({ base, metallic, roughness, ext = null, backdrop = false }, seg = 128, matrix = null) {
  const m = sphereMesh(seg);
  // [arrays (POSITION, NORMAL, TANGENT?, TEXCOORD_0?, indices), material]
  const prims = [[[m.positions, m.positions, m.tangents, m.uvs, m.indices], {
    name: 'sphere',
    pbrMetallicRoughness: { baseColorFactor: [base[0], base[1], base[2], 1], metallicFactor: metallic, roughnessFactor: roughness },
    ...(ext ? { extensions: ext } : {}),
  }]];
  if (backdrop) {
    backdropMesh().forEach((b, k) => prims.push([[b.positions, b.normals, null, null, b.indices], {
      name: `backdrop ${k}`,
      pbrMetallicRoughness: { baseColorFactor: [...b.color, 1], metallicFactor: 0, roughnessFactor: BACKDROP.roughness },
    }]));
  }
  const arrays = prims.flatMap(([a]) => a.filter((x) => x));
  const bin = new Uint8Array(arrays.reduce((n, a) => n + a.byteLength, 0));
  const views = [], accessors = [], meshes = [];
  let offset = 0;
  const accessor = (a, type, target, minmax = null) => {
    bin.set(new Uint8Array(a.buffer, a.byteOffset, a.byteLength), offset);
    views.push({ buffer: 0, byteOffset: offset, byteLength: a.byteLength, target });
    offset += a.byteLength;
    const n = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 }[type];
    accessors.push({ bufferView: views.length - 1, componentType: a instanceof Uint32Array ? 5125 : 5126, count: a.length / n, type, ...(minmax ?? {}) });
    return accessors.length - 1;
  };
  const bounds = (p) => {
    const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < p.length; i++) { min[i % 3] = Math.min(min[i % 3], p[i]); max[i % 3] = Math.max(max[i % 3], p[i]); }
    return { min, max };
  };
  prims.forEach(([[P, N, T, UV, I]], k) => {
    const attributes = { POSITION: accessor(P, 'VEC3', 34962, bounds(P)), NORMAL: accessor(N, 'VEC3', 34962) };
    if (T) attributes.TANGENT = accessor(T, 'VEC4', 34962);
    if (UV) attributes.TEXCOORD_0 = accessor(UV, 'VEC2', 34962);
    meshes.push({ primitives: [{ attributes, indices: accessor(I, 'SCALAR', 34963), material: k }] });
  });
  const json = {
    asset: { version: '2.0', generator: 'ibl tests/engines' },
    ...(ext ? { extensionsUsed: Object.keys(ext) } : {}),
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [
      { name: 'root', children: meshes.map((_, k) => k + 1), ...(matrix ? { matrix } : {}) },
      ...meshes.map((_, k) => ({ mesh: k, name: prims[k][1].name })),
    ],
    meshes,
    materials: prims.map(([, material]) => material),
    buffers: [{ byteLength: bin.byteLength }],
    bufferViews: views,
    accessors,
  };
  const js = new TextEncoder().encode(JSON.stringify(json));
  const jsPad = (4 - (js.length % 4)) % 4;
  const jsonLen = js.length + jsPad;
  const total = 12 + 8 + jsonLen + 8 + bin.byteLength;
  const out = new Uint8Array(total);
  const dv = new DataView(out.buffer);
  dv.setUint32(0, 0x46546c67, true); dv.setUint32(4, 2, true); dv.setUint32(8, total, true);
  dv.setUint32(12, jsonLen, true); dv.setUint32(16, 0x4e4f534a, true);
  out.set(js, 20);
  for (let k = 0; k < jsPad; k++) out[20 + js.length + k] = 0x20;
  const o = 20 + jsonLen;
  dv.setUint32(o, bin.byteLength, true); dv.setUint32(o + 4, 0x004e4942, true);
  out.set(bin, o + 8);
  return out;
}

export async function fetchBytes(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return new Uint8Array(await r.arrayBuffer());
}
