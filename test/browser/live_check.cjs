// The live viewer in Debian's headless Chromium (playwright-core from web/'s npm packages): opens
// strata-view's page while strata-play replays a session through strata-vio and strata-mapper,
// waits until DONE_FILE exists (the replay has ended), the page's stats account for every frame
// the mapper received (fused, dropped or rejected) and the scene has settled, and writes what
// the page holds as JSON (console errors, the mapper's stats as the page shows them, the last
// camera pose, mesh counts, latencies from the mapper's publish to the page's draw) and a
// screenshot, for test/test_view_live_chain.cpp to check against what the mapper published.
//   node live_check.cjs WEB_DIR URL DONE_FILE OUT.json SHOT.png
'use strict';
const fs = require('fs');
const path = require('path');

async function main() {
  const [webDir, url, doneFile, outPath, shotPath] = process.argv.slice(2);
  const { chromium } = require(path.join(webDir, 'node_modules', 'playwright-core'));
  const browser = await chromium.launch({
    executablePath: process.env.STRATA_CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
      '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const out = { consoleErrors: [], pageErrors: [] };
  try {
    const page = await browser.newPage({ viewport: { width: 1024, height: 768 } });
    page.on('console', (m) => { if (m.type() === 'error') out.consoleErrors.push(m.text()); });
    page.on('pageerror', (e) => out.pageErrors.push(String(e)));
    // The server may still be starting: retry the first load for a while.
    for (let i = 0; ; ++i) {
      try {
        await page.goto(url);
        break;
      } catch (e) {
        if (i > 100) throw e;
        await page.waitForTimeout(200);
      }
    }
    await page.waitForFunction(() => window.strata && window.strata.connected, null, { timeout: 60000 });
    for (let waited = 0; !fs.existsSync(doneFile); waited += 200) {
      if (waited > 240000) throw new Error(`no ${doneFile} after 240 s: the replay did not end`);
      await page.waitForTimeout(200);
    }
    // Every frame the mapper received accounted for: fused, dropped or rejected.
    await page.waitForFunction(() => {
      const s = window.strata.stats;
      return s && s['frames received'] > 0 && s.frames + s.dropped + s.rejected >= s['frames received'];
    }, null, { timeout: 120000, polling: 200 });
    // Settled: no mesh block for a second and a half (the stats and the slice keep coming).
    let last = -1;
    for (let i = 0; i < 60; ++i) {
      const now = await page.evaluate(() => window.strata.meshMessages);
      if (now === last) break;
      last = now;
      await page.waitForTimeout(1500);
    }
    await page.waitForTimeout(500);
    await page.screenshot({ path: shotPath });
    out.state = await page.evaluate(() => {
      const s = window.strata;
      const l = [...s.latenciesMs].sort((a, b) => a - b);
      const q = (f) => (l.length ? l[Math.min(l.length - 1, Math.floor(f * l.length))] : null);
      return { connected: s.connected, hello: s.hello, stats: s.stats, lastPose: s.lastPose,
        meshes: s.meshes, triangles: s.triangles, trajectoryPoints: s.trajectoryPoints, slice: s.slice,
        errors: s.errors, messages: s.messages,
        latency_ms: { n: l.length, p50: q(0.5), p95: q(0.95), max: q(1) } };
    });
  } finally {
    await browser.close();
  }
  fs.writeFileSync(outPath, JSON.stringify(out, null, 1));
}

main().catch((e) => {
  console.error(`live_check: ${e && e.stack ? e.stack : e}`);
  process.exit(1);
});
