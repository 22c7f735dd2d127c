import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { launch, openPage, screenshot, serveDist } from './harness.mjs';

let server;
let browser;

before(async () => {
  server = await serveDist();
  browser = await launch();
});

after(async () => {
  await browser?.close();
  server?.close();
});

test('changing the spreading factor changes the time on air readout', async () => {
  const { page, problems } = await openPage(browser, server.origin);
  await page.goto(server.url);
  const toa = page.locator('#toa');
  await page.waitForFunction(() => document.querySelector('#toa')?.textContent?.includes('ms'));
  const before7 = await toa.textContent();
  await page.getByLabel('Spreading factor').first().selectOption('12');
  await page.waitForFunction((old) => document.querySelector('#toa')?.textContent !== old, before7);
  const after12 = await toa.textContent();
  const ms = (s) => Number.parseFloat(s);
  assert.ok(ms(after12) > 10 * ms(before7), `SF12 (${after12}) should take far longer than SF7 (${before7})`);
  await screenshot(page, 'airtime');
  assert.deepEqual(problems, []);
});
