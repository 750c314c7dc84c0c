// Serving files to headless Chromium and running page.js's luxelThree there: shared by check.mjs
// (the plain lightmap recipe) and directional_check.mjs (the directional one).
import { existsSync, mkdtempSync, readFileSync, rmSync, statSync } from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.glb': 'model/gltf-binary', '.json': 'application/json' };

// Serves `roots` ([[url prefix, folder], ...], most specific first) on 127.0.0.1, opens index.html
// (from the root served at '/') in headless Chromium with WebGL through SwiftShader, and calls
// window.luxelThree(job) for each job. Returns { renders: [{..., pixels: Float32Array}], messages }
// or throws with the browser's messages.
export async function renderInChromium({ chromium: executablePath, roots, jobs }) {
  const { chromium } = await import('playwright-core');
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, 'http://localhost').pathname);
    if (url === '/favicon.ico') {
      res.writeHead(204).end();
      return;
    }
    const [prefix, root] = roots.find(([p]) => url.startsWith(p));
    const file = path.resolve(root, '.' + url.slice(prefix.length - 1).replace(/\/$/, '/index.html'));
    if (!file.startsWith(root + path.sep) || !existsSync(file) || !statSync(file).isFile()) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] ?? 'application/octet-stream', 'Cache-Control': 'no-store' });
    res.end(readFileSync(file));
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const origin = `http://127.0.0.1:${server.address().port}`;
  const flags = [
    '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync',
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  ];
  const profile = mkdtempSync(path.join(os.tmpdir(), 'luxel-three-check-'));
  let context;
  const renders = [], messages = [];
  try {
    // launchPersistentContext: the fresh profile folder is Chromium's --user-data-dir.
    context = await chromium.launchPersistentContext(profile, { executablePath, headless: true, args: flags, timeout: 60000 });
    const page = context.pages()[0] ?? await context.newPage();
    page.on('console', (m) => messages.push(`console.${m.type()}: ${m.text()}`));
    page.on('pageerror', (e) => messages.push(`page error: ${e.message}`));
    await page.goto(`${origin}/index.html`);
    try {
      await page.waitForFunction(() => window.luxelThreeReady === true, null, { timeout: 20000 });
      for (const job of jobs) {
        const r = await page.evaluate((a) => window.luxelThree(a), job);
        const b = Buffer.from(r.pixels, 'base64');
        renders.push({ ...r, pixels: new Float32Array(b.buffer, b.byteOffset, b.length / 4) });
      }
    } catch (e) {
      throw new Error(`${e.message.split('\n')[0]}\n${messages.join('\n')}`);
    }
  } finally {
    await context?.close();
    server.close();
    rmSync(profile, { recursive: true, force: true });
  }
  const warnings = messages.filter((m) => !/GPU stall due to ReadPixels|Automatic fallback to software WebGL/.test(m));
  return { renders, messages: warnings };
}
