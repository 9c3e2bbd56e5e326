// End-to-end test of `voussoir report --pdf` (issue 27): the bundled portal's report printed
// to PDF by headless Chromium, the command's own way (`--pdf`) and through playwright's
// print of the same page; the page count of both agree and is what the chapters need; no
// figure is cut: under print media, at the A4 content width, every figure asks not to be
// split (break-inside: avoid) and fits in one page's content height, so Chromium's
// fragmentation keeps it whole; and with poppler's pdfinfo present, its page count agrees.
//
// Run from the repository root after `cargo build --release` and `npm ci --prefix tests/e2e`:
//   node --test tests/e2e/
// Skipped (with a note) where no Chromium is installed; CI installs Debian's (.ci/run).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { BIN, CHROMIUM, ROOT, launchBrowser, scenePath } from './helpers.mjs';

const skip = existsSync(CHROMIUM) ? false : `${CHROMIUM} not found: apt-get install chromium (or set CHROMIUM)`;

// Page objects of a PDF as Chromium writes them (uncompressed dictionaries `/Type /Page`).
function pdfPages(bytes) {
  const text = bytes.toString('latin1');
  return (text.match(/\/Type\s*\/Page(?![a-zA-Z])/g) || []).length;
}

// A4 at the page's margins (20 mm top, 18 mm bottom, 16 mm each side), in CSS pixels.
const MM = 96 / 25.4;
const CONTENT_WIDTH = (210 - 32) * MM;
const CONTENT_HEIGHT = (297 - 38) * MM;

test('the portal report prints to A4 PDF with every figure whole', { skip, timeout: 180000 }, async () => {
  const dir = mkdtempSync(path.join(os.tmpdir(), 'voussoir-report-'));
  const html = path.join(dir, 'report.html');
  const pdf = path.join(dir, 'report.pdf');
  execFileSync(BIN, ['report', scenePath('assess_portal.toml'), '-o', html, '--pdf', pdf], {
    cwd: ROOT, env: { ...process.env, VOUSSOIR_CHROMIUM: CHROMIUM },
  });
  const bytes = readFileSync(pdf);
  assert.equal(bytes.subarray(0, 5).toString('latin1'), '%PDF-');
  const pages = pdfPages(bytes);

  const browser = await launchBrowser();
  try {
    const context = await browser.newContext({ viewport: { width: Math.floor(CONTENT_WIDTH), height: 1000 } });
    const page = await context.newPage();
    const requests = [];
    page.on('request', (r) => { if (!r.url().startsWith('file:')) requests.push(r.url()); });
    await page.goto('file://' + html);
    await page.emulateMedia({ media: 'print' });
    const layout = await page.evaluate(() => ({
      chapters: document.querySelectorAll('section.chapter').length,
      newPages: [...document.querySelectorAll('section.chapter.new-page')]
        .filter((s) => getComputedStyle(s).breakBefore === 'page').length,
      figures: [...document.querySelectorAll('figure')].map((f) => ({
        id: f.id,
        height: f.getBoundingClientRect().height,
        avoid: getComputedStyle(f).breakInside,
      })),
    }));
    assert.deepEqual(requests, [], 'the page fetched something');
    assert.equal(layout.chapters, 9);
    assert.equal(layout.figures.length, 6);
    for (const f of layout.figures) {
      assert.equal(f.avoid, 'avoid', `${f.id} may be split across pages`);
      assert.ok(f.height > 50 && f.height <= CONTENT_HEIGHT, `${f.id} is ${f.height} px high, a page holds ${CONTENT_HEIGHT}`);
    }
    // Playwright's print of the same page (the CSS page size) has as many pages.
    const again = await page.pdf({ preferCSSPageSize: true });
    assert.equal(pdfPages(again), pages, 'the two prints disagree');
    // One page at least per chapter that starts a page, the first page, and no runaway.
    assert.ok(pages >= layout.newPages + 1 && pages <= 20, `${pages} pages`);
    await context.close();
  } finally {
    await browser.close();
  }
  const info = spawnSync('pdfinfo', [pdf], { encoding: 'utf8' });
  if (info.status === 0) {
    const m = /^Pages:\s+(\d+)/m.exec(info.stdout);
    assert.ok(m, info.stdout);
    assert.equal(Number(m[1]), pages, 'pdfinfo counts other pages');
    assert.match(info.stdout, /Page size:\s+59[45]\.\d+ x 84[12]\.\d+ pts \(A4\)/);
  }
});

test('--pdf without a browser says what it looked for', { timeout: 60000 }, () => {
  const dir = mkdtempSync(path.join(os.tmpdir(), 'voussoir-report-'));
  const r = spawnSync(BIN, ['report', scenePath('portal.toml'), '--pdf', path.join(dir, 'r.pdf')], {
    cwd: ROOT, encoding: 'utf8', env: { PATH: dir },
  });
  assert.notEqual(r.status, 0);
  assert.match(r.stderr, /no headless Chromium found \(looked for \$VOUSSOIR_CHROMIUM, then chromium, chromium-browser, google-chrome, google-chrome-stable on the PATH\)/);
  assert.match(r.stderr, /apt-get install chromium/);
  assert.equal(existsSync(path.join(dir, 'r.pdf')), false);
});
