// End-to-end tests of the page of `voussoir serve` in headless Chromium (issue 17): the page's
// numbers are the CLI's for the same scene, errors are shown beside their field, the TOML it
// downloads re-analyses to the same multiplier, and an update takes under 50 ms for n <= 200.
//
// Run from the repository root after `cargo build --release` and `npm ci --prefix tests/e2e`:
//   node --test tests/e2e/
// VOUSSOIR_BIN names the binary (default target/release/voussoir), CHROMIUM the browser
// (default /usr/bin/chromium).
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  analyze, analyzeFails, chartSettled, download, field, launchBrowser, median, openPage,
  scenePath, settled, startServer,
} from './helpers.mjs';

const SCENE = scenePath('semicircular.toml');
let server;
let browser;

before(async () => {
  server = await startServer(SCENE);
  browser = await launchBrowser();
});

after(async () => {
  if (browser) await browser.close();
  if (server) await server.stop();
});

// The numbers the page shows: lambda in large type (4 decimals) and the two bounds (6).
async function shown(page) {
  return page.evaluate(() => ({
    lambda: document.getElementById('v-lambda').textContent,
    lower: document.getElementById('v-lower').textContent,
    upper: document.getElementById('v-upper').textContent,
    status: document.getElementById('v-status').dataset.status,
    drawing: document.querySelector('#v-drawing svg').outerHTML,
  }));
}

// The page writes a missing multiplier (null) as a dash.
const digits = (x, d) => (typeof x === 'number' ? x.toFixed(d) : '—');

function assertShows(s, cli, what) {
  assert.equal(s.status, cli.status, `${what}: status`);
  assert.equal(s.lambda, digits(cli.lambda_lower, 4), `${what}: lambda in large type`);
  assert.equal(s.lower, digits(cli.lambda_lower, 6), `${what}: lower bound`);
  assert.equal(s.upper, digits(cli.lambda_upper, 6), `${what}: upper bound`);
}

// Every field of `analyze --json` except wall times and the scene's origin (the page's scene
// came over HTTP, the CLI's from the file) must be the CLI's, exactly.
function sameAnalysis(page, cli, what) {
  const strip = (o) => {
    const c = JSON.parse(JSON.stringify(o));
    delete c.solve_time_s;
    delete c.kinematic_time_s;
    if (c.scene) delete c.scene.origin;
    return c;
  };
  assert.deepEqual(strip(page), strip(cli), `${what}: the downloaded JSON is the CLI's`);
}

test('the page opens on the scene of the command line with the CLI\'s multiplier', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    const cli = analyze(SCENE);
    assertShows(await shown(page), cli, 'first load');
    // The drawing is the server's SVG: blocks, thrust line, hinges, mechanism.
    for (const g of ['blocks', 'thrust-line', 'hinges', 'mechanism']) {
      assert.equal(await page.locator(`#v-drawing svg g[id="${g}"]`).count(), 1, `drawing has ${g}`);
    }
    // The thickness field shows the scene's value, with its unit.
    const t = field(page, 'arch.thickness');
    assert.equal(Number(await t.number.inputValue()), 0.15);
    assert.equal(Number(await t.slider.inputValue()), 0.15);
    assert.match(await t.row.locator('.unit').textContent(), /^m$/);
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test('moving the thickness slider changes lambda and the drawing to the CLI\'s values', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    const before = await shown(page);
    const t = field(page, 'arch.thickness');
    await t.slider.focus();
    for (let i = 0; i < 4; i++) await page.keyboard.press('ArrowRight');
    await settled(page);
    const value = await t.slider.inputValue();
    assert.ok(Number(value) > 0.15, `the slider moved up (${value})`);
    assert.equal(await t.number.inputValue(), value, 'the number field follows the slider');
    const after = await shown(page);
    assert.notEqual(after.lambda, before.lambda, 'lambda changed');
    assert.notEqual(after.drawing, before.drawing, 'the drawing changed');
    const cli = analyze(SCENE, { 'arch.thickness': value });
    assertShows(after, cli, `t = ${value}`);
    // Exactly, through the JSON the page downloads.
    const json = JSON.parse((await download(page, '#v-dl-json')).text);
    assert.equal(json.lambda_lower, cli.lambda_lower);
    assert.equal(json.lambda_upper, cli.lambda_upper);
    sameAnalysis(json, cli, `t = ${value}`);
    // The chart of lambda against the thickness has its marker at the slider's value.
    await chartSettled(page);
    assert.match(await page.locator('#v-chart-title').textContent(), /thickness/i);
    assert.ok(await page.locator('#v-chart svg polyline.series').count() >= 1, 'chart has a line');
    assert.equal(await page.locator('#v-chart svg circle.marker').count(), 1, 'chart has a marker');
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test('a burst of slider events ends on the last value (the drawing never lags behind)', async () => {
  const { page, context } = await openPage(browser, server.url);
  try {
    // Count the analysis requests in flight at once: never more than one.
    let open = 0;
    let most = 0;
    let sent = 0;
    const isAnalysis = (r) => r.url().endsWith('/api/analyze');
    page.on('request', (r) => { if (isAnalysis(r)) { sent += 1; open += 1; most = Math.max(most, open); } });
    const done = (r) => { if (isAnalysis(r)) open -= 1; };
    page.on('requestfinished', done);
    page.on('requestfailed', done);
    const t = field(page, 'arch.thickness');
    await t.slider.focus();
    const events = 12;
    for (let i = 0; i < events; i++) await page.keyboard.press('ArrowRight');
    await settled(page);
    const value = await t.slider.inputValue();
    assert.equal(Number(value), 0.21, 'twelve steps of 0.005 from 0.15');
    assert.equal(most, 1, 'at most one analysis request in flight');
    assert.ok(sent >= 1 && sent <= events, `${sent} requests for ${events} events`);
    assertShows(await shown(page), analyze(SCENE, { 'arch.thickness': value }), `t = ${value}`);
  } finally {
    await context.close();
  }
});

test('validation errors are shown beside the field they name, and cleared', async () => {
  const { page, context } = await openPage(browser, server.url);
  try {
    const cases = [['arch.thickness', '0'], ['arch.radius', '-1']];
    for (const [key, bad] of cases) {
      // The CLI refuses the same value, naming the key.
      const cli = analyzeFails(SCENE, { [key]: bad });
      assert.notEqual(cli.status, 0);
      assert.match(cli.stderr, new RegExp(key.replace('.', '\\.')));
      const f = field(page, key);
      const good = await f.number.inputValue();
      await f.number.fill(bad);
      await f.number.press('Enter');
      await settled(page);
      await f.error.waitFor({ state: 'visible' });
      const message = await f.error.textContent();
      assert.match(message, new RegExp(key.split('.')[1]), `the message names ${key}: ${message}`);
      assert.ok(await f.row.evaluate((r) => r.classList.contains('has-error')));
      assert.ok(await page.locator('#v-message').isHidden(), 'no general message for a named field');
      // Only that field shows an error, and downloads wait for a valid scene.
      assert.equal(await page.locator('.field-error:visible').count(), 1);
      assert.ok(await page.locator('#v-dl-toml').isDisabled());
      // Putting the value back clears it.
      await f.number.fill(good);
      await f.number.press('Enter');
      await settled(page);
      await f.error.waitFor({ state: 'hidden' });
      assert.ok(await page.locator('#v-dl-toml').isEnabled());
    }
    // The server's own limit (the CLI takes more) is shown the same way, with the limit.
    const limits = await page.evaluate(async () => (await (await fetch('/api/parameters')).json()).limits);
    const n = field(page, 'arch.voussoirs');
    await n.number.fill(String(limits.max_voussoirs + 2));
    await n.number.press('Enter');
    await settled(page);
    await n.error.waitFor({ state: 'visible' });
    assert.match(await n.error.textContent(), new RegExp(`at most ${limits.max_voussoirs}`));
    await n.number.fill('32');
    await n.number.press('Enter');
    await settled(page);
    await n.error.waitFor({ state: 'hidden' });
    assertShows(await shown(page), analyze(SCENE), 'after the errors');
  } finally {
    await context.close();
  }
});

test('the downloaded TOML re-analyses with the CLI to the same lambda', async () => {
  const { page, context } = await openPage(browser, server.url);
  try {
    const t = field(page, 'arch.thickness');
    await t.number.fill('0.2');
    await t.number.press('Enter');
    const n = field(page, 'arch.voussoirs');
    await n.number.fill('48');
    await n.number.press('Enter');
    await settled(page);
    const toml = await download(page, '#v-dl-toml');
    assert.match(toml.name, /\.toml$/);
    const dir = mkdtempSync(path.join(os.tmpdir(), 'voussoir-e2e-'));
    const file = path.join(dir, 'scene.toml');
    writeFileSync(file, toml.text);
    const again = analyze(file);
    const json = JSON.parse((await download(page, '#v-dl-json')).text);
    assert.equal(again.lambda_lower, json.lambda_lower, 'same lambda_lower, exactly');
    assert.equal(again.scene.thickness, 0.2);
    assert.equal(again.scene.voussoirs, 48);
    sameAnalysis(json, again, 'the downloaded TOML');
    // And the drawing downloaded is an SVG document of that scene.
    const svg = await download(page, '#v-dl-svg');
    assert.match(svg.text, /<svg[\s>]/);
    assert.match(svg.text, /t = 0\.2 m, 48 voussoirs/);
  } finally {
    await context.close();
  }
});

test('a preset and the direction toggle give the CLI\'s values for that scene', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    await page.click('#v-shapes button[data-preset="portal"]');
    await settled(page);
    assert.equal(await field(page, 'piers.height').row.count(), 1, 'the piers\' fields appear');
    await page.click('#v-direction button[data-direction="left"]');
    await settled(page);
    const dir = mkdtempSync(path.join(os.tmpdir(), 'voussoir-e2e-'));
    const file = path.join(dir, 'portal.toml');
    writeFileSync(file, (await download(page, '#v-dl-toml')).text);
    const cli = analyze(file, {}, 'left');
    assert.equal(cli.scene.portal, true);
    assertShows(await shown(page), cli, 'portal, leftward');
    const json = JSON.parse((await download(page, '#v-dl-json')).text);
    assert.equal(json.direction, 'left');
    sameAnalysis(json, cli, 'portal, leftward');
    // The portal is symmetric: to the left it fails at the multiplier it has to the right,
    // with the mirror image of its hinges (joint j of J + 1 joints becomes J - j).
    const right = analyze(file, {}, 'right');
    assert.ok(Math.abs(json.lambda_lower - right.lambda_lower) <= 1e-9 * right.lambda_lower,
      `left ${json.lambda_lower}, right ${right.lambda_lower}`);
    const last = json.joints.length - 1;
    assert.deepEqual(json.hinges.map((h) => last - h.joint).sort((a, b) => a - b),
      right.hinges.map((h) => h.joint).sort((a, b) => a - b));
    // The chart of the pier height (1 m, a whole number in JSON) runs over real values.
    const swept = page.waitForResponse((r) => r.url().endsWith('/api/sweep'));
    const h = field(page, 'piers.height');
    await h.slider.focus();
    await page.keyboard.press('ArrowRight');
    const rows = (await (await swept).json()).rows;
    const asked = JSON.parse((await swept).request().postData()).points;
    assert.equal(rows.length, asked, 'one row per point asked for');
    assert.ok(rows.some((r) => !Number.isInteger(r.value)), 'pier heights between whole metres');
    await settled(page);
    await chartSettled(page);
    assert.match(await page.locator('#v-chart-title').textContent(), /pier height/i);
    // Back to a plain arch: the piers' fields go away.
    await page.click('#v-shapes button[data-preset="circular"]');
    await settled(page);
    assert.equal(await field(page, 'piers.height').row.count(), 0);
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test('the line-load slider of the loaded portal gives the CLI\'s values for that load', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    await page.click('#v-shapes button[data-preset="loaded_portal"]');
    await settled(page);
    // loads[0] is a point load (no intensity): only the line load, loads[1], has a slider.
    assert.equal(await field(page, 'loads[0].intensity').row.count(), 0);
    const q = field(page, 'loads[1].intensity');
    assert.equal(await q.row.count(), 1);
    const before = await shown(page);
    await q.slider.focus();
    for (let i = 0; i < 4; i++) await page.keyboard.press('ArrowRight');
    await settled(page);
    const value = Number(await q.number.inputValue());
    assert.ok(value > 6000, `the intensity moved up from 6000 N/m: ${value}`);
    const cli = analyze(scenePath('loaded_portal.toml'), { 'loads[1].intensity': value });
    const after = await shown(page);
    assertShows(after, cli, `loads[1].intensity = ${value}`);
    assert.ok(Number(after.lambda) < Number(before.lambda), 'a heavier deck load lowers lambda here');
    sameAnalysis(JSON.parse((await download(page, '#v-dl-json')).text), cli, 'line load');
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test('an update takes under 50 ms (median) for 200 voussoirs', async (t) => {
  const { page, context } = await openPage(browser, server.url);
  try {
    const n = field(page, 'arch.voussoirs');
    await n.number.fill('200');
    await n.number.press('Enter');
    await settled(page);
    const th = field(page, 'arch.thickness');
    await th.slider.focus();
    // The first move starts the chart's sweep; let it finish so it does not share the cores.
    await page.keyboard.press('ArrowRight');
    await settled(page);
    await chartSettled(page);
    await page.evaluate(() => { window.voussoirTimings.length = 0; });
    const moves = 30;
    for (let i = 0; i < moves; i++) {
      await page.keyboard.press(i % 10 < 5 ? 'ArrowRight' : 'ArrowLeft');
      await settled(page);
    }
    const timings = await page.evaluate(() => window.voussoirTimings.slice());
    assert.equal(timings.length, moves, 'one timed update per slider event');
    const json = JSON.parse((await download(page, '#v-dl-json')).text);
    assert.equal(json.blocks, 200);
    assert.equal(json.lambda_lower, analyze(SCENE, {
      'arch.voussoirs': 200, 'arch.thickness': await th.slider.inputValue(),
    }).lambda_lower);
    const med = median(timings);
    const max = Math.max(...timings);
    const load = os.loadavg().map((x) => x.toFixed(2)).join(' ');
    t.diagnostic(`update latency, n = 200, ${moves} slider events: median ${med.toFixed(1)} ms, `
      + `max ${max.toFixed(1)} ms (load average ${load})`);
    assert.ok(med < 50, `median update ${med.toFixed(1)} ms, over 50 ms`);
    // The page shows the last update time.
    assert.match(await page.locator('#v-timing').textContent(), /updated in \d+ ms/);
  } finally {
    await context.close();
  }
});
