// temporary: screenshots for looking (not committed)
import { field, launchBrowser, openPage, scenePath, settled, chartSettled, startServer } from './helpers.mjs';
const scene = process.argv[2] || 'semicircular.toml';
const tag = process.argv[3] || 'x';
const server = await startServer(scenePath(scene));
const browser = await launchBrowser();
try {
  for (const width of [1366, 1024, 800]) {
    const { page, context, problems } = await openPage(browser, server.url, { width, height: 768 });
    await chartSettled(page);
    if (process.argv[4]) {
      const f = field(page, process.argv[4]);
      await f.number.fill(process.argv[5]);
      await f.number.press('Enter');
      await settled(page); await chartSettled(page);
    }
    await page.screenshot({ path: `/tmp/shots/${tag}-${width}.png`, fullPage: true });
    if (problems.length) console.error(problems.join('\n'));
    await context.close();
  }
} finally { await browser.close(); await server.stop(); }
