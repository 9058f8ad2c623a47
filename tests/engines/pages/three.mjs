// three.js as a peer (set=own): the .hdr panorama through three's own pipeline only:
// HDRLoader -> PMREMGenerator.fromEquirectangular -> the material's envMap; the sphere is the
// glTF of common.mjs read by three's GLTFLoader, which makes a MeshStandardMaterial of the core
// material and a MeshPhysicalMaterial where KHR_materials_* extensions are used (ior, specular,
// clearcoat, iridescence, anisotropy: GLTFLoader's GLTFMaterials*Extension classes).
//
// Conventions (three r187, node_modules/three):
//   - src/renderers/shaders/ShaderChunk/common.glsl.js, equirectUv(dir):
//       u = atan(dir.z, dir.x) / (2 pi) + 0.5,  v = asin(dir.y) / pi + 0.5
//     with the HDRLoader's texture flipY = true (examples/jsm/loaders/HDRLoader.js), so texture
//     v = 1 is the file's first row. In file rows (row 0 at the top) that is
//     u = 0.5 + atan2(z, x)/(2 pi), row v' = 1 - v = acos(y)/pi: ibl's equirect convention
//     (docs/conventions.md) exactly. PMREMGenerator renders the panorama into a cube render
//     target through equirectUv (src/extras/PMREMGenerator.js, _getEquirectMaterial) and the
//     material samples it with the world-space reflection (envmap_physical_pars_fragment:
//     textureLod(envMap, envMapRotation * reflectVec, ...)); for a render-target cube no x flip
//     is applied (WebGLMaterials.js applies flipEnvMap only to non-render-target cube textures).
//     World: right-handed, +Y up, the camera looks down its -Z: the same as ibl's. So no
//     rotation is applied here (envMapRotation stays identity).
//
// Contract (tests/engines/run.mjs): ?set=own&hdr=URL&roughness=R&metallic=M&base=R,G,B&size=N
// &scale=K&view=front|side[&ext=JSON][&backdrop=1]; draws into <canvas id="c">, then window.iblDone = {ok, notes|error}.

import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { HDRLoader } from 'three/addons/loaders/HDRLoader.js';
import { params, sphereGlb } from './common.mjs';

function fail(message) {
  throw new Error(message);
}

const nextFrame = () => new Promise((resolve) => requestAnimationFrame(() => resolve()));

async function main() {
  const p = params({ set: 'own', sets: ['own'] });
  const canvas = document.getElementById('c');

  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, alpha: false, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(p.size, p.size, true);
  renderer.toneMapping = THREE.NoToneMapping;
  renderer.toneMappingExposure = 1;
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.setClearColor(0x000000, 1);

  const hdr = await new HDRLoader().loadAsync(p.hdr);
  hdr.mapping = THREE.EquirectangularReflectionMapping;
  const pmrem = new THREE.PMREMGenerator(renderer);
  const envTarget = pmrem.fromEquirectangular(hdr);
  const envMap = envTarget.texture;

  const scene = new THREE.Scene();
  scene.background = null;
  // With backdrop=1 the GLB holds the backdrop too: three draws it first into its transmission
  // render target (WebGLRenderer, renderTransmissionPass), which a transmissive material reads.
  const glb = sphereGlb(p, 512);
  const gltf = await new GLTFLoader().parseAsync(glb.buffer, '');
  let mesh = null;
  gltf.scene.traverse((o) => {
    if (!o.isMesh) return;
    if (o.material.name === 'sphere') mesh = o;
    o.material.envMap = envMap;
    o.material.envMapIntensity = p.scale;
    o.material.needsUpdate = true;
  });
  if (!mesh) fail('GLTFLoader gave no sphere');
  const material = mesh.material;
  scene.add(gltf.scene);

  const camera = new THREE.OrthographicCamera(-1.1, 1.1, 1.1, -1.1, 0.1, 100);
  if (p.view === 'side') camera.position.set(10, 0, 0);
  else camera.position.set(0, 0, 10);
  camera.up.set(0, 1, 0);
  camera.lookAt(0, 0, 0);
  camera.updateMatrixWorld();

  renderer.render(scene, camera);
  const err = renderer.getContext().getError();
  if (err !== 0) fail(`WebGL error 0x${err.toString(16)}`);
  await nextFrame();
  renderer.render(scene, camera);
  await nextFrame();
  await nextFrame();

  const levels = envMap.mipmaps ? envMap.mipmaps.length : 0;
  return [
    `three ${THREE.REVISION}: HDRLoader (${hdr.image.width}x${hdr.image.height}, ${hdr.type === THREE.FloatType ? 'float' : 'half'}) -> PMREMGenerator.fromEquirectangular`,
    `PMREM cube ${envTarget.width}^2, ${levels} levels (roughness(lod) = 1 - sqrt(1 - lod/maxLod))`,
    `GLTFLoader: ${material.type}${p.ext ? ' (' + Object.keys(p.ext).join(', ') + ')' : ''}, envMapIntensity ${p.scale}, envMapRotation identity (three equirect u,v = ibl's)`,
    'NoToneMapping, SRGBColorSpace output',
  ].join('; ');
}

main().then(
  (notes) => { window.iblDone = { ok: true, notes }; },
  (e) => { window.iblDone = { ok: false, error: String(e && e.stack ? e.stack : e) }; },
);
