// Checks that three.js shows directional lightmaps (`luxel bake --lightmaps --directional MODE`, the
// LUXEL_lightmap_directional extension) as luxel shows them itself (`luxel render --mode lightmap
// --directional MODE`), with the directional recipe of docs/baking.md run as written.
//
//   node directional_check.mjs --luxel PATH/TO/luxel --out DIR [--mode sh-l1|sh-l2|dominant] [--vertex 1|2]
//                              [--elements N] [--size N] [--tolerance F] [--chromium PATH] [--docs FILE]
//
// With --vertex 1, the same for directions per vertex (`luxel bake --vertex-colors --directional
// MODE`, the LUXEL_vertex_directional extension, docs/baking.md's vertex recipe), against the same
// lightmap render, with the plain vertex-colour recipe (no directions) for contrast. With --vertex 2,
// irradiance vertex colours beside lightmaps (`--lightmaps --vertex-colors-for floor --directional
// MODE`, the floor a 40 x 40 grid) with that section's recipes.
//
// 1. writes a scene into DIR: a 4 x 4 m floor (OBJ, uvs along x and z) whose normal map (MTL `norm`,
//    a 16 x 1 PNG) has stripes 1 m wide tilted 12 degrees towards +x and -x in turn, a lamp 4 m off
//    along +x and 2 m up (light at 63 to 76 degrees from the floor's normal), and a camera looking
//    straight down (scene JSON);
// 2. bakes it (the glb) and renders it with luxel's lightmap mode (DIR/luxel.exr), the same texel
//    budget for both, hence the same atlas and the same solve;
// 3. renders the glb in three.js in headless Chromium with the directional recipe, and with the
//    plain recipe (no directions) for contrast;
// 4. compares the mean radiance of each stripe's inner half: the directional recipe must agree
//    with luxel within --tolerance (2%, relative, per channel), and the plain recipe must miss a
//    stripe by more than that (the stripes differ by a factor of 2 to 4: no direction, no stripes).
//
// Exit status: 0 pass, 1 fail, 77 skipped (Chromium or node_modules missing; the reason is printed).
import { mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

import { renderInChromium } from './browser.mjs';
import { luxelRunner, parseArguments, regionMean, relative, reporter, requireBrowser } from './check_common.mjs';
import { writePng } from './debug_png.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const started = Date.now();
const report = reporter('directional-check');
const { log, fail } = report;

const opts = {
  luxel: '', out: '', mode: 'sh-l1', vertex: 0, elements: 1600, size: 256, tolerance: 0.02,
  chromium: process.env.LUXEL_CHROMIUM || '/usr/bin/chromium',
  docs: path.resolve(here, '../../docs/baking.md'),
};
parseArguments(opts, 'node directional_check.mjs --luxel PATH --out DIR [--mode M] [--elements N] [--size N] [--tolerance F] [--chromium PATH] [--docs FILE]', report);
requireBrowser(opts.chromium, here, report);
const { EXRLoader } = await import('three/addons/loaders/EXRLoader.js');
const THREE = await import('three');

// The recipes: docs/baking.md's ```js blocks, the directional one and the plain one.
const blocks = [...readFileSync(opts.docs, 'utf8').matchAll(/```js\n([\s\S]*?)```/g)].map((m) => m[1]);
// Per vertex: the vertex recipe, and the plain vertex-colour one (the complete example's lines from
// `const S` to the traverse's end, as html_check.mjs takes them). With --vertex 2, irradiance vertex
// colours beside lightmaps (--vertex-colors-for): that section's directional recipe, which takes
// LUXEL_VERTEX_GLSL from the vertex recipe, and its plain MeshBasicMaterial one.
const vertexPlain = blocks.find((b) => b.includes('import ') && b.includes('const S'));
const glsl = blocks.find((b) => b.includes('const LUXEL_VERTEX_GLSL'));  // the vertex recipes' shared reading
const vertexRecipes = blocks.filter((b) => b.includes('LUXEL_vertex_directional') && b.includes('traverse'));
const withGlsl = (recipe) => (glsl && recipe ? `${glsl}\n${recipe}` : undefined);
let directional, plain;
if (opts.vertex === 2) {
  directional = withGlsl(vertexRecipes.find((b) => b.includes("vertexColors: 'irradiance'")));
  plain = blocks.find((b) => b.includes("vertexColors: 'irradiance'") && !b.includes('LUXEL_vertex_directional'));
} else if (opts.vertex) {
  directional = withGlsl(vertexRecipes.find((b) => !b.includes("vertexColors: 'irradiance'")));
  plain = vertexPlain?.slice(vertexPlain.indexOf('const S'), vertexPlain.indexOf('\n});\n', vertexPlain.indexOf('const S')) + 5);
} else {
  directional = blocks.find((b) => b.includes('LUXEL_lightmap_directional'));
  plain = blocks.find((b) => b.includes('material.userData.luxel') && !b.includes('LUXEL_lightmap_directional'));
}
if (!directional || !plain) fail(`${opts.docs}: no directional or no plain ${opts.vertex ? 'vertex-colour' : 'lightmap'} recipe (\`\`\`js blocks)`);

// ---- 1. the scene ---------------------------------------------------------------------------------
mkdirSync(opts.out, { recursive: true });
const tilt = 12 * Math.PI / 180;
const stripes = Buffer.alloc(16 * 3);
for (let x = 0; x < 16; ++x) {
  const n = [x < 8 ? Math.sin(tilt) : -Math.sin(tilt), 0, Math.cos(tilt)];  // tangent space: +x is +u
  n.forEach((v, c) => { stripes[x * 3 + c] = Math.round(255 * (0.5 + 0.5 * v)); });
}
writePng(path.join(opts.out, 'stripes.png'), 16, 1, stripes);
writeFileSync(path.join(opts.out, 'floor.mtl'), 'newmtl floor\nKd 0.5 0.5 0.5\nnorm stripes.png\n');
if (opts.vertex === 2) {
  // Vertex colours at the mesh's own vertices: a 40 x 40 grid of quads, 10 cm apart, so that they
  // resolve the lamp's fall-off as the lightmap's texels do.
  const n = 40, lines = ['mtllib floor.mtl', 'o floor'];
  for (let j = 0; j <= n; ++j)
    for (let i = 0; i <= n; ++i) {
      const x = -2 + 4 * i / n, z = 2 - 4 * j / n;
      lines.push(`v ${x} 0 ${z}`, `vt ${(x + 2) / 2} ${(2 - z) / 2}`);
    }
  lines.push('usemtl floor');
  const at = (i, j) => j * (n + 1) + i + 1;
  for (let j = 0; j < n; ++j)
    for (let i = 0; i < n; ++i) {
      const c = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
      lines.push(`f ${c.map((k) => `${k}/${k}`).join(' ')}`);
    }
  writeFileSync(path.join(opts.out, 'floor.obj'), lines.join('\n') + '\n');
} else {
  writeFileSync(path.join(opts.out, 'floor.obj'),
    'mtllib floor.mtl\no floor\nv -2 0 2\nv 2 0 2\nv 2 0 -2\nv -2 0 -2\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\nusemtl floor\nf 1/1 2/2 3/3 4/4\n');
}
writeFileSync(path.join(opts.out, 'floor.json'), JSON.stringify({
  name: 'striped floor',
  meshes: [{ file: 'floor.obj' }],
  lights: [{ type: 'point', name: 'lamp', position: [6, 2, 0], intensity: 20 }],
  cameras: [{ name: 'top', eye: [0, 5, 0], target: [0, 0, 0], up: [0, 0, -1], fov: 50 }],
}, null, 2));

// ---- 2. luxel -------------------------------------------------------------------------------------
const scene = path.join(opts.out, 'floor.json'), glb = path.join(opts.out, 'floor.glb'), exr = path.join(opts.out, 'luxel.exr');
rmSync(glb, { force: true });
rmSync(exr, { force: true });
const luxel = luxelRunner(opts.luxel, report);
const elements = String(opts.elements), size = opts.size;
const what = opts.vertex === 2 ? ['--lightmaps', '--vertex-colors-for', 'floor'] : [opts.vertex ? '--vertex-colors' : '--lightmaps'];
luxel(['bake', scene, '-o', glb, ...what, '--directional', opts.mode, '--elements', elements]);
luxel(['render', scene, '--mode', 'lightmap', '--directional', opts.mode, '--elements', elements,
       '--size', `${size}x${size}`, '--spp', '16', '-o', exr]);
const exrBytes = readFileSync(exr);
const ref = new EXRLoader().setDataType(THREE.FloatType).parse(exrBytes.buffer.slice(exrBytes.byteOffset, exrBytes.byteOffset + exrBytes.length));
if (ref.width !== size || ref.height !== size) fail(`${exr}: ${ref.width}x${ref.height}, expected ${size}x${size}`);

// ---- 3. three.js ----------------------------------------------------------------------------------
let renders;
try {
  const r = await renderInChromium({
    chromium: opts.chromium, roots: [['/out/', path.resolve(opts.out)], ['/', here]],
    jobs: [directional, plain].map((recipe) => ({ glb: '/out/floor.glb', recipe, variant: 'recipe', size,
                                                   kind: opts.vertex ? 'vertex' : 'lightmap' })),
  });
  renders = r.renders;
  if (r.messages.length) log(`browser messages:\n  ${r.messages.join('\n  ')}`);
} catch (e) {
  fail(e.message);
}
log(`three.js r${renders[0].three}, ${renders[0].material}, WebGL renderer: ${renders[0].glRenderer}`);

// ---- 4. comparison --------------------------------------------------------------------------------
// The camera sees x in [-h, h] across the image (h = 5 tan 25 degrees), +x to the right; stripe s
// covers x in [s, s + 1] for s = -2 .. 1; its inner half, away from the normal map's blend at the
// stripes' edges, and rows well inside the floor.
const h = 5 * Math.tan(25 * Math.PI / 180);
const column = (x) => Math.round((0.5 + x / (2 * h)) * size);
const regions = [-2, -1, 0, 1].map((s) => [column(s + 0.25), Math.round(0.38 * size), column(s + 0.75), Math.round(0.62 * size)]);
const mean = (pixels, region) => regionMean(pixels, size, region);
const pct = (v) => `${(v * 100).toFixed(2)}%`;
let ok = true;
const worst = (pixels) => Math.max(...regions.map((r) => relative(mean(pixels, r), mean(ref.data, r))));
log(`stripe means (green channel, W m^-2 sr^-1), mode ${opts.mode}; tolerance ${pct(opts.tolerance)} per channel:`);
regions.forEach((r, i) => {
  const l = mean(ref.data, r), t = mean(renders[0].pixels, r), p = mean(renders[1].pixels, r), d = relative(t, l);
  ok &&= d <= opts.tolerance;
  console.log(`  stripe ${i}  luxel ${l[1].toFixed(5)}  three.js ${t[1].toFixed(5)}  ${pct(d)}${d <= opts.tolerance ? '' : '  <- over tolerance'}` +
              `   (plain recipe ${p[1].toFixed(5)})`);
});
const plainWorst = worst(renders[1].pixels), rejected = plainWorst > opts.tolerance;
ok &&= rejected;
log(`the plain recipe (no directions): worst stripe ${pct(plainWorst)} off${rejected ? ', rejected' : ' - NOT rejected: the comparison cannot tell'}`);
log(`${ok ? 'PASS' : 'FAIL'} in ${((Date.now() - started) / 1000).toFixed(1)} s (files in ${opts.out})`);
process.exit(ok ? 0 : 1);
