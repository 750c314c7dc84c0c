// Loads a glb that `luxel bake --lightmaps` wrote with three.js's GLTFLoader, applies the lightMap
// recipe of docs/baking.md (its source text, passed in by check.mjs, run as written), renders from
// the glTF camera into a float render target (linear radiance: three.js applies neither tone
// mapping nor the sRGB output transfer when rendering to a render target) and returns the pixels.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

function base64(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

// The recipe decodes asynchronously, in promise callbacks: an exception there is reported here.
let asyncError = null;
window.addEventListener('unhandledrejection', (e) => { asyncError ??= e.reason; });
window.addEventListener('error', (e) => { asyncError ??= e.error ?? e.message; });

// variant: 'recipe' (the documented recipe, as written); a deliberately wrong convention applied on
// top of it, which the comparison must reject: 'no-lightmap' (lightMap removed), 'uv0' (the
// lightmap read through TEXCOORD_0 instead of TEXCOORD_1), 'flip-v' (TEXCOORD_1's v flipped, as
// with an image loaded flipped); or, for information, 'standard': the recipe's decoded lightmap on
// the MeshStandardMaterial GLTFLoader made.
// suns: for a transfer bake, turn its suns before rendering (the recipe's gltf.userData.luxelRelight).
// kind: 'lightmap' (meshes whose material has extras.luxel: the recipe must give each a lightMap),
// or 'vertex' (meshes with COLOR_0: the recipe replaces their materials as it runs).
window.luxelThree = async ({ glb, recipe, variant = 'recipe', size = 256, suns = null, kind = 'lightmap' }) => {
  const renderer = new THREE.WebGLRenderer({ antialias: false });
  try {
    asyncError = null;
    renderer.setSize(size, size, false);
    renderer.toneMapping = THREE.NoToneMapping;
    const gl = renderer.getContext();
    const dbg = gl.getExtension('WEBGL_debug_renderer_info');
    const glRenderer = dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);

    const gltf = await new GLTFLoader().loadAsync(glb);
    const lightmapped = [];
    const baked = kind === 'vertex' ? (o) => o.geometry.attributes.color : (o) => o.material.userData.luxel;
    gltf.scene.traverse((o) => o.isMesh && baked(o) && lightmapped.push(o));
    if (lightmapped.length === 0)
      throw new Error(kind === 'vertex' ? `${glb}: no mesh has COLOR_0 (was it baked with --vertex-colors?)`
                                        : `${glb}: no material has extras.luxel (was it baked with --lightmaps?)`);
    const loaded = new Map(lightmapped.map((o) => [o, o.material]));

    // The recipe, as docs/baking.md writes it, with the names it assumes: THREE, gltf (what
    // GLTFLoader returned) and renderer (the WebGLRenderer that will draw the scene).
    new Function('THREE', 'gltf', 'renderer', recipe)(THREE, gltf, renderer);
    // It finishes in promise callbacks: wait until every mesh with a lightmap has one.
    for (let t = 0; kind === 'lightmap' && lightmapped.some((o) => !o.material.lightMap); t += 20) {
      if (asyncError) throw new Error(`the recipe failed: ${asyncError?.stack ?? asyncError}`);
      if (t > 20000) throw new Error('the recipe set no material.lightMap within 20 s');
      await sleep(20);
    }

    if (suns) {
      if (!gltf.userData.luxelRelight) throw new Error('the recipe set no gltf.userData.luxelRelight to turn the suns with');
      gltf.userData.luxelRelight(suns);
    }
    if (variant === 'no-lightmap') {
      for (const o of lightmapped) { o.material.lightMap = null; o.material.needsUpdate = true; }
    } else if (variant === 'uv0') {
      for (const o of lightmapped) { o.material.lightMap.channel = 0; o.material.needsUpdate = true; }
    } else if (variant === 'flip-v') {
      const done = new Set();
      for (const o of lightmapped) {
        const uv1 = o.geometry.attributes.uv1;
        if (!uv1 || done.has(uv1)) continue;
        done.add(uv1);
        for (let i = 0; i < uv1.count; ++i) uv1.setY(i, 1 - uv1.getY(i));
        uv1.needsUpdate = true;
      }
    } else if (variant === 'standard') {
      for (const o of lightmapped) {
        const m = loaded.get(o);
        m.lightMap = o.material.lightMap;
        m.lightMapIntensity = 1;
        m.needsUpdate = true;
        o.material = m;
      }
    } else if (variant !== 'recipe') {
      throw new Error(`unknown variant ${variant}`);
    }

    if (gltf.cameras.length === 0) throw new Error(`${glb}: no camera`);
    const camera = gltf.cameras[0];
    camera.aspect = 1;  // glTF's camera has no aspectRatio; the image is square
    camera.updateProjectionMatrix();

    if (!renderer.extensions.has('EXT_color_buffer_float')) throw new Error('no EXT_color_buffer_float: cannot render to a float target');
    const target = new THREE.WebGLRenderTarget(size, size, {
      type: THREE.FloatType, format: THREE.RGBAFormat, minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter,
      generateMipmaps: false, depthBuffer: true,
    });
    renderer.setRenderTarget(target);
    renderer.setClearColor(0x000000, 1);
    renderer.clear();
    renderer.render(gltf.scene, camera);
    const pixels = new Float32Array(size * size * 4);
    renderer.readRenderTargetPixels(target, 0, 0, size, size, pixels);  // rows bottom-up
    renderer.setRenderTarget(null);
    target.dispose();
    if (asyncError) throw new Error(`the recipe failed: ${asyncError?.stack ?? asyncError}`);

    const o = lightmapped[0], t = o.material.lightMap;
    const types = { [THREE.FloatType]: 'FloatType', [THREE.HalfFloatType]: 'HalfFloatType', [THREE.UnsignedByteType]: 'UnsignedByteType' };
    return {
      width: size, height: size, pixels: base64(new Uint8Array(pixels.buffer)),
      three: THREE.REVISION, glRenderer, material: o.material.type,
      lightMap: t && { mesh: o.name, type: types[t.type] ?? t.type, channel: t.channel, flipY: t.flipY,
                       colorSpace: t.colorSpace || 'none', intensity: o.material.lightMapIntensity },
    };
  } finally {
    renderer.dispose();
    renderer.forceContextLoss();
  }
};
window.luxelThreeReady = true;
