// The playground's cold load in headless Chromium, as a user at 1280×800 meets it, over several
// loads (each in a fresh browser context: nothing cached):
// - first results: navigation start until the results table has rows (for the whole set, its
//   first flight, shown while the rest runs);
// - final results: until the results are the settings' own (no first flight standing in);
// - all drawn: until nothing is being computed or drawn (`<body data-busy>` gone);
// - long tasks: main-thread tasks over 50 ms until then (count, longest, sum);
// - each panel's drawing time (the page's `draw <panel>` performance measures, www/later.ts).
// Reports, never asserts: wall-clock time on a shared machine is a measurement, not a test.
//   npm run bench:page [-- loads [query]]      e.g. -- 5 '?flight=all' (builds dist/ first)
import { launch, serveDist } from '../tests/e2e/harness.mjs';

const loads = Number(process.argv[2] ?? 7);
const query = process.argv[3] ?? '';
const server = await serveDist();
const browser = await launch();

/** Runs in the page before its scripts: records long tasks and when results and idleness arrive. */
function observe() {
  const t = (window.__timing = { long: [] });
  new PerformanceObserver((list) => {
    for (const e of list.getEntries()) t.long.push(e.duration);
  }).observe({ type: 'longtask', buffered: true });
  const check = () => {
    const rows = document.querySelector('#results-table tbody')?.rows.length ?? 0;
    t.first ??= rows > 0 ? performance.now() : undefined;
    if (rows > 0 && !document.querySelector('[data-panel="results"]').classList.contains('partial')) t.final ??= performance.now();
    if (t.first !== undefined && t.idle === undefined && !('busy' in document.body.dataset)) {
      t.idle = performance.now();
      window.__idle?.();
    }
  };
  document.addEventListener('DOMContentLoaded', () => new MutationObserver(check).observe(document.body, { subtree: true, childList: true, attributes: true }));
}

const runs = [];
for (let i = 0; i < loads; i++) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 800 } });
  const page = await context.newPage();
  await page.addInitScript(observe);
  await page.goto(server.url + query);
  // Waits on a promise the observer resolves, not with waitForFunction: that injects Playwright's
  // own script into the page, ~100 ms of the page's thread in the middle of the load it measures.
  await page.evaluate(() => new Promise((resolve) => (window.__timing.idle !== undefined ? resolve() : (window.__idle = resolve))));
  runs.push(
    await page.evaluate(() => ({
      ...window.__timing,
      draws: Object.fromEntries(performance.getEntriesByType('measure').filter((m) => m.name.startsWith('draw ')).map((m) => [m.name.slice(5), m.duration])),
    })),
  );
  await context.close();
}
await browser.close();
server.close();

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const range = (xs) => `${Math.round(Math.min(...xs))}–${Math.round(Math.max(...xs))}`;
const row = (label, xs) => `| ${label} | ${Math.round(median(xs))} | ${range(xs)} |`;
console.log(`Cold loads of the playground${query ? ` (${query})` : ''} at 1280×800 (headless Chromium, ${loads} loads), ms:\n`);
console.log('| measure | median | range |\n|---|---:|---:|');
console.log(row('first results', runs.map((r) => r.first)));
console.log(row('final results', runs.map((r) => r.final)));
console.log(row('every panel drawn', runs.map((r) => r.idle)));
console.log(row('long tasks (> 50 ms), count', runs.map((r) => r.long.length)));
console.log(row('longest task', runs.map((r) => Math.max(0, ...r.long))));
console.log(row('long tasks, sum', runs.map((r) => r.long.reduce((a, b) => a + b, 0))));
for (const panel of Object.keys(runs[0].draws)) console.log(row(`draw ${panel}`, runs.map((r) => r.draws[panel] ?? 0)));
