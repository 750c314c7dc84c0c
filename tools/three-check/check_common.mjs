// What every check in this folder does the same way: lines prefixed with its name, the exit codes
// (0 pass, 1 fail, 77 skipped: CTest's SKIP_RETURN_CODE), --name value arguments, what it needs
// (Chromium, the npm packages), running luxel, and region means of a float image.
import { spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import path from 'node:path';

export const SKIP = 77;

export function reporter(name) {
  return {
    log: (s) => console.log(`${name}: ${s}`),
    fail: (s) => { console.error(`${name}: FAIL: ${s}`); process.exit(1); },
    skip: (s) => { console.log(`${name}: SKIP: ${s}`); process.exit(SKIP); },
  };
}

// Fills `opts` (defaults, their types) from --key value pairs; --luxel and --out are required and
// the luxel executable must exist.
export function parseArguments(opts, usage, { fail }) {
  for (let i = 2; i < process.argv.length; i += 2) {
    const key = process.argv[i].replace(/^--/, ''), value = process.argv[i + 1];
    if (!(key in opts) || value === undefined) {
      console.error(`usage: ${usage}`);
      process.exit(2);
    }
    opts[key] = typeof opts[key] === 'number' ? Number(value) : value;
  }
  if (!opts.luxel || !opts.out) fail('--luxel and --out are required');
  if (!existsSync(opts.luxel)) fail(`${opts.luxel}: no luxel executable (build the luxel-cli target)`);
}

// Skips (exit 77, saying why) without Chromium or this folder's npm packages.
export function requireBrowser(chromium, here, { skip }) {
  if (!existsSync(chromium))
    skip(`${chromium} not found: install Debian's chromium (scripts/install-deps.sh) or set LUXEL_CHROMIUM`);
  for (const pkg of ['three', 'playwright-core'])
    if (!existsSync(path.join(here, 'node_modules', pkg, 'package.json')))
      skip(`${path.join(here, 'node_modules', pkg)} missing: run npm ci in tools/three-check (scripts/install-deps.sh does)`);
}

// Runs `luxel ARGS -q`, failing the check with its stderr when it fails, logging the time.
export function luxelRunner(luxel, { log, fail }) {
  return (args) => {
    const t = Date.now();
    const r = spawnSync(luxel, [...args, '-q'], { encoding: 'utf8' });
    if (r.status !== 0) fail(`luxel ${args.join(' ')}: exit ${r.status}\n${r.stderr}${r.error ?? ''}`);
    log(`luxel ${args.join(' ')} (${((Date.now() - t) / 1000).toFixed(2)} s)`);
  };
}

// Mean RGB of `pixels` (RGBA floats, rows bottom-up, size x size) over [x0, y0, x1, y1) in pixels,
// top-left origin.
export function regionMean(pixels, size, [x0, y0, x1, y1]) {
  const s = [0, 0, 0];
  for (let y = y0; y < y1; ++y)
    for (let x = x0; x < x1; ++x)
      for (let c = 0; c < 3; ++c) s[c] += pixels[((size - 1 - y) * size + x) * 4 + c];
  return s.map((v) => v / ((x1 - x0) * (y1 - y0)));
}

// The largest relative difference of the three channels.
export const relative = (a, b) => Math.max(...a.map((v, c) => Math.abs(v - b[c]) / Math.max(Math.abs(b[c]), 1e-6)));
