// Checks that three.js relights transfer lightmaps (`luxel bake --lightmaps --transfer N`, the
// LUXEL_lightmap_transfer extension) as luxel relights them itself (`luxel render --mode lightmap
// --transfer N --sun-direction D`), with the transfer recipe of docs/baking.md run as written and
// its gltf.userData.luxelRelight turning the sun.
//
//   node transfer_check.mjs --luxel PATH/TO/luxel --out DIR [--bands N] [--elements N] [--size N]
//                           [--tolerance F] [--chromium PATH] [--docs FILE]
//
// 1. writes a scene into DIR: a 4 x 4 m floor, a 4 x 2 m wall along its far edge and a 1 m block
//    on the floor (OBJ, no uvs: luxel lays the lightmap out), a sun from behind the camera and a
//    sky (scene JSON), and a camera looking at the corner;
// 2. bakes it with the sun where the scene has it (the glb), and renders it with luxel's lightmap
//    mode with the sun turned to D (DIR/luxel.exr), the same texel budget for both;
// 3. renders the glb in three.js in headless Chromium with the transfer recipe, the sun turned to D
//    through luxelRelight, and with the plain recipe (the fallback lightmap, the sun where it was);
// 4. compares the mean radiance of regions (floor in front, floor by the wall, wall, block's front):
//    the relit three.js image within --tolerance (2%, per channel) of luxel's, the fallback off by
//    more (the sun has moved).
//
// Exit status: 0 pass, 1 fail, 77 skipped (Chromium or node_modules missing; the reason is printed).
import { mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { renderInChromium } from './browser.mjs';
import { luxelRunner, parseArguments, regionMean, relative, reporter, requireBrowser } from './check_common.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const started = Date.now();
const report = reporter('transfer-check');
const { log, fail } = report;

const opts = {
  luxel: '', out: '', bands: 3, elements: 3000, size: 256, tolerance: 0.02,
  chromium: process.env.LUXEL_CHROMIUM || '/usr/bin/chromium',
  docs: path.resolve(here, '../../docs/baking.md'),
};
parseArguments(opts, 'node transfer_check.mjs --luxel PATH --out DIR [--bands N] [--elements N] [--size N] [--tolerance F] [--chromium PATH] [--docs FILE]', report);
requireBrowser(opts.chromium, here, report);
const { EXRLoader } = await import('three/addons/loaders/EXRLoader.js');
const THREE = await import('three');

const blocks = [...readFileSync(opts.docs, 'utf8').matchAll(/```js\n([\s\S]*?)```/g)].map((m) => m[1]);
const transfer = blocks.find((b) => b.includes('LUXEL_lightmap_transfer'));
const plain = blocks.find((b) => b.includes('material.userData.luxel') && !b.includes('gltfExtensions'));
if (!transfer || !plain) fail(`${opts.docs}: no transfer or no plain lightmap recipe (\`\`\`js blocks)`);

// ---- 1. the scene ---------------------------------------------------------------------------------
mkdirSync(opts.out, { recursive: true });
writeFileSync(path.join(opts.out, 'corner.mtl'), 'newmtl grey\nKd 0.5 0.5 0.5\nnewmtl red\nKd 0.6 0.2 0.2\n');
const quads = [
  ['floor', 'grey', [[-2, 0, 2], [2, 0, 2], [2, 0, -2], [-2, 0, -2]]],
  ['wall', 'red', [[-2, 0, -2], [2, 0, -2], [2, 2, -2], [-2, 2, -2]]],
  // A 1 m block standing on the floor at x in [0.5, 1.5], z in [-0.5, 0.5]: its top and four sides.
  ['block', 'grey', [[0.5, 1, 0.5], [1.5, 1, 0.5], [1.5, 1, -0.5], [0.5, 1, -0.5]]],
  ['block', 'grey', [[0.5, 0, 0.5], [1.5, 0, 0.5], [1.5, 1, 0.5], [0.5, 1, 0.5]]],
  ['block', 'grey', [[1.5, 0, -0.5], [0.5, 0, -0.5], [0.5, 1, -0.5], [1.5, 1, -0.5]]],
  ['block', 'grey', [[0.5, 0, -0.5], [0.5, 0, 0.5], [0.5, 1, 0.5], [0.5, 1, -0.5]]],
  ['block', 'grey', [[1.5, 0, 0.5], [1.5, 0, -0.5], [1.5, 1, -0.5], [1.5, 1, 0.5]]],
];
let obj = 'mtllib corner.mtl\n', v = 0;
for (const [name, mtl, corners] of quads) {
  obj += `o ${name}${v}\nusemtl ${mtl}\n` + corners.map((c) => `v ${c.join(' ')}\n`).join('') + `f ${v + 1} ${v + 2} ${v + 3} ${v + 4}\n`;
  v += 4;
}
writeFileSync(path.join(opts.out, 'corner.obj'), obj);
const bakedSun = [0.3, -0.8, -0.5], turnedSun = [-0.4, -0.8, -0.3];  // where the scene has it, where it turns to
writeFileSync(path.join(opts.out, 'corner.json'), JSON.stringify({
  name: 'corner',
  meshes: [{ file: 'corner.obj' }],
  lights: [{ type: 'directional', name: 'sun', direction: bakedSun, intensity: 3 },
           { type: 'sky', name: 'sky', intensity: 0.3 }],
  cameras: [{ name: 'view', eye: [0, 3, 5], target: [0, 0.5, -1], up: [0, 1, 0], fov: 50 }],
}, null, 2));

// ---- 2. luxel -------------------------------------------------------------------------------------
const scene = path.join(opts.out, 'corner.json'), glb = path.join(opts.out, 'corner.glb'), exr = path.join(opts.out, 'luxel.exr');
rmSync(glb, { force: true });
rmSync(exr, { force: true });
const luxel = luxelRunner(opts.luxel, report);
const bands = String(opts.bands), elements = String(opts.elements), size = opts.size;
luxel(['bake', scene, '-o', glb, '--lightmaps', '--transfer', bands, '--elements', elements]);
luxel(['render', scene, '--mode', 'lightmap', '--transfer', bands, '--sun-direction', turnedSun.join(','),
       '--elements', elements, '--size', `${size}x${size}`, '--spp', '16', '-o', exr]);
const exrBytes = readFileSync(exr);
const ref = new EXRLoader().setDataType(THREE.FloatType).parse(exrBytes.buffer.slice(exrBytes.byteOffset, exrBytes.byteOffset + exrBytes.length));

// ---- 3. three.js ----------------------------------------------------------------------------------
const sun = { direction: turnedSun, irradiance: [3, 3, 3] };
let renders;
try {
  const r = await renderInChromium({
    chromium: opts.chromium, roots: [['/out/', path.resolve(opts.out)], ['/', here]],
    jobs: [{ glb: '/out/corner.glb', recipe: transfer, size, suns: [sun] },
           { glb: '/out/corner.glb', recipe: plain, size }],
  });
  renders = r.renders;
  if (r.messages.length) log(`browser messages:\n  ${r.messages.join('\n  ')}`);
} catch (e) {
  fail(e.message);
}
log(`three.js r${renders[0].three}, ${renders[0].material}, WebGL renderer: ${renders[0].glRenderer}`);

// ---- 4. comparison --------------------------------------------------------------------------------
// Regions in fractions of the image (x0, y0, x1, y1, top-left origin), inside each surface.
const regions = {
  'floor, front': [0.20, 0.80, 0.45, 0.92],
  'floor, by the wall': [0.15, 0.57, 0.35, 0.62],
  'wall': [0.25, 0.28, 0.45, 0.42],
  'block, front': [0.62, 0.55, 0.78, 0.68],
};
const box = ([x0, y0, x1, y1]) => [x0, y0, x1, y1].map((f) => Math.round(f * size));
const mean = (pixels, region) => regionMean(pixels, size, box(region));
const pct = (v) => `${(v * 100).toFixed(2)}%`;
let ok = true, fallbackWorst = 0;
log(`region means (red channel), ${opts.bands} bands, the sun turned to ${turnedSun}; tolerance ${pct(opts.tolerance)}:`);
for (const [name, r] of Object.entries(regions)) {
  const l = mean(ref.data, r), t = mean(renders[0].pixels, r), f = mean(renders[1].pixels, r), d = relative(t, l);
  if (!(l[0] > 0)) { ok = false; log(`${name}: luxel's image is black there: the region misses the surface`); }
  ok &&= d <= opts.tolerance;
  fallbackWorst = Math.max(fallbackWorst, relative(f, l));
  console.log(`  ${name.padEnd(18)}  luxel ${l[0].toFixed(5)}  three.js ${t[0].toFixed(5)}  ${pct(d)}${d <= opts.tolerance ? '' : '  <- over tolerance'}` +
              `   (fallback, sun unturned: ${f[0].toFixed(5)})`);
}
const rejected = fallbackWorst > opts.tolerance;
ok &&= rejected;
log(`the fallback lightmap (the sun where it was baked): worst region ${pct(fallbackWorst)} off${rejected ? ', rejected' : ' - NOT rejected: the comparison cannot tell'}`);
log(`${ok ? 'PASS' : 'FAIL'} in ${((Date.now() - started) / 1000).toFixed(1)} s (files in ${opts.out})`);
process.exit(ok ? 0 : 1);
