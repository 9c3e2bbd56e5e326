// Regenerates the page's screenshots in docs/ at 1366x768 (not a test: run it by hand after a
// change to the page, from the repository root, and look at the pictures):
//   node tests/e2e/screenshots.mjs
// docs/web-arch.png: the bundled semicircular arch as the page opens, its thickness charted.
// docs/web-portal.png: the portal preset, earthquake to the left, the pier height moved up.
import path from 'node:path';
import { field, launchBrowser, openPage, ROOT, scenePath, settled, chartSettled, startServer } from './helpers.mjs';

const server = await startServer(scenePath('semicircular.toml'));
const browser = await launchBrowser();
try {
  {
    const { page, context, problems } = await openPage(browser, server.url);
    await chartSettled(page);
    // One slider step and back, so the page shows an update time as it does in use.
    const t = field(page, 'arch.thickness');
    await t.slider.focus();
    await page.keyboard.press('ArrowRight');
    await settled(page);
    await page.keyboard.press('ArrowLeft');
    await settled(page);
    await chartSettled(page);
    await t.slider.blur();
    await page.screenshot({ path: path.join(ROOT, 'docs', 'web-arch.png') });
    if (problems.length) console.error(problems.join('\n'));
    await context.close();
  }
  {
    const { page, context, problems } = await openPage(browser, server.url);
    await page.click('#v-shapes button[data-preset="portal"]');
    await settled(page);
    await page.click('#v-direction button[data-direction="left"]');
    await settled(page);
    const h = field(page, 'piers.height');
    await h.slider.focus();
    for (let i = 0; i < 6; i++) await page.keyboard.press('ArrowRight');
    await settled(page);
    await chartSettled(page);
    await h.slider.blur();
    await page.screenshot({ path: path.join(ROOT, 'docs', 'web-portal.png') });
    if (problems.length) console.error(problems.join('\n'));
    await context.close();
  }
  console.log('wrote docs/web-arch.png and docs/web-portal.png');
} finally {
  await browser.close();
  await server.stop();
}
