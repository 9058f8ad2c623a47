#!/usr/bin/env node
// The engines themselves as the test of ibl's engine targets (docs/targets.md, "In the engines
// themselves"). Bakes a real HDRI with `ibl bake --target ibl,filament,babylon,gltf-sample-viewer`,
// loads the files with each engine's own loader in headless Chromium (SwiftShader WebGL 2), renders
// a sphere per material with tone mapping off, reads the canvas back and compares it with
// `ibl render sphere --mode split-sum` and `--mode reference` of the same camera and material,
// and with the engine fed by its own pipeline where it has one in the browser.
//
// Usage: node tests/engines/run.mjs --ibl build/ibl [--work DIR] [--docs] [--only ENGINE,...]
//                                   [--orient]
//
// Page contract (tests/engines/pages/<engine>.html):
//   ?set=ibl|own&bake=<url of the bake folder>&hdr=<url of the .hdr>&roughness=R&metallic=M
//   &base=R,G,B&size=N&scale=K&view=front|side[&ext=<the material's glTF extensions as JSON>]
//   [&backdrop=1]
// The page draws into <canvas id="c"> of N x N pixels one sphere of radius 1 at the origin,
// orthographic camera at (0,0,10) (view=side: (10,0,0)) looking at the origin, up +Y, 2.2 x 2.2
// world units, right-handed world; glTF metallic-roughness material (base colour linear,
// metallic M, perceptual roughness R, dielectric F0 0.04) with the KHR_materials_* extensions in
// `ext` as the engine's glTF loader would apply them (the tangents along the parallels,
// common.mjs's sphereMesh), no lights but the environment, whose
// intensity is multiplied by K, no skybox (black), tone mapping off, sRGB-encoded output; with
// backdrop=1, common.mjs's opaque backdrop behind the sphere, drawn as the engine draws opaque
// objects before transmissive ones (its glTF loader's way where it has one); then
// sets window.iblDone = {ok: true, notes} once the frame is presented, or {ok: false, error}.

import { spawnSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import zlib from 'node:zlib';

import { sphereGlb } from './pages/common.mjs';

if (+process.versions.node.split('.')[0] < 20) {
  console.error(`run.mjs: Node ${process.versions.node} is too old: playwright-core needs Node >= 20`);
  process.exit(1);
}

const here = path.dirname(fileURLToPath(import.meta.url));
const repo = path.resolve(here, '..', '..');
const t0 = Date.now();

// ---------------------------------------------------------------------------------------------
// Settings

const HDRI = 'data/hdri/apartment.exr';  // why this one: docs/targets.md, "In the engines themselves"
const BAKE_SIZE = 128;
const IMAGE = 128;                       // canvas and render size (the sphere spans 116 px)
const BASE = [0.9, 0.6, 0.3];
const ROUGHNESS = [0, 0.25, 0.5, 0.75, 1];
const METALLIC = [1, 0];
const REF_SPP = 128;                     // its noise: 2.7 % in the metric against 1024 (dielectric r = 0.5)
const OWN_ROUGHNESS = [0.25, 0.5, 1];    // the cases an engine with both sets also renders with its own pipeline (Babylon's prefiltering takes 7 s a load on SwiftShader)
const EPS = 0.01;                        // the metric's floor, in canvas units (1 = white)
const TOP = 0.85;                        // K puts the 99.5th percentile of the split sum here

// Engine world -> ibl world: the direction in which ibl's environment holds what the engine
// shows in direction d, as each target defines it (docs/targets.md). The ibl render that an
// engine's view is compared with looks from rot(engine's camera).
const ROT = {
  identity: (d) => [d[0], d[1], d[2]],
  // Filament (cmgen's axes, panorama input): texel(d) = ours at (d.z, d.y, -d.x).
  filament: (d) => [d[2], d[1], -d[0]],
  // Babylon: texel(d) = ours at (d.z, d.y, d.x) in its left-handed world; a right-handed scene
  // flips z before the lookup (REFLECTIONMAP_OPPOSITEZ): ours at (-d.z, d.y, d.x).
  babylon: (d) => [-d[2], d[1], d[0]],
};

// [engine, page, sets, rotation, ss]: ss, where given, is the ibl split sum this engine's view is
// compared with, rendered the way the engine shades where ibl has an option for it (extra
// `ibl render --mode split-sum` arguments; the reference is the rotation's own). The glTF Sample
// Viewer looks up along the reflection vector (ibl.glsl: textureLod(u_GGXEnvSampler,
// u_EnvRotation*reflection, lod)), not along a dominant direction: --no-dominant. Its
// multiple-scattering term (Fdez-Aguera's, getIBLGGXFresnel) is kept on our side too (ibl's
// energy compensation; the same as the viewer's for F0 = 1), as --multiscatter off would leave
// out what both do.
// extensions: the glTF material extensions the engine renders (docs/materials.md, "In the
// engines"); a case using any other is left out for that engine and listed as not rendered.
const ENGINES = [
  { name: 'filament', page: 'filament.html', sets: ['ibl'], rot: 'filament', extensions: ['KHR_materials_ior', 'KHR_materials_specular', 'KHR_materials_clearcoat', 'KHR_materials_transmission', 'KHR_materials_volume'] },
  { name: 'babylon', page: 'babylon.html', sets: ['ibl', 'own'], rot: 'babylon', extensions: ['KHR_materials_ior', 'KHR_materials_specular', 'KHR_materials_clearcoat', 'KHR_materials_iridescence', 'KHR_materials_anisotropy', 'KHR_materials_transmission', 'KHR_materials_volume'] },
  { name: 'three', page: 'three.html', sets: ['own'], rot: 'identity', extensions: ['KHR_materials_ior', 'KHR_materials_specular', 'KHR_materials_clearcoat', 'KHR_materials_iridescence', 'KHR_materials_anisotropy', 'KHR_materials_transmission', 'KHR_materials_volume'] },
  { name: 'sample-viewer', page: 'sample-viewer.html', sets: ['ibl'], rot: 'identity', ss: { key: 'nodominant', args: ['--no-dominant'] }, extensions: ['KHR_materials_ior', 'KHR_materials_specular', 'KHR_materials_clearcoat', 'KHR_materials_iridescence', 'KHR_materials_anisotropy', 'KHR_materials_transmission', 'KHR_materials_volume'] },
];

// The material extensions' cases (docs/materials.md, "In the engines"): the glTF material's
// extensions (the page's `ext`) and the `ibl render sphere` options that make the same material.
// Each is one sphere of the core cases' base colour; the engines that do not render an extension
// are left out of its case. The transmission cases (`backdrop`) put the opaque backdrop of
// common.mjs (BACKDROP: a wall of stripes) behind the sphere, as each engine shows through a
// transmissive surface what it drew of the opaque objects first; ibl renders the same scene as a
// glTF (sphereGlb), and the metric covers the sphere's disk alone.
const EXTENSION_CASES = [
  { name: 'ior 2', m: 0, r: 0.25, ext: { KHR_materials_ior: { ior: 2 } }, args: ['--ior', '2'] },
  // The same material: a specular layer of factor 1 changes nothing in glTF (Filament 1.53 needs it,
  // MEASURED below).
  { name: 'ior 2 + specular 1', m: 0, r: 0.25, ext: { KHR_materials_ior: { ior: 2 }, KHR_materials_specular: { specularFactor: 1 } }, args: ['--ior', '2', '--specular', '1'] },
  { name: 'specular 0.3', m: 0, r: 0.25, ext: { KHR_materials_specular: { specularFactor: 0.3 } }, args: ['--specular', '0.3'] },
  { name: 'clearcoat 1, coat r=0.1', m: 0, r: 0.5, ext: { KHR_materials_clearcoat: { clearcoatFactor: 1, clearcoatRoughnessFactor: 0.1 } }, args: ['--clearcoat', '1', '--clearcoat-roughness', '0.1'] },
  { name: 'clearcoat 1, coat r=0.1', m: 1, r: 0.5, ext: { KHR_materials_clearcoat: { clearcoatFactor: 1, clearcoatRoughnessFactor: 0.1 } }, args: ['--clearcoat', '1', '--clearcoat-roughness', '0.1'] },
  { name: 'iridescence 1, film ior 1.3, 400 nm', m: 0, r: 0.25, ext: { KHR_materials_iridescence: { iridescenceFactor: 1, iridescenceIor: 1.3, iridescenceThicknessMaximum: 400 } }, args: ['--iridescence', '1', '--iridescence-ior', '1.3', '--iridescence-thickness', '400'] },
  { name: 'iridescence 1, film ior 1.3, 400 nm', m: 1, r: 0.25, ext: { KHR_materials_iridescence: { iridescenceFactor: 1, iridescenceIor: 1.3, iridescenceThicknessMaximum: 400 } }, args: ['--iridescence', '1', '--iridescence-ior', '1.3', '--iridescence-thickness', '400'] },
  { name: 'anisotropy 0.8', m: 1, r: 0.5, ext: { KHR_materials_anisotropy: { anisotropyStrength: 0.8 } }, args: ['--anisotropy', '0.8'] },
  // A thin wall tints once per crossing; the engines draw the sphere's front alone (one crossing),
  // ibl's reference both walls: a light tint keeps that difference small.
  { name: 'transmission 1, thin wall', m: 0, r: 0, backdrop: true, base: [0.9, 0.8, 0.6], ext: { KHR_materials_transmission: { transmissionFactor: 1 } } },
  { name: 'transmission 1, thin wall', m: 0, r: 0.3, backdrop: true, base: [0.9, 0.8, 0.6], ext: { KHR_materials_transmission: { transmissionFactor: 1 } } },
  { name: 'transmission 1, volume 2 (attenuation 0.8, 0.6, 0.4 after 2)', m: 0, r: 0, backdrop: true, base: [1, 1, 1],
    ext: { KHR_materials_transmission: { transmissionFactor: 1 }, KHR_materials_volume: { thicknessFactor: 2, attenuationDistance: 2, attenuationColor: [0.8, 0.6, 0.4] } } },
];
// The backdrop cases' reference: the light crosses the sphere's two walls before it reaches the
// backdrop (each crossing is a bounce).
const BACKDROP_BOUNCES = 8;

// Thresholds, from what was measured (MEASURED: the engine with ibl's files against
// `ibl render --mode split-sum`, against the engine's own pipeline, and the engine's own
// pipeline against `ibl render --mode reference`, per engine and case): a check fails above
// SLACK times the measured value (at least the floor). An engine or case not measured yet gets
// DEFAULT_SS (vs split sum), DEFAULT_OWN (vs own) and DEFAULT_REF (own pipeline vs reference).
// OWN_MARGIN: ibl's files against the reference may be worse than the engine's own pipeline by
// this much (absolute, in the metric's units) per case.
const SLACK = 1.75;
const FLOOR_SS = 0.02, FLOOR_OWN = 0.01, FLOOR_REF = 0.02;
const DEFAULT_SS = 0.12, DEFAULT_OWN = 0.05, DEFAULT_REF = 0.12;
const OWN_MARGIN = 0.01;
// An extension's case: the engine is taken to ignore the extension where it is at least this much
// (absolute, in the metric's units) nearer ibl's split sum without it than with it; nearer with it
// by any amount is a pass; in between, no check.
const UNDECIDED = 0.005;
const MEASURED = {
  // engine: { case: [vs split sum, vs own pipeline, own pipeline vs reference] }, measured
  // 2026-12-03, the dielectrics again 2026-12-05 after glTF's fresnel_mix (docs/targets.md), the
  // material extensions' cases 2026-12-07, the transmission cases (the sphere in front of the
  // backdrop) 2026-12-07 (docs/materials.md, "In the engines")
  filament: {
    'metal r=0': [0.068], 'metal r=0.25': [0.034], 'metal r=0.5': [0.043], 'metal r=0.75': [0.044], 'metal r=1': [0.008],
    'dielectric r=0': [0.029], 'dielectric r=0.25': [0.025], 'dielectric r=0.5': [0.017], 'dielectric r=0.75': [0.018], 'dielectric r=1': [0.028],
    'ior 2, dielectric r=0.25': [0.076],
    'ior 2 + specular 1, dielectric r=0.25': [0.025],
    'specular 0.3, dielectric r=0.25': [0.018],
    'clearcoat 1, coat r=0.1, dielectric r=0.5': [0.016],
    'clearcoat 1, coat r=0.1, metal r=0.5': [0.039],
    'transmission 1, thin wall, dielectric r=0': [0.096], 'transmission 1, thin wall, dielectric r=0.3': [0.139],
    'transmission 1, volume 2 (attenuation 0.8, 0.6, 0.4 after 2), dielectric r=0': [0.302],
  },
  babylon: {
    'metal r=0': [0.122], 'metal r=0.25': [0.071, 0.014, 0.085], 'metal r=0.5': [0.056, 0.008, 0.096], 'metal r=0.75': [0.059], 'metal r=1': [0.027, 0.004, 0.088],
    'dielectric r=0': [0.050], 'dielectric r=0.25': [0.044, 0.005, 0.053], 'dielectric r=0.5': [0.032, 0.004, 0.042], 'dielectric r=0.75': [0.026], 'dielectric r=1': [0.025, 0.004, 0.030],
    'ior 2, dielectric r=0.25': [0.041],
    'ior 2 + specular 1, dielectric r=0.25': [0.041],
    'specular 0.3, dielectric r=0.25': [0.028],
    'clearcoat 1, coat r=0.1, dielectric r=0.5': [0.044],
    'clearcoat 1, coat r=0.1, metal r=0.5': [0.059],
    'iridescence 1, film ior 1.3, 400 nm, dielectric r=0.25': [0.126],
    'iridescence 1, film ior 1.3, 400 nm, metal r=0.25': [0.11],
    'anisotropy 0.8, metal r=0.5': [0.177],
    'transmission 1, thin wall, dielectric r=0': [0.159], 'transmission 1, thin wall, dielectric r=0.3': [0.122],
    'transmission 1, volume 2 (attenuation 0.8, 0.6, 0.4 after 2), dielectric r=0': [0.114],
  },
  // Its own HDRLoader + PMREMGenerator only (three.js reads no prefiltered files).
  three: {
    'metal r=0': [null, null, 0.021], 'metal r=0.25': [null, null, 0.045], 'metal r=0.5': [null, null, 0.086], 'metal r=0.75': [null, null, 0.130], 'metal r=1': [null, null, 0.074],
    'dielectric r=0': [null, null, 0.032], 'dielectric r=0.25': [null, null, 0.031], 'dielectric r=0.5': [null, null, 0.022], 'dielectric r=0.75': [null, null, 0.018], 'dielectric r=1': [null, null, 0.026],
    'ior 2, dielectric r=0.25': [null, null, 0.031],
    'ior 2 + specular 1, dielectric r=0.25': [null, null, 0.031],
    'specular 0.3, dielectric r=0.25': [null, null, 0.019],
    'clearcoat 1, coat r=0.1, dielectric r=0.5': [null, null, 0.022],
    'clearcoat 1, coat r=0.1, metal r=0.5': [null, null, 0.068],
    'iridescence 1, film ior 1.3, 400 nm, dielectric r=0.25': [null, null, 0.034],
    'iridescence 1, film ior 1.3, 400 nm, metal r=0.25': [null, null, 0.045],
    'anisotropy 0.8, metal r=0.5': [null, null, 0.345],
    'transmission 1, thin wall, dielectric r=0': [null, null, 0.555], 'transmission 1, thin wall, dielectric r=0.3': [null, null, 0.807],
    'transmission 1, volume 2 (attenuation 0.8, 0.6, 0.4 after 2), dielectric r=0': [null, null, 1.429],
  },
  // Against the split sum with --no-dominant (ENGINES' ss). Metal r = 1 is the viewer's
  // multiple-scattering term (Fdez-Aguera's) against ibl's: 0.75-0.95 of ibl's brightness
  // (docs/targets.md).
  'sample-viewer': {
    'metal r=0': [0.029], 'metal r=0.25': [0.011], 'metal r=0.5': [0.008], 'metal r=0.75': [0.024], 'metal r=1': [0.123],
    'dielectric r=0': [0.030], 'dielectric r=0.25': [0.025], 'dielectric r=0.5': [0.012], 'dielectric r=0.75': [0.012], 'dielectric r=1': [0.023],
    'ior 2, dielectric r=0.25': [0.023],
    'ior 2 + specular 1, dielectric r=0.25': [0.023],
    'specular 0.3, dielectric r=0.25': [0.009],
    'clearcoat 1, coat r=0.1, dielectric r=0.5': [0.011],
    'clearcoat 1, coat r=0.1, metal r=0.5': [0.008],
    'iridescence 1, film ior 1.3, 400 nm, dielectric r=0.25': [0.003],
    'iridescence 1, film ior 1.3, 400 nm, metal r=0.25': [0.006],
    'anisotropy 0.8, metal r=0.5': [0.113],
    'transmission 1, thin wall, dielectric r=0': [0.041], 'transmission 1, thin wall, dielectric r=0.3': [0.064],
    'transmission 1, volume 2 (attenuation 0.8, 0.6, 0.4 after 2), dielectric r=0': [0.053],
  },
};
// Where an engine departs from the extension's specification (measured; docs/materials.md, "In the
// engines"): the check that the engine is nearer ibl's split sum with the extension than without is
// not made there, and the table says why.
const DEPARTURES = {
  filament: {
    'ior 2, dielectric r=0.25': "gltfio 1.53's ubershader for a material with KHR_materials_ior and no KHR_materials_specular leaves the specular strength at 0: no dielectric reflection (fixed after 1.53; with a specular layer of factor 1 it is right)",
  },
  babylon: {
    'iridescence 1, film ior 1.3, 400 nm, dielectric r=0.25': "Babylon's film over a dielectric brightens the rim toward white where the specification's (ibl's, the Sample Viewer's, three.js's) stays tinted",
    'iridescence 1, film ior 1.3, 400 nm, metal r=0.25': "Babylon's film over a metal is as far from ibl's as the metal without it (the Sample Viewer and three.js: within 0.6 and 3.4 %)",
  },
};
// What the table says beside a case where the engine is measured but shows something the
// specification does not ask for (the checks are made).
const NOTES = {
  filament: {
    'transmission 1, thin wall, dielectric r=0': "gltfio 1.53 gives a transmissive material without KHR_materials_specular no reflection, as with KHR_materials_ior alone",
    'transmission 1, thin wall, dielectric r=0.3': "no reflection, as at r = 0, and 6.7 % with a specular layer of factor 1; the frame behind as sharp as through smooth glass",
    'transmission 1, volume 2 (attenuation 0.8, 0.6, 0.4 after 2), dielectric r=0': 'no reflection, as for the thin wall',
  },
};
function threshold(engine, key, which) {  // which: 'ss', 'own' or 'ref'
  const k = { ss: 0, own: 1, ref: 2 }[which];
  const m = MEASURED[engine]?.[key]?.[k];
  if (m === undefined || m === null) return [DEFAULT_SS, DEFAULT_OWN, DEFAULT_REF][k];
  return Math.max([FLOOR_SS, FLOOR_OWN, FLOOR_REF][k], +(SLACK * m).toFixed(3));
}
// Time limits: the whole run (IBL_ENGINES_TIMEOUT_S), one `ibl` command, one page's wait.
const RUN_TIMEOUT_S = +(process.env.IBL_ENGINES_TIMEOUT_S || 900);
const IBL_TIMEOUT_S = 300;
const PAGE_TIMEOUT_S = 90;

// ---------------------------------------------------------------------------------------------
// Arguments

const args = process.argv.slice(2);
const opt = { ibl: null, work: path.join(repo, 'out', 'engines'), docs: false, only: null, orient: false };
for (let i = 0; i < args.length; i++) {
  const a = args[i];
  if (a === '--ibl') opt.ibl = path.resolve(args[++i]);
  else if (a === '--work') opt.work = path.resolve(args[++i]);
  else if (a === '--docs') opt.docs = true;
  else if (a === '--only') opt.only = args[++i].split(',');
  else if (a === '--orient') opt.orient = true;
  else if (a === '-h' || a === '--help') {
    console.log('usage: node tests/engines/run.mjs --ibl build/ibl [--work DIR] [--docs] [--only ENGINE,...] [--orient]');
    process.exit(0);
  } else {
    console.error(`run.mjs: unknown argument ${a}`);
    process.exit(2);
  }
}
if (!opt.ibl) {
  console.error('run.mjs: --ibl PATH is required');
  process.exit(2);
}
if (opt.only) {
  const unknown = opt.only.filter((n) => !ENGINES.some((e) => e.name === n));
  if (unknown.length) {
    console.error(`run.mjs: --only: unknown engine ${unknown.join(', ')} (known: ${ENGINES.map((e) => e.name).join(', ')})`);
    process.exit(1);
  }
}
const W = opt.work;
fs.mkdirSync(W, { recursive: true });

function log(...m) {
  console.log(`[${((Date.now() - t0) / 1000).toFixed(1).padStart(5)} s]`, ...m);
}

// What the run is doing (printed if the deadline passes), and what to close on the way out.
let doing = 'starting';
let context = null, server = null, userData = null, timedOut = false;
const halt = () => new Promise(() => {});  // after the deadline: wait for the exit below, print nothing more
process.on('exit', () => { if (userData) fs.rmSync(userData, { recursive: true, force: true }); });
setTimeout(async () => {
  timedOut = true;
  console.error(`run.mjs: timed out after ${RUN_TIMEOUT_S} s (IBL_ENGINES_TIMEOUT_S) while ${doing}`);
  console.log('engines: timed out');
  const closing = Promise.allSettled([context?.close(), server && new Promise((r) => server.close(r))]);
  await Promise.race([closing, new Promise((r) => setTimeout(r, 10000))]);
  process.exit(1);
}, RUN_TIMEOUT_S * 1000).unref();

// ---------------------------------------------------------------------------------------------
// ibl

function ibl(argv, { quiet = true } = {}) {
  if (Date.now() - t0 > RUN_TIMEOUT_S * 1000) throw new Error(`timed out after ${RUN_TIMEOUT_S} s (IBL_ENGINES_TIMEOUT_S) before ibl ${argv.join(' ')}`);
  doing = `running ibl ${argv.join(' ')}`;
  const r = spawnSync(opt.ibl, argv, { cwd: repo, encoding: 'utf8', timeout: IBL_TIMEOUT_S * 1000, killSignal: 'SIGKILL' });
  if (r.error?.code === 'ETIMEDOUT') throw new Error(`ibl ${argv.join(' ')}: timed out after ${IBL_TIMEOUT_S} s (killed)`);
  if (r.error) throw new Error(`ibl ${argv.join(' ')}: ${r.error.message}`);
  if (r.status !== 0) {
    throw new Error(`ibl ${argv.join(' ')}: exit ${r.status ?? r.signal}\n${r.stdout}${r.stderr}`);
  }
  if (!quiet) process.stdout.write(r.stdout);
  return r.stdout + r.stderr;
}

function fileHash(files) {
  const h = createHash('sha1');
  for (const f of files) h.update(fs.readFileSync(f));
  return h.digest('hex');
}

// Runs `ibl ARGV -o OUT` unless OUT exists from the same command over the same inputs.
function cached(out, argv, inputsKey) {
  const key = createHash('sha1').update(JSON.stringify([argv, inputsKey])).digest('hex');
  const stamp = out + '.key';
  if (fs.existsSync(out) && fs.existsSync(stamp) && fs.readFileSync(stamp, 'utf8') === key) return false;
  ibl([...argv, '-o', out]);
  fs.writeFileSync(stamp, key);
  return true;
}

// ---------------------------------------------------------------------------------------------
// EXR (what ibl render writes: scanline, ZIP or NONE or ZIPS, HALF or FLOAT channels)

function half(h) {
  const s = h & 0x8000 ? -1 : 1, e = (h >> 10) & 31, f = h & 1023;
  if (e === 0) return s * f * 2 ** -24;
  if (e === 31) return f ? NaN : s * Infinity;
  return s * (1 + f / 1024) * 2 ** (e - 15);
}

function readExr(file) {
  const d = fs.readFileSync(file);
  if (d.readUInt32LE(0) !== 20000630) throw new Error(`${file}: not an EXR`);
  let i = 8;
  const attr = {};
  const cstr = () => { const j = d.indexOf(0, i); const s = d.toString('latin1', i, j); i = j + 1; return s; };
  for (;;) {
    const name = cstr();
    if (!name) break;
    const type = cstr();
    const size = d.readInt32LE(i); i += 4;
    attr[name] = { type, data: d.subarray(i, i + size) };
    i += size;
  }
  const chans = [];
  { const c = attr.channels.data; let k = 0;
    while (c[k]) { const j = c.indexOf(0, k); const n = c.toString('latin1', k, j); k = j + 1;
      chans.push({ name: n, type: c.readInt32LE(k) }); k += 16; } }
  const comp = attr.compression.data[0];
  const dw = attr.dataWindow.data;
  const x0 = dw.readInt32LE(0), y0 = dw.readInt32LE(4), x1 = dw.readInt32LE(8), y1 = dw.readInt32LE(12);
  const w = x1 - x0 + 1, h = y1 - y0 + 1;
  const lines = { 0: 1, 1: 1, 2: 1, 3: 16 }[comp];
  if (!lines) throw new Error(`${file}: EXR compression ${comp} not supported here`);
  const nChunks = Math.ceil(h / lines);
  const bytesPer = chans.map((c) => (c.type === 1 ? 2 : 4));
  const px = Object.fromEntries(chans.map((c) => [c.name, new Float32Array(w * h)]));
  for (let c = 0; c < nChunks; c++) {
    const off = Number(d.readBigUInt64LE(i + 8 * c));
    const y = d.readInt32LE(off) - y0, size = d.readInt32LE(off + 4);
    let raw = d.subarray(off + 8, off + 8 + size);
    const n = Math.min(lines, h - y);
    const want = n * w * bytesPer.reduce((a, b) => a + b, 0);
    if (comp !== 0 && size < want) {
      const z = zlib.inflateSync(raw);
      const t = Buffer.alloc(z.length);
      for (let k = 1; k < z.length; k++) z[k] = (z[k - 1] + z[k] - 128) & 255;
      const half_ = (z.length + 1) >> 1;
      for (let k = 0, a = 0, b = half_; k < z.length; k++) t[k] = k & 1 ? z[b++] : z[a++];
      raw = t;
    }
    let o = 0;
    for (let l = 0; l < n; l++)
      for (let ch = 0; ch < chans.length; ch++) {
        const arr = px[chans[ch].name];
        for (let x = 0; x < w; x++) {
          const v = chans[ch].type === 1 ? half(raw.readUInt16LE(o)) : chans[ch].type === 2 ? raw.readFloatLE(o) : raw.readUInt32LE(o);
          arr[(y + l) * w + x] = v;
          o += bytesPer[ch];
        }
      }
  }
  return { w, h, R: px.R, G: px.G, B: px.B, A: px.A || new Float32Array(w * h).fill(1) };
}

// ---------------------------------------------------------------------------------------------
// Colour

const toLinear = new Float32Array(256).map((_, v) => {
  const c = v / 255;
  return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
});
function toSrgb8(x) {
  x = Math.min(1, Math.max(0, x));
  const c = x <= 0.0031308 ? 12.92 * x : 1.055 * x ** (1 / 2.4) - 0.055;
  return Math.round(c * 255);
}

// ---------------------------------------------------------------------------------------------
// The cases and the ibl renders

// id: the case's part of the file names; base: its base colour. A backdrop case has a `without`:
// the same scene without the extensions (the sphere opaque), rendered in the split sum alone.
const cases = [];
for (const m of METALLIC) for (const r of ROUGHNESS) cases.push({ r, m, base: BASE, key: `${m ? 'metal' : 'dielectric'} r=${r}`, id: `m${m}-r${r}`, args: [] });
EXTENSION_CASES.forEach((x, k) => {
  const c = { base: BASE, args: [], ...x, key: `${x.name}, ${x.m ? 'metal' : 'dielectric'} r=${x.r}`, id: `x${k}-m${x.m}-r${x.r}` };
  if (c.backdrop) c.without = { ...c, ext: null, id: `${c.id}-without` };
  cases.push(c);
});
const renders = (e, c) => !c.ext || Object.keys(c.ext).every((x) => e.extensions.includes(x));

const engines = ENGINES.filter((e) => (!opt.only || opt.only.includes(e.name)));
const present = [];
let missingPages = 0;
for (const e of engines) {
  if (fs.existsSync(path.join(here, 'pages', e.page))) present.push(e);
  else { console.error(`FAILED tests/engines/pages/${e.page} does not exist: ${e.name} not checked`); missingPages++; }
}

const vec = (v) => v.map((x) => +x.toFixed(6)).join(',');
const scale10 = (d) => d.map((x) => 10 * x);

log(`preparing ${W}`);
const hdr = path.join(W, 'apartment.hdr');
cached(hdr, ['convert', HDRI], fileHash([path.join(repo, HDRI)]));
const bakeDir = path.join(W, 'bake');
// Baked every run (1.5 s): the bake is what the phase tests.
ibl(['bake', hdr, '--target', 'ibl,filament,babylon,gltf-sample-viewer', '--size', String(BAKE_SIZE), '--force', '-q', '-o', bakeDir]);
// The renders depend on the ibl set and on the renderer (the command and its library).
const lib = path.join(path.dirname(opt.ibl), 'libibl.so');
const bakeKey = fileHash([path.join(bakeDir, 'specular.ktx2'), path.join(bakeDir, 'source.ktx2'), path.join(bakeDir, 'irradiance.ktx2'), opt.ibl, ...(fs.existsSync(lib) ? [lib] : [])]);

// Cameras needed: each engine's front view mapped into ibl's world; an engine with its own split
// sum settings (ss) adds a split-sum-only camera `<rot>-<ss.key>`.
const cameras = new Map();  // key -> eye
const ssExtra = new Map();  // camera key -> extra split-sum arguments
const camRot = new Map();   // camera key -> the engine's rotation (ROT's key)
for (const e of present) {
  const eyeIbl = scale10(ROT[e.rot]([0, 0, 1]));
  cameras.set(e.rot, eyeIbl);
  camRot.set(e.rot, e.rot);
  if (e.ss) { cameras.set(`${e.rot}-${e.ss.key}`, eyeIbl); ssExtra.set(`${e.rot}-${e.ss.key}`, e.ss.args); camRot.set(`${e.rot}-${e.ss.key}`, e.rot); }
}
if (opt.orient) for (const [k, v] of Object.entries({ pz: [0, 0, 10], px: [10, 0, 0], nz: [0, 0, -10], nx: [-10, 0, 0] })) cameras.set('orient-' + k, v);

// A backdrop case's scene as ibl renders it from camera camKey: the GLB the pages build, its root
// turned by the engine's rotation (the engine's world -> ibl's, as the environment is).
const sceneDir = path.join(W, 'scenes');
fs.mkdirSync(sceneDir, { recursive: true });
function sceneGlbPath(camKey, c) {
  const rot = ROT[camRot.get(camKey)];
  const [x, y, z] = [rot([1, 0, 0]), rot([0, 1, 0]), rot([0, 0, 1])];
  const file = path.join(sceneDir, `${camRot.get(camKey)}-${c.id}.glb`);
  const glb = sphereGlb({ base: c.base, metallic: c.m, roughness: c.r, ext: c.ext, backdrop: true }, 128, [...x, 0, ...y, 0, ...z, 0, 0, 0, 0, 1]);
  if (!fs.existsSync(file) || !fs.readFileSync(file).equals(Buffer.from(glb))) fs.writeFileSync(file, glb);
  return file;
}
function renderArgs(c, eyeIbl, mode, extra = [], glb = null) {
  const scene = glb ? [glb, '--ssao', 'off', '--ssr', 'off', ...(mode === 'reference' ? ['--bounces', String(BACKDROP_BOUNCES)] : [])]
    : ['sphere', '--base-color', vec(c.base), '--metallic', String(c.m), '--roughness', String(c.r), ...c.args];
  return ['render', ...scene, '--bake', bakeDir, '--camera', 'ortho', '--ortho-width', '2.2',
    '--look-from', vec(eyeIbl), '--look-at', '0,0,0', '--up', '0,1,0', '--size', `${IMAGE}x${IMAGE}`,
    '--diffuse', 'lambert', '--background', '0,0,0', '--tonemap', 'none', '--ev100', '0', '-q',
    '--mode', mode, ...(mode === 'reference' ? ['--spp', String(REF_SPP)] : ['--spp', '16']),
    // The engines do not widen their lobes by the normal's change across the pixel (Filament's
    // specular antialiasing is off by default; the Sample Viewer and Babylon.js have none).
    ...(mode === 'reference' ? [] : ['--specular-aa', 'off']), ...extra];
}
const rdir = path.join(W, 'renders');
function renderPath(camKey, c, mode) { return path.join(rdir, `${camKey}-${c.id}-${mode}.exr`); }
fs.mkdirSync(rdir, { recursive: true });
let nRendered = 0;
const tr = Date.now();
for (const [camKey, eyeIbl] of cameras)
  for (const c of cases)
    for (const mode of ['split-sum', 'reference']) {
      if (camKey.startsWith('orient') && (mode === 'reference' || c !== cases[2])) continue;
      if (ssExtra.has(camKey) && mode === 'reference') continue;  // the reference has no such settings
      if (c.ext && !present.some((e) => renders(e, c) && (camKey === e.rot || camKey === `${e.rot}-${e.ss?.key}`))) continue;
      if (c.backdrop && camKey.startsWith('orient')) continue;
      for (const cc of mode === 'split-sum' && c.without ? [c, c.without] : [c]) {
        const out = renderPath(camKey, cc, mode);
        const glb = cc.backdrop ? sceneGlbPath(camKey, cc) : null;
        if (cached(out, renderArgs(cc, eyeIbl, mode, ssExtra.get(camKey) ?? [], glb), glb ? bakeKey + fileHash([glb]) : bakeKey)) nRendered++;
      }
    }
log(`ibl renders: ${nRendered} made (${((Date.now() - tr) / 1000).toFixed(1)} s), the others cached`);

// ---------------------------------------------------------------------------------------------
// HTTP server: /engines/ -> tests/engines/, /work/ -> the work folder

const MIME = {
  '.html': 'text/html; charset=utf-8', '.js': 'text/javascript', '.mjs': 'text/javascript',
  '.wasm': 'application/wasm', '.json': 'application/json', '.png': 'image/png',
  '.hdr': 'application/octet-stream', '.ktx': 'application/octet-stream', '.ktx2': 'image/ktx2',
  '.env': 'application/octet-stream', '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json',
  '.bin': 'application/octet-stream', '.map': 'application/json', '.txt': 'text/plain', '.css': 'text/css',
};
const roots = { '/engines/': here, '/work/': W };
server = http.createServer((req, res) => {
  const u = new URL(req.url, 'http://x');
  const p = decodeURIComponent(u.pathname);
  for (const [prefix, root] of Object.entries(roots)) {
    if (!p.startsWith(prefix)) continue;
    const f = path.resolve(root, '.' + p.slice(prefix.length - 1));
    if (!f.startsWith(root + path.sep)) break;
    fs.readFile(f, (err, data) => {
      if (err) { res.writeHead(404); res.end('not found'); return; }
      res.writeHead(200, { 'Content-Type': MIME[path.extname(f)] || 'application/octet-stream', 'Cache-Control': 'no-store' });
      res.end(data);
    });
    return;
  }
  res.writeHead(404); res.end('not found');
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const origin = `http://127.0.0.1:${server.address().port}`;

// ---------------------------------------------------------------------------------------------
// Browser

function fatal(msg) {
  console.error(`run.mjs: ${msg}`);
  server.close();
  process.exit(1);
}
let chromium, PNG;
try {
  ({ chromium } = await import(path.join(here, 'node_modules', 'playwright-core', 'index.mjs')));
  ({ PNG } = (await import(path.join(here, 'node_modules', 'pngjs', 'lib', 'png.js'))).default);
} catch (err) {
  fatal(`the npm packages in tests/engines/node_modules are missing or broken (run scripts/setup.sh): ${err.message.split('\n')[0]}`);
}
const chromiumPath = process.env.CHROMIUM || '/usr/bin/chromium';
doing = `launching Chromium (${chromiumPath})`;
userData = fs.mkdtempSync(path.join(os.tmpdir(), 'ibl-engines-'));
try {
context = await chromium.launchPersistentContext(userData, {
  executablePath: chromiumPath,
  headless: true,
  args: ['--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
    '--ignore-gpu-blocklist', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--disable-default-apps', '--disable-extensions',
    '--force-color-profile=srgb'],
  viewport: { width: IMAGE + 32, height: IMAGE + 32 },
  deviceScaleFactor: 1,
});
} catch (err) {
  fatal(`cannot launch Chromium at ${chromiumPath} (CHROMIUM overrides it; run scripts/setup.sh): ${err.message.split('\n')[0]}`);
}
// Nothing leaves 127.0.0.1: any other request is aborted and fails the run.
const offHost = [];
await context.route('**/*', (route) => {
  const u = new URL(route.request().url());
  if (u.protocol === 'data:' || u.protocol === 'blob:' || u.hostname === '127.0.0.1') return route.continue();
  offHost.push(u.href);
  return route.abort('blockedbyclient');
});
let failures = missingPages, passes = 0;
const results = [];
const notes = {};
try {
  // WebGL 2 and float render targets (the engines' prefiltering and HDR paths need them).
  {
    const page = await context.newPage();
    await page.goto(`${origin}/engines/`).catch(() => {});
    const gl = await page.evaluate(() => {
      const c = document.createElement('canvas');
      const g = c.getContext('webgl2');
      if (!g) return null;
      return { renderer: g.getParameter(g.RENDERER), cbf: !!g.getExtension('EXT_color_buffer_float') };
    });
    await page.close();
    if (!gl || !gl.cbf) throw new Error(`Chromium gives no WebGL 2 with EXT_color_buffer_float: ${JSON.stringify(gl)}`);
    log(`WebGL 2: ${gl.renderer}`);
  }

  const shots = path.join(W, 'shots');
  fs.mkdirSync(shots, { recursive: true });
  async function capture(e, set, c, scale) {
    const q = new URLSearchParams({
      set, bake: '/work/bake', hdr: '/work/apartment.hdr', roughness: String(c.r), metallic: String(c.m),
      base: c.base.join(','), size: String(IMAGE), scale: String(scale), view: 'front',
      ...(c.ext ? { ext: JSON.stringify(c.ext) } : {}), ...(c.backdrop ? { backdrop: '1' } : {}),
    });
    const page = await context.newPage();
    const consoleLines = [];
    page.on('console', (m) => consoleLines.push(`${m.type()}: ${m.text()}`));
    page.on('pageerror', (err) => consoleLines.push(`pageerror: ${err.message}`));
    doing = `rendering ${e.name} set=${set} ${c.key}`;
    try {
      await page.goto(`${origin}/engines/pages/${e.page}?${q}`, { timeout: PAGE_TIMEOUT_S * 1000 });
      const h = await page.waitForFunction(() => window.iblDone, null, { timeout: PAGE_TIMEOUT_S * 1000 });
      const done = await h.jsonValue();
      if (!done.ok) throw new Error(done.error);
      notes[`${e.name}/${set}`] = done.notes;
      const png = await page.locator('#c').screenshot({ animations: 'disabled' });
      fs.writeFileSync(path.join(shots, `${e.name}-${set}-${c.id}.png`), png);
      return PNG.sync.read(png);
    } catch (err) {
      throw new Error(`${e.name} set=${set} ${c.key}: ${err.message}\n  ${consoleLines.slice(-8).join('\n  ')}`);
    } finally {
      await page.close();
    }
  }

  // Mean per-pixel relative error over the sphere, per channel averaged:
  // |a - b| / (b + EPS), a and b in canvas units (b = ibl's radiance x K).
  function compare(a, b, mask) {
    let sum = 0, n = 0;
    for (let i = 0; i < mask.length; i++) {
      if (!mask[i]) continue;
      for (let ch = 0; ch < 3; ch++) sum += Math.abs(a[ch][i] - b[ch][i]) / (Math.abs(b[ch][i]) + EPS);
      n += 3;
    }
    return n ? sum / n : NaN;
  }
  const linear = (png) => {
    const n = png.width * png.height, out = [new Float32Array(n), new Float32Array(n), new Float32Array(n)], clip = new Uint8Array(n);
    for (let i = 0; i < n; i++) {
      for (let ch = 0; ch < 3; ch++) {
        const v = png.data[4 * i + ch];
        out[ch][i] = toLinear[v];
        if (v === 255) clip[i] = 1;
      }
    }
    return { rgb: out, clip };
  };
  const exrScaled = (ex, K) => [ex.R.map((v) => v * K), ex.G.map((v) => v * K), ex.B.map((v) => v * K)];

  for (const e of present) {
    const camKey = e.rot;
    const ssKey = e.ss ? `${e.rot}-${e.ss.key}` : e.rot;
    for (const c of cases) {
      if (!renders(e, c)) continue;
      const ss = readExr(renderPath(ssKey, c, 'split-sum'));
      const ref = readExr(renderPath(camKey, c, 'reference'));
      // The sphere's pixels: fully covered in both renders, and their 4 neighbours too.
      const mask0 = new Uint8Array(ss.w * ss.h);
      // A backdrop case covers the whole image: its mask is the sphere's disk (radius 1 in the
      // view's 2.2 units), less two pixels at the rim.
      const inDisk = (i) => {
        const u = (((i % ss.w) + 0.5) / ss.w) * 2.2 - 1.1, v = ((Math.floor(i / ss.w) + 0.5) / ss.h) * 2.2 - 1.1;
        return Math.hypot(u, v) < 1 - (2 * 2.2) / ss.w;
      };
      const full = (i) => ss.A[i] >= 0.999 && ref.A[i] >= 0.999 && (!c.backdrop || inDisk(i));
      for (let y = 1; y < ss.h - 1; y++)
        for (let x = 1; x < ss.w - 1; x++) {
          const i = y * ss.w + x;
          mask0[i] = full(i) && full(i - 1) && full(i + 1) && full(i - ss.w) && full(i + ss.w) ? 1 : 0;
        }
      const maxc = [];
      for (let i = 0; i < mask0.length; i++) if (mask0[i]) maxc.push(Math.max(ss.R[i], ss.G[i], ss.B[i]));
      maxc.sort((a, b) => a - b);
      const p995 = maxc[Math.floor(0.995 * (maxc.length - 1))];
      const K = +(TOP / p995).toPrecision(4);
      const row = { engine: e.name, case: c, K, clipped: 0, pixels: 0 };
      const imgs = {};
      const sets = e.sets.filter((set) => !(set === 'own' && e.sets.includes('ibl') && (c.ext || !OWN_ROUGHNESS.includes(c.r))));
      try {
        for (const set of sets) imgs[set] = linear(await capture(e, set, c, K));
      } catch (err) {
        // A page that fails is a failed check; the other engines and cases still run.
        if (timedOut) await halt();
        console.error(`FAILED ${err.message}`);
        failures++;
        continue;
      }
      const mask = mask0.slice();
      for (const set of sets) for (let i = 0; i < mask.length; i++) if (imgs[set].clip[i]) { if (mask[i]) row.clipped++; mask[i] = 0; }
      row.pixels = mask.reduce((a, b) => a + b, 0);
      const S = exrScaled(ss, K), R = exrScaled(ref, K);
      if (imgs.ibl) {
        row.iblVsSs = compare(imgs.ibl.rgb, S, mask);
        row.iblVsRef = compare(imgs.ibl.rgb, R, mask);
      }
      if (imgs.own) row.ownVsRef = compare(imgs.own.rgb, R, mask);
      if (imgs.ibl && imgs.own) row.iblVsOwn = compare(imgs.ibl.rgb, imgs.own.rgb, mask);
      row.ssVsRef = compare(S, R, mask);
      // An extension's case: the engine's image (its ibl set, else its own pipeline) against ibl's
      // split sum with the extension and without it. The engine must be nearer ibl's with it (else
      // it ignored the extension); within UNDECIDED of the other, the check is not made (three.js's
      // own pipeline differs from ibl's split sum as much as a dielectric's film does).
      const engineImg = (imgs.ibl ?? imgs.own).rgb;
      if (c.ext) {
        const base = c.without ?? cases.find((b) => !b.ext && b.m === c.m && b.r === c.r);
        const S0 = exrScaled(readExr(renderPath(ssKey, base, 'split-sum')), K);
        row.effect = compare(S0, S, mask);
        row.engineVsSs = compare(engineImg, S, mask);
        row.engineVsBase = compare(engineImg, S0, mask);
        row.decided = row.engineVsSs < row.engineVsBase || row.engineVsSs >= row.engineVsBase + UNDECIDED;
      }
      // Checks
      row.checks = [];
      if (row.iblVsSs !== undefined) {
        const t = threshold(e.name, c.key, 'ss');
        row.checks.push({ what: `vs split sum <= ${t}`, ok: row.iblVsSs <= t });
      }
      if (row.iblVsOwn !== undefined) {
        const t = threshold(e.name, c.key, 'own');
        row.checks.push({ what: `vs own pipeline <= ${t}`, ok: row.iblVsOwn <= t });
      }
      if (row.ownVsRef !== undefined) {
        const t = threshold(e.name, c.key, 'ref');
        row.checks.push({ what: `own pipeline vs reference <= ${t}`, ok: row.ownVsRef <= t });
      }
      if (row.iblVsRef !== undefined && row.ownVsRef !== undefined) {
        row.checks.push({ what: `vs reference <= own + ${OWN_MARGIN}`, ok: row.iblVsRef <= row.ownVsRef + OWN_MARGIN });
      }
      const departure = DEPARTURES[e.name]?.[c.key];
      if (departure) row.departure = departure;
      if (NOTES[e.name]?.[c.key]) row.note = NOTES[e.name][c.key];
      if (row.effect !== undefined && row.decided && !departure) {
        row.checks.push({ what: `nearer ibl's split sum with ${Object.keys(c.ext).join(', ')} than without`, ok: row.engineVsSs < row.engineVsBase });
      }
      for (const ch of row.checks) ch.ok ? passes++ : failures++;
      results.push(row);
      const f = (v) => (v === undefined ? '     -' : (100 * v).toFixed(1).padStart(5) + '%');
      log(`${e.name.padEnd(13)} ${c.key.padEnd(16)} K ${String(K).padEnd(7)} ibl/ss ${f(row.iblVsSs)} ibl/ref ${f(row.iblVsRef)} own/ref ${f(row.ownVsRef)} ibl/own ${f(row.iblVsOwn)} ss/ref ${f(row.ssVsRef)} clipped ${row.clipped}` +
        (row.effect !== undefined ? ` extension's effect ${f(row.effect)}, engine vs ibl ${f(row.engineVsSs)}, without it ${f(row.engineVsBase)}` : '') +
        row.checks.filter((x) => !x.ok).map((x) => `  FAILED ${x.what}`).join(''));
    }
  }

  if (opt.orient) {
    // Which ibl camera each engine's front view matches best (development aid).
    for (const e of present) {
      if (!e.sets.includes('ibl') && !e.sets.includes('own')) continue;
      const c = cases[2];
      const set = e.sets[0];
      const img = linear(await capture(e, set, c, 1));
      const line = [];
      for (const k of ['pz', 'px', 'nz', 'nx']) {
        const ss = readExr(renderPath('orient-' + k, c, 'split-sum'));
        const m = new Uint8Array(ss.w * ss.h).map((_, i) => (ss.A[i] >= 0.999 && !img.clip[i] ? 1 : 0));
        line.push(`${k} ${(100 * compare(img.rgb, exrScaled(ss, 1), m)).toFixed(1)}%`);
      }
      log(`orient ${e.name} set=${set}: ${line.join('  ')}`);
    }
  }

  if (opt.docs) await writeDocs(results, shots);
} catch (err) {
  if (timedOut) await halt();
  console.error(String(err.stack || err));
  failures++;
} finally {
  doing = 'closing the browser';
  await context.close();
  server.close();
  fs.rmSync(userData, { recursive: true, force: true });
}
if (timedOut) await halt();
for (const u of offHost) {
  console.error(`FAILED a page requested ${u}, not on 127.0.0.1 (aborted)`);
  failures++;
}
if (passes + failures === 0) {
  console.error('FAILED no check ran');
  failures++;
}

// ---------------------------------------------------------------------------------------------
// Table

console.log('');
console.log('| engine | material | vs split sum | vs reference | own pipeline vs reference | ibl vs own | split sum vs reference | K | clipped |');
console.log('| --- | --- | --- | --- | --- | --- | --- | --- | --- |');
const pc = (v) => (v === undefined ? '–' : `${(100 * v).toFixed(1)} %`);
for (const r of results) {
  console.log(`| ${r.engine} | ${r.case.key} | ${pc(r.iblVsSs)} | ${pc(r.iblVsRef)} | ${pc(r.ownVsRef)} | ${pc(r.iblVsOwn)} | ${pc(r.ssVsRef)} | ${r.K} | ${r.clipped} |`);
}
log(`wall time ${((Date.now() - t0) / 1000).toFixed(1)} s`);
console.log(`engines: ${passes} passed, ${failures} failed`);
process.exit(failures ? 1 : 0);

// ---------------------------------------------------------------------------------------------
// --docs: the generated part of docs/targets.md's "In the engines themselves", and a sheet of the
// images (docs/images/engines.png): one row per image kind, one column per case of roughness
// 0, 0.5, 1 (metal, then dielectric).

async function writeDocs(results, shots) {
  const rows = results.filter((r) => !r.case.ext);
  const doc = path.join(repo, 'docs', 'targets.md');
  let text = fs.readFileSync(doc, 'utf8');
  const begin = '<!-- engines:begin -->', end = '<!-- engines:end -->';
  const a = text.indexOf(begin), b = text.indexOf(end);
  if (a < 0 || b < a) throw new Error('docs/targets.md has no <!-- engines:begin --> ... <!-- engines:end --> section');
  const pc = (v) => (v === undefined ? '–' : `${(100 * v).toFixed(1)} %`);
  const lines = [
    begin,
    '',
    `Measured by \`node tests/engines/run.mjs --ibl build/ibl --docs\` (${new Date().toISOString().slice(0, 10)}; ` +
      `${path.basename(HDRI)} as a Radiance .hdr baked at ${BAKE_SIZE}², ${IMAGE}² images, base colour ${BASE.join(', ')}, ` +
      `reference ${REF_SPP} samples per pixel; the mean relative error per pixel and channel, |a − b| / (b + ${EPS}), ` +
      'in canvas units; K the environment scale the page got):',
    '',
    '| engine | material | ibl files vs split sum | ibl files vs reference | own pipeline vs reference | ibl files vs own | split sum vs reference | K | clipped pixels |',
    '| --- | --- | --- | --- | --- | --- | --- | --- | --- |',
  ];
  for (const r of rows) {
    lines.push(`| ${r.engine} | ${r.case.key} | ${pc(r.iblVsSs)} | ${pc(r.iblVsRef)} | ${pc(r.ownVsRef)} | ${pc(r.iblVsOwn)} | ${pc(r.ssVsRef)} | ${r.K} | ${r.clipped} |`);
  }
  const mean = (eng, k) => {
    const v = rows.filter((r) => r.engine === eng && r[k] !== undefined).map((r) => r[k]);
    return v.length ? v.reduce((x, y) => x + y, 0) / v.length : undefined;
  };
  lines.push('', '| engine | mean: ibl files vs split sum | ibl files vs reference | own pipeline vs reference | ibl files vs own |', '| --- | --- | --- | --- | --- |');
  for (const eng of [...new Set(rows.map((r) => r.engine))]) {
    lines.push(`| ${eng} | ${pc(mean(eng, 'iblVsSs'))} | ${pc(mean(eng, 'iblVsRef'))} | ${pc(mean(eng, 'ownVsRef'))} | ${pc(mean(eng, 'iblVsOwn'))} |`);
  }
  lines.push('', end);
  text = text.slice(0, a) + lines.join('\n') + text.slice(b + end.length);
  fs.writeFileSync(doc, text);

  // The extensions' table in docs/materials.md: every extension case, per engine, also where the
  // engine does not render the extension.
  const mdoc = path.join(repo, 'docs', 'materials.md');
  let mtext = fs.readFileSync(mdoc, 'utf8');
  const xbegin = '<!-- engines-extensions:begin -->', xend = '<!-- engines-extensions:end -->';
  const xa = mtext.indexOf(xbegin), xb = mtext.indexOf(xend);
  if (xa < 0 || xb < xa) throw new Error('docs/materials.md has no <!-- engines-extensions:begin --> ... <!-- engines-extensions:end --> section');
  const xlines = [
    xbegin,
    '',
    `Measured by \`node tests/engines/run.mjs --ibl build/ibl --docs\` (${new Date().toISOString().slice(0, 10)}; ` +
      'the setting of docs/targets.md, "In the engines themselves"; the engine with ibl\'s files, three.js with its own pipeline):',
    '',
    '| case | engine | engine vs split sum | engine vs reference | split sum vs reference | engine vs split sum without the extension | the extension\'s effect on the split sum | K | clipped pixels |',
    '| --- | --- | --- | --- | --- | --- | --- | --- | --- |',
  ];
  for (const c of cases.filter((c) => c.ext)) {
    for (const e of present) {
      const r = results.find((row) => row.case === c && row.engine === e.name);
      if (!renders(e, c)) xlines.push(`| ${c.key} | ${e.name} | not rendered: the engine ignores ${Object.keys(c.ext).join(', ')} | | | | | | |`);
      else if (!r) xlines.push(`| ${c.key} | ${e.name} | failed | | | | | | |`);
      else xlines.push(`| ${c.key} | ${e.name} | ${pc(r.engineVsSs)} | ${pc(r.iblVsRef ?? r.ownVsRef)} | ${pc(r.ssVsRef)} | ${pc(r.engineVsBase)}${r.departure ? ` (${r.departure})` : r.decided ? '' : ` (not checked: within ${100 * UNDECIDED} % of the other)`}${r.note ? ` (${r.note})` : ''} | ${pc(r.effect)} | ${r.K} | ${r.clipped} |`);
    }
  }
  xlines.push('', xend);
  mtext = mtext.slice(0, xa) + xlines.join('\n') + mtext.slice(xb + xend.length);
  fs.writeFileSync(mdoc, mtext);

  sheet(results, shots, cases.filter((c) => !c.ext && [0, 0.5, 1].includes(c.r)), path.join(repo, 'docs', 'images', 'engines.png'));
  sheet(results, shots, cases.filter((c) => c.ext && !c.backdrop), path.join(repo, 'docs', 'images', 'engines-extensions.png'));
  sheet(results, shots, cases.filter((c) => c.backdrop), path.join(repo, 'docs', 'images', 'engines-transmission.png'));
}

// A sheet of the images: one row per image kind (ibl's renders from each engine's camera, then each
// engine's sets), one column per case; black where an engine does not render a case.
function sheet(results, shots, cols, outPng) {
  const T = 64;  // tile size: the sheet stays under 300 KB
  const kinds = [];
  const seen = new Set();
  for (const e of present) {
    if (!seen.has(e.rot)) {
      seen.add(e.rot);
      kinds.push({ exr: e.rot, mode: 'split-sum' }, { exr: e.rot, mode: 'reference' });
    }
    if (e.ss) kinds.push({ exr: `${e.rot}-${e.ss.key}`, mode: 'split-sum', engine: e.name });
    for (const set of e.sets) kinds.push({ shot: `${e.name}-${set}` });
  }
  // Rows with no image in any column (an engine's set that renders none of these cases) go.
  const shown = (k, c) => (k.shot ? results.some((r) => r.case === c && r.engine === k.shot.slice(0, k.shot.lastIndexOf('-'))) && fs.existsSync(path.join(shots, `${k.shot}-${c.id}.png`)) : fs.existsSync(renderPath(k.exr, c, k.mode)));
  for (let i = kinds.length - 1; i >= 0; i--) if (!cols.some((c) => shown(kinds[i], c))) kinds.splice(i, 1);
  const Wd = T * cols.length, Hd = T * kinds.length;
  const png = new PNG({ width: Wd, height: Hd });
  png.data.fill(0);
  for (let i = 3; i < png.data.length; i += 4) png.data[i] = 255;
  const put = (col, rowI, rgb8) => {  // rgb8(x, y) over IMAGE x IMAGE, box-resampled to T x T
    for (let y = 0; y < T; y++)
      for (let x = 0; x < T; x++) {
        const acc = [0, 0, 0];
        let n = 0;
        const x0 = Math.floor((x * IMAGE) / T), x1 = Math.floor(((x + 1) * IMAGE) / T);
        const y0 = Math.floor((y * IMAGE) / T), y1 = Math.floor(((y + 1) * IMAGE) / T);
        for (let yy = y0; yy < y1; yy++) for (let xx = x0; xx < x1; xx++) { const v = rgb8(xx, yy); acc[0] += v[0]; acc[1] += v[1]; acc[2] += v[2]; n++; }
        const o = 4 * ((rowI * T + y) * Wd + col * T + x);
        for (let ch = 0; ch < 3; ch++) png.data[o + ch] = Math.round(acc[ch] / n);
      }
  };
  cols.forEach((c, col) => {
    kinds.forEach((k, rowI) => {
      const row = results.find((r) => r.case === c && (k.shot ? k.shot.startsWith(r.engine + '-') : k.engine ? r.engine === k.engine : ROT[ENGINES.find((e) => e.name === r.engine).rot] === ROT[k.exr]));
      const K = row ? row.K : 1;
      if (k.shot) {
        const f = path.join(shots, `${k.shot}-${c.id}.png`);
        if (!row || !fs.existsSync(f)) return;
        const img = PNG.sync.read(fs.readFileSync(f));
        put(col, rowI, (x, y) => { const o = 4 * (y * img.width + x); return [img.data[o], img.data[o + 1], img.data[o + 2]]; });
      } else {
        const file = renderPath(k.exr, c, k.mode);
        if (!fs.existsSync(file)) return;
        const ex = readExr(file);
        put(col, rowI, (x, y) => { const i = y * ex.w + x; return [toSrgb8(ex.R[i] * K), toSrgb8(ex.G[i] * K), toSrgb8(ex.B[i] * K)]; });
      }
    });
  });
  fs.mkdirSync(path.dirname(outPng), { recursive: true });
  fs.writeFileSync(outPng, PNG.sync.write(png, { colorType: 2 }));
  log(`wrote ${path.relative(repo, outPng)} (${Wd}x${Hd}: rows ${kinds.map((k) => k.shot || `${k.exr} ${k.mode}`).join(', ')})`);
}
