// Starts the studio server (the CLI's Release build) and Debian's Chromium under Playwright, for the browser tests
// and the docs' screenshots.
import { spawn } from 'node:child_process';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const cliDll = process.env.STUDIO_CLI ?? path.join(root, 'src/HairSim.Cli/bin/Release/net10.0/HairSim.Cli.dll');
export const chromiumPath = process.env.CHROMIUM ?? '/usr/bin/chromium';

/** Why the browser tests cannot run here, or null when they can. */
export function missing() {
  if (!existsSync(chromiumPath)) return `no Chromium at ${chromiumPath} (install Debian's chromium package, or set CHROMIUM)`;
  if (!existsSync(cliDll)) return `the CLI is not built at ${cliDll} (dotnet build -c Release src/HairSim.Cli)`;
  return null;
}

/** Runs `hairsim studio` on a free loopback port; resolves with its URL once it prints it. */
export function startServer(args = []) {
  const child = spawn('dotnet', [cliDll, 'studio', '--port', '0', ...args], { stdio: ['ignore', 'pipe', 'pipe'] });
  let output = '';
  const url = new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`the studio did not start within 60 s:\n${output}`)), 60_000);
    const read = chunk => {
      output += chunk;
      const m = /HairSheet Studio: (http:\/\/\S+)/.exec(output);
      if (m) { clearTimeout(timer); resolve(m[1]); }
    };
    child.stdout.on('data', read);
    child.stderr.on('data', read);
    child.on('exit', code => { clearTimeout(timer); reject(new Error(`the studio exited with ${code}:\n${output}`)); });
  });
  return { child, url, stop: () => child.kill('SIGINT') };
}

/** Headless Chromium with WebGL through SwiftShader (no GPU here) and no background connections (a closed network). */
export function launchBrowser() {
  return chromium.launch({
    executablePath: chromiumPath,
    headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
      '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
}

/** Polls fn until it returns a truthy value (or throws after timeoutMs with the last value). */
export async function until(fn, what, timeoutMs = 20_000) {
  const start = Date.now();
  let last;
  for (;;) {
    last = await fn();
    if (last) return last;
    if (Date.now() - start > timeoutMs) throw new Error(`timed out waiting for ${what} (last: ${JSON.stringify(last)})`);
    await new Promise(r => setTimeout(r, 100));
  }
}

/** Real-mouse helpers on a studio page: page coordinates of world points (through the page's camera) and drags. */
export function pageHelpers(page) {
  async function screen(point) {
    const [x, y] = await page.evaluate(p => window.studio.view.project(p), point);
    const box = await page.locator('#view').boundingBox();
    return [box.x + x, box.y + y];
  }
  async function drag(points) {
    await page.mouse.move(...points[0]);
    await page.mouse.down();
    for (const p of points.slice(1)) await page.mouse.move(...p, { steps: 4 });
    await page.mouse.up();
  }
  /** The strokes the tests and the docs use: a cut below the chin, a fringe selected by its roots, fitted slicked back. */
  async function cutBelowChin(y = -0.12) {
    await page.click('[data-tool=cut]');
    const left = await screen([-0.3, y, 0.1]), right = await screen([0.3, y, 0.1]);
    await drag([left, [(left[0] + right[0]) / 2, left[1]], right]);
  }
  /** Bangs: a short stroke across the forehead, in front of the face only, ending the hair that hangs over the eyes. */
  async function cutBangs(y = 0.025) {
    await page.click('[data-tool=cut]');
    const left = await screen([-0.065, y, 0.12]), right = await screen([0.065, y, 0.12]);
    await drag([left, [(left[0] + right[0]) / 2, left[1]], right]);
  }
  async function selectFringe() {
    await page.click('[data-tool=select]');
    const a = await screen([-0.035, 0.07, 0.08]), b = await screen([0.035, 0.05, 0.085]);   // a patch at the hairline
    await drag([a, [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2], b]);
  }
  /** From the side, as an artist would: a stroke from the forehead up and back over the crown (slicked back). */
  async function fitSlickedBack() {
    await page.click('[data-view=side]');
    await page.click('[data-tool=fit]');
    const stroke = [];
    for (let i = 0; i <= 16; i++) {
      const a = (50 - 140 * i / 16) * Math.PI / 180;   // 50° in front of the crown to 90° behind it
      stroke.push(await screen([0, 0.108 * Math.cos(a), 0.103 * Math.sin(a)]));
    }
    await drag(stroke);
    await page.click('[data-view=front]');
  }
  return { screen, drag, cutBelowChin, cutBangs, selectFringe, fitSlickedBack };
}
