// Regenerates the README's screenshot, docs/playground.png: the production build (npm run build)
// in headless Chromium at 1280×800, once the first results and charts are drawn.
//   node scripts/screenshot.mjs [query, e.g. '?model=dr,ctra-plus,3d-ctra,imm']
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { launch, openPage, serveDist } from '../tests/e2e/harness.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const query = process.argv[2] ?? '';
const server = await serveDist();
const browser = await launch();
try {
  const { page, problems } = await openPage(browser, server.origin, { width: 1280, height: 800 });
  await page.goto(server.url + query);
  await page.waitForSelector('#results-table tbody tr', { timeout: 30_000 });
  await page.waitForSelector('#chart-error svg', { timeout: 30_000 });
  await page.waitForSelector('#chart-distance svg', { timeout: 30_000 });
  await page.waitForFunction(() => !('busy' in document.body.dataset), null, { timeout: 30_000 });
  const path = join(root, 'docs', 'playground.png');
  await page.screenshot({ path });
  if (problems.length) throw new Error(problems.join('\n'));
  console.log(`wrote ${path}`);
} finally {
  await browser.close();
  server.close();
}
