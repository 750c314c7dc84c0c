// Checks the page `luxel bake ... --html` writes: opened from disk (file://) in headless Chromium
// with the network cut off, it must show the bake as luxel shows it itself, and log no error.
//
//   node html_check.mjs --luxel PATH/TO/luxel --out DIR [--elements N] [--size N] [--tolerance F]
//                       [--pixel-tolerance F] [--chromium PATH] [--docs PATH/TO/baking.md]
//
// 1. bakes the Cornell box twice with --html, into DIR/lightmaps.{glb,html} (--lightmaps) and
//    DIR/vertex-colors.{glb,html} (--vertex-colors), and renders luxel's own view of each bake
//    from the scene's camera, with the same element budget: `luxel render --mode lightmap` (the
//    same atlas and solve) and `luxel render --mode radiosity` (the same elements and the same
//    smooth per-vertex radiance), as linear EXR;
// 2. reads each page as text: no http:// or https:// anywhere in it (so no script, style, image or
//    import from the network), no src= or href= attribute, every import-map entry a data: URL, and
//    the display recipes of docs/baking.md (its ```js blocks) copied into it character for character;
// 3. opens each page in headless Chromium (Debian's /usr/bin/chromium, SwiftShader, playwright-core)
//    from file://, with every http(s) request aborted and host names unresolvable, in a 256x256
//    window; waits for the viewer's first frame and reads the canvas back (8-bit sRGB, tone-mapped);
// 4. tone-maps luxel's EXR exactly as the page does (three.js's ACESFilmicToneMapping at the
//    exposure the page chose, then the sRGB transfer) and compares: the mean of each region away
//    from edges (floor, back wall, red and green walls, ceiling) within --tolerance (1.5 of 255)
//    in every channel, and 95% of the pixels away from edges within --pixel-tolerance (2.5 of 255,
//    the largest channel); the red wall red and the green wall green; the same image tone-mapped a
//    third of a stop brighter, and without tone mapping, must each miss a region by more than the
//    tolerance (or the comparison proves nothing);
// 5. drives the page: W walks the camera forward (towards the orbit target), R goes back to the
//    scene's camera, + raises the exposure a third of a stop, and the page logged no error,
//    requested nothing but its own file, and kept its frame count going.
//
// Exit status: 0 pass, 1 fail, 77 skipped (Chromium or node_modules missing; the reason is printed).
import { existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import zlib from 'node:zlib';

import { luxelRunner, parseArguments, reporter, requireBrowser } from './check_common.mjs';
import { writeDebugPng } from './debug_png.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const started = Date.now();
const report = reporter('html-check');
const { log, fail } = report;

// ---- arguments ------------------------------------------------------------------------------------
const opts = {
  luxel: '', out: '', elements: 10000, size: 256, tolerance: 1.5, 'pixel-tolerance': 2.5,
  chromium: process.env.LUXEL_CHROMIUM || '/usr/bin/chromium',
  docs: path.resolve(here, '../../docs/baking.md'),
};
parseArguments(opts, 'node html_check.mjs --luxel PATH --out DIR [--elements N] [--size N] [--tolerance F] [--pixel-tolerance F] [--chromium PATH] [--docs FILE]', report);
requireBrowser(opts.chromium, here, report);
const { chromium } = await import('playwright-core');
const { EXRLoader } = await import('three/addons/loaders/EXRLoader.js');
const THREE = await import('three');

// ---- 1. luxel: the bakes with their pages, and luxel's own view of each ---------------------------
const size = opts.size, elements = String(opts.elements);
mkdirSync(opts.out, { recursive: true });
const luxel = luxelRunner(opts.luxel, report);
function readExr(file) {
  const b = readFileSync(file);
  const image = new EXRLoader().setDataType(THREE.FloatType).parse(b.buffer.slice(b.byteOffset, b.byteOffset + b.length));
  if (image.width !== size || image.height !== size) fail(`${file}: ${image.width}x${image.height}, expected ${size}x${size}`);
  return image.data;  // RGBA, rows bottom-up
}
const cases = [
  { name: 'lightmaps', bake: ['--lightmaps'], mode: 'lightmap', shows: 'lightmaps' },
  { name: 'vertex-colors', bake: ['--vertex-colors'], mode: 'radiosity', shows: 'vertex colours (radiance)' },
  // Directions per vertex, through the vertex recipe: with no normal map, the same picture.
  { name: 'vertex-directions', bake: ['--vertex-colors', '--directional', 'sh-l1'], mode: 'radiosity',
    shows: 'vertex colours (radiance, with directions)' },
  // Irradiance vertex colours on the blocks with their directions, lightmaps on the rest: the
  // regions compared lie on the lightmapped walls. Not per pixel: a block's colours are its eight
  // corners' (docs/baking.md), not the lightmap the render reads (directional_check.mjs --vertex 2
  // checks that recipe on a grid fine enough to compare).
  { name: 'vertex-colors-for-directions', bake: ['--lightmaps', '--vertex-colors-for', 'short*,tall*', '--directional', 'sh-l1'],
    mode: 'lightmap', shows: 'lightmaps and vertex colours (irradiance, with directions)', perPixel: false },
];
for (const c of cases) {
  c.glb = path.join(opts.out, `${c.name}.glb`);
  c.html = path.join(opts.out, `${c.name}.html`);
  c.exr = path.join(opts.out, `luxel-${c.name}.exr`);
  for (const f of [c.glb, c.html, c.exr]) rmSync(f, { force: true });
  luxel(['bake', 'cornell', '-o', c.glb, ...c.bake, '--elements', elements, '--html']);
  luxel(['render', 'cornell', '--mode', c.mode, '--elements', elements, '--size', `${size}x${size}`, '--spp', '16', '-o', c.exr]);
  if (!existsSync(c.html)) fail(`luxel bake ... --html wrote no ${c.html}`);
  c.ref = readExr(c.exr);
}

// ---- 2. the page's text ---------------------------------------------------------------------------
// docs/baking.md's ```js blocks, the recipes the page must apply: the whole block, or for the first
// (a complete example, with its imports and renderer) the lines from `const S` to the traverse's end.
const docs = readFileSync(opts.docs, 'utf8');
const blocks = [...docs.matchAll(/```js\n([\s\S]*?)```/g)].map((m) => m[1]);
const recipes = blocks.map((b) => (b.includes('import ') && b.includes('const S') ? b.slice(b.indexOf('const S'), b.indexOf('\n});\n', b.indexOf('const S')) + 5) : b));
if (recipes.length < 3) fail(`${opts.docs}: expected three \`\`\`js recipe blocks, found ${recipes.length}`);
let ok = true;
const check = (pass, what) => { ok &&= pass; log(`${what}${pass ? '' : '  <- FAIL'}`); return pass; };
for (const c of cases) {
  const text = readFileSync(c.html, 'utf8');
  const mb = (text.length / 2 ** 20).toFixed(1);
  const url = text.search(/https?:\/\//i);
  check(url < 0, `${c.name}.html: no http(s):// URL${url < 0 ? '' : `: ...${text.slice(Math.max(0, url - 60), url + 60)}...`}`);
  check(!/\s(src|href)\s*=/i.test(text), `${c.name}.html: no src= or href= attribute`);
  const map = JSON.parse(text.match(/<script type="importmap">([\s\S]*?)<\/script>/)?.[1] ?? '{"imports":{}}');
  const entries = Object.entries(map.imports ?? {});
  check(entries.length >= 2 && entries.every(([, url]) => url.startsWith('data:text/javascript;base64,')),
        `${c.name}.html: the import map's ${entries.length} modules are all data: URLs`);
  recipes.forEach((r, i) => check(text.includes(r), `${c.name}.html: holds docs/baking.md's js block ${i + 1} as written`));
  const glb = readFileSync(c.glb);
  check(text.includes(glb.toString('base64')), `${c.name}.html: holds ${path.basename(c.glb)} (base64)`);
  log(`${c.name}.html: ${mb} MiB, ${entries.length} three.js modules (${entries.map(([k]) => k).join(', ')}), the glb ${(glb.length / 1024).toFixed(0)} KiB`);
}

// ---- 3. the pages in headless Chromium, from file:// ------------------------------------------------
const flags = [
  '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync',
  '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--host-resolver-rules=MAP * ~NOTFOUND',
];
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
let browser;
try {
  browser = await chromium.launch({ executablePath: opts.chromium, headless: true, args: flags, timeout: 60000 });
  for (const c of cases) {
    const context = await browser.newContext({ viewport: { width: size, height: size }, deviceScaleFactor: 1 });
    await context.route(/^https?:/, (route) => route.abort());
    const page = await context.newPage();
    const messages = [], errors = [], requests = [];
    page.on('console', (m) => {
      messages.push(`console.${m.type()}: ${m.text()}`);
      if (m.type() === 'error') errors.push(`console.error: ${m.text()}`);
    });
    page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
    page.on('request', (r) => requests.push(r.url()));
    const url = pathToFileURL(c.html).href;
    const t = Date.now();
    await page.goto(url);
    try {
      await page.waitForFunction(() => window.luxelViewer?.ready || window.luxelViewer?.error, null, { timeout: 60000 });
    } catch (e) {
      fail(`${c.name}.html: no frame within 60 s\n${messages.join('\n')}`);
    }
    const state = await page.evaluate(() => ({ ...window.luxelViewer, about: undefined, readPixels: undefined, camera: undefined }));
    if (state.error) fail(`${c.name}.html: the viewer failed: ${state.error}\n${messages.join('\n')}`);
    log(`${c.name}.html: first frame after ${((Date.now() - t) / 1000).toFixed(1)} s; three.js r${state.three}, shows ${state.shows}, ` +
        `from ${state.view}, exposure ${state.exposure.toFixed(4)}`);
    check(state.shows === c.shows, `${c.name}.html: the page shows ${c.shows}`);
    check(state.view === "the scene's camera 'default'", `${c.name}.html: the page starts from ${state.view}`);
    const shot = await page.evaluate(() => window.luxelViewer.readPixels());
    if (shot.width !== size || shot.height !== size) fail(`${c.name}.html: the canvas is ${shot.width}x${shot.height}, expected ${size}x${size}`);
    c.pixels = new Uint8Array(Buffer.from(shot.pixels, 'base64'));
    c.exposure = state.exposure;

    // ---- 5. navigation and exposure keys ----
    const canvas = page.locator('#luxel-view');
    await canvas.focus();
    const before = await page.evaluate(() => window.luxelViewer.camera());
    const dist = (a, b) => Math.hypot(...a.map((v, i) => v - b[i]));
    await page.keyboard.down('KeyW');
    await sleep(400);
    await page.keyboard.up('KeyW');
    const walked = await page.evaluate(() => window.luxelViewer.camera());
    const toTarget = before.target.map((v, i) => v - before.position[i]);
    const moved = walked.position.map((v, i) => v - before.position[i]);
    const along = moved.reduce((s, v, i) => s + v * toTarget[i], 0) / (Math.hypot(...toTarget) || 1);
    check(along > 1e-3 && Math.abs(dist(walked.position, walked.target) - dist(before.position, before.target)) < 1e-6,
          `${c.name}.html: W walks forward, the orbit target with the camera (${along.toFixed(3)} m)`);
    await page.keyboard.press('KeyR');
    const back = await page.evaluate(() => window.luxelViewer.camera());
    check(dist(back.position, before.position) < 1e-9 && dist(back.target, before.target) < 1e-9, `${c.name}.html: R goes back to the scene's camera`);
    await page.keyboard.press('Equal');
    const brighter = await page.evaluate(() => window.luxelViewer.exposure);
    check(Math.abs(brighter / c.exposure - 2 ** (1 / 3)) < 1e-3, `${c.name}.html: + raises the exposure a third of a stop (x${(brighter / c.exposure).toFixed(4)})`);
    const frames = await page.evaluate(() => window.luxelViewer.frames);
    check(frames >= 3, `${c.name}.html: ${frames} frames drawn`);
    await sleep(100);
    const late = await page.evaluate(() => window.luxelViewer.error);
    if (late) errors.push(`viewer error: ${late}`);

    check(errors.length === 0, `${c.name}.html: no errors logged${errors.length ? `:\n  ${errors.join('\n  ')}` : ''}`);
    const foreign = requests.filter((u) => !(u === url || u.startsWith('data:') || u.startsWith('blob:')));
    check(foreign.length === 0, `${c.name}.html: requested nothing but itself, data: and blob: URLs${foreign.length ? `: ${foreign.join(', ')}` : ''}`);
    const warnings = messages.filter((m) => !m.startsWith('console.error') && !/GPU stall due to ReadPixels|Automatic fallback to software WebGL/.test(m));
    if (warnings.length) log(`${c.name}.html: browser messages:\n  ${warnings.join('\n  ')}`);
    await context.close();
  }
} finally {
  await browser?.close();
}

// ---- 4. comparison --------------------------------------------------------------------------------
// three.js's ACESFilmicToneMapping (src/renderers/shaders/ShaderChunk/tonemapping_pars_fragment.glsl.js,
// r187), then its sRGB transfer, to 0-255: what the canvas holds for luxel's linear radiance.
const acesIn = [[0.59719, 0.35458, 0.04823], [0.07600, 0.90834, 0.01566], [0.02840, 0.13383, 0.83777]];
const acesOut = [[1.60475, -0.53108, -0.07367], [-0.10208, 1.10813, -0.00605], [-0.00327, -0.07276, 1.07602]];
const mul = (m, v) => m.map((row) => row[0] * v[0] + row[1] * v[1] + row[2] * v[2]);
const fit = (x) => (x * (x + 0.0245786) - 0.000090537) / (x * (0.983729 * x + 0.4329510) + 0.238081);
const saturate = (x) => Math.min(1, Math.max(0, x));
const srgb = (x) => 255 * (x <= 0.0031308 ? 12.92 * x : 1.055 * x ** 0.41666 - 0.055);
const aces = (rgb, exposure) => mul(acesOut, mul(acesIn, rgb.map((v) => v * exposure / 0.6)).map(fit)).map(saturate);
const display = (ref, exposure, curve = aces) => {
  const out = new Float32Array(size * size * 4);
  for (let i = 0; i < size * size * 4; i += 4) out.set([...curve([ref[i], ref[i + 1], ref[i + 2]], exposure).map(srgb), 255], i);
  return out;
};

// Regions in fractions of the image, top-left origin (x0, y0, x1, y1), inside each surface and away
// from its edges and from the blocks, for the built-in cornell camera (as check.mjs).
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
const fmt = (v) => v.map((x) => x.toFixed(1).padStart(5)).join(', ');
function compare(pixels, expected, ref) {
  const byRegion = Object.entries(regions).map(([name, r]) => {
    const e = mean(expected, r), t = mean(pixels, r);
    return { name, e, t, d: Math.max(...e.map((v, c) => Math.abs(v - t[c]))) };
  });
  // Pixels away from edges: luxel's linear luminance within 10% of its 3x3 neighbourhood's.
  const lum = (p, i) => 0.2126 * p[i] + 0.7152 * p[i + 1] + 0.0722 * p[i + 2];
  const diffs = [];
  for (let y = 1; y < size - 1; ++y)
    for (let x = 1; x < size - 1; ++x) {
      const i = (y * size + x) * 4, l = lum(ref, i);
      let flat = l > 1e-3;
      for (let dy = -1; dy <= 1 && flat; ++dy)
        for (let dx = -1; dx <= 1; ++dx) flat &&= Math.abs(lum(ref, i + (dy * size + dx) * 4) - l) <= 0.1 * l;
      if (flat) diffs.push(Math.max(...[0, 1, 2].map((c) => Math.abs(pixels[i + c] - expected[i + c]))));
    }
  diffs.sort((a, b) => a - b);
  const q = (f) => diffs[Math.min(diffs.length - 1, Math.floor(f * diffs.length))];
  return { byRegion, worst: Math.max(...byRegion.map((r) => r.d)), count: diffs.length, median: q(0.5), p95: q(0.95), p99: q(0.99) };
}

for (const c of cases) {
  const expected = display(c.ref, c.exposure);
  const r = compare(c.pixels, expected, c.ref);
  log(`${c.name}.html against luxel render --mode ${c.mode}, tone-mapped as the page does (ACES, exposure ${c.exposure.toFixed(4)}, sRGB), ` +
      `0-255; tolerance ${opts.tolerance} per channel:`);
  for (const g of r.byRegion) {
    const pass = g.d <= opts.tolerance;
    ok &&= pass;
    console.log(`  ${g.name.padEnd(10)}  luxel ${fmt(g.e)}  page ${fmt(g.t)}  ${g.d.toFixed(2)}${pass ? '' : '  <- over tolerance'}`);
  }
  const perPixel = `${c.name}.html: per pixel, largest channel, ${r.count} pixels away from edges: median ${r.median.toFixed(2)}, ` +
    `95th percentile ${r.p95.toFixed(2)}, 99th ${r.p99.toFixed(2)}; 95th percentile tolerance ${opts['pixel-tolerance']}`;
  if (c.perPixel === false) log(`${perPixel} (not checked: see the case)`);
  else check(r.p95 <= opts['pixel-tolerance'], perPixel);
  const red = mean(c.pixels, regions['red wall']), green = mean(c.pixels, regions['green wall']);
  check(red[0] > red[1] + 40 && red[0] > red[2] + 40, `${c.name}.html: the red wall is red (${fmt(red)})`);
  check(green[1] > green[0] + 40 && green[1] > green[2] + 40, `${c.name}.html: the green wall is green (${fmt(green)})`);
  // The comparison must tell a wrong display from the right one.
  for (const [what, wrong] of [
    ['a third of a stop brighter', display(c.ref, c.exposure * 2 ** (1 / 3))],
    ['no tone mapping (exposure, clamp, sRGB)', display(c.ref, c.exposure, (rgb, e) => rgb.map((v) => saturate(v * e)))],
  ]) {
    const w = compare(c.pixels, wrong, c.ref);
    check(w.worst > opts.tolerance, `${c.name}.html: luxel's image ${what}: worst region ${w.worst.toFixed(1)} off, ` +
          `${w.worst > opts.tolerance ? 'rejected' : 'NOT rejected: the comparison cannot tell'}`);
  }
  if (zlib.crc32) {
    writePng(path.join(opts.out, `page-${c.name}.png`), c.pixels);
    writePng(path.join(opts.out, `luxel-${c.name}.png`), expected);
  }
}

// Images to look at: DIR/page-CASE.png (the canvas) and DIR/luxel-CASE.png (luxel's render, tone-mapped
// as the page does), with the regions outlined.
function writePng(file, pixels) {
  const rgb = Buffer.alloc(size * size * 3);
  for (let y = 0; y < size; ++y)
    for (let x = 0; x < size; ++x)
      for (let c = 0; c < 3; ++c) rgb[(y * size + x) * 3 + c] = Math.round(Math.min(255, Math.max(0, pixels[((size - 1 - y) * size + x) * 4 + c])));
  writeDebugPng(file, size, rgb, Object.values(regions).map(box));
}

log(`${ok ? 'PASS' : 'FAIL'} in ${((Date.now() - started) / 1000).toFixed(1)} s (images in ${opts.out})`);
process.exit(ok ? 0 : 1);
