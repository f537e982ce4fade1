// HairSheet Studio in a real browser: real mouse and keyboard events on the page, checked against the library's
// state as the server reports it. Run: npm test (after `dotnet build -c Release src/HairSim.Cli`).
import { describe, it, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { missing, startServer, launchBrowser, until, pageHelpers } from './harness.mjs';

const skip = missing();
if (skip) console.log(`studio browser tests: SKIPPED: ${skip}`);
const artifacts = process.env.STUDIO_ARTIFACTS ?? path.join(process.cwd(), 'artifacts');

describe('HairSheet Studio in Chromium', { skip: skip ?? false }, () => {
  let server, browser, page, url, ui;
  const api = async p => (await fetch(new URL(`api/${p}`, url))).json();
  const state = () => api('state');

  async function download(selector) {
    const [file] = await Promise.all([page.waitForEvent('download'), page.click(selector)]);
    return readFileSync(await file.path());
  }

  before(async () => {
    mkdirSync(artifacts, { recursive: true });
    server = startServer(['--groom', 'small']);
    url = await server.url;
    browser = await launchBrowser();
    page = await browser.newPage({ viewport: { width: 1200, height: 800 } });
    ui = pageHelpers(page);
    page.on('pageerror', e => console.log(`page error: ${e.message}`));
    await page.goto(url);
    await until(() => page.evaluate(() => window.studio?.ready && window.studio.framesReceived > 10), 'the first frames');
    // Let the hair settle so strokes meet it where it hangs.
    await until(async () => (await state()).simTime > 1.5, 'the hair to settle');
  });

  after(async () => {
    await browser?.close();
    server?.stop();
  });

  it('draws the hair and the head (not a blank canvas)', async () => {
    const stats = await page.evaluate(() => window.studio.view.pixelStats());
    await page.screenshot({ path: path.join(artifacts, 'studio.png') });
    assert.ok(stats.differing > 0.02, `only ${(100 * stats.differing).toFixed(2)} % of the canvas is drawn`);
    assert.ok(stats.colours > 100, `only ${stats.colours} colours on the canvas`);
    const s = await state();
    assert.equal(s.strands, 960);
    assert.ok(s.simHz > 0 || s.frame > 60, 'the simulation runs');
  });

  it('cuts the strands a mouse stroke crosses, at the stroke', async () => {
    const before = await state();
    await ui.cutBelowChin();
    const after = await until(async () => { const s = await state(); return s.cutStrands > 0 && s; }, 'the cut');
    assert.ok(after.cutStrands > 20, `${after.cutStrands} strands cut`);
    assert.ok(after.liveParticles < before.liveParticles, 'particles past the cut are gone');
    assert.ok(after.totalRestLength < before.totalRestLength - 0.05 * after.cutStrands * 0.25,
      `rest length ${before.totalRestLength.toFixed(2)} → ${after.totalRestLength.toFixed(2)} m`);
    assert.equal(after.undoCount, before.undoCount + 1);
    // The page drew the shorter strands: its topology follows the server's.
    await until(() => page.evaluate(r => window.studio.view.topology.revision === r, after.revision), 'the new topology');
  });

  it('selects the fringe with a rectangle and fits it to a stroke', async () => {
    const before = await state();
    const savedBefore = Buffer.from(await (await fetch(new URL('api/save', url))).arrayBuffer());
    await ui.selectFringe();
    const selected = await until(async () => { const s = await state(); return s.selection.length > 0 && s; }, 'a selection');
    assert.ok(selected.selection.length >= 5, `${selected.selection.length} strands selected`);
    await until(() => page.evaluate(() => window.studio.view.selection.size > 0), 'the selection highlighted');

    await ui.fitSlickedBack();
    const after = await until(async () => { const s = await state(); return s.undoCount === before.undoCount + 1 && s; }, 'the fit');
    assert.equal(after.message.startsWith('Fitted'), true, after.message);
    const savedAfter = Buffer.from(await (await fetch(new URL('api/save', url))).arrayBuffer());
    assert.notDeepEqual(savedAfter, savedBefore, 'the fit changed the haircut');
  });

  it('undoes with Ctrl+Z back to the uncut groom, and redoes', async () => {
    const before = await state();
    await page.keyboard.press('Control+z');
    await page.keyboard.press('Control+z');
    const undone = await until(async () => { const s = await state(); return s.undoCount === before.undoCount - 2 && s; }, 'two undos');
    assert.equal(undone.cutStrands, 0);
    assert.equal(undone.liveParticles, undone.particles);
    assert.equal(undone.totalRestLength, (await api('state')).totalRestLength);
    await page.click('#redo');
    const redone = await until(async () => { const s = await state(); return s.redoCount === 1 && s; }, 'a redo');
    assert.ok(redone.cutStrands > 0, 'the cut is back');
  });

  it('saves a .hairstyle, loads it back after another change, and gets the saved haircut', async () => {
    const saved = await state();
    const file = await download('#save');
    assert.equal(file.subarray(0, 4).toString('latin1').length, 4);
    writeFileSync(path.join(artifacts, 'haircut.hairstyle'), file);
    await page.click('#clear-selection');
    await until(async () => (await state()).selection.length === 0, 'the selection cleared');
    await page.click('#regrow');
    await until(async () => (await state()).cutStrands === 0, 'the regrow');
    await page.setInputFiles('#load-file', path.join(artifacts, 'haircut.hairstyle'));
    const loaded = await until(async () => { const s = await state(); return s.message.startsWith('Loaded') && s; }, 'the load');
    assert.equal(loaded.cutStrands, saved.cutStrands);
    assert.equal(loaded.liveParticles, saved.liveParticles);
    assert.ok(Math.abs(loaded.totalRestLength - saved.totalRestLength) < 1e-9, 'the same rest lengths');
  });

  it('refuses a corrupt file with a message and keeps the haircut', async () => {
    const before = await state();
    const bad = path.join(artifacts, 'corrupt.hairstyle');
    writeFileSync(bad, Buffer.from('not a hairstyle at all'));
    await page.setInputFiles('#load-file', bad);
    await until(() => page.evaluate(() => document.querySelector('#message').classList.contains('error')), 'the error message');
    const after = await state();
    assert.equal(after.liveParticles, before.liveParticles);
    assert.equal(after.cutStrands, before.cutStrands);
  });

  it('exports the strands as .hair, OBJ and USD', async () => {
    const hair = await download('a[href="api/export/hair"]');
    assert.equal(hair.subarray(0, 4).toString('latin1'), 'HAIR');
    const obj = (await download('a[href="api/export/obj"]')).toString();
    assert.match(obj, /^v /m);
    assert.match(obj, /^l /m);
    const usd = (await download('a[href="api/export/usda"]')).toString();
    assert.match(usd, /#usda 1\.0/);
  });

  it('changes settings live from the panel', async () => {
    await page.locator('#gravity').fill('0.5');
    await until(async () => Math.abs((await state()).settings.gravity - 0.5) < 1e-6, 'gravity 0.5 g');
    // Hair volume on the fast path (the reference path steps the full groom too slowly for a live check).
    await page.locator('#volumeFriction').fill('20');
    await until(async () => (await state()).settings.volumeFriction === 20, 'volume friction 20');
    await page.locator('#volumeDensity').fill('0.5');
    await until(async () => (await state()).settings.volumeDensity === 0.5, 'volume density 0.5');
    await page.check('#volume');
    await until(async () => (await state()).settings.volume === true, 'hair volume on');
    const before = (await state()).frame;
    await until(async () => { const s = await state(); return s.frame > before && s.metrics.nonFinite === 0; }, 'hair steps on, finite');
    await page.uncheck('#volume');
    await until(async () => (await state()).settings.volume === false, 'hair volume off');
    await page.selectOption('#path', 'Reference');
    await until(async () => (await state()).settings.path === 'Reference', 'the reference path');
  });

  it('grows a groom on the mesh head and draws the mesh', async () => {
    await page.selectOption('#groom', 'mesh head');
    await page.locator('#density').fill('4');
    await page.click('#grow');
    const s = await until(async () => { const t = await state(); return t.groom === 'mesh head' && t.hasMesh && t; }, 'the mesh groom', 60_000);
    assert.equal(s.strands, 1200);
    await until(() => page.evaluate(() => window.studio.view.meshGroup.children.length === 1), 'the head mesh drawn');
    await until(() => page.evaluate(r => window.studio.view.topology?.strands === 1200, s.revision), 'the new strands drawn');
    await page.screenshot({ path: path.join(artifacts, 'studio-mesh-head.png') });
  });

  it('paints the mesh head\'s scalp, grows hair only there, and undoes the stroke', async () => {
    const post = (p, body) => fetch(new URL(`api/${p}`, url), { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
    await page.click('[data-tool=paint]');
    await until(() => page.evaluate(() => window.studio.view.lines.visible === false), 'the hair hidden while painting');
    const start = (await state()).scalp;
    assert.ok(start.painted > 1000, `painting starts from the mesh's own scalp (${start.painted} triangles)`);
    await until(() => page.evaluate(n => window.studio.view.scalpShown() === n, start.painted), 'the scalp drawn on the head');

    // A degenerate stroke (a click with the rectangle) is refused with a message and changes nothing.
    await page.check('input[name=shape][value=rectangle]');
    const [cx, cy] = await ui.screen([0, 0.085, 0.05]);
    await page.mouse.click(cx, cy);
    await until(() => page.evaluate(() => document.querySelector('#message').classList.contains('error')), 'the refusal');
    assert.match(await page.textContent('#message'), /rectangle/);
    await page.check('input[name=shape][value=lasso]');
    await page.mouse.click(cx, cy);
    await until(async () => /lasso/.test(await page.textContent('#message')), 'the lasso refused');
    assert.equal((await state()).scalp.revision, start.revision);

    // Clear, then a brush stroke across the top of the forehead.
    await page.click('#scalp-clear');
    await until(async () => (await state()).scalp.painted === 0, 'the scalp cleared');
    await page.check('input[name=shape][value=brush]');
    const radius = await page.evaluate(() => window.studio.options.brushRadius);
    const from = [-0.04, 0.085, 0.05], to = [0.04, 0.085, 0.05];
    const a = await ui.screen(from), b = await ui.screen(to);
    await ui.drag([a, [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2], b]);
    const painted = await until(async () => { const s = await state(); return s.scalp.painted > 0 && s; }, 'the paint stroke');
    assert.ok(painted.scalp.painted > 20, `${painted.scalp.painted} triangles painted`);
    assert.ok(painted.scalp.growStrands > 0 && painted.scalp.growStrands < painted.strands, `${painted.scalp.growStrands} strands to grow`);
    assert.equal(painted.strands, 1200, 'painting leaves the hair alone');
    await until(() => page.evaluate(n => window.studio.view.scalpShown() === n, painted.scalp.painted), 'the painted patch drawn');
    await page.screenshot({ path: path.join(artifacts, 'studio-scalp-paint.png') });

    // A paint request without a camera, straight to the server: refused, the mask as it was.
    const bad = await post('scalp/paint', { shape: 'brush', points: [10, 10] });
    assert.equal(bad.status, 400);
    assert.equal((await state()).scalp.revision, painted.scalp.revision);

    // Grow: the groom's density on the painted patch, every root under the stroke.
    await page.click('#scalp-grow');
    const grown = await until(async () => { const s = await state(); return s.message.startsWith('Grew') && s; }, 'the hair grown on the scalp', 60_000);
    assert.equal(grown.strands, painted.scalp.growStrands);
    await until(() => page.evaluate(r => window.studio.view.topology?.revision === r && window.studio.lastHeader?.revision === r, grown.revision),
      'the new strands drawn');
    const off = await page.evaluate(([from, to, radius]) => {
      const view = window.studio.view, a = view.project(from), b = view.project(to);
      const d = [b[0] - a[0], b[1] - a[1]], len2 = d[0] ** 2 + d[1] ** 2;
      const far = [];
      for (const root of view.roots()) {
        const p = view.project(root);
        const t = Math.max(0, Math.min(1, ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2));
        const dist = Math.hypot(p[0] - a[0] - t * d[0], p[1] - a[1] - t * d[1]);
        if (dist > radius + 15) far.push(dist);
      }
      return { roots: view.roots().length, far };
    }, [from, to, radius]);
    assert.equal(off.roots, grown.strands);
    assert.deepEqual(off.far, [], `roots off the painted stroke (px from it): ${off.far.slice(0, 5).join(', ')}`);
    // The hair shown again over the painted scalp (the panel's switch), for the picture.
    await page.uncheck('#hide-hair');
    assert.equal(await page.evaluate(() => window.studio.view.lines.visible), true);
    await page.screenshot({ path: path.join(artifacts, 'studio-scalp-grown.png') });
    await page.check('#hide-hair');

    // Ctrl+Z in the paint tool takes back the stroke (the scalp is clear again), not the hair; Redo brings it back.
    await page.keyboard.press('Control+z');
    const undone = await until(async () => { const s = await state(); return s.scalp.painted === 0 && s; }, 'the stroke undone');
    assert.equal(undone.strands, grown.strands);
    await page.click('#redo');
    await until(async () => (await state()).scalp.painted === painted.scalp.painted, 'the stroke redone');

    // Back to the mesh's own scalp and the full groom for the tests that follow; the hair shows again outside the tool.
    await page.click('#scalp-colours');
    await until(async () => (await state()).scalp.painted === start.painted, 'the mesh colours\' scalp');
    await page.click('#scalp-grow');
    await until(async () => { const s = await state(); return s.strands === 1200 && s.message.startsWith('Grew') && s; }, 'the full groom', 60_000);
    await page.click('[data-tool=view]');
    assert.equal(await page.evaluate(() => window.studio.view.lines.visible), true);
  });

  it('cuts with a finger on a touch screen', async () => {
    // A second page with touch input (Chromium's own touch events, through the DevTools protocol): the same tool
    // code takes pointer events from a finger as from a mouse.
    const context = await browser.newContext({ viewport: { width: 1200, height: 800 }, hasTouch: true });
    const touchPage = await context.newPage();
    await touchPage.goto(url);
    await until(() => touchPage.evaluate(() => window.studio?.ready && window.studio.framesReceived > 3), 'the touch page');
    const before = await state();
    await touchPage.tap('[data-tool=cut]');
    const touchUi = pageHelpers(touchPage);
    const [x0, y] = await touchUi.screen([-0.3, -0.15, 0.1]), [x1] = await touchUi.screen([0.3, -0.15, 0.1]);
    const cdp = await context.newCDPSession(touchPage);
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [{ x: x0, y }] });
    for (let i = 1; i <= 20; i++) await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: [{ x: x0 + (x1 - x0) * i / 20, y }] });
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
    const after = await until(async () => { const t = await state(); return t.undoCount > before.undoCount && t; }, 'the touch cut');
    assert.ok(after.cutStrands > before.cutStrands, `${before.cutStrands} → ${after.cutStrands} cut strands`);
    await context.close();
  });

  it('moves and shakes the head from the keyboard', async () => {
    await page.click('[data-tool=view]');
    await page.keyboard.press('ArrowRight');
    await page.keyboard.press('Space');
    const s = await until(async () => { const t = await state(); return t.head.shake && t; }, 'the shake');
    assert.ok(Math.abs(s.head.position[0] - 0.01) < 1e-6, `head at x = ${s.head.position[0]}`);
    await page.keyboard.press('Space');
    await until(async () => !(await state()).head.shake, 'the shake to stop');
  });
});
