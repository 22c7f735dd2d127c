// The playground as the browser test files open it: one server for dist/ and one Chromium per test
// file (`usePlayground()`), and the steps every test shares: open the page, wait for results,
// read the results table, run axe, open a lesson.
import { after, afterEach, before } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { launch, nativeJson, openPage, serveDist } from './harness.mjs';

let server;
let browser;
let context;
let keeper;
/** What the kept-open playground reported: console errors, uncaught exceptions, foreign requests. */
let keeperProblems = [];

/** Starts the server and the browser before this file's tests, closes each test's pages after it,
 * and stops both after the last test.
 *
 * The tests' pages share one browser context, and in it one renderer process (`launch`'s
 * `oneRenderer`), in which the playground stays open, idle once drawn, from the first test to the
 * last. Chromium otherwise starts a renderer for every new page, which compiles the page's
 * JavaScript and its WebAssembly module again. Measured over eight loads in a row (2026-12-04):
 * 1.55 core-s and 1.25 s a load with a blank page kept open, as before; 1.47 core-s with the
 * playground kept open but a renderer per page; 1.2 with one renderer and a document of the site
 * kept open; 1.15 with the playground kept open, whose compiled module the next page finds in the
 * process; 1.05 core-s and 0.9 s with the server's caching headers too. The page stores nothing
 * (no cookies, no storage), so a test sees nothing of the ones before it; the permissions a test
 * grants are cleared after it. `npm run bench:page` times cold loads, each in a fresh context. */
export function usePlayground() {
  before(async () => {
    server = await serveDist();
    browser = await launch({ oneRenderer: true });
    context = await browser.newContext({ acceptDownloads: true });
    ({ page: keeper, problems: keeperProblems } = await openPage(context, server.origin));
    await keeper.goto(server.url);
  });
  // A test's pages close with it. Left open, each went on computing its remaining panels (the SF
  // chart, the whole set) in its two workers while the next tests ran, on the same two cores.
  afterEach(async () => {
    await Promise.all([
      ...(context?.pages().filter((page) => page !== keeper).map((page) => page.close()) ?? []),
      ...(browser?.contexts().filter((other) => other !== context).map((other) => other.close()) ?? []),
    ]);
    await context?.clearPermissions();
  });
  // The kept-open playground is a page too: whatever it reported from its load to the file's end
  // fails the file, as a test's own page's problems fail the test.
  after(async () => {
    const problems = [...keeperProblems];
    await browser?.close();
    server?.close();
    assert.deepEqual(problems, [], 'the playground kept open beside the tests reported problems');
  });
}

/** Where this file's page is served, and the context its pages share. */
export const playground = {
  get url() {
    return server.url;
  },
  get context() {
    return context;
  },
};

/** Opens the page (with an optional query) and waits for its results. */
export async function open(query = '', viewport) {
  const { page, problems } = await openPage(context, server.origin, viewport);
  await page.goto(server.url + query);
  await waitForResults(page);
  return { page, problems };
}

/** How often the browser suite's waits (`until`) test the page, in ms. Playwright's default tests
 * it in every animation frame, which keeps the page producing frames (and serialised the results
 * table, or encoded the 3D view as a PNG, sixty times a second) on the cores the page computes on:
 * the suite took 212 s and 415 s of CPU so, 189 s and 371 s with its two commonest waits at 100 ms
 * (193 s and 378 s with every wait at 100 ms). */
const POLL_MS = 100;

/** `page.waitForFunction(predicate, arg)`, testing the page every POLL_MS (30 s at most unless
 * `options` say otherwise). */
export const until = (page, predicate, arg = null, options = {}) => page.waitForFunction(predicate, arg, { timeout: 30_000, polling: POLL_MS, ...options });

/** Waits until the results table has rows other than `previous`, and not a whole set's first
 * flight shown while the rest runs (`.partial`). */
export async function waitForResults(page, previous) {
  await until(
    page,
    (old) => {
      // The table's rows, in one table or the two it is split into where one would not fit.
      const bodies = [...document.querySelectorAll('#results-table tbody')];
      const partial = document.querySelector('[data-panel="results"]')?.classList.contains('partial');
      return bodies.length > 0 && bodies[0].rows.length > 0 && bodies.map((t) => t.innerHTML).join('') !== old && !partial;
    },
    previous,
  );
}

export const tableHtml = (page) => page.locator('#results-table tbody').evaluateAll((bodies) => bodies.map((t) => t.innerHTML).join(''));
export const cell = (page, model, fieldName) => page.locator(`#results-table tr[data-model="${model}"] td[data-field="${fieldName}"]`).textContent();
export const number = (text) => Number.parseFloat(text);
export const cellNumber = async (page, model, field) => number(await cell(page, model, field));

export const MODELS = ['dr', 'ctra-plus', '3d-ctra'];
/** The stations' names as the page writes them. */
export const LABELS = { dr: 'DR', 'ctra-plus': 'CTRA+', '3d-ctra': '3D-CTRA', imm: 'IMM', mission: 'Mission' };
/** "DR’s 1.47× (1.39–1.58)": how the verdict quotes a CLI result's p75 against the lowest station's, paired over the same runs. */
export const ratioWords = ({ model, p75VsLowest: v }) => `${LABELS[model]}’s ${v.ratio.toFixed(2)}× (${v.interval[0].toFixed(2)}–${v.interval[1].toFixed(2)})`;
/** "a, b and c", as the page lists. */
export const listed = (words) => (words.length < 2 ? words.join('') : `${words.slice(0, -1).join(', ')} and ${words.at(-1)}`);
/** Each model's p75 and its shown 95 % interval, as the table shows them. */
export async function shownP75(page, models = MODELS) {
  return Promise.all(
    models.map(async (m) => {
      const text = await cell(page, m, 'p75');
      const ci = text.match(/\(([\d.]+)–([\d.]+)\)/);
      return { model: m, p75: number(text), ci: ci ? [Number(ci[1]), Number(ci[2])] : null };
    }),
  );
}

/** Runs axe-core on the page; returns every violation as "impact rule: target" lines. */
export async function axe(page) {
  // Evaluated through the DevTools protocol: the page's CSP rightly refuses inline scripts.
  await page.evaluate(readFileSync(join(process.cwd(), 'node_modules', 'axe-core', 'axe.min.js'), 'utf8'));
  const result = await page.evaluate(async () => await window.axe.run(document, { resultTypes: ['violations'] }));
  // Every violation counts, whatever its impact.
  return result.violations.flatMap((v) => v.nodes.map((n) => `${v.impact} ${v.id}: ${n.target.join(' ')}`));
}

/** The texts of the charts in `selector`, each as a reader sees it: Plot writes a wrapped text's
 * lines as tspans with no space between them, so they are joined by one. */
export function chartTexts(page, selector) {
  return page.locator(`${selector} svg text`).evaluateAll((texts) =>
    texts.map((t) => (t.querySelector('tspan') ? [...t.querySelectorAll('tspan')].map((s) => s.textContent).join(' ') : t.textContent)),
  );
}

/** Every chart's axis label (Plot marks them → and ↑) that overlaps other text of its chart, as
 * "chart id: label over text" lines: at the page's 13 px and presentation mode's 18 px, Plot's
 * default margins once put them on the tick labels. */
export function axisLabelOverlaps(page) {
  return page.evaluate(() => {
    const out = new Set();
    for (const svg of document.querySelectorAll('.chart svg')) {
      const texts = [...svg.querySelectorAll('text')].filter((t) => t.textContent.trim() && t.getBoundingClientRect().height > 0);
      for (const label of texts.filter((t) => /[→↑]/.test(t.textContent))) {
        const a = label.getBoundingClientRect();
        for (const other of texts) {
          const b = other.getBoundingClientRect();
          // A pixel of slack: glyph boxes of neighbouring lines may touch.
          if (other !== label && a.left < b.right - 1 && b.left < a.right - 1 && a.top < b.bottom - 1 && b.top < a.bottom - 1) {
            out.add(`${svg.closest('[id]')?.id}: "${label.textContent}" over "${other.textContent}"`);
          }
        }
      }
    }
    return [...out];
  });
}

/** Every pair of texts drawn by one mark of the charts within `selector` (an axis's tick labels
 * share a group) that overlap, as "chart id: a over b" lines: a phone's swarm strip once printed
 * "1,000" into "2,000". */
export function tickLabelOverlaps(page, selector = '.chart') {
  return page.evaluate((selector) => {
    const out = [];
    for (const group of document.querySelectorAll(`${selector} svg g`)) {
      const boxes = [...group.children].filter((t) => t.tagName === 'text' && t.textContent.trim()).map((t) => ({ text: t.textContent, r: t.getBoundingClientRect() }));
      for (const [i, a] of boxes.entries()) {
        for (const b of boxes.slice(i + 1)) {
          if (a.r.left < b.r.right - 1 && b.r.left < a.r.right - 1 && a.r.top < b.r.bottom - 1 && b.r.top < a.r.bottom - 1) {
            out.push(`${group.closest('[id]')?.id}: "${a.text}" over "${b.text}"`);
          }
        }
      }
    }
    return out;
  }, selector);
}

/** Every chart text that runs past the box its chart is drawn in (which scrolls sideways and cuts
 * off what lies outside it), as "panel: text" lines: in presentation mode "1,000" and "−140" ran
 * past the left edge and the x axis's label 2 px past the bottom. */
export function chartTextsCut(page) {
  return page.evaluate(() =>
    [...document.querySelectorAll('.chart svg text')]
      .filter((t) => t.textContent.trim() && t.getBoundingClientRect().height > 0 && !t.ownerSVGElement.parentElement.closest('svg'))
      .flatMap((t) => {
        const [box, r] = [t.closest('.chart').getBoundingClientRect(), t.getBoundingClientRect()];
        const cut = r.left < box.left - 1 || r.right > box.right + 1 || r.top < box.top - 1 || r.bottom > box.bottom + 1;
        return cut ? [`${t.closest('[data-panel]')?.dataset.panel}: "${t.textContent}" at ${Math.round(r.left - box.left)},${Math.round(r.top - box.top)}..${Math.round(r.right - box.left)},${Math.round(r.bottom - box.top)} in ${Math.round(box.width)}×${Math.round(box.height)}`] : [];
      }),
  );
}

/** Waits until no simulation or drawing is under way (`<body data-busy>` gone). */
export const idle = (page) => until(page, () => !('busy' in document.body.dataset));

/** The page's layout shifts so far that no input caused (Chromium's Layout Instability API, the
 * entries it buffers from the load on): their sum, which is the cumulative layout shift while it
 * fits one session window (the page's first seconds), and what moved in the largest, as
 * "element top→top" lines. */
export function layoutShifts(page) {
  return page.evaluate(
    () =>
      new Promise((resolve) => {
        new PerformanceObserver((list, observer) => {
          observer.disconnect();
          const shifts = list.getEntries().filter((e) => !e.hadRecentInput);
          const largest = shifts.reduce((a, b) => (b.value > (a?.value ?? 0) ? b : a), undefined);
          const moved = (largest?.sources ?? []).map((s) => `${s.node?.id || s.node?.className || s.node?.nodeName} ${Math.round(s.previousRect.top)}→${Math.round(s.currentRect.top)}`);
          resolve({ total: shifts.reduce((sum, e) => sum + e.value, 0), moved });
        }).observe({ type: 'layout-shift', buffered: true });
        // No shift at all: the observer is never called.
        setTimeout(() => resolve({ total: 0, moved: [] }), 500);
      }),
  );
}

/** Clicks `button` and returns the file it downloads (a Buffer). When none comes within 30 s the
 * error says what the page showed instead: the note beside the button (why there is nothing to
 * save; none at all when the click's handler never reached it), whether the page was still busy,
 * what lay on top of the button, whether the click itself was done, and any error the page raised
 * meanwhile. */
export async function downloaded(page, button) {
  const raised = [];
  const onError = (e) => raised.push(e.message);
  const onConsole = (m) => m.type() === 'error' && raised.push(m.text());
  page.on('pageerror', onError);
  page.on('console', onConsole);
  try {
    return await downloadedFrom(page, button, raised);
  } finally {
    page.off('pageerror', onError);
    page.off('console', onConsole);
  }
}

async function downloadedFrom(page, button, raised) {
  const describe = () =>
    button.evaluate((b) => {
      const r = b.getBoundingClientRect();
      const top = document.elementFromPoint(r.x + r.width / 2, r.y + r.height / 2);
      return {
        why: (b.closest('.buttons') ?? b.parentElement)?.querySelector('.download-why')?.textContent ?? null,
        busy: 'busy' in document.body.dataset,
        onTop: top === b || b.contains(top) ? 'the button' : (top?.outerHTML.slice(0, 160) ?? null),
      };
    });
  let clicked = 'not yet';
  const [download] = await Promise.all([
    page.waitForEvent('download').catch(async (e) => {
      const seen = await describe().catch((why) => `(not readable: ${why.message})`);
      throw new Error(`no download from ${button}: ${e.message.split('\n')[0]}; the page beside the button: ${JSON.stringify(seen)}; the click: ${clicked}; errors meanwhile: ${JSON.stringify(raised)}`);
    }),
    button.click().then(
      () => (clicked = 'done'),
      (e) => (clicked = `failed: ${e.message.split('\n')[0]}`),
    ),
  ]);
  return readFileSync(await download.path());
}

/** Scrolls to the 3D view as a reader does (it is drawn once it comes within a screen of the
 * viewport, www/main.ts) and waits for it: its canvas, then nothing left to draw. Returns the canvas. */
export async function view3d(page) {
  await page.locator('[data-panel="trajectory"]').scrollIntoViewIfNeeded();
  await page.waitForSelector('#chart-trajectory canvas');
  await idle(page);
  return page.locator('#chart-trajectory canvas');
}

/** Opens the playground, picks `title` from the Lessons menu and waits for its numbers (and, unless
 * `settled` is false, for every panel). */
export async function lesson(title, { settled = true } = {}) {
  // A user need not wait for the default results before picking a lesson, and the lesson's link
  // loads the page afresh: waiting for them here cost each lesson test a whole first run.
  const opened = await openPage(context, server.origin);
  await opened.page.goto(server.url);
  await opened.page.getByText('Lessons', { exact: true }).click();
  await opened.page.getByRole('link', { name: title }).click();
  await opened.page.waitForURL(/[?&]lesson=/);
  await waitForResults(opened.page);
  // A lesson whose claim is in the results table need not wait for the charts of a whole set
  // (the SF chart runs it six more times).
  if (settled) await idle(opened.page);
  assert.match(await opened.page.locator('#lesson-title').textContent(), new RegExp(title.replace(/[?+]/g, '\\$&')));
  return opened;
}

/** Asserts that a "Settings and results (JSON)" download holds what `loratrack simulate ARGS --json`
 * prints (but the echo's `series` flag: the page always asks for the plotted series), and that its
 * command line is that one; returns the CLI's JSON. */
export function assertDownloadIsCli(download, args) {
  const cli = nativeJson(['simulate', ...args]);
  const strip = ({ settings: _a, command: _b, series: _c, config: { series: _d, ...config }, ...rest }) => ({ config, ...rest });
  assert.deepStrictEqual(strip(download), strip(cli));
  assert.equal(download.command, ['loratrack', 'simulate', ...args].join(' '));
  return cli;
}
