// Drives the viewer page in Debian's headless Chromium with playwright-core (from web/'s npm
// packages) and writes what it saw as JSON, for test/test_view_browser.cpp to check against the
// server's truth: console errors, the WebSocket, the scene's counts, the ESDF slice, the answers to
// distance queries (one of them a real click on the canvas), and a screenshot.
//   node view_check.cjs WEB_DIR URL OUT.json SHOT.png QUERIES.json
// QUERIES.json: {"slice_z": h, "points": [[x, y, z], ...]}. Exit 0 when it ran (the checks are the
// caller's), 1 with a message when the browser or the page failed.
'use strict';
const fs = require('fs');
const path = require('path');

async function main() {
  const [webDir, url, outPath, shotPath, queriesPath] = process.argv.slice(2);
  const { chromium } = require(path.join(webDir, 'node_modules', 'playwright-core'));
  const queries = JSON.parse(fs.readFileSync(queriesPath, 'utf8'));
  const browser = await chromium.launch({
    executablePath: process.env.STRATA_CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
      '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const out = { consoleErrors: [], pageErrors: [], answers: [] };
  try {
    const page = await browser.newPage({ viewport: { width: 1024, height: 768 } });
    page.on('console', (m) => { if (m.type() === 'error') out.consoleErrors.push(m.text()); });
    page.on('pageerror', (e) => out.pageErrors.push(String(e)));
    const t0 = Date.now();
    await page.goto(url);
    await page.waitForFunction(() => window.strata && window.strata.synced && window.strata.firstSceneDrawn, null, { timeout: 90000 });
    out.loadMs = Date.now() - t0;

    await page.evaluate((z) => window.strataSetSlice(z), queries.slice_z);
    await page.waitForFunction((z) => window.strata.slice && Math.abs(window.strata.slice.z - z) < 1e-6, queries.slice_z, { timeout: 30000 });

    const ask = async (point) => {
      const before = await page.evaluate(() => (window.strata.lastAnswer ? window.strata.lastAnswer.id : 0));
      await page.evaluate((p) => window.strataQuery(p), point);
      await page.waitForFunction((b) => window.strata.lastAnswer && window.strata.lastAnswer.id > b, before, { timeout: 30000 });
      return page.evaluate(() => window.strata.lastAnswer);
    };
    for (const p of queries.points) out.answers.push(await ask(p));

    // A real click in the middle of the canvas: the page raycasts the mesh and asks the server.
    const before = await page.evaluate(() => (window.strata.lastAnswer ? window.strata.lastAnswer.id : 0));
    await page.mouse.click(512, 384);
    try {
      await page.waitForFunction((b) => window.strata.lastAnswer && window.strata.lastAnswer.id > b, before, { timeout: 15000 });
      out.click = await page.evaluate(() => window.strata.lastAnswer);
    } catch (e) {
      out.click = null;  // the centre of the view missed the surface
    }

    await page.waitForTimeout(300);
    await page.screenshot({ path: shotPath });
    out.state = await page.evaluate(() => {
      const s = window.strata;
      return { connected: s.connected, synced: s.synced, meshes: s.meshes, triangles: s.triangles,
        vertices: s.vertices, objects: s.objects, stats: s.stats, slice: s.slice, errors: s.errors,
        framesDrawn: s.framesDrawn, fps: s.fps, hello: s.hello };
    });
  } finally {
    await browser.close();
  }
  fs.writeFileSync(outPath, JSON.stringify(out, null, 1));
}

main().catch((e) => {
  console.error(`view_check: ${e && e.stack ? e.stack : e}`);
  process.exit(1);
});
