// Measures how interactive the studio is per groom (simulation rate, frames the page receives and draws per second)
// in headless Chromium, and takes the docs' screenshots. Writes a markdown table.
// Run: node tests/studio/measure.mjs [--out docs/studio-figures.md] [--shots docs/img] [--seconds 6]
import { writeFileSync, mkdirSync } from 'node:fs';
import path from 'node:path';
import os from 'node:os';
import { missing, startServer, launchBrowser, until, pageHelpers } from './harness.mjs';

const arg = (name, fallback) => { const i = process.argv.indexOf(`--${name}`); return i > 0 ? process.argv[i + 1] : fallback; };
const out = arg('out', 'studio-figures.md'), shots = arg('shots', null), seconds = +arg('seconds', 6);
const grooms = (arg('grooms', 'small,medium,long,reference')).split(',');
const why = missing();
if (why) { console.error(`cannot measure: ${why}`); process.exit(1); }

const rows = [];
const browser = await launchBrowser();
for (const groom of grooms) {
  const server = startServer(['--groom', groom]);
  const url = await server.url;
  const page = await browser.newPage({ viewport: { width: 1200, height: 800 } });
  await page.goto(url);
  await until(() => page.evaluate(() => window.studio?.ready && window.studio.framesReceived > 3), 'frames', 60_000);
  await new Promise(r => setTimeout(r, 2000));   // past the JIT and the first uploads
  const api = async () => (await fetch(new URL('api/state', url))).json();
  const s0 = await api();
  const p0 = await page.evaluate(() => ({ received: window.studio.framesReceived, drawn: window.studio.framesDrawn, t: performance.now() }));
  await new Promise(r => setTimeout(r, seconds * 1000));
  const s1 = await api();
  const p1 = await page.evaluate(() => ({ received: window.studio.framesReceived, drawn: window.studio.framesDrawn, t: performance.now() }));
  const wall = (p1.t - p0.t) / 1000;
  rows.push({
    groom, strands: s1.strands, particles: s1.particles, stepMs: s1.stepMs,
    simHz: (s1.frame - s0.frame) / wall, received: (p1.received - p0.received) / wall, drawn: (p1.drawn - p0.drawn) / wall,
    frameKb: (64 + 6 * s1.particles) / 1024,
  });
  console.log(JSON.stringify(rows[rows.length - 1]));
  if (shots && groom === (process.env.SHOT_GROOM ?? 'reference')) {
    mkdirSync(shots, { recursive: true });
    await page.screenshot({ path: path.join(shots, 'studio.png') });
    // The same groom styled through the page as a user would: a cut below the chin, bangs cut above the eyes and a patch at the hairline fitted slicked back, then a side view.
    const ui = pageHelpers(page);
    await ui.cutBelowChin();
    await until(async () => (await api()).cutStrands > 0, 'the cut', 60_000);
    await ui.cutBangs();
    await until(async () => (await api()).undoCount === 2, 'the bangs', 60_000);
    await ui.selectFringe();
    await until(async () => (await api()).selection.length > 0, 'the selection', 60_000);
    await ui.fitSlickedBack();
    await until(async () => (await api()).undoCount === 3, 'the fit', 60_000);
    await page.click('[data-tool=view]');
    await page.click('#clear-selection');
    // The overlay is empty once a stroke is sent, but headless Chromium with software WebGL was seen compositing the
    // last stroke into later screenshots of the reference groom: hide it for the pictures.
    await page.evaluate(() => { window.studio.drawOverlay(); document.getElementById('overlay').style.visibility = 'hidden'; });
    await new Promise(r => setTimeout(r, 6000));
    await page.screenshot({ path: path.join(shots, 'studio-styled.png') });
    await page.click('[data-view=side]');
    await new Promise(r => setTimeout(r, 6000));
    await page.screenshot({ path: path.join(shots, 'studio-styled-side.png') });
  }
  await page.close();
  server.stop();
  await new Promise(r => setTimeout(r, 500));
}
await browser.close();

const table = [
  `Measured by \`node tests/studio/measure.mjs\` on ${os.cpus().length} cores (${os.cpus()[0]?.model ?? 'unknown CPU'}), headless`,
  'Chromium with software WebGL (SwiftShader: the machine that measured it has no GPU), server and browser on the same cores,',
  `${seconds} s per groom after 2 s of warm-up. "Simulation" counts 1/60 s frames stepped per wall second (60 = real time);`,
  '"received" and "drawn" are what the page fetched and rendered per second.',
  '',
  '| groom | strands | particles | step (ms) | simulation (frames/s) | frame size (KB) | received (frames/s) | drawn (frames/s) |',
  '| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |',
  ...rows.map(r => `| ${r.groom} | ${r.strands.toLocaleString('en')} | ${r.particles.toLocaleString('en')} | ${r.stepMs.toFixed(2)} | ` +
    `${r.simHz.toFixed(0)} | ${r.frameKb.toFixed(0)} | ${r.received.toFixed(1)} | ${r.drawn.toFixed(1)} |`),
  '',
].join('\n');
writeFileSync(out, table);
console.log(table);
