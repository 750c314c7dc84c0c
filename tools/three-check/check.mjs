// Checks that three.js shows the lightmaps `luxel bake --lightmaps` writes as luxel shows them
// itself (`luxel render --mode lightmap`), following the recipe of docs/baking.md literally.
//
//   node check.mjs --luxel PATH/TO/luxel --out DIR [--elements N] [--size N] [--tolerance F]
//                  [--pixel-tolerance F] [--chromium PATH] [--docs PATH/TO/baking.md] [--recipe FILE.js]
//
// 1. bakes the Cornell box into DIR/cornell.glb (TEXCOORD_1, RGBM pages) and renders it with
//    `luxel render --mode lightmap` into DIR/luxel.exr, from the scene's camera (exported as the
//    glTF camera), both with the same element budget, hence the same atlas and the same solve;
// 2. serves this folder and DIR on 127.0.0.1 (node:http) and opens page.js in headless Chromium
//    (Debian's /usr/bin/chromium, WebGL through SwiftShader, driven by playwright-core, a fresh
//    profile); the page loads the glb with GLTFLoader, runs the ```js block of docs/baking.md that
//    applies material.userData.luxel, renders into a float render target and returns linear
//    radiance;
// 3. compares the two images: the mean radiance per region (floor, back wall, red and green walls,
//    ceiling, away from edges) must agree within --tolerance (2%, relative, per channel), the
//    luminance of 95% of the pixels away from edges within --pixel-tolerance (3%); the red wall
//    must be red and the green wall green; and three deliberately wrong conventions (no lightmap,
//    the lightmap read through TEXCOORD_0, TEXCOORD_1's v flipped) must each miss a region by more
//    than --tolerance. It also reports, without asserting, the same lightmap on GLTFLoader's
//    MeshStandardMaterial.
//
// Exit status: 0 pass, 1 fail, 77 skipped (Chromium or node_modules missing; the reason is printed).
import { mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import zlib from 'node:zlib';

import { renderInChromium } from './browser.mjs';
import { luxelRunner, parseArguments, reporter, requireBrowser } from './check_common.mjs';
import { writeDebugPng } from './debug_png.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const started = Date.now();
const report = reporter('three-check');
const { log, fail } = report;

// ---- arguments ------------------------------------------------------------------------------------
const opts = {
  luxel: '', out: '', elements: 10000, size: 256, tolerance: 0.02, 'pixel-tolerance': 0.03,
  chromium: process.env.LUXEL_CHROMIUM || '/usr/bin/chromium',
  docs: path.resolve(here, '../../docs/baking.md'),
  recipe: '',  // a .js file to run instead of the docs' recipe (to try a change before documenting it)
};
parseArguments(opts, 'node check.mjs --luxel PATH --out DIR [--elements N] [--size N] [--tolerance F] [--pixel-tolerance F] [--chromium PATH] [--docs FILE] [--recipe FILE.js]', report);
requireBrowser(opts.chromium, here, report);
const { EXRLoader } = await import('three/addons/loaders/EXRLoader.js');
const { EXRExporter, ZIP_COMPRESSION } = await import('three/addons/exporters/EXRExporter.js');
const THREE = await import('three');

// The recipe: the ```js block of docs/baking.md that applies material.userData.luxel.
const docs = readFileSync(opts.docs, 'utf8');
let recipe = [...docs.matchAll(/```js\n([\s\S]*?)```/g)].map((m) => m[1]).find((b) => b.includes('material.userData.luxel'));
if (opts.recipe) recipe = readFileSync(opts.recipe, 'utf8');
if (!recipe) fail(`${opts.docs}: no \`\`\`js block using material.userData.luxel (the lightmap recipe)`);

// ---- 1. luxel: the glb and its own lightmapped render ---------------------------------------------
mkdirSync(opts.out, { recursive: true });
const glb = path.join(opts.out, 'cornell.glb'), exr = path.join(opts.out, 'luxel.exr');
rmSync(glb, { force: true });
rmSync(exr, { force: true });
const luxel = luxelRunner(opts.luxel, report);
const elements = String(opts.elements), size = opts.size;
luxel(['bake', 'cornell', '-o', glb, '--lightmaps', '--elements', elements]);
luxel(['render', 'cornell', '--mode', 'lightmap', '--elements', elements, '--size', `${size}x${size}`, '--spp', '16', '-o', exr]);

// EXRLoader returns RGBA float rows bottom-up, as readRenderTargetPixels does.
const exrBytes = readFileSync(exr);
const ref = new EXRLoader().setDataType(THREE.FloatType).parse(exrBytes.buffer.slice(exrBytes.byteOffset, exrBytes.byteOffset + exrBytes.length));
if (ref.width !== size || ref.height !== size) fail(`${exr}: ${ref.width}x${ref.height}, expected ${size}x${size}`);

// ---- 2. three.js in headless Chromium -------------------------------------------------------------
const variants = ['recipe', 'no-lightmap', 'uv0', 'flip-v', 'standard'];
const renders = {};
try {
  const r = await renderInChromium({
    chromium: opts.chromium, roots: [['/out/', path.resolve(opts.out)], ['/', here]],
    jobs: variants.map((variant) => ({ glb: '/out/cornell.glb', recipe, variant, size })),
  });
  variants.forEach((v, i) => { renders[v] = r.renders[i]; });
  if (r.messages.length) log(`browser messages:\n  ${r.messages.join('\n  ')}`);
} catch (e) {
  fail(e.message);
}
const info = renders.recipe;
log(`three.js r${info.three}, ${info.material}, WebGL renderer: ${info.glRenderer}`);
log(`lightMap as the recipe set it: ${JSON.stringify(info.lightMap)}`);

// ---- 3. comparison --------------------------------------------------------------------------------
// Regions in fractions of the image, top-left origin (x0, y0, x1, y1), inside each surface and away
// from its edges and from the blocks, for the built-in cornell camera (outlined in DIR/*.png).
const regions = {
  'floor': [0.20, 0.88, 0.26, 0.94],
  'back wall': [0.40, 0.20, 0.60, 0.36],
  'red wall': [0.06, 0.30, 0.14, 0.60],
  'green wall': [0.86, 0.30, 0.94, 0.60],
  'ceiling': [0.22, 0.03, 0.36, 0.09],
};
const box = ([x0, y0, x1, y1]) => [x0, y0, x1, y1].map((v) => Math.round(v * size));
function mean(pixels, region) {
  const [x0, y0, x1, y1] = box(region), s = [0, 0, 0];
  for (let y = y0; y < y1; ++y)
    for (let x = x0; x < x1; ++x)
      for (let c = 0; c < 3; ++c) s[c] += pixels[((size - 1 - y) * size + x) * 4 + c];  // rows are bottom-up
  return s.map((v) => v / ((x1 - x0) * (y1 - y0)));
}
// The largest relative difference of the three channels.
const relative = (a, b) => Math.max(...a.map((v, c) => Math.abs(v - b[c]) / Math.max(Math.abs(b[c]), 1e-6)));
const lum = (p, i) => 0.2126 * p[i] + 0.7152 * p[i + 1] + 0.0722 * p[i + 2];
// Pixels where luxel's image is smooth (its 3x3 neighbourhood within 10% of the centre's
// luminance): away from edges, where three.js's one sample per pixel and luxel's 16 jittered ones
// see different surfaces.
const smooth = [];
for (let y = 1; y < size - 1; ++y)
  for (let x = 1; x < size - 1; ++x) {
    const i = (y * size + x) * 4, l = lum(ref.data, i);
    let flat = l > 1e-3;
    for (let dy = -1; dy <= 1 && flat; ++dy)
      for (let dx = -1; dx <= 1; ++dx) flat &&= Math.abs(lum(ref.data, i + (dy * size + dx) * 4) - l) <= 0.1 * l;
    if (flat) smooth.push(i);
  }
function compare(pixels) {
  const byRegion = Object.entries(regions).map(([name, r]) => {
    const l = mean(ref.data, r), t = mean(pixels, r);
    return { name, l, t, d: relative(t, l) };
  });
  const diffs = smooth.map((i) => Math.abs(lum(pixels, i) - lum(ref.data, i)) / lum(ref.data, i)).sort((a, b) => a - b);
  const q = (f) => diffs[Math.min(diffs.length - 1, Math.floor(f * diffs.length))];
  return { byRegion, worst: Math.max(...byRegion.map((r) => r.d)), median: q(0.5), p95: q(0.95), p99: q(0.99) };
}
const pct = (v, digits = 2) => `${(v * 100).toFixed(digits)}%`;
const fmt = (v) => v.map((x) => x.toFixed(4)).join(', ');
const perPixel = (c) => `median ${pct(c.median)}, 95th percentile ${pct(c.p95)}, 99th ${pct(c.p99)}`;

let ok = true;
const result = compare(info.pixels);
log(`region means, linear RGB radiance (W m^-2 sr^-1); tolerance ${pct(opts.tolerance, 1)} per channel:`);
for (const r of result.byRegion) {
  const pass = r.d <= opts.tolerance;
  ok &&= pass;
  console.log(`  ${r.name.padEnd(10)}  luxel ${fmt(r.l)}  three.js ${fmt(r.t)}  ${pct(r.d)}${pass ? '' : '  <- over tolerance'}`);
}
const pixelPass = result.p95 <= opts['pixel-tolerance'];
ok &&= pixelPass;
log(`per pixel, luminance, ${smooth.length} pixels away from edges: ${perPixel(result)}; ` +
    `95th percentile tolerance ${pct(opts['pixel-tolerance'], 1)}${pixelPass ? '' : '  <- over tolerance'}`);

// Colour: the walls' colour is the lightmap times the base colour, in three.js's image.
const red = mean(info.pixels, regions['red wall']), green = mean(info.pixels, regions['green wall']);
if (!(red[0] > 3 * red[1] && red[0] > 3 * red[2])) { ok = false; log(`the red wall is not red in three.js: ${fmt(red)}`); }
if (!(green[1] > 2 * green[0] && green[1] > 2 * green[2])) { ok = false; log(`the green wall is not green in three.js: ${fmt(green)}`); }

// Wrong conventions must fail the same comparison, or the comparison proves nothing.
for (const variant of ['no-lightmap', 'uv0', 'flip-v']) {
  const c = compare(renders[variant].pixels), rejected = c.worst > opts.tolerance;
  ok &&= rejected;
  log(`wrong convention '${variant}': worst region ${pct(c.worst, 1)} off${rejected ? ', rejected' : ' - NOT rejected: the comparison cannot tell'}`);
}
// For information: the decoded lightmap on GLTFLoader's MeshStandardMaterial (docs/baking.md says
// why it is darker since three.js r186).
{
  const c = compare(renders.standard.pixels), Y = (v) => 0.2126 * v[0] + 0.7152 * v[1] + 0.0722 * v[2];
  const signed = c.byRegion.map((r) => `${r.name} ${((Y(r.t) / Y(r.l) - 1) * 100).toFixed(1)}%`).join(', ');
  log(`for information, the lightmap on MeshStandardMaterial instead: luminance ${signed}; per pixel ${perPixel(c)}`);
}

// Images to look at (DIR/three.png, DIR/luxel.png, DIR/three-VARIANT.png): the same exposure,
// linear -> sRGB, clamped, with the regions outlined; and DIR/three.exr, linear, beside DIR/luxel.exr.
function writePng(file, pixels) {
  const rgb = Buffer.alloc(size * size * 3);
  const srgb = (v) => Math.round(255 * Math.min(1, Math.max(0, v <= 0.0031308 ? 12.92 * v : 1.055 * v ** (1 / 2.4) - 0.055)));
  for (let y = 0; y < size; ++y)
    for (let x = 0; x < size; ++x)
      for (let c = 0; c < 3; ++c) rgb[(y * size + x) * 3 + c] = srgb(4 * pixels[((size - 1 - y) * size + x) * 4 + c]);
  writeDebugPng(file, size, rgb, Object.values(regions).map(box));
}
{
  const t = new THREE.DataTexture(info.pixels, size, size, THREE.RGBAFormat, THREE.FloatType);
  writeFileSync(path.join(opts.out, 'three.exr'), await new EXRExporter().parse(t, { type: THREE.FloatType, compression: ZIP_COMPRESSION }));
}
if (zlib.crc32) {  // Node 20.15 and later
  writePng(path.join(opts.out, 'luxel.png'), ref.data);
  for (const [v, r] of Object.entries(renders)) writePng(path.join(opts.out, v === 'recipe' ? 'three.png' : `three-${v}.png`), r.pixels);
}

log(`${ok ? 'PASS' : 'FAIL'} in ${((Date.now() - started) / 1000).toFixed(1)} s (images in ${opts.out})`);
process.exit(ok ? 0 : 1);
