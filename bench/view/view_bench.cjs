// The viewer's load and frame-rate benchmark in Debian's headless Chromium (playwright-core from
// web/'s npm packages): time from navigation to the whole scene drawn, then the frame rate while
// the camera orbits the scene for a few seconds. JSON on stdout.
//   node bench/view/view_bench.cjs WEB_DIR URL [ORBIT_SECONDS] [--gl swiftshader|gpu]
// bench/view/run.sh starts strata view and runs this on a 2 M-triangle mesh.
'use strict';
const path = require('path');

async function main() {
  const args = process.argv.slice(2);
  const [webDir, url] = args;
  const orbitSeconds = Number(args[2] || 5);
  const gl = args.includes('--gl') ? args[args.indexOf('--gl') + 1] : 'swiftshader';
  const { chromium } = require(path.join(webDir, 'node_modules', 'playwright-core'));
  const glArgs = gl === 'gpu' ? ['--enable-gpu', '--ignore-gpu-blocklist']
    : ['--disable-gpu', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'];
  const browser = await chromium.launch({
    executablePath: process.env.STRATA_CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', '--disable-frame-rate-limit', ...glArgs],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    const t0 = Date.now();
    await page.goto(url);
    await page.waitForFunction(() => window.strata && window.strata.synced && window.strata.firstSceneDrawn,
      null, { timeout: 300000, polling: 20 });
    const openMs = Date.now() - t0;
    const renderer = await page.evaluate(() => {
      const c = document.createElement('canvas').getContext('webgl2');
      const ext = c && c.getExtension('WEBGL_debug_renderer_info');
      return ext ? c.getParameter(ext.UNMASKED_RENDERER_WEBGL) : 'unknown';
    });
    const orbit = await page.evaluate(async (seconds) => {
      const start = performance.now();
      const frames0 = window.strata.framesDrawn;
      const intervals = [];
      let last = start;
      await new Promise((resolve) => {
        const step = (now) => {
          window.strataOrbitStep(0.02);
          intervals.push(now - last);
          last = now;
          if (now - start < seconds * 1000) requestAnimationFrame(step); else resolve();
        };
        requestAnimationFrame(step);
      });
      const elapsed = (performance.now() - start) / 1000;
      intervals.sort((a, b) => a - b);
      return { seconds: elapsed, frames: window.strata.framesDrawn - frames0,
        fps: (window.strata.framesDrawn - frames0) / elapsed,
        p95_frame_ms: intervals[Math.floor(0.95 * (intervals.length - 1))] };
    }, orbitSeconds);
    const state = await page.evaluate(() => ({ triangles: window.strata.triangles, meshes: window.strata.meshes }));
    console.log(JSON.stringify({ url, gl, renderer, open_ms: openMs, triangles: state.triangles,
      meshes: state.meshes, orbit }, null, 1));
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  console.error(`view_bench: ${e && e.stack ? e.stack : e}`);
  process.exit(1);
});
