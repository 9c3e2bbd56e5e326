// Shared by the end-to-end tests: start `voussoir serve`, drive Debian's Chromium with
// playwright-core, and run the CLI the page is compared with.
import { spawn, execFileSync, spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

// The repository root (tests/e2e/..): the tests run from anywhere.
export const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');
// The binary: VOUSSOIR_BIN, else the release build in cargo's target directory.
export const BIN = path.resolve(ROOT, process.env.VOUSSOIR_BIN
  || path.join(process.env.CARGO_TARGET_DIR || 'target', 'release', 'voussoir'));
export const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';

export function scenePath(name) {
  return path.join(ROOT, 'data', name);
}

// Starts `voussoir serve --port 0 SCENE` and resolves with its URL, read from the first line
// it prints (`voussoir serve: listening on http://127.0.0.1:PORT/`).
export function startServer(scene) {
  if (!existsSync(BIN)) {
    throw new Error(`${BIN} not found: build it with \`cargo build --release\` or set VOUSSOIR_BIN`);
  }
  const child = spawn(BIN, ['serve', '--port', '0', scene], {
    cwd: ROOT, stdio: ['ignore', 'pipe', 'pipe'],
  });
  let stderr = '';
  child.stderr.on('data', (d) => { stderr += d; });
  return new Promise((resolve, reject) => {
    let stdout = '';
    const timer = setTimeout(() => {
      child.kill();
      reject(new Error(`voussoir serve printed no URL within 20 s; stdout: ${stdout} stderr: ${stderr}`));
    }, 20000);
    child.stdout.on('data', (d) => {
      stdout += d;
      const line = stdout.split('\n')[0];
      if (!stdout.includes('\n')) return;
      const m = /^voussoir serve: listening on (http:\/\/127\.0\.0\.1:\d+\/)\s*$/.exec(line);
      clearTimeout(timer);
      if (!m) {
        child.kill();
        reject(new Error(`unexpected first line from voussoir serve: ${JSON.stringify(line)}`));
        return;
      }
      resolve({
        url: m[1],
        stop: () => new Promise((done) => {
          if (child.exitCode !== null || child.signalCode !== null) return done();
          child.once('exit', () => done());
          child.kill('SIGTERM');
        }),
        stderr: () => stderr,
      });
    });
    child.once('exit', (code) => {
      clearTimeout(timer);
      reject(new Error(`voussoir serve exited (${code}) before printing its URL: ${stderr}`));
    });
  });
}

export function launchBrowser() {
  if (!existsSync(CHROMIUM)) {
    throw new Error(`${CHROMIUM} not found: apt-get install chromium (or set CHROMIUM)`);
  }
  return chromium.launch({
    executablePath: CHROMIUM,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
}

// `voussoir analyze SCENE --json [--set KEY=VALUE ...] [--direction D]`, parsed.
// `direction` null: no --direction (a live action has none).
export function analyze(scene, sets = {}, direction = 'right') {
  const args = ['analyze', scene, '--json'];
  if (direction !== null) args.push('--direction', direction);
  for (const [k, v] of Object.entries(sets)) args.push('--set', `${k}=${v}`);
  return JSON.parse(execFileSync(BIN, args, { cwd: ROOT, encoding: 'utf8' }));
}

// The CLI run expected to fail: its exit code and stderr.
export function analyzeFails(scene, sets = {}) {
  const args = ['analyze', scene, '--json'];
  for (const [k, v] of Object.entries(sets)) args.push('--set', `${k}=${v}`);
  const r = spawnSync(BIN, args, { cwd: ROOT, encoding: 'utf8' });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

// Opens the page and waits for the first drawing.
export async function openPage(browser, url, viewport = { width: 1366, height: 768 }) {
  const context = await browser.newContext({ viewport, acceptDownloads: true });
  const page = await context.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`console: ${m.text()}`); });
  await page.goto(url);
  await settled(page);
  await page.waitForSelector('#v-drawing svg');
  return { page, context, problems };
}

// Waits until no analysis is in flight or pending (the page marks <body data-busy>).
export async function settled(page) {
  await page.waitForFunction(() => document.body.dataset.busy === 'false', null, { timeout: 20000 });
}

// Waits until the sweep chart has been drawn (or says why not).
export async function chartSettled(page) {
  await page.waitForFunction(() => document.body.dataset.sweeping === 'false', null, { timeout: 20000 });
}

// Clicks a download button and returns the downloaded file's path and text.
export async function download(page, buttonId) {
  const [dl] = await Promise.all([page.waitForEvent('download'), page.click(buttonId)]);
  const file = await dl.path();
  const { readFileSync } = await import('node:fs');
  return { file, name: dl.suggestedFilename(), text: readFileSync(file, 'utf8') };
}

// The slider and number field of a parameter.
export function field(page, key) {
  const row = page.locator(`.field[data-key="${key}"]`);
  return {
    row,
    slider: row.locator('input[type="range"]'),
    number: row.locator('input[type="number"]'),
    error: row.locator('.field-error'),
  };
}

export function median(xs) {
  const s = [...xs].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
}
