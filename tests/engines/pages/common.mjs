// Shared by the engine pages (tests/engines/pages/*.html): the URL parameters of the page
// contract (tests/engines/run.mjs) and a UV sphere as a glTF binary (GLB) with one glTF
// metallic-roughness material, for engines that take their materials from glTF (Filament's gltfio).

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
  };
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

// A UV sphere of radius 1 (exact normals), `seg` segments around, seg/2 rings, as a GLB.
export function sphereGlb({ base, metallic, roughness }, seg = 128) {
  const rings = seg / 2;
  const pos = [], nrm = [], idx = [];
  for (let j = 0; j <= rings; j++) {
    const th = (Math.PI * j) / rings;
    for (let i = 0; i <= seg; i++) {
      const ph = (2 * Math.PI * i) / seg;
      const x = Math.sin(th) * Math.cos(ph), y = Math.cos(th), z = -Math.sin(th) * Math.sin(ph);
      pos.push(x, y, z);
      nrm.push(x, y, z);
    }
  }
  const row = seg + 1;
  for (let j = 0; j < rings; j++)
    for (let i = 0; i < seg; i++) {
      const a = j * row + i, b = a + row;
      idx.push(a, b, a + 1, a + 1, b, b + 1);
    }
  const P = new Float32Array(pos), N = new Float32Array(nrm), I = new Uint32Array(idx);
  const bin = new Uint8Array(P.byteLength + N.byteLength + I.byteLength);
  bin.set(new Uint8Array(P.buffer), 0);
  bin.set(new Uint8Array(N.buffer), P.byteLength);
  bin.set(new Uint8Array(I.buffer), P.byteLength + N.byteLength);
  const json = {
    asset: { version: '2.0', generator: 'ibl tests/engines' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, name: 'sphere' }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, NORMAL: 1 }, indices: 2, material: 0 }] }],
    materials: [{
      name: 'sphere',
      pbrMetallicRoughness: {
        baseColorFactor: [base[0], base[1], base[2], 1],
        metallicFactor: metallic,
        roughnessFactor: roughness,
      },
    }],
    buffers: [{ byteLength: bin.byteLength }],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: P.byteLength, target: 34962 },
      { buffer: 0, byteOffset: P.byteLength, byteLength: N.byteLength, target: 34962 },
      { buffer: 0, byteOffset: P.byteLength + N.byteLength, byteLength: I.byteLength, target: 34963 },
    ],
    accessors: [
      { bufferView: 0, componentType: 5126, count: P.length / 3, type: 'VEC3', min: [-1, -1, -1], max: [1, 1, 1] },
      { bufferView: 1, componentType: 5126, count: N.length / 3, type: 'VEC3' },
      { bufferView: 2, componentType: 5125, count: I.length, type: 'SCALAR' },
    ],
  };
  let js = new TextEncoder().encode(JSON.stringify(json));
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
