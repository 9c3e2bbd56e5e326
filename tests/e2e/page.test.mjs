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

// The page's console errors, less the browser's note of each 400 answer (a refusal the
// test asked for).
const unexpected = (problems) => problems.filter((p) => !/status of 400 \(Bad Request\)/.test(p));

// The page writes a missing multiplier (null) as a dash.
const digits = (x, d) => (typeof x === 'number' ? x.toFixed(d) : '—');

function assertShows(s, cli, what) {
  assert.equal(s.status, cli.status, `${what}: status`);
  // The large number is the governing multiplier (the non-associative one when computed).
  const big = typeof cli.lambda_governing === 'number' ? cli.lambda_governing : cli.lambda_lower;
  assert.equal(s.lambda, digits(big, 4), `${what}: lambda in large type`);
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
    // Twelve input events in one task, as a fast drag delivers them: the first is sent, the
    // other eleven arrive while it is in flight and are merged into one request.
    const events = 12;
    await t.slider.evaluate((slider, n) => {
      for (let i = 0; i < n; i++) {
        slider.stepUp();
        slider.dispatchEvent(new Event('input', { bubbles: true }));
      }
    }, events);
    await settled(page);
    const value = await t.slider.inputValue();
    assert.equal(Number(value), 0.21, 'twelve steps of 0.005 from 0.15');
    assert.equal(most, 1, 'at most one analysis request in flight');
    assert.ok(sent >= 1 && sent < events, `events were merged: ${sent} requests for ${events} events`);
    assert.equal(sent, 2, 'the first event\'s scene, then the last one\'s');
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
    // A portal's arch must embrace 180 degrees: no Embrace field (`not_with: ["piers"]`).
    await page.click('#v-shapes button[data-preset="portal"]');
    await settled(page);
    assert.equal(await field(page, 'piers.height').row.count(), 1, 'the piers\' fields appear');
    assert.equal(await field(page, 'arch.embrace_deg').row.count(), 0, 'no Embrace field on a portal');
    // The loaded portal is not symmetric (a point load on its right haunch): the direction
    // changes lambda, so a TOML read back in the wrong direction would be caught.
    await page.click('#v-shapes button[data-preset="loaded_portal"]');
    await settled(page);
    assert.equal(await field(page, 'arch.embrace_deg').row.count(), 0, 'no Embrace field on a portal');
    await page.click('#v-direction button[data-direction="left"]');
    await settled(page);
    const toml = await download(page, '#v-dl-toml');
    assert.match(toml.name, /-left\.toml$/, `the file name says left: ${toml.name}`);
    const first = toml.text.split('\n')[0];
    assert.match(first, /^# analysed with the earthquake to the left: voussoir analyze FILE --direction left\s*$/,
      `the TOML's first line tells the direction: ${first}`);
    const dir = mkdtempSync(path.join(os.tmpdir(), 'voussoir-e2e-'));
    const file = path.join(dir, toml.name);
    writeFileSync(file, toml.text);
    const cli = analyze(file, {}, 'left');
    assert.equal(cli.scene.portal, true);
    assertShows(await shown(page), cli, 'loaded portal, leftward');
    const json = JSON.parse((await download(page, '#v-dl-json')).text);
    assert.equal(json.direction, 'left');
    assert.equal(cli.lambda_lower, json.lambda_lower, 'the CLI to the left on the TOML: the page\'s lambda_lower exactly');
    sameAnalysis(json, cli, 'loaded portal, leftward');
    const right = analyze(file, {}, 'right');
    assert.ok(Math.abs(json.lambda_lower - right.lambda_lower) > 1e-3 * right.lambda_lower,
      `the direction matters here: left ${json.lambda_lower}, right ${right.lambda_lower}`);
    assert.equal(right.lambda_lower, analyze(scenePath('loaded_portal.toml')).lambda_lower,
      'to the right, the TOML is the bundled scene');
    // The chart of the pier height (a whole number in JSON) runs over real values.
    const swept = page.waitForResponse((r) => r.url().endsWith('/api/sweep'));
    const h = field(page, 'piers.height');
    await h.slider.focus();
    await page.keyboard.press('ArrowRight');
    const rows = (await (await swept).json()).rows;
    const asked = JSON.parse((await swept).request().postData());
    assert.equal(asked.direction, 'left', 'the chart is of the leftward multiplier');
    assert.equal(rows.length, asked.points, 'one row per point asked for');
    assert.ok(rows.some((r) => !Number.isInteger(r.value)), 'pier heights between whole metres');
    await settled(page);
    await chartSettled(page);
    assert.match(await page.locator('#v-chart-title').textContent(), /pier height/i);
    // Back to a plain arch: the piers' fields go away, the Embrace field comes back.
    await page.click('#v-shapes button[data-preset="circular"]');
    await settled(page);
    assert.equal(await field(page, 'piers.height').row.count(), 0);
    assert.equal(await field(page, 'arch.embrace_deg').row.count(), 1);
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

test('the bridge preset: the axle slider moves the tandem and the adequacy factor follows the CLI', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    // Opened with the earthquake pointing left: live loads have no earthquake, so the page
    // goes on to the right (the server refuses a direction there) and hides what means nothing.
    await page.click('#v-direction button[data-direction="left"]');
    await settled(page);
    await page.click('#v-shapes button[data-preset="bridge"]');
    await settled(page);
    const bridge = scenePath('rolling_bridge.toml');
    assertShows(await shown(page), analyze(bridge, {}, null), 'bridge as bundled');
    assert.equal(await page.locator('#v-message').isVisible(), false, 'no error is shown');
    assert.equal(await page.locator('#v-direction button[data-direction="right"]').getAttribute('aria-pressed'), 'true');
    assert.equal(await page.locator('.direction').isVisible(), false, 'no earthquake direction for live loads');
    assert.equal(await page.locator('fieldset[data-section="seismic"]').isVisible(), false,
      'no vertical acceleration for live loads');
    assert.equal(await page.locator('#v-na-row').isVisible(), false, 'no empty non-associative row');
    const at = field(page, 'vehicles[0].at');
    assert.equal(await at.row.count(), 1, 'the vehicle position has a field');
    const before = Number(await at.number.inputValue());
    const swept = page.waitForResponse((r) => r.url().endsWith('/api/sweep'));
    await at.slider.focus();
    for (let i = 0; i < 6; i++) await page.keyboard.press('ArrowRight');
    await settled(page);
    const value = Number(await at.number.inputValue());
    assert.ok(value > before, `the tandem moved right from ${before}: ${value}`);
    const cli = analyze(bridge, { 'vehicles[0].at': value }, null);
    assertShows(await shown(page), cli, `vehicles[0].at = ${value}`);
    assert.notEqual(cli.lambda_lower, analyze(bridge, {}, null).lambda_lower, 'the position matters');
    // The chart is lambda against the position: every row a position on the arch.
    const rows = (await (await swept).json()).rows;
    assert.ok(rows.length > 2 && rows.every((r) => typeof r.lambda_lower === 'number'),
      'every position of the chart has a multiplier');
    await chartSettled(page);
    assert.match(await page.locator('#v-chart-title').textContent(), /vehicle position/i);
    assert.deepEqual(unexpected(problems), []);
  } finally {
    await context.close();
  }
});

test('the chart recovers once a refused value is corrected', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    await chartSettled(page);
    const n = field(page, 'arch.voussoirs');
    // 12.5 voussoirs: the server refuses the analysis and the chart's sweep (wrong type).
    const refused = analyzeFails(SCENE, { 'arch.voussoirs': '12.5' });
    assert.notEqual(refused.status, 0);
    await n.number.fill('12.5');
    await n.number.press('Enter');
    await settled(page);
    await chartSettled(page);
    await n.error.waitFor({ state: 'visible' });
    assert.equal(await page.locator('#v-chart svg').count(), 0, 'no chart for a refused scene');
    assert.match(await page.locator('#v-chart').textContent(), /voussoirs/, 'the chart says why');
    // A valid value: the chart of the voussoirs is drawn (the failed sweep is not remembered).
    await n.number.fill('24');
    await n.number.press('Enter');
    await settled(page);
    await chartSettled(page);
    await n.error.waitFor({ state: 'hidden' });
    assert.match(await page.locator('#v-chart-title').textContent(), /voussoirs/i);
    assert.ok(await page.locator('#v-chart svg polyline.series').count() >= 1, 'the chart has its line');
    assert.equal(await page.locator('#v-chart svg circle.marker').count(), 1, 'and its marker');
    assert.equal(await page.locator('#v-chart .placeholder').count(), 0, 'and no message');
    assertShows(await shown(page), analyze(SCENE, { 'arch.voussoirs': 24 }), 'n = 24');
    assert.deepEqual(unexpected(problems), []);
  } finally {
    await context.close();
  }
});

test('a value typed beyond the slider widens it, and the slider steps on from there', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    const t = field(page, 'arch.thickness');
    const [lo, hi] = await t.row.locator('.bound').allTextContents();
    assert.ok(Number(hi) < 0.7, `0.7 is beyond the slider (${lo} to ${hi})`);
    await t.number.fill('0.7');
    await t.number.press('Enter');
    await settled(page);
    assert.equal(await t.slider.inputValue(), '0.7', 'the slider holds the value typed');
    assert.equal(await t.slider.getAttribute('max'), '0.7');
    assert.deepEqual(await t.row.locator('.bound').allTextContents(), [lo, '0.7'], 'the new end is shown');
    await t.slider.focus();
    await page.keyboard.press('ArrowLeft');
    await settled(page);
    assert.equal(await t.slider.inputValue(), '0.695', 'one step down from 0.7');
    assert.equal(await t.number.inputValue(), '0.695');
    assertShows(await shown(page), analyze(SCENE, { 'arch.thickness': 0.695 }), 't = 0.695');
    // A value the server refuses does not widen the slider: 0 goes back to the range.
    await t.number.fill('0');
    await t.number.press('Enter');
    await settled(page);
    await t.error.waitFor({ state: 'visible' });
    assert.equal(await t.slider.getAttribute('min'), lo, 'the refused 0 leaves the range as it was');
    assert.deepEqual(await t.row.locator('.bound').allTextContents(), [lo, '0.7']);
    assert.deepEqual(unexpected(problems), []);
  } finally {
    await context.close();
  }
});

test('a pointed arch\'s voussoir slider takes even numbers only, and its chart refuses none for parity', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    await page.click('#v-shapes button[data-preset="pointed"]');
    await settled(page);
    const n = field(page, 'arch.voussoirs');
    assert.equal(await n.slider.getAttribute('step'), '2');
    assert.equal(await n.number.getAttribute('step'), '2');
    const seen = [];
    await n.slider.focus();
    const swept = page.waitForResponse((r) => r.url().endsWith('/api/sweep')
      && JSON.parse(r.request().postData()).key === 'arch.voussoirs');
    // End reaches the slider's top (more voussoirs than this arch's geometry takes: refused,
    // as the CLI refuses it); the last value, a page up from the bottom, is valid.
    for (const key of ['ArrowRight', 'ArrowRight', 'ArrowLeft', 'End', 'ArrowLeft', 'Home', 'ArrowRight', 'PageUp']) {
      await page.keyboard.press(key);
      seen.push(Number(await n.slider.inputValue()));
    }
    await settled(page);
    assert.ok(seen.every((v) => Number.isInteger(v) && v % 2 === 0), `even values only: ${seen}`);
    assert.equal(seen[1], 36, 'two steps of 2 from 32');
    // The page shows the CLI's values for the slider's last value.
    const last = seen[seen.length - 1];
    assertShows(await shown(page), analyze(scenePath('pointed.toml'), { 'arch.voussoirs': last }), `n = ${last}`);
    // The chart asks for even counts only: none is refused for being odd. (A count the
    // geometry cannot take, the CLI refuses too.)
    const response = await swept;
    const rows = (await response.json()).rows;
    const body = JSON.parse(response.request().postData());
    assert.equal(body.key, 'arch.voussoirs');
    assert.ok(rows.length >= 2);
    assert.ok(rows.every((r) => r.value % 2 === 0), `even values: ${rows.map((r) => r.value)}`);
    assert.deepEqual(rows.filter((r) => r.error && /even/.test(r.error)), [], 'none refused as odd');
    for (const r of rows.filter((x) => x.error)) {
      const cli = analyzeFails(scenePath('pointed.toml'), { 'arch.voussoirs': r.value });
      assert.notEqual(cli.status, 0, `the CLI refuses n = ${r.value} too`);
    }
    await chartSettled(page);
    assert.ok(await page.locator('#v-chart svg polyline.series').count() >= 1);
    const refusedRows = rows.filter((r) => r.error).length;
    const legend = await page.locator('#v-chart').textContent();
    if (refusedRows === 0) assert.doesNotMatch(legend, /refused/);
    else assert.match(legend, new RegExp(`${refusedRows} of ${rows.length} values refused`));
    assert.deepEqual(unexpected(problems), []);
  } finally {
    await context.close();
  }
});

// A shown field holds the scene's value, what leaving the key out means, or nothing.
async function noMadeUpValues(page) {
  const bad = await page.evaluate(() => {
    const { state } = window.voussoir;
    const get = (obj, key) => key.replace(/\[(\d+)\]/g, '.$1').split('.')
      .reduce((o, k) => (o !== null && typeof o === 'object' && k in o ? o[k] : undefined), obj);
    const out = [];
    // (A list field, a stepped pier's widths, is checked by its own test.)
    for (const row of document.querySelectorAll('.field:not(.field-list)')) {
      const p = state.byKey.get(row.dataset.key);
      const number = row.querySelector('input[type="number"]');
      const v = get(state.scene, p.key);
      const absent = typeof p.absent === 'string' ? p.absent.split(/\s+/)[0] : undefined;
      const ok = v !== undefined ? Number(number.value) === v
        : absent === 'inf' ? number.value === '' && number.placeholder === '∞'
          : absent !== undefined ? Number(number.value) === Number(absent) : number.value === '';
      if (!ok) out.push(`${p.key}: "${number.value}" (scene: ${v}, absent: ${p.absent})`);
    }
    return out;
  });
  assert.deepEqual(bad, [], 'fields show only the scene\'s values or what leaving them out means');
}

test('a scene of user blocks opens with the CLI\'s lambda and no chart error', async () => {
  const blocks = scenePath('blocks_dxf_arch.toml');
  const other = await startServer(blocks);
  const { page, context, problems } = await openPage(browser, other.url);
  try {
    await chartSettled(page);
    const cli = analyze(blocks);
    assertShows(await shown(page), cli, 'blocks from a DXF');
    // No arch keys: nothing to chart until a slider is moved, and no refusal shown.
    assert.equal(await field(page, 'arch.thickness').row.count(), 0);
    assert.equal(await page.locator('#v-chart svg').count(), 0);
    assert.match(await page.locator('#v-chart').textContent(), /^Move a slider to chart λ/);
    assert.ok(await page.locator('#v-message').isHidden(), 'no banner');
    assert.equal(await page.locator('.field-error:visible').count(), 0, 'no field error');
    await noMadeUpValues(page);
    // Its line load's slider: the CLI's value, and a chart with no refusal.
    const q = field(page, 'loads[0].intensity');
    await q.slider.focus();
    await page.keyboard.press('ArrowRight');
    await settled(page);
    await chartSettled(page);
    const value = Number(await q.number.inputValue());
    assert.ok(value > 20000, `the line load moved up: ${value}`);
    assertShows(await shown(page), analyze(blocks, { 'loads[0].intensity': value }), `q = ${value}`);
    assert.ok(await page.locator('#v-chart svg polyline.series').count() >= 1, 'the chart of the line load');
    assert.doesNotMatch(await page.locator('#v-chart').textContent(), /refused|could not/);
    // The TOML names its blocks file by an absolute path: saved elsewhere, it analyses to the
    // page's multiplier.
    const toml = await download(page, '#v-dl-toml');
    const file = path.join(mkdtempSync(path.join(os.tmpdir(), 'voussoir-e2e-')), toml.name);
    writeFileSync(file, toml.text);
    const json = JSON.parse((await download(page, '#v-dl-json')).text);
    assert.equal(analyze(file).lambda_lower, json.lambda_lower, 'the TOML saved elsewhere: the same lambda_lower');
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
    await other.stop();
  }
});

test('piers given side by side ([piers.left], [piers.right]) have no common pier sliders', async () => {
  const dir = mkdtempSync(path.join(os.tmpdir(), 'voussoir-e2e-'));
  const file = path.join(dir, 'unequal_piers.toml');
  writeFileSync(file, [
    '[arch]', 'shape = "circular"', 'radius = 1.0', 'thickness = 0.2', 'voussoirs = 32', '',
    '[piers]', 'height = 1.2', 'width = 0.4', 'courses = 3', '',
    '[piers.right]', 'height = 0.8', '',
    '[material]', 'unit_weight = 20000.0', 'depth = 1.0', '',
  ].join('\n'));
  const other = await startServer(file);
  const { page, context, problems } = await openPage(browser, other.url);
  try {
    for (const key of ['piers.height', 'piers.width', 'piers.courses', 'arch.embrace_deg']) {
      assert.equal(await field(page, key).row.count(), 0, `no ${key} field`);
    }
    assert.equal(await field(page, 'arch.thickness').row.count(), 1);
    await noMadeUpValues(page);
    for (const direction of ['right', 'left']) {
      await page.click(`#v-direction button[data-direction="${direction}"]`);
      await settled(page);
      assertShows(await shown(page), analyze(file, {}, direction), `unequal piers, ${direction}`);
    }
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
    await other.stop();
  }
});

// WCAG contrast of two CSS colours (rgb()/rgba() as getComputedStyle writes them).
function contrast(fg, bg) {
  const lum = (c) => {
    const [r, g, b] = c.match(/[\d.]+/g).slice(0, 3).map(Number).map((v) => {
      const x = v / 255;
      return x <= 0.03928 ? x / 12.92 : ((x + 0.055) / 1.055) ** 2.4;
    });
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
  };
  const [a, b] = [lum(fg), lum(bg)].sort((x, y) => y - x);
  return (a + 0.05) / (b + 0.05);
}

test('accessibility: labels, descriptions, live errors, readable faint text, quiet results', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    const params = await page.evaluate(async () => (await (await fetch('/api/parameters')).json()).parameters);
    const friction = params.find((p) => p.key === 'material.friction');
    const box = field(page, 'material.friction').row.locator('input[type="checkbox"]');
    assert.equal(await box.getAttribute('aria-label'), `${friction.label}: infinite`);
    assert.equal(friction.label, 'Friction coefficient');
    // Each number field and slider is described by its error and its help; the help is in the
    // page (for a screen reader) though not shown, the error is a polite live region.
    const t = field(page, 'arch.thickness');
    const thickness = params.find((p) => p.key === 'arch.thickness');
    for (const input of [t.number, t.slider]) {
      const ids = (await input.getAttribute('aria-describedby')).split(/\s+/);
      const texts = await Promise.all(ids.map((id) => page.locator(`[id="${id}"]`).evaluate((e) => ({
        text: e.textContent, live: e.getAttribute('aria-live'), cls: e.className,
      }))));
      assert.ok(texts.some((x) => x.text === thickness.help), 'described by its help');
      assert.ok(texts.some((x) => x.cls === 'field-error' && x.live === 'polite'), 'and by its live error');
    }
    // The help is shown (not only read) while the field or its slider has the focus.
    const help = t.row.locator('.field-help');
    const width = async () => (await help.boundingBox()).width;
    assert.ok(await width() <= 1, 'the help takes no room without focus');
    await t.slider.focus();
    assert.ok(await width() > 100, 'the help is shown while the slider has focus');
    await t.slider.blur();
    await t.number.fill('0');
    await t.number.press('Enter');
    await settled(page);
    await t.error.waitFor({ state: 'visible' });
    assert.equal(await t.error.getAttribute('aria-live'), 'polite');
    assert.match(await t.error.textContent(), /thickness/);
    await t.number.fill('0.15');
    await t.number.press('Enter');
    await settled(page);
    // Faint text (range ends, the update time) reaches 4.5:1 on its background.
    for (const [sel, bgSel] of [['.field .bound', '.panel'], ['#v-timing', 'body']]) {
      const fg = await page.locator(sel).first().evaluate((e) => getComputedStyle(e).color);
      const bg = await page.locator(bgSel).first().evaluate((e) => getComputedStyle(e).backgroundColor);
      const c = contrast(fg, bg);
      assert.ok(c >= 4.5, `${sel} ${fg} on ${bg}: ${c.toFixed(2)}:1`);
    }
    // The results panel is not a live region; the status and lambda are announced once the
    // values have settled, not at every step of a drag.
    assert.equal(await page.locator('#v-result').getAttribute('aria-live'), null);
    assert.equal(await page.locator('[aria-live]:not(.field-error)').count(), 1, 'one announcement region');
    assert.equal(await page.locator('#v-announce').getAttribute('aria-live'), 'polite');
    await page.evaluate(() => {
      window.announced = [];
      new MutationObserver(() => window.announced.push(document.getElementById('v-announce').textContent))
        .observe(document.getElementById('v-announce'), { childList: true, characterData: true, subtree: true });
    });
    await t.slider.focus();
    const steps = 8;
    for (let i = 0; i < steps; i++) {
      await page.keyboard.press('ArrowRight');
      await settled(page);
    }
    const lambda = await page.locator('#v-lambda').textContent();
    await page.waitForFunction((l) => document.getElementById('v-announce').textContent.endsWith('lambda ' + l), lambda);
    const announced = await page.evaluate(() => window.announced);
    assert.ok(announced.length < steps, `${announced.length} announcements for ${steps} steps: ${announced}`);
    assert.match(announced[announced.length - 1], /^Collapse mechanism, lambda \d\.\d{4}$/);
    assert.deepEqual(unexpected(problems), []);
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

// ---- issue 26 -------------------------------------------------------------------------------

// A scene file in a temporary directory.
function tempScene(name, lines) {
  const dir = mkdtempSync(path.join(os.tmpdir(), 'voussoir-e2e-'));
  const file = path.join(dir, name);
  writeFileSync(file, lines.join('\n') + '\n');
  return file;
}

test('a stepped pier has a field for its widths and no width or course slider', async () => {
  const stepped = scenePath('stepped_portal.toml');
  const other = await startServer(stepped);
  const { page, context, problems } = await openPage(browser, other.url);
  try {
    // The keys a stepped pier does not take have no field (they could only be refused).
    for (const key of ['piers.width', 'piers.courses', 'piers.bottom_width', 'piers.top_width']) {
      assert.equal(await field(page, key).row.count(), 0, `no ${key} field`);
    }
    assert.equal(await field(page, 'piers.height').row.count(), 1, 'the height applies');
    const widths = page.locator('.field[data-key="piers.widths"] input[type="text"]');
    assert.equal(await widths.inputValue(), '0.55, 0.45, 0.35, 0.3', 'the scene\'s widths');
    assertShows(await shown(page), analyze(stepped), 'stepped portal');
    // Three courses, typed: the CLI's values for those widths.
    await widths.fill('0.6, 0.5, 0.4');
    await widths.press('Enter');
    await settled(page);
    assertShows(await shown(page), analyze(stepped, { 'piers.widths': '[0.6, 0.5, 0.4]' }),
      'widths 0.6, 0.5, 0.4');
    assert.equal(await page.locator('.field.has-error').count(), 0);
    // A width that is not a number is refused beside the field, as the CLI refuses it.
    await widths.fill('0.6, x');
    await widths.press('Enter');
    await settled(page);
    const error = page.locator('.field[data-key="piers.widths"] .field-error');
    assert.match(await error.textContent(), /piers\.widths/);
    assert.ok(await page.locator('#v-dl-json').isDisabled(), 'downloads disabled');
    assert.notEqual(analyzeFails(stepped, { 'piers.widths': '[0.6, "x"]' }).status, 0);
    await widths.fill('0.6, 0.5, 0.4');
    await widths.press('Enter');
    await settled(page);
    assert.equal(await error.textContent(), '', 'the error is cleared');
    // The chart (of the thickness) is of the new piers: its line is there and no row failed.
    await chartSettled(page);
    assert.ok(await page.locator('#v-chart svg polyline.series').count() >= 1);
    assert.deepEqual(unexpected(problems), []);
  } finally {
    await context.close();
    await other.stop();
  }
  // A battered pier: its base and top widths and its courses, no single width.
  const battered = scenePath('battered_portal.toml');
  const third = await startServer(battered);
  const opened = await openPage(browser, third.url);
  try {
    const p = opened.page;
    for (const key of ['piers.bottom_width', 'piers.top_width', 'piers.courses']) {
      assert.equal(await field(p, key).row.count(), 1, `a ${key} field`);
    }
    for (const key of ['piers.width', 'piers.widths']) {
      assert.equal(await field(p, key).row.count(), 0, `no ${key} field`);
    }
    const top = field(p, 'piers.top_width');
    await top.number.fill('0.35');
    await top.number.press('Enter');
    await settled(p);
    assertShows(await shown(p), analyze(battered, { 'piers.top_width': '0.35' }), 'top width 0.35');
    assert.deepEqual(opened.problems, []);
  } finally {
    await opened.context.close();
    await third.stop();
  }
});

// The x-axis tick labels of the chart (centred under their ticks; the y-axis ones are
// right-aligned), and the pairs of neighbours whose boxes overlap.
async function tickOverlaps(page) {
  return page.evaluate(() => {
    const boxes = [...document.querySelectorAll('#v-chart svg text.tick[text-anchor="middle"]')]
      .map((t) => t.getBoundingClientRect()).sort((a, b) => a.left - b.left);
    const out = [];
    for (let i = 1; i < boxes.length; i++) {
      if (boxes[i].left < boxes[i - 1].right) out.push([boxes[i - 1].right, boxes[i].left]);
    }
    return { count: boxes.length, out };
  });
}

test('the compressive strength is charted in MPa, its labels apart', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    const fc = field(page, 'material.compressive_strength');
    await fc.row.locator('input[type="checkbox"]').uncheck();
    await settled(page);
    await fc.number.fill('5000000');
    await fc.number.press('Enter');
    await settled(page);
    await chartSettled(page);
    assertShows(await shown(page), analyze(SCENE, { 'material.compressive_strength': 5e6 }), 'fc = 5 MPa');
    assert.match(await page.locator('#v-chart-title').textContent(), /compressive strength/i);
    const labels = await page.locator('#v-chart svg text.tick').allTextContents();
    assert.ok(labels.every((t) => t.length <= 4), `short labels: ${labels}`);
    assert.match(await page.locator('#v-chart svg text.axis-label').first().textContent(), /\(MPa\)/);
    assert.match(await page.locator('#v-chart .chart-legend').textContent(), /at 5 MPa/);
    const { count, out } = await tickOverlaps(page);
    assert.ok(count >= 3, `x-axis labels: ${count}`);
    assert.deepEqual(out, [], 'no two x-axis labels overlap');
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test('an upper bound with rigid hinges on a crushing scene is drawn and named as such', async () => {
  // Crushing and joints that slide: the certified mechanism about the compressed zones does
  // not apply, and the search's upper bound is the rigid structure's.
  const file = tempScene('crushing_sliding.toml', [
    '[arch]', 'shape = "circular"', 'radius = 1.0', 'thickness = 0.5', 'voussoirs = 32', '',
    '[material]', 'unit_weight = 20000.0', 'depth = 1.0', 'friction = 0.6',
    'compressive_strength = 5e6',
  ]);
  const cli = analyze(file);
  assert.equal(cli.kinematic_search, 'exhaustive');
  assert.match(cli.kinematic_note, /rigid hinges/);
  const other = await startServer(file);
  const { page, context, problems } = await openPage(browser, other.url);
  try {
    assertShows(await shown(page), cli, 'crushing and sliding');
    assert.equal(await page.locator('#v-upper-how').textContent(), 'rigid hinges');
    assert.match(await page.locator('#v-note').textContent(), /upper bound ignores crushing/);
    await chartSettled(page);
    // The thickness chart: no dashed "upper" line, a dotted one named for what it is.
    assert.equal(await page.locator('#v-chart svg .series-upper').count(), 0, 'no plain upper line');
    assert.ok(await page.locator('#v-chart svg polyline.series-upper-rigid').count() >= 1);
    const legend = await page.locator('#v-chart .chart-legend').textContent();
    assert.match(legend, /dotted: upper bound with rigid hinges \(ignores crushing\)/);
    assert.doesNotMatch(legend, /dashed/);
    // The JSON download is still the CLI's (the page's own field is not in it).
    const json = JSON.parse((await download(page, '#v-dl-json')).text);
    assert.equal(json.upper_rigid, undefined);
    sameAnalysis(json, cli, 'crushing and sliding');
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
    await other.stop();
  }
});

test('the layout reflows at 1024 and 800 px: nothing overlaps or leaves the window', async () => {
  for (const width of [1024, 800]) {
    const { page, context, problems } = await openPage(browser, server.url, { width, height: 768 });
    try {
      await chartSettled(page);
      const box = await page.evaluate(() => {
        const r = (sel) => {
          const b = document.querySelector(sel).getBoundingClientRect();
          return { left: b.left, right: b.right, top: b.top + window.scrollY, bottom: b.bottom + window.scrollY, width: b.width };
        };
        return {
          scrollWidth: document.documentElement.scrollWidth,
          inner: window.innerWidth,
          panels: ['.controls', '#v-drawing', '#v-result', '.chart-panel', '.downloads']
            .map((sel) => ({ sel, ...r(sel) })),
          topbar: [...document.querySelectorAll('.topbar button, .topbar .brand')].map((e) => {
            const b = e.getBoundingClientRect();
            return { right: b.right, width: b.width };
          }),
        };
      });
      assert.ok(box.scrollWidth <= box.inner, `${width}: no horizontal scrolling (${box.scrollWidth})`);
      for (const b of box.topbar) assert.ok(b.right <= width && b.width > 20, `${width}: top bar fits`);
      const drawing = box.panels.find((p) => p.sel === '#v-drawing');
      assert.ok(drawing.width >= width * 0.5, `${width}: the drawing has half the width (${drawing.width})`);
      for (const [i, a] of box.panels.entries()) {
        assert.ok(a.right <= width + 0.5, `${width}: ${a.sel} inside the window`);
        for (const b of box.panels.slice(i + 1)) {
          const apart = a.right <= b.left + 0.5 || b.right <= a.left + 0.5
            || a.bottom <= b.top + 0.5 || b.bottom <= a.top + 0.5;
          assert.ok(apart, `${width}: ${a.sel} and ${b.sel} do not overlap`);
        }
      }
      // Every control can still be reached and used: a slider step updates lambda.
      const t = field(page, 'arch.thickness');
      await t.slider.focus();
      await page.keyboard.press('ArrowRight');
      await settled(page);
      assertShows(await shown(page), analyze(SCENE, { 'arch.thickness': await t.slider.inputValue() }),
        `${width} px`);
      assert.deepEqual(problems, []);
    } finally {
      await context.close();
    }
  }
});

test('tabbing through the sliders asks for no sweep', async () => {
  const { page, context, problems } = await openPage(browser, server.url);
  try {
    await chartSettled(page);
    const sweeps = [];
    page.on('request', (r) => { if (r.url().endsWith('/api/sweep')) sweeps.push(r.postDataJSON().key); });
    await field(page, 'arch.thickness').slider.focus();
    for (let i = 0; i < 8; i++) await page.keyboard.press('Tab');
    await page.waitForTimeout(300);
    assert.deepEqual(sweeps, [], 'moving the focus is not moving a slider');
    // A key that moves a slider charts its parameter, once.
    await field(page, 'arch.radius').slider.focus();
    await page.keyboard.press('ArrowRight');
    await page.keyboard.press('ArrowRight');
    await settled(page);
    await chartSettled(page);
    assert.deepEqual(sweeps, ['arch.radius']);
    assert.deepEqual(problems, []);
  } finally {
    await context.close();
  }
});

test('with joints that slide at collapse the multiplier is named an upper bound', async () => {
  // Issue 25: a thick semicircle with mu = 0.4 slides at its springing; the static program's
  // associative friction then gives an upper bound of the real collapse multiplier.
  const file = tempScene('sliding.toml', [
    '[arch]', 'shape = "circular"', 'radius = 1.0', 'thickness = 0.25', 'voussoirs = 32', '',
    '[material]', 'friction = 0.4',
  ]);
  const cli = analyze(file);
  assert.equal(cli.friction_exact, false);
  assert.equal(cli.lambda_associative, cli.lambda_lower);
  const other = await startServer(file);
  const { page, context, problems } = await openPage(browser, other.url);
  try {
    assertShows(await shown(page), cli, 'sliding');
    assert.equal(await page.locator('#v-lambda-relation').textContent(), '≤');
    assert.equal(await page.locator('#v-lower-name').textContent(), 'upper bound');
    assert.equal(await page.locator('#v-lower-how').textContent(), 'associative friction');
    const caveat = page.locator('#v-friction');
    assert.ok(await caveat.isVisible(), 'the caveat is shown');
    assert.equal(await caveat.textContent(), cli.friction_note);
    assert.match(cli.friction_note, /upper bound of the real \(non-associative\) collapse multiplier/);
    // The thickness chart's solid line is the static one, named for what it is.
    await chartSettled(page);
    assert.match(await page.locator('#v-chart .chart-legend').textContent(),
      /solid: static, associative friction/);
    // More friction: the arch rocks (no joint slips in the mechanism), the multiplier is exact
    // again and the caveat goes.
    const mu = field(page, 'material.friction');
    await mu.number.fill('1');
    await mu.number.press('Enter');
    await settled(page);
    assert.ok(!(await caveat.isVisible()), 'no caveat when nothing slides');
    assert.equal(await page.locator('#v-lower-name').textContent(), 'lower bound');
    assert.notEqual(await page.locator('#v-lambda-relation').textContent(), '≤');
    assert.deepEqual(unexpected(problems), []);
  } finally {
    await context.close();
    await other.stop();
  }
});
