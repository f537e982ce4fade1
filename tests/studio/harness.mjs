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
