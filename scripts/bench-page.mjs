// The playground's cold load in headless Chromium, as a user at 1280×800 meets it, over several
// loads (each in a fresh browser context: nothing cached):
// - first results: navigation start until the results table has rows (for the whole set, its
//   first flight, shown while the rest runs);
// - final results: until the results are the settings' own (no first flight standing in);
// - all drawn: until nothing is being computed or drawn (`<body data-busy>` gone): every panel but
//   the 3D view, which is drawn once it comes near the viewport (2.5 screens down at 1280×800);
// - a setting change once all is drawn (the SF, to SF8): until its results, and until all is
//   drawn again;
// - the 3D view: from scrolling to it, after all the rest is drawn, until it is drawn;
// - long tasks: main-thread tasks over 50 ms until then (count, longest, sum);
// - layout shift: the Layout Instability API's shifts until then, summed (its CLS while loading);
// - each panel's drawing time (the page's `draw <panel>` performance measures, www/later.ts);
// - with `--upload FILE`, then a flight uploaded as a user does (Trajectory → CSV file): from the
//   file's choice until its results, until its error chart and 3D view are drawn, and the long
//   tasks between (the distance and SF charts, which simulate the flight again at every distance
//   and SF, come later and are not waited for). `cargo bench --bench core -- long_flight` writes
//   the 10⁶-row flights to target/tmp/long-flight-25hz.csv and -10khz.csv.
// Reports, never asserts: wall-clock time on a shared machine is a measurement, not a test.
//   npm run bench:page [-- loads [query]]      e.g. -- 5 '?flight=all' (builds dist/ first)
//   node scripts/bench-page.mjs --upload target/tmp/long-flight-25hz.csv 5 '?model=all'
//   node scripts/bench-page.mjs --compare DIR_A DIR_B [loads [query]]
// compares two builds (copies of dist/): one load of each in turn, so that the machine's drift,
// which on this 2-core machine moves the first results by more than most changes do, falls on
// both alike. Batches of loads per build, one build after the other, once misled (docs/performance.md).
import { resolve } from 'node:path';
import { launch, serveDist } from '../tests/e2e/harness.mjs';

const argv = process.argv.slice(2);
const uploadAt = argv.indexOf('--upload');
const upload = uploadAt >= 0 ? resolve(argv.splice(uploadAt, 2)[1]) : null;
const compare = argv[0] === '--compare' ? argv.slice(1, 3).map((d) => resolve(d)) : null;
const args = compare ? argv.slice(3) : argv;
const loads = Number(args[0] ?? (compare ? 8 : 7));
const query = args[1] ?? '';
const builds = compare ?? [undefined];
const servers = await Promise.all(builds.map((dir) => serveDist(dir)));
const browser = await launch();

/** Runs in the page before its scripts: records long tasks and when results and idleness arrive. */
function observe() {
  const t = (window.__timing = { long: [], shift: 0 });
  new PerformanceObserver((list) => {
    for (const e of list.getEntries()) t.long.push(e.duration);
  }).observe({ type: 'longtask', buffered: true });
  new PerformanceObserver((list) => {
    for (const e of list.getEntries()) if (t.idle === undefined && !e.hadRecentInput) t.shift += e.value;
  }).observe({ type: 'layout-shift', buffered: true });
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

/** One cold load of the build `server` serves: its timings and each panel's drawing time. */
async function load(server) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 800 } });
  const page = await context.newPage();
  await page.addInitScript(observe);
  await page.goto(server.url + query);
  // Waits on a promise the observer resolves, not with waitForFunction: that injects Playwright's
  // own script into the page, ~100 ms of the page's thread in the middle of the load it measures.
  await page.evaluate(() => new Promise((resolve) => (window.__timing.idle !== undefined ? resolve() : (window.__idle = resolve))));
  const run = await page.evaluate(() => ({
    ...window.__timing,
    draws: Object.fromEntries(performance.getEntriesByType('measure').filter((m) => m.name.startsWith('draw ')).map((m) => [m.name.slice(5), m.duration])),
  }));
  // A setting changed once all is drawn, as a reader does next (the SF, to SF8; the drone runs
  // stay cached): until the results are the new settings' own, and until all is drawn again.
  const change = await page.evaluate(
    () =>
      new Promise((resolve) => {
        const table = () => document.querySelector('#results-table tbody')?.innerHTML;
        const before = table();
        const start = performance.now();
        let results;
        const observer = new MutationObserver(() => {
          const partial = document.querySelector('[data-panel="results"]').classList.contains('partial');
          results ??= table() !== before && !partial ? performance.now() - start : undefined;
          if (results === undefined || 'busy' in document.body.dataset) return;
          observer.disconnect();
          resolve({ results, idle: performance.now() - start });
        });
        observer.observe(document.body, { subtree: true, childList: true, attributes: true, characterData: true });
        const sf = document.querySelector('#sf');
        sf.value = '8';
        for (const type of ['input', 'change']) sf.dispatchEvent(new Event(type, { bubbles: true }));
      }),
  );
  // The 3D view is drawn once it comes near the viewport: the time from scrolling to it until it is drawn.
  const view3d = await page.evaluate(
    () =>
      new Promise((resolve) => {
        // A build that draws it on load has already drawn it: nothing to wait for.
        if (performance.getEntriesByName('draw trajectory').length > 0) return resolve(0);
        const start = performance.now();
        setTimeout(() => resolve(Number.NaN), 10_000);
        new PerformanceObserver((list, observer) => {
          const drawn = list.getEntries().find((e) => e.name === 'draw trajectory');
          if (!drawn) return;
          observer.disconnect();
          resolve(drawn.startTime + drawn.duration - start);
        }).observe({ type: 'measure' });
        document.querySelector('[data-panel="trajectory"]').scrollIntoView();
      }),
  );
  const uploaded = upload ? await uploadFlight(page) : undefined;
  await context.close();
  return { ...run, change, view3d, uploaded };
}

/** Uploads `upload` on a page that has drawn everything: until its results (the table is the
 * new flight's), until its error chart and 3D view are drawn, and the long tasks until then. */
async function uploadFlight(page) {
  await page.getByLabel('Trajectory', { exact: true }).selectOption('csv');
  await page.evaluate(() => {
    const table = () => document.querySelector('#results-table tbody')?.innerHTML;
    const u = (window.__timing.upload = { start: performance.now(), long: [] });
    const before = table();
    new MutationObserver((_, observer) => {
      if (table() === before || document.querySelector('[data-panel="results"]').classList.contains('partial')) return;
      u.results = performance.now() - u.start;
      observer.disconnect();
    }).observe(document.body, { subtree: true, childList: true, characterData: true });
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) if (e.startTime >= u.start) u.long.push(e.duration);
    }).observe({ type: 'longtask' });
  });
  await page.locator('#csv').setInputFiles(upload);
  // The 3D view, once shown, draws each new flight too.
  await page.waitForFunction(
    () => {
      const { start, results } = window.__timing.upload;
      const since = (name) => performance.getEntriesByName(name).some((m) => m.startTime > start);
      return results !== undefined && since('draw error') && (since('draw trajectory') || !performance.getEntriesByName('draw trajectory').length);
    },
    null,
    { timeout: 300_000, polling: 100 },
  );
  return page.evaluate(() => {
    const { start, results, long } = window.__timing.upload;
    const end = (name) => performance.getEntriesByName(name).filter((m) => m.startTime > start).map((m) => m.startTime + m.duration - start)[0] ?? Number.NaN;
    return { results, chart: end('draw error'), view3d: end('draw trajectory'), long: [...long] };
  });
}

// runs[b]: build b's loads; the builds take turns, in alternating order.
const runs = builds.map(() => []);
for (let i = 0; i < loads; i++) {
  const order = builds.map((_, b) => b);
  if (i % 2) order.reverse();
  for (const b of order) runs[b].push(await load(servers[b]));
}
await browser.close();
servers.forEach((s) => s.close());

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const range = (xs) => `${Math.round(Math.min(...xs))}–${Math.round(Math.max(...xs))}`;
const cells = (xs) => `${Math.round(median(xs))} | ${range(xs)}`;
const row = (label, f) => `| ${label} | ${runs.map((r) => cells(r.map(f))).join(' | ')} |`;
const heads = compare ? compare.map((d) => `${d}: median | range`).join(' | ') : 'median | range';
console.log(`Cold loads of the playground${query ? ` (${query})` : ''} at 1280×800 (headless Chromium, ${loads} loads${compare ? ' of each build, in turn' : ''}), ms:\n`);
console.log(`| measure | ${heads} |\n|---|${builds.map(() => '---:|---:|').join('')}`);
console.log(row('first results', (r) => r.first));
console.log(row('final results', (r) => r.final));
console.log(row('every panel drawn', (r) => r.idle));
console.log(row('after SF → 8 once all is drawn: results', (r) => r.change.results));
console.log(row('after SF → 8: every panel drawn again', (r) => r.change.idle));
console.log(row('3D view drawn, from scrolling to it', (r) => r.view3d));
console.log(row('long tasks (> 50 ms), count', (r) => r.long.length));
console.log(row('longest task', (r) => Math.max(0, ...r.long)));
console.log(row('long tasks, sum', (r) => r.long.reduce((a, b) => a + b, 0)));
console.log(row('layout shift while loading, × 1000', (r) => 1000 * r.shift));
for (const panel of Object.keys(runs[0][0].draws)) console.log(row(`draw ${panel}`, (r) => r.draws[panel] ?? 0));
if (upload) {
  console.log(row(`${upload.split('/').pop()} uploaded: results`, (r) => r.uploaded.results));
  console.log(row('uploaded: its error chart drawn', (r) => r.uploaded.chart));
  console.log(row('uploaded: its 3D view drawn', (r) => r.uploaded.view3d));
  console.log(row('uploaded: long tasks (> 50 ms) until both are drawn, count', (r) => r.uploaded.long.length));
  console.log(row('uploaded: longest task', (r) => Math.max(0, ...r.uploaded.long)));
}
