// The viewer in the page that `luxel bake ... --html` writes: apps/luxel/html_page.cpp puts it in
// html_viewer/page.html, with the glb (base64, in the element #luxel-glb) and three.js's modules
// (data: URLs in the import map), so that the page opens from disk with no network. It shows the
// bake with the display recipes of docs/baking.md, copied below exactly as that file writes them
// (tests/web/html_viewer.mjs checks that they still agree), ACES tone mapping with an exposure
// control, and orbit and walk navigation. window.luxelViewer reports its state to that test.
// The page holds it inline, in a script element: this file must not contain that element's end tag,
// nor an HTML comment's opening (html_page.cpp refuses to write such a page).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const about = JSON.parse($('luxel-bake').textContent);
const viewer = (window.luxelViewer = { ready: false, error: null, frames: 0, three: THREE.REVISION, about });

// ---- docs/baking.md's display recipes, as it writes them ------------------------------------------
// (Unindented, so that each body is the documentation's text character for character.)

// "Displaying them (three.js)": --vertex-colors, COLOR_0 holds radiance / S; shown unlit.
function showRadiance(gltf) {
const S = gltf.scene.userData.luxel?.vertexColorScale ?? 1;
gltf.scene.traverse((o) => {
  if (!o.isMesh || !o.geometry.attributes.color) return;
  o.material = new THREE.MeshBasicMaterial({
    vertexColors: true,
    color: new THREE.Color(S, S, S),   // linear, may exceed 1
    side: o.material.side,             // keeps doubleSided
  });
});
}

// "Directions per vertex": the reading and the shader edits the two vertex recipes share.
// Directions per vertex (LUXEL_vertex_directional, docs/baking.md): how the irradiance changes from
// the vertex normal n0 to the shading normal n, for the vertex recipes below.
const LUXEL_VERTEX_GLSL = `
float luxelL1(vec3 q, vec3 n) {  // one light along q plus a constant (Sloan 2008), in units of m0
  float len = length(q), r = min(len, 1.0);
  return 0.25 * (1.0 - r) + max(dot(n, q), 0.0) * (len > 0.0 ? r / len : 0.0);
}
vec3 luxelVertexDirectional(vec3 n, vec3 n0) {
  vec3 f, f0;
#if LUXEL_MODE == 1  // sh-l1: the x, y, z of m1 / m0 per channel
  vec3 qx = 2.0 * vLuxelDir0 - 1.0, qy = 2.0 * vLuxelDir1 - 1.0, qz = 2.0 * vLuxelDir2 - 1.0;
  for (int c = 0; c < 3; ++c) {
    vec3 q = vec3(qx[c], qy[c], qz[c]);
    f[c] = luxelL1(q, n);
    f0[c] = luxelL1(q, n0);
  }
#elif LUXEL_MODE == 2  // dominant: the luminance's m1 / m0
  vec3 q = 2.0 * vLuxelDir0 - 1.0;
  f = vec3(luxelL1(q, n));
  f0 = vec3(luxelL1(q, n0));
#else  // sh-l2: c_i / c_0 = (2v - 1) * bound, read linearly (Ramamoorthi and Hanrahan 2001)
  vec3 q[9];
  q[0] = vec3(1.0);
  q[1] = (2.0 * vLuxelDir0 - 1.0) * 1.7320508;
  q[2] = (2.0 * vLuxelDir1 - 1.0) * 1.7320508;
  q[3] = (2.0 * vLuxelDir2 - 1.0) * 1.7320508;
  q[4] = (2.0 * vLuxelDir3 - 1.0) * 2.2360680;
  q[5] = (2.0 * vLuxelDir4 - 1.0) * 2.2360680;
  q[6] = (2.0 * vLuxelDir5 - 1.0) * 2.2360680;
  q[7] = (2.0 * vLuxelDir6 - 1.0) * 2.2360680;
  q[8] = (2.0 * vLuxelDir7 - 1.0) * 2.2360680;
  for (int k = 0; k < 2; ++k) {
    vec3 d = k == 0 ? n : n0;
    vec3 e = 3.1415927 * 0.282095 * q[0]
           + 2.0943951 * 0.488603 * (q[1] * d.y + q[2] * d.z + q[3] * d.x)
           + 0.7853982 * (1.092548 * (q[4] * d.x * d.y + q[5] * d.y * d.z + q[7] * d.x * d.z)
                          + 0.315392 * q[6] * (3.0 * d.z * d.z - 1.0) + 0.546274 * q[8] * (d.x * d.x - d.y * d.y));
    if (k == 0) f = e; else f0 = e;
  }
#endif
  return vec3(f0.r > 0.0 ? max(f.r, 0.0) / f0.r : 1.0, f0.g > 0.0 ? max(f.g, 0.0) / f0.g : 1.0,
              f0.b > 0.0 ? max(f.b, 0.0) / f0.b : 1.0);
}`;
// A MeshLambertMaterial's shaders with the primitive's directions (`dir`, its extension) passed to
// the fragment shader, the reading above there, and its output replaced by `output`, GLSL that
// sets outgoingLight from luxelVertexDirectional(luxelN, luxelN0): the normal map's normal and
// the vertex's, in world space.
function luxelVertexShader(shader, dir, output) {
  const modes = { 'sh-l1': 1, 'dominant': 2, 'sh-l2': 3 };
  const varyings = dir.attributes.map((a, i) => `varying vec3 vLuxelDir${i};`).join('\n');
  shader.vertexShader = shader.vertexShader
    .replace('#include <common>', '#include <common>\n' + varyings + '\n' +
      dir.attributes.map((a) => `attribute vec3 ${a.toLowerCase()};`).join('\n'))
    .replace('#include <color_vertex>', '#include <color_vertex>\n' +
      dir.attributes.map((a, i) => `vLuxelDir${i} = ${a.toLowerCase()};`).join('\n'));
  shader.fragmentShader = shader.fragmentShader
    .replace('#include <common>', `#include <common>\n#define LUXEL_MODE ${modes[dir.mode]}\n` + varyings)
    .replace('void main() {', LUXEL_VERTEX_GLSL + '\nvoid main() {')
    .replace('#include <opaque_fragment>',
      'vec3 luxelN = normalize(inverseTransformDirection(normal, viewMatrix));\n' +
      'vec3 luxelN0 = normalize(inverseTransformDirection(nonPerturbedNormal, viewMatrix));\n' +
      output + '\n#include <opaque_fragment>');
}

// "Directions per vertex": --vertex-colors --directional, COLOR_0 holds radiance / S, shaded at the
// normal map's normal on MeshLambertMaterials.
function showDirectionalRadiance(gltf) {
// Directions per vertex: each primitive's LUXEL_vertex_directional (docs/baking.md). COLOR_0 × S is
// radiance; its reflected part follows the normal map as the light arrives.
const S = gltf.scene.userData.luxel?.vertexColorScale ?? 1;
gltf.scene.traverse((o) => {
  const dir = o.isMesh && o.geometry.attributes.color && o.userData.gltfExtensions?.LUXEL_vertex_directional;
  if (!dir) return;
  const m = o.material;
  const l = new THREE.MeshLambertMaterial({
    name: m.name, vertexColors: true, side: m.side, color: new THREE.Color(S, S, S),  // diffuseColor = COLOR_0 x S
    emissive: m.emissive, emissiveMap: m.emissiveMap, emissiveIntensity: m.emissiveIntensity,
    normalMap: m.normalMap, normalScale: m.normalScale,  // GLTFLoader's, y already as three.js wants it
  });
  l.onBeforeCompile = (shader) => luxelVertexShader(shader, dir,
    'outgoingLight = totalEmissiveRadiance + (diffuseColor.rgb - totalEmissiveRadiance) * luxelVertexDirectional(luxelN, luxelN0);');
  l.customProgramCacheKey = () => `luxel-vertex-directional-${dir.mode}`;
  o.material = l;
});
}

// "Vertex colours for some meshes, lightmaps for the rest" with --directional: COLOR_0 holds
// irradiance / S, shaded at the normal map's normal on MeshLambertMaterials.
function showDirectionalIrradiance(gltf) {
// --vertex-colors-for with --directional: COLOR_0 x S is irradiance H, which follows the normal map
// as the light arrives (luxelVertexShader: "Directions per vertex").
const S = gltf.scene.userData.luxel?.vertexColorScale ?? 1;   // vertexColors: 'irradiance'
gltf.scene.traverse((o) => {
  const dir = o.isMesh && o.geometry.attributes.color && o.userData.gltfExtensions?.LUXEL_vertex_directional;
  if (!dir) return;
  const m = o.material;
  const l = new THREE.MeshLambertMaterial({
    name: m.name, map: m.map, vertexColors: true, side: m.side, transparent: m.transparent, alphaTest: m.alphaTest,
    color: m.color.clone().multiplyScalar(S / Math.PI),   // base colour x H / pi
    emissive: m.emissive, emissiveMap: m.emissiveMap, emissiveIntensity: m.emissiveIntensity,
    normalMap: m.normalMap, normalScale: m.normalScale,
  });
  l.onBeforeCompile = (shader) => luxelVertexShader(shader, dir,
    'outgoingLight = totalEmissiveRadiance + diffuseColor.rgb * luxelVertexDirectional(luxelN, luxelN0);');
  l.customProgramCacheKey = () => `luxel-vertex-irradiance-directional-${dir.mode}`;
  o.material = l;
});
}

// "Vertex colours for some meshes, lightmaps for the rest": --vertex-colors-for, COLOR_0 holds
// irradiance / S; times the base colour / pi.
function showIrradiance(gltf) {
const S = gltf.scene.userData.luxel?.vertexColorScale ?? 1;   // vertexColors: 'irradiance'
gltf.scene.traverse((o) => {
  if (!o.isMesh || !o.geometry.attributes.color) return;
  const m = o.material;
  o.material = new THREE.MeshBasicMaterial({
    map: m.map, vertexColors: true, side: m.side, transparent: m.transparent, alphaTest: m.alphaTest,
    color: m.color.clone().multiplyScalar(S / Math.PI),   // base colour x H / pi
  });
});
}

// "Lightmaps": RGBM pages decoded on the GPU into half-float lightmaps on MeshLambertMaterials.
// It finishes in promise callbacks (waitForLightmaps below).
function showLightmaps(gltf, renderer) {
// RGBM page -> linear irradiance H = rgb × a × rgbmRange, one texel per pixel, into a half-float
// texture: bilinear, no mipmaps, flipY false, like the glTF texture it comes from.
function decodeRGBM(tex, range) {
  const target = new THREE.WebGLRenderTarget(tex.image.width, tex.image.height,
                                             { type: THREE.HalfFloatType, depthBuffer: false });
  const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), new THREE.ShaderMaterial({
    uniforms: { rgbm: { value: tex }, range: { value: range } },
    vertexShader: 'varying vec2 vUv; void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }',
    fragmentShader: 'uniform sampler2D rgbm; uniform float range; varying vec2 vUv;\n' +
      'void main() { vec4 c = texture2D(rgbm, vUv); gl_FragColor = vec4(c.rgb * c.a * range, 1.0); }',
  }));
  quad.frustumCulled = false;
  const previous = renderer.getRenderTarget();
  renderer.setRenderTarget(target);
  renderer.render(quad, new THREE.Camera());
  renderer.setRenderTarget(previous);
  quad.geometry.dispose();
  quad.material.dispose();
  target.texture.channel = 1;  // TEXCOORD_1
  return target.texture;
}
const pages = new Map(), lambert = new Map();
gltf.scene.traverse((o) => {
  const lm = o.isMesh && o.material.userData.luxel;
  if (!lm) return;
  if (!pages.has(lm.lightMap))
    pages.set(lm.lightMap, gltf.parser.getDependency('texture', lm.lightMap).then((t) => decodeRGBM(t, lm.rgbmRange)));
  pages.get(lm.lightMap).then((lightMap) => {
    const m = o.material;
    if (!lambert.has(m))
      lambert.set(m, new THREE.MeshLambertMaterial({
        name: m.name, color: m.color, map: m.map, side: m.side,
        emissive: m.emissive, emissiveMap: m.emissiveMap, emissiveIntensity: m.emissiveIntensity,
        lightMap, lightMapIntensity: 1,
      }));
    o.material = lambert.get(m);
  });
});
}

// "Directional lightmaps": the same, with the normal map kept and the LUXEL_lightmap_directional
// textures read at the normal map's normal. It finishes in promise callbacks too.
function showDirectionalLightmaps(gltf, renderer) {
// Directional lightmaps: material.userData.gltfExtensions.LUXEL_lightmap_directional (docs/baking.md).
const LUXEL_DIRECTIONAL_GLSL = `
float luxelL1(vec3 q, vec3 n) {  // one light along q plus a constant (Sloan 2008), in units of m0
  float len = length(q), r = min(len, 1.0);
  return 0.25 * (1.0 - r) + max(dot(n, q), 0.0) * (len > 0.0 ? r / len : 0.0);
}
vec3 luxelDirectional(vec3 n, vec3 n0) {
  vec3 f, f0;
#if LUXEL_MODE == 1  // sh-l1: the x, y, z of m1 / m0 per channel
  vec3 qx = 2.0 * texture2D(luxelDir0, vLightMapUv).rgb - 1.0;
  vec3 qy = 2.0 * texture2D(luxelDir1, vLightMapUv).rgb - 1.0;
  vec3 qz = 2.0 * texture2D(luxelDir2, vLightMapUv).rgb - 1.0;
  for (int c = 0; c < 3; ++c) {
    vec3 q = vec3(qx[c], qy[c], qz[c]);
    f[c] = luxelL1(q, n);
    f0[c] = luxelL1(q, n0);
  }
#elif LUXEL_MODE == 2  // dominant: the luminance's m1 / m0
  vec3 q = 2.0 * texture2D(luxelDir0, vLightMapUv).rgb - 1.0;
  f = vec3(luxelL1(q, n));
  f0 = vec3(luxelL1(q, n0));
#else  // sh-l2: c_i / c_0 = (2v - 1) * bound, read linearly (Ramamoorthi and Hanrahan 2001)
  vec3 q[9];
  q[0] = vec3(1.0);
  q[1] = (2.0 * texture2D(luxelDir0, vLightMapUv).rgb - 1.0) * 1.7320508;
  q[2] = (2.0 * texture2D(luxelDir1, vLightMapUv).rgb - 1.0) * 1.7320508;
  q[3] = (2.0 * texture2D(luxelDir2, vLightMapUv).rgb - 1.0) * 1.7320508;
  q[4] = (2.0 * texture2D(luxelDir3, vLightMapUv).rgb - 1.0) * 2.2360680;
  q[5] = (2.0 * texture2D(luxelDir4, vLightMapUv).rgb - 1.0) * 2.2360680;
  q[6] = (2.0 * texture2D(luxelDir5, vLightMapUv).rgb - 1.0) * 2.2360680;
  q[7] = (2.0 * texture2D(luxelDir6, vLightMapUv).rgb - 1.0) * 2.2360680;
  q[8] = (2.0 * texture2D(luxelDir7, vLightMapUv).rgb - 1.0) * 2.2360680;
  for (int k = 0; k < 2; ++k) {
    vec3 d = k == 0 ? n : n0;
    vec3 e = 3.1415927 * 0.282095 * q[0]
           + 2.0943951 * 0.488603 * (q[1] * d.y + q[2] * d.z + q[3] * d.x)
           + 0.7853982 * (1.092548 * (q[4] * d.x * d.y + q[5] * d.y * d.z + q[7] * d.x * d.z)
                          + 0.315392 * q[6] * (3.0 * d.z * d.z - 1.0) + 0.546274 * q[8] * (d.x * d.x - d.y * d.y));
    if (k == 0) f = e; else f0 = e;
  }
#endif
  // The lightmap is the irradiance at the geometric normal: scale it by how f changes from there.
  return vec3(f0.r > 0.0 ? max(f.r, 0.0) / f0.r : 1.0, f0.g > 0.0 ? max(f.g, 0.0) / f0.g : 1.0,
              f0.b > 0.0 ? max(f.b, 0.0) / f0.b : 1.0);
}`;
function decodeRGBM(tex, range) {  // as in the plain recipe
  const target = new THREE.WebGLRenderTarget(tex.image.width, tex.image.height,
                                             { type: THREE.HalfFloatType, depthBuffer: false });
  const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), new THREE.ShaderMaterial({
    uniforms: { rgbm: { value: tex }, range: { value: range } },
    vertexShader: 'varying vec2 vUv; void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }',
    fragmentShader: 'uniform sampler2D rgbm; uniform float range; varying vec2 vUv;\n' +
      'void main() { vec4 c = texture2D(rgbm, vUv); gl_FragColor = vec4(c.rgb * c.a * range, 1.0); }',
  }));
  quad.frustumCulled = false;
  const previous = renderer.getRenderTarget();
  renderer.setRenderTarget(target);
  renderer.render(quad, new THREE.Camera());
  renderer.setRenderTarget(previous);
  quad.geometry.dispose();
  quad.material.dispose();
  target.texture.channel = 1;  // TEXCOORD_1
  return target.texture;
}
const modes = { 'sh-l1': 1, 'dominant': 2, 'sh-l2': 3 };
const pages = new Map(), lambert = new Map();
gltf.scene.traverse((o) => {
  const lm = o.isMesh && o.material.userData.luxel;
  if (!lm) return;
  const dir = o.material.userData.gltfExtensions?.LUXEL_lightmap_directional;
  if (!pages.has(lm.lightMap))
    pages.set(lm.lightMap, gltf.parser.getDependency('texture', lm.lightMap).then((t) => decodeRGBM(t, lm.rgbmRange)));
  const textures = (dir?.textures ?? []).map((t) => gltf.parser.getDependency('texture', t.index));
  Promise.all([pages.get(lm.lightMap), ...textures]).then(([lightMap, ...directions]) => {
    const m = o.material;
    if (!lambert.has(m)) {
      const l = new THREE.MeshLambertMaterial({
        name: m.name, color: m.color, map: m.map, side: m.side,
        emissive: m.emissive, emissiveMap: m.emissiveMap, emissiveIntensity: m.emissiveIntensity,
        normalMap: m.normalMap, normalScale: m.normalScale,  // GLTFLoader's, y already as three.js wants it
        lightMap, lightMapIntensity: 1,
      });
      if (dir) {
        l.onBeforeCompile = (shader) => {
          directions.forEach((t, i) => { shader.uniforms[`luxelDir${i}`] = { value: t }; });
          shader.fragmentShader = shader.fragmentShader
            .replace('#include <common>', `#include <common>\n#define LUXEL_MODE ${modes[dir.mode]}\n` +
              directions.map((t, i) => `uniform sampler2D luxelDir${i};`).join('\n'))
            .replace('#include <lights_fragment_maps>', 'vec3 luxelN = normalize(inverseTransformDirection(normal, viewMatrix));\n' +
              'vec3 luxelN0 = normalize(inverseTransformDirection(nonPerturbedNormal, viewMatrix));\n' +
              THREE.ShaderChunk.lights_fragment_maps.replace('irradiance += lightMapIrradiance;',
                'irradiance += lightMapIrradiance * luxelDirectional(luxelN, luxelN0);'))
            .replace('void main() {', LUXEL_DIRECTIONAL_GLSL + '\nvoid main() {');
        };
        l.customProgramCacheKey = () => `luxel-directional-${dir.mode}`;
      }
      lambert.set(m, l);
    }
    o.material = lambert.get(m);
  });
});
}

// "Transfer lightmaps in the glb": the transfer relit in the shader from the sky's SH and the suns.
function showTransferLightmaps(gltf, renderer) {
// Transfer lightmaps: material.userData.gltfExtensions.LUXEL_lightmap_transfer (docs/baking.md).
const shBasis = (x, y, z) => [0.282095, 0.488603 * y, 0.488603 * z, 0.488603 * x,
  1.092548 * x * y, 1.092548 * y * z, 0.315392 * (3 * z * z - 1), 1.092548 * x * z, 0.546274 * (x * x - y * y),
  0.590044 * y * (3 * x * x - y * y), 2.890611 * x * y * z, 0.457046 * y * (5 * z * z - 1),
  0.373176 * z * (5 * z * z - 3), 0.457046 * x * (5 * z * z - 1), 1.445306 * z * (x * x - y * y),
  0.590044 * x * (x * x - 3 * y * y)];
// The light's SH: the sky's, plus each sun's irradiance along where it comes from.
function transferLight(ext, suns) {
  const light = ext.sky.map((c) => new THREE.Vector3(...c));
  for (const sun of suns) {
    const d = new THREE.Vector3(...sun.direction).normalize().negate(), y = shBasis(d.x, d.y, d.z);
    light.forEach((l, i) => l.add(new THREE.Vector3(...sun.irradiance).multiplyScalar(y[i])));
  }
  return light;
}
function decodeRGBM(tex, range) {  // as in the plain recipe
  const target = new THREE.WebGLRenderTarget(tex.image.width, tex.image.height,
                                             { type: THREE.HalfFloatType, depthBuffer: false });
  const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), new THREE.ShaderMaterial({
    uniforms: { rgbm: { value: tex }, range: { value: range } },
    vertexShader: 'varying vec2 vUv; void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }',
    fragmentShader: 'uniform sampler2D rgbm; uniform float range; varying vec2 vUv;\n' +
      'void main() { vec4 c = texture2D(rgbm, vUv); gl_FragColor = vec4(c.rgb * c.a * range, 1.0); }',
  }));
  quad.frustumCulled = false;
  const previous = renderer.getRenderTarget();
  renderer.setRenderTarget(target);
  renderer.render(quad, new THREE.Camera());
  renderer.setRenderTarget(previous);
  quad.geometry.dispose();
  quad.material.dispose();
  target.texture.channel = 1;  // TEXCOORD_1
  return target.texture;
}
const lights = [];  // every material's light uniform, for luxelRelight
gltf.userData.luxelRelight = (suns) => lights.forEach(({ ext, uniform }) => { uniform.value = transferLight(ext, suns); });
const lambert = new Map();
gltf.scene.traverse((o) => {
  const ext = o.isMesh && o.material.userData.gltfExtensions?.LUXEL_lightmap_transfer;
  if (!ext) return;
  const band0 = gltf.parser.getDependency('texture', ext.band0.index).then((t) => decodeRGBM(t, ext.band0.rgbmRange));
  const ratios = ext.ratios.map((r) => gltf.parser.getDependency('texture', r.index));
  Promise.all([band0, ...ratios]).then(([lightMap, ...ratio]) => {
    const m = o.material;
    if (!lambert.has(m)) {
      const n = ext.bands * ext.bands, uniform = { value: transferLight(ext, ext.suns) };
      lights.push({ ext, uniform });
      const l = new THREE.MeshLambertMaterial({ name: m.name, color: m.color, map: m.map, side: m.side,
        emissive: m.emissive, emissiveMap: m.emissiveMap, emissiveIntensity: m.emissiveIntensity,
        lightMap, lightMapIntensity: 1 });
      l.onBeforeCompile = (shader) => {
        shader.uniforms.luxelLight = uniform;
        shader.uniforms.luxelScale = { value: ext.ratioScale };
        ratio.forEach((t, i) => { shader.uniforms[`luxelRatio${i}`] = { value: t }; });
        const unpack = ratio.map((t, k) => `  { vec4 r = texture2D(luxelRatio${k}, vLightMapUv);` +
          [0, 1, 2, 3].map((c) => (4 * k + c < 3 * (n - 1) ? ` q[${4 * k + c}] = r[${c}];` : '')).join('') + ' }').join('\n');
        shader.fragmentShader = shader.fragmentShader
          .replace('#include <common>', `#include <common>\nuniform vec3 luxelLight[${n}];\n` +
            `uniform float luxelScale[${n - 1}];\n` +
            ratio.map((t, i) => `uniform sampler2D luxelRatio${i};`).join('\n'))
          .replace('void main() {', `vec3 luxelTransfer(vec3 t0) {\n  float q[${3 * (n - 1)}];\n${unpack}\n` +
            `  vec3 sum = luxelLight[0];\n  for (int i = 1; i < ${n}; ++i) {\n` +
            '    sum += (2.0 * vec3(q[3 * i - 3], q[3 * i - 2], q[3 * i - 1]) - 1.0) * luxelScale[i - 1] * luxelLight[i];\n' +
            '  }\n  return max(t0 * sum, vec3(0.0));\n}\nvoid main() {')
          .replace('#include <lights_fragment_maps>', THREE.ShaderChunk.lights_fragment_maps.replace(
            'irradiance += lightMapIrradiance;', 'irradiance += luxelTransfer(lightMapIrradiance);'));
      };
      l.customProgramCacheKey = () => `luxel-transfer-${ext.bands}`;
      lambert.set(m, l);
    }
    o.material = lambert.get(m);
  });
});
}

// ---- the viewer ----------------------------------------------------------------------------------
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
const status = $('luxel-status');

// The first error, shown on the page and logged; the viewer stops drawing. Errors in promise
// callbacks (the lightmap recipe's) and in event handlers end up here too.
let stop = () => {};
function fail(e) {
  if (viewer.error) return;
  viewer.error = String(e?.stack ?? e);
  status.className = 'error';
  status.textContent = `The bake could not be shown: ${e?.message ?? e}`;
  console.error(e);
  stop();
}
window.addEventListener('unhandledrejection', (e) => fail(e.reason));
window.addEventListener('error', (e) => fail(e.error ?? e.message));

function glbBytes() {
  const text = atob($('luxel-glb').textContent.trim());
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
  return bytes.buffer;
}

async function waitForLightmaps(meshes) {
  for (let t = 0; meshes.some((o) => !o.material.lightMap); t += 10) {
    if (viewer.error) throw new Error(viewer.error);
    if (t > 60000) throw new Error('the lightmaps were not decoded within 60 s');
    await sleep(10);
  }
}

// The log-average luminance of what the camera sees, mapped to middle grey (0.18), as luxel's own
// images do (src/io/tonemap.cpp: Reinhard et al. 2002, with delta 1e-4 of the mean luminance);
// pixels that show nothing are left out. Rendered small into a float target: linear radiance.
function autoExposure(renderer, scene, camera) {
  const float = renderer.extensions.has('EXT_color_buffer_float');
  const w = 128, h = Math.max(1, Math.round(128 / camera.aspect));
  const target = new THREE.WebGLRenderTarget(w, h, { type: float ? THREE.FloatType : THREE.HalfFloatType });
  const clear = renderer.getClearAlpha();
  try {
    renderer.setRenderTarget(target);
    renderer.setClearAlpha(0);
    renderer.clear();
    renderer.render(scene, camera);
    const raw = float ? new Float32Array(w * h * 4) : new Uint16Array(w * h * 4);
    renderer.readRenderTargetPixels(target, 0, 0, w, h, raw);
    const px = float ? raw : Float32Array.from(raw, (v) => THREE.DataUtils.fromHalfFloat(v));
    let sum = 0, weights = 0, logSum = 0;
    const lum = (i) => Math.max(0, 0.2126 * px[i] + 0.7152 * px[i + 1] + 0.0722 * px[i + 2]);
    for (let i = 0; i < px.length; i += 4) {
      const weight = Math.min(1, Math.max(0, px[i + 3]));
      if (!Number.isFinite(lum(i))) continue;
      sum += weight * lum(i);
      weights += weight;
    }
    if (!(weights > 0 && sum > 0)) return 1;
    const delta = 1e-4 * (sum / weights);
    for (let i = 0; i < px.length; i += 4) {
      const weight = Math.min(1, Math.max(0, px[i + 3]));
      if (Number.isFinite(lum(i))) logSum += weight * Math.log(delta + lum(i));
    }
    return 0.18 / Math.exp(logSum / weights);
  } finally {
    renderer.setRenderTarget(null);
    renderer.setClearAlpha(clear);
    target.dispose();
  }
}

function base64(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

async function main() {
  $('luxel-title').textContent = about.scene;
  $('luxel-about').textContent = `${about.glb}: ${about.bake}; luxel ${about.luxel}, three.js r${THREE.REVISION}`;
  const canvas = $('luxel-view');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.setSize(window.innerWidth, window.innerHeight, false);
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.toneMapping = THREE.ACESFilmicToneMapping;
  renderer.setClearColor(0x000000, 1);

  status.textContent = 'Loading the bake\u2026';
  const gltf = await new GLTFLoader().parseAsync(glbBytes(), '');
  const scene = gltf.scene;
  const baked = scene.userData.luxel ?? {};
  let directions = false;  // per vertex: LUXEL_vertex_directional
  scene.traverse((o) => { directions ||= Boolean(o.isMesh && o.userData.gltfExtensions?.LUXEL_vertex_directional); });
  if (baked.vertexColors === 'irradiance' && directions) showDirectionalIrradiance(gltf);
  else if (baked.vertexColors === 'irradiance') showIrradiance(gltf);
  else if (baked.vertexColors && directions) showDirectionalRadiance(gltf);
  else if (baked.vertexColors) showRadiance(gltf);
  const lightmapped = [];
  scene.traverse((o) => o.isMesh && o.material.userData.luxel && lightmapped.push(o));
  if (lightmapped.length) {
    const has = (name) => lightmapped.some((o) => o.material.userData.gltfExtensions?.[name]);
    if (has('LUXEL_lightmap_transfer')) showTransferLightmaps(gltf, renderer);
    else if (has('LUXEL_lightmap_directional')) showDirectionalLightmaps(gltf, renderer);
    else showLightmaps(gltf, renderer);
    await waitForLightmaps(lightmapped);
  }
  viewer.shows = [lightmapped.length && 'lightmaps',
                  baked.vertexColors && `vertex colours (${baked.vertexColors}${directions ? ', with directions' : ''})`]
    .filter(Boolean).join(' and ') || 'no baked light';

  // The starting view, as `luxel render` chooses it (src/session/session.cpp, chooseCamera): the
  // scene's camera named "default", else its first (the glb carries them as glTF cameras), else
  // the bounding box framed from +z with a 45-degree field of view.
  scene.updateMatrixWorld(true);
  const bounds = new THREE.Box3().setFromObject(scene);
  const centre = bounds.isEmpty() ? new THREE.Vector3() : bounds.getCenter(new THREE.Vector3());
  const radius = bounds.isEmpty() ? 1 : Math.max(1e-6, bounds.getSize(new THREE.Vector3()).length() / 2);
  const camera = new THREE.PerspectiveCamera(45, window.innerWidth / window.innerHeight, radius / 2000, radius * 40);
  const controls = new OrbitControls(camera, canvas);
  const start = { position: new THREE.Vector3(), quaternion: new THREE.Quaternion(), target: new THREE.Vector3(),
                  up: new THREE.Vector3(0, 1, 0), fov: 45 };
  const cameras = gltf.cameras.filter((c) => c.isPerspectiveCamera);
  const sceneCamera = cameras.find((c) => c.name === 'default') ?? cameras[0];
  if (sceneCamera) {
    sceneCamera.matrixWorld.decompose(start.position, start.quaternion, new THREE.Vector3());
    start.fov = sceneCamera.fov;
    start.up.set(0, 1, 0).applyQuaternion(start.quaternion);  // orbit about the camera's own up
    const forward = new THREE.Vector3(0, 0, -1).applyQuaternion(start.quaternion);
    const d = Math.max(forward.dot(centre.clone().sub(start.position)), radius * 0.05);
    start.target.copy(start.position).addScaledVector(forward, d);
  } else {
    start.target.copy(centre);
    start.position.copy(centre).add(new THREE.Vector3(0, 0, 1.1 * radius / Math.tan(THREE.MathUtils.degToRad(start.fov / 2))));
  }
  viewer.view = sceneCamera ? `the scene's camera '${sceneCamera.name}'` : 'the bounds, framed from +z';

  let needsRender = true;
  const requestRender = () => { needsRender = true; };
  controls.addEventListener('change', requestRender);
  function startView() {
    camera.fov = start.fov;
    camera.up.copy(start.up);
    camera.position.copy(start.position);
    camera.quaternion.copy(start.quaternion);
    camera.updateProjectionMatrix();
    controls.target.copy(start.target);
    controls.update();  // looks at the target: the same orientation, the target lying straight ahead
    requestRender();
  }
  startView();

  // Exposure: automatic for the starting view, then in stops from there (slider, - and +).
  const slider = $('luxel-exposure'), sliderValue = $('luxel-exposure-value');
  let automatic = 1, stops = 0;
  function setExposure(s) {
    stops = Math.min(8, Math.max(-8, Math.round(s * 30) / 30));
    renderer.toneMappingExposure = viewer.exposure = automatic * 2 ** stops;
    slider.value = String(stops);
    sliderValue.textContent = `${stops >= 0 ? '+' : '\u2212'}${Math.abs(stops).toFixed(1)} EV`;
    requestRender();
  }
  function measureExposure() {
    automatic = viewer.automaticExposure = autoExposure(renderer, scene, camera);
    setExposure(0);
  }
  measureExposure();
  slider.addEventListener('input', () => setExposure(Number(slider.value)));

  // Walking: W A S D along the ground plane (perpendicular to the camera's up), Q E along up; the
  // orbit's target moves with the camera. Half the scene's radius a second, four times that with Shift.
  const keys = new Set();
  let running = false;
  const moves = { KeyW: [0, 0, 1], KeyS: [0, 0, -1], KeyD: [1, 0, 0], KeyA: [-1, 0, 0], KeyE: [0, 1, 0], KeyQ: [0, -1, 0] };
  function walk(dt) {
    const v = new THREE.Vector3();
    if (!keys.size) return false;
    const up = camera.up.clone().normalize();
    const forward = camera.getWorldDirection(new THREE.Vector3());
    forward.addScaledVector(up, -forward.dot(up));
    if (forward.lengthSq() < 1e-8)  // looking straight up or down: forward is the top of the view
      forward.set(0, 1, 0).applyQuaternion(camera.quaternion).addScaledVector(up, -up.dot(forward));
    forward.normalize();
    const right = new THREE.Vector3().crossVectors(forward, up).normalize();
    for (const k of keys) {
      const m = moves[k];
      v.addScaledVector(right, m[0]).addScaledVector(up, m[1]).addScaledVector(forward, m[2]);
    }
    if (v.lengthSq() === 0) return false;
    v.normalize().multiplyScalar(radius * 0.5 * (running ? 4 : 1) * dt);
    camera.position.add(v);
    controls.target.add(v);
    controls.update();
    return true;
  }
  const help = $('luxel-help');
  window.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;  // the browser's own shortcuts
    running = e.shiftKey;
    if (moves[e.code]) keys.add(e.code);
    else if (e.key === '-' || e.code === 'NumpadSubtract') setExposure(stops - 1 / 3);
    else if (e.key === '+' || e.key === '=' || e.code === 'NumpadAdd') setExposure(stops + 1 / 3);
    else if (e.key === '0' || e.code === 'Numpad0') measureExposure();
    else if (e.code === 'KeyR') startView();
    else if (e.code === 'KeyH' || e.key === '?') help.hidden = !help.hidden;
    else return;
    e.preventDefault();
  });
  window.addEventListener('keyup', (e) => {
    running = e.shiftKey;
    keys.delete(e.code);
  });
  window.addEventListener('blur', () => keys.clear());
  window.addEventListener('resize', () => {
    renderer.setSize(window.innerWidth, window.innerHeight, false);
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    requestRender();
  });

  function render() {
    renderer.render(scene, camera);
    viewer.frames += 1;
  }
  // For tests/web/html_viewer.mjs: a frame drawn as the loop draws it, read back as 8-bit sRGB
  // (what the canvas shows: tone-mapped), rows bottom-up; and where the camera is.
  viewer.readPixels = () => {
    render();
    const gl = renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const pixels = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    return { width: w, height: h, pixels: base64(pixels) };
  };
  viewer.camera = () => ({ position: camera.position.toArray(), target: controls.target.toArray() });

  let last = performance.now();
  stop = () => renderer.setAnimationLoop(null);
  renderer.setAnimationLoop((now) => {
    const dt = Math.min(0.1, Math.max(0, (now - last) / 1000));
    last = now;
    if (walk(dt)) needsRender = true;
    if (!needsRender) return;
    needsRender = false;
    render();
    if (!viewer.ready) {
      viewer.ready = true;
      status.textContent = viewer.shows === 'no baked light' ? 'This glb holds no baked light (bake it with --lightmaps or --vertex-colors).' : '';
    }
  });
}

main().catch(fail);
