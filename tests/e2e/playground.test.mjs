// The playground as a user drives it, in headless Chromium against the production build served
// under a sub-path: settings, results, downloads, links, embedding, every screen size and the 3D
// view. Every test fails on a console error, an uncaught exception, an HTTP error or a request to
// any other host. The other panels, the lessons and presentation mode are in
// playground-panels.test.mjs; the two files run side by side.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { commandJson, nativeJson, nativeText, planePlan, scratchDir, openPage, screenshot, serveDist } from './harness.mjs';
import { assertDownloadIsCli, axe, LABELS, axisLabelOverlaps, cell, cellNumber, chartTexts, chartTextsCut, downloaded, idle, layoutShifts, listed, number, open, playground, ratioWords, shownP75, tableHtml, tickLabelOverlaps, until, usePlayground, view3d, waitForResults } from './page.mjs';

usePlayground();

test('opens with the paper defaults and names no best model from one flight and one seed; ten seeds give intervals equal to the CLI', async () => {
  const { page, problems } = await open();
  assert.equal(await page.getByLabel('Spreading factor', { exact: true }).inputValue(), '7');
  assert.equal(await page.getByLabel('Bandwidth').inputValue(), '250');
  assert.equal(await page.locator('#results-table tbody tr').count(), 3);
  // One 81-s flight, one seed: no interval, so no verdict.
  assert.equal(await page.locator('#results-table tr.best').count(), 0);
  assert.match(await page.locator('#verdict-text').textContent(), /One flight with one seed cannot tell/);
  assert.match(await page.locator('#results-table caption').first().textContent(), /over 1 flight × 1 seed/);
  const before = await tableHtml(page);
  await page.getByRole('button', { name: 'Repeat with 10 seeds' }).click();
  await waitForResults(page, before);
  await idle(page);
  assert.equal(await page.getByLabel('Seeds (repeats)').inputValue(), '10');
  assert.match(await page.locator('#results-table caption').first().textContent(), /over 1 flight × 10 seeds/);
  const shown = await shownP75(page);
  const cli = nativeJson(['simulate', '--synthetic', '1', '--seeds', '10']);
  for (const s of shown) {
    const r = cli.results.find((x) => x.model === s.model);
    assert.equal(s.p75.toFixed(2), r.error3d.p75.toFixed(2), s.model);
    assert.deepEqual(s.ci, r.ci95.p75.map((v) => Number(v.toFixed(2))), s.model);
  }
  // A best model is named exactly when, on the same runs resampled together, every other's p75 is
  // clearly higher than the lowest one's (the core's paired intervals wholly above 1), and the
  // verdict quotes each ratio as the core computed it.
  const versus = cli.results.filter((x) => x.p75VsLowest);
  assert.equal(versus.length, cli.results.length - 1);
  const lowest = cli.results.find((x) => !x.p75VsLowest);
  assert.equal(lowest.model, versus[0].p75VsLowest.lowest);
  assert.equal(lowest.error3d.p75, Math.min(...cli.results.map((x) => x.error3d.p75)));
  const clear = versus.every((x) => x.p75VsLowest.interval[0] > 1);
  assert.equal(await page.locator('#results-table tr.best').count(), clear ? 1 : 0);
  const verdict = await page.locator('#verdict-text').textContent();
  if (clear) assert.equal(await page.locator('#results-table tr.best').getAttribute('data-model'), lowest.model);
  else assert.ok(verdict.startsWith(`No clear lowest p75: ${LABELS[lowest.model]}’s is lowest`), verdict);
  for (const x of versus) assert.ok(verdict.includes(ratioWords(x)), `${ratioWords(x)} in ${verdict}`);
  assert.match(page.url(), /seeds=10/);
  await page.waitForSelector('#chart-error svg');
  await page.waitForSelector('#chart-axes svg');
  await page.waitForSelector('#chart-distance svg', { timeout: 30_000 });
  await page.waitForSelector('#chart-airtime svg');
  // The sweep charts run one seed: beside a table of ten, each says so (its SF7 point is not the
  // table's p75).
  for (const name of ['sf', 'distance']) {
    await until(page, (n) => /This chart runs seed 1 alone; the results table pools 10 seeds\./.test(document.querySelector(`#${n}-rests-on`)?.textContent ?? ''), name);
  }
  // So does the error-over-time chart, which draws the first flight's first seed.
  assert.equal(await page.locator('#error-rests-on').textContent(), 'This chart is synthetic 1 with seed 1 alone; the results table pools 1 flight × 10 seeds.');
  await screenshot(page, 'playground');
  assert.deepEqual(problems, []);
});

test('SF12 shows the SF12 interval, the same number as the time-on-air table, and the results before that table is redrawn', async () => {
  const { page, problems } = await open();
  await idle(page);
  const before = await tableHtml(page);
  // When the results change, and when each panel's drawing starts (the page's `draw <panel>` measures).
  const changed = await page.evaluate(() => {
    const rows = () => document.querySelector('#results-table tbody')?.innerHTML;
    const old = rows();
    new MutationObserver((_, observer) => {
      if (rows() === old) return;
      window.__resultsAt = performance.now();
      observer.disconnect();
    }).observe(document.body, { childList: true, subtree: true, characterData: true });
    return performance.now();
  });
  await page.getByLabel('Spreading factor', { exact: true }).selectOption('12');
  await waitForResults(page, before);
  await idle(page);
  const interval = number(await cell(page, '3d-ctra', 'interval'));
  const { resultsAt, airtimeAt } = await page.evaluate((since) => ({
    resultsAt: window.__resultsAt,
    airtimeAt: performance.getEntriesByName('draw airtime').find((m) => m.startTime > since)?.startTime,
  }), changed);
  // The settings' own charts wait for the run's answer instead of holding it back.
  assert.ok(airtimeAt !== undefined && airtimeAt >= resultsAt, `airtime drawn from ${airtimeAt} ms, results at ${resultsAt} ms`);
  // The highlighted row of the airtime table is SF12 / 250 kHz; its last column is 12 B.
  const tableCell = await page.locator('.airtime-table tr.current td').last().textContent();
  assert.ok(Math.abs(number(tableCell.split('·')[1]) - interval) < 0.006, `${interval} vs ${tableCell}`);
  assert.ok(interval > 50, `SF12 interval ${interval} s`);
  assert.deepEqual(problems, []);
});

test('at a 1 Hz sensor rate each interval says how often the packets went, as the CLI counts them; at 10 Hz the interval alone', async () => {
  const { page, problems } = await open('?sensorRate=1');
  await idle(page);
  const cli = nativeJson(['simulate', '--synthetic', '1', '--sensor-rate', '1']);
  const csv = (await downloaded(page, page.getByRole('button', { name: 'Results (CSV)' }))).toString('utf8').trim().split('\n').map((l) => l.split(','));
  for (const [i, m] of cli.results.entries()) {
    // A packet waits for a whole-second step: SF7's 3.08 s become 4 s, DR's 2.83 s 3 s.
    assert.ok(Math.abs(m.sentEvery - Math.ceil(m.interval)) < 1e-9, `${m.model}: ${m.sentEvery}`);
    assert.ok(m.sentSlower, `${m.model}: the core's flag the cell and the CLI's line read`);
    assert.equal(await cell(page, m.model, 'interval'), `${m.interval.toFixed(2)} s sent every ${m.sentEvery.toFixed(2)}\u00a0s`);
    assert.equal(Number(csv[i + 1][csv[0].indexOf('sent_every_s')]), m.sentEvery);
  }
  // Back at 10 Hz the step adds at most 0.1 s, and the cell is the interval alone.
  const before = await tableHtml(page);
  await page.getByRole('button', { name: 'Reset', exact: true }).click();
  await waitForResults(page, before);
  for (const m of nativeJson(['simulate', '--synthetic', '1']).results) {
    assert.equal(m.sentSlower, false, m.model);
    assert.equal(await cell(page, m.model, 'interval'), `${m.interval.toFixed(2)} s`);
  }
  assert.deepEqual(problems, []);
});

test('5 km at SF7 loses packets and the bandwidth changes the time on air', async () => {
  const { page, problems } = await open();
  assert.equal(await cell(page, 'dr', 'delivery'), '100 %');
  let before = await tableHtml(page);
  await page.getByRole('slider', { name: /Distance/ }).fill('5000');
  await waitForResults(page, before);
  const delivery = number(await cell(page, 'dr', 'delivery'));
  assert.ok(delivery < 100, `delivery at 5 km: ${delivery} %`);
  const toa250 = number(await cell(page, 'dr', 'toa'));
  before = await tableHtml(page);
  await page.getByLabel('Bandwidth').selectOption('125');
  await waitForResults(page, before);
  assert.ok(Math.abs(number(await cell(page, 'dr', 'toa')) - 2 * toa250) < 0.2);
  await screenshot(page, 'five-km');
  assert.deepEqual(problems, []);
});

test('one model at a time, and the whole synthetic set', async () => {
  // At 100 Hz one model's whole set runs for seconds, not a few hundred milliseconds: on a busy
  // machine the page's main thread could otherwise first be polled after the set had ended.
  const { page, problems } = await open('?sensorRate=100');
  let before = await tableHtml(page);
  await page.getByLabel('Model').selectOption('ctra-plus');
  await waitForResults(page, before);
  assert.equal(await page.locator('#results-table tbody tr').count(), 1);
  before = await tableHtml(page);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('all');
  // The whole set shows its progress while it runs (polled every 10 ms: animation frames are
  // throttled on a busy machine)...
  await until(
    page,
    () => {
      const p = document.querySelector('#progress');
      return p && !p.hidden && p.value > 0;
    },
    null,
    { polling: 10 },
  );
  // ...and the next change interrupts it: the results that arrive are for SF8.
  await page.getByLabel('Spreading factor', { exact: true }).selectOption('8');
  await waitForResults(page, before);
  // The table can change before the run ends (the first flights come first): read the status once
  // all is drawn.
  await idle(page);
  assert.match(await page.locator('#status').textContent(), /30 flights, 2640 s/);
  const interval = number(await cell(page, 'ctra-plus', 'interval'));
  assert.ok(interval > 5, `SF8 interval expected, got ${interval} s`);
  assert.match(await page.locator('#ttn-note').textContent(), /30 s of airtime a day/);
  assert.deepEqual(problems, []);
});

test('the whole set shows its first flight at once, marked as that flight alone with the CLI’s numbers, then the whole set', async () => {
  // At 300 Hz the set takes several seconds; its first flight is a thirtieth of that. The first
  // flight's own numbers come from the CLI before the page opens: run in the page's partial
  // state, the CLI took a second of the few the test has before the set ends. At 100 Hz, on this
  // 2-core machine with the fuzzers running beside the suite, the set once ended while the test
  // was still reading the partial table.
  const cli = nativeJson(['simulate', '--synthetic', '1', '--sensor-rate', '300']);
  const { page, problems } = await openPage(playground.context, new URL(playground.url).origin, { width: 1280, height: 800 });
  await page.goto(`${playground.url}?flight=all&sensorRate=300`);
  await page.waitForSelector('[data-panel="results"].partial #results-table tbody tr', { timeout: 30_000 });
  assert.match(await page.locator('#results-table caption').first().textContent(), /over 1 flight × 1 seed/);
  assert.match(await page.locator('#status').textContent(), /Flight 1 of the 30 shown, its numbers alone/);
  assert.equal(await page.locator('#verdict').isVisible(), false);
  const marker = await page.locator('#results-table').evaluate((t) => getComputedStyle(t, '::before').content);
  assert.match(marker, /First flight only/);
  const shown = await shownP75(page);
  // The downloads and Pin would give the previous report, not this table: they say why they wait.
  await page.getByRole('button', { name: 'Results (CSV)' }).click();
  const why = page.locator('[data-panel="results"] .download-why');
  assert.match(await why.textContent(), /The whole set is still running: its results can be saved or pinned when it ends/);
  assert.equal(await page.locator('[data-panel="results"].partial').count(), 1, 'the set still running while checked');
  for (const s of shown) assert.equal(s.p75.toFixed(2), cli.results.find((x) => x.model === s.model).error3d.p75.toFixed(2), s.model);
  assert.deepEqual(await axe(page), []);
  await waitForResults(page);
  assert.match(await page.locator('#results-table caption').first().textContent(), /over 30 flights × 1 seed/);
  assert.equal(await page.locator('[data-panel="results"].partial').count(), 0);
  assert.equal(await why.textContent(), '');
  const download = await downloaded(page, page.getByRole('button', { name: 'Results (CSV)' }));
  // The file is the set's report: 30 runs per station, the p75s the table now shows.
  const [header, ...rows] = download.toString('utf8').trim().split('\n').map((l) => l.split(','));
  const final = await shownP75(page);
  for (const row of rows) {
    const col = (name) => row[header.indexOf(name)];
    assert.equal(col('runs'), '30', row.join(','));
    assert.equal(Number(col('p75_m')).toFixed(2), final.find((f) => f.model === col('model')).p75.toFixed(2), col('model'));
  }
  assert.equal(rows.length, 3);
  // The error chart still draws the first flight; every station's band held over the set (the
  // CSV's under_bound95, as the coverage cells' titles give it), so the note under it says only
  // which flight it draws.
  const held = rows.map((row) => `${Math.round(100 * Number(row[header.indexOf('under_bound95')]))} %`);
  const titles = await page.locator('#results-table td[data-field="coverage"]').evaluateAll((cells) => cells.map((c) => c.getAttribute('title')));
  for (const [i, title] of titles.entries()) assert.ok(title.includes(`stayed under its 95 % bound (the error chart's band) ${held[i]} of the time`), `${held[i]} in ${title}`);
  assert.ok(held.every((h) => parseInt(h, 10) >= 90), held.join(', '));
  await until(page, () => /pools 30 flights/.test(document.querySelector('#error-rests-on')?.textContent ?? ''));
  assert.equal(await page.locator('#error-rests-on').textContent(), 'This chart is synthetic 1 with seed 1 alone; the results table pools 30 flights × 1 seed.');
  assert.deepEqual(problems, []);
});

test('an answer that arrives as a newer run starts is not shown over it: the status and progress stay the new run\'s', async () => {
  const { page, problems } = await openPage(playground.context, new URL(playground.url).origin, { width: 1280, height: 800 });
  // The page shows an answer in the task after the message that brought it. Here SF8 is chosen in
  // the very task in which the whole set's first flight (at SF7) arrives from the last worker: the
  // SF7 set stops, an SF8 set starts, and SF7's first flight must not then take over the page.
  await page.addInitScript(() => {
    const Base = window.Worker;
    // The pool's workers, each with some of the three stations: as many answer with a first flight.
    let spawned = 0;
    let partials = 0;
    window.Worker = class extends Base {
      constructor(...args) {
        super(...args);
        spawned++;
      }
      set onmessage(handler) {
        super.onmessage = (e) => {
          handler(e);
          if (!(e.data && 'partial' in e.data) || ++partials !== Math.min(3, spawned)) return;
          const seen = () => ({ status: document.querySelector('#status').textContent, progress: !document.querySelector('#progress').hidden, partial: document.querySelector('[data-panel="results"]').classList.contains('partial') });
          const choose = () => {
            // The form answers once the page's script (main.ts) has taken over the run boot.ts
            // started: on a busy machine the workers, their module already compiled in this
            // renderer, can answer before it has (the status still the HTML's "Loading…").
            if (document.querySelector('#status').textContent === 'Loading…') return setTimeout(choose, 0);
            const sf = document.querySelector('#sf');
            sf.value = '8';
            sf.dispatchEvent(new Event('input', { bubbles: true }));
            // Read once the page has had its next tasks (the deferred answer's among them), well
            // before the new run's fresh workers can answer.
            setTimeout(() => (window.__afterSwitch = seen()), 10);
          };
          choose();
        };
      }
    };
  });
  await page.goto(`${playground.url}?flight=all`);
  const after = await until(page, () => window.__afterSwitch).then((h) => h.jsonValue());
  assert.match(after.status, /^Simulating 30 flights/, JSON.stringify(after));
  assert.equal(after.progress, true);
  assert.equal(after.partial, false);
  await waitForResults(page);
  assert.match(await page.locator('#status').textContent(), /synthetic all: 30 flights/);
  // The numbers are SF8's: its frames' time on air, as the CLI gives it.
  const sf8 = nativeJson(['simulate', '--synthetic', '1', '--sf', '8']).results.find((r) => r.model === 'dr');
  assert.equal(await cell(page, 'dr', 'toa'), `${(sf8.timeOnAir * 1e3).toFixed(1)} ms`);
  assert.equal(await page.locator('[data-panel="results"].stale').count(), 0);
  assert.deepEqual(problems, []);
});

test('a setting chosen before the page’s script runs is kept, simulated and put in the link', async () => {
  const { page, problems } = await openPage(playground.context, new URL(playground.url).origin);
  // main.ts held back, as on a slow phone: the form, parsed with the HTML, already works.
  let release;
  const held = new Promise((resolve) => (release = resolve));
  await page.route(/\/assets\/main-[^/]*\.js$/, async (route) => {
    await held;
    await route.continue();
  });
  await page.goto(playground.url);
  await page.selectOption('#sf', '9');
  assert.equal(await page.locator('#status').textContent(), 'Loading…');
  release();
  await waitForResults(page);
  assert.equal(await page.locator('#sf').inputValue(), '9');
  assert.match(new URL(page.url()).search, /(^\?|&)sf=9(&|$)/);
  // The numbers are SF9's: its frames' time on air, as the CLI gives it.
  const sf9 = nativeJson(['simulate', '--synthetic', '1', '--sf', '9']).results.find((r) => r.model === 'dr');
  assert.equal(await cell(page, 'dr', 'toa'), `${(sf9.timeOnAir * 1e3).toFixed(1)} ms`);
  assert.equal(await page.locator('[data-panel="results"].stale').count(), 0);
  assert.deepEqual(problems, []);
});

test('a good CSV is simulated and a bad one is refused next to the control', async () => {
  const { page, problems } = await open();
  const dir = scratchDir();
  const good = join(dir, 'circle.csv');
  const rows = ['t,x,y,z'];
  for (let i = 0; i <= 600; i++) {
    const t = i * 0.1;
    rows.push(`${t.toFixed(1)},${(30 * Math.cos(t / 6)).toFixed(3)},${(30 * Math.sin(t / 6)).toFixed(3)},${(20 + t / 10).toFixed(3)}`);
  }
  writeFileSync(good, rows.join('\n'));
  const bad = join(dir, 'bad.csv');
  writeFileSync(bad, 't,x,y,z\n0,1,2,3\n1,1,2,oops\n');

  let before = await tableHtml(page);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('csv');
  // Until a file is chosen nothing runs, and the synthetic flight's numbers say they are old.
  await until(page, () => /^Choose a CSV file to simulate it; the results below are for the previous settings\.$/.test(document.querySelector('#status')?.textContent ?? ''));
  assert.equal(await page.locator('[data-panel="results"].stale').count(), 1);
  await page.getByLabel('CSV file').setInputFiles(good);
  await waitForResults(page, before);
  assert.match(await page.locator('#status').textContent(), /circle\.csv/);
  assert.equal(await page.locator('[data-panel="results"].stale').count(), 0);

  await page.getByLabel('CSV file').setInputFiles(bad);
  await page.waitForSelector('#csv-error:not([hidden])');
  assert.match(await page.locator('#csv-error').textContent(), /line 3: column 'z' is not a number/);
  // The page stays usable: the previous results remain and the controls still work.
  assert.equal(await page.locator('#results-table tbody tr').count(), 3);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('synthetic');
  before = await tableHtml(page);
  await page.getByLabel('Spreading factor', { exact: true }).selectOption('8');
  await waitForResults(page, before);
  assert.deepEqual(problems, []);
});

test('the command line under the results gives their numbers, a shell reading it as copied, for a link and for an uploaded flight', async () => {
  const models = ['dr', 'ctra-plus', '3d-ctra', 'imm'];
  const { page, problems } = await open('?flight=canberra&sf=8&distance=2500&prediction=bounded&model=dr,ctra-plus,3d-ctra,imm&seeds=2&gateways=800,0;-300,400,25');
  await page.locator('[data-panel="results"] details.explain summary').click();
  const line = await page.locator('[data-command="results"] code').textContent();
  assert.match(line, /^loratrack simulate --sample canberra .*--gateway 800,0 --gateway -300,400,25/);
  const cli = commandJson(line);
  assert.equal(cli.config.seeds, 2);
  for (const shown of await shownP75(page, models)) {
    assert.equal(shown.p75.toFixed(2), cli.results.find((r) => r.model === shown.model).error3d.p75.toFixed(2), shown.model);
  }
  // Copy command copies that line; the JSON download carries it.
  await page.context().grantPermissions(['clipboard-read', 'clipboard-write']);
  await page.getByRole('button', { name: 'Copy command', exact: true }).click();
  assert.equal(await page.evaluate(() => navigator.clipboard.readText()), line);
  const json = JSON.parse((await downloaded(page, page.locator('#download-json'))).toString('utf8'));
  assert.equal(json.command, line);
  // An uploaded flight is named by its file, quoted for the shell, and runs where the file is.
  const dir = scratchDir();
  const file = join(dir, "Pat's flight.csv");
  writeFileSync(file, ['t,x,y,z', ...Array.from({ length: 601 }, (_, i) => `${i / 10},${(2 * i) / 10},${Math.sin(i / 50).toFixed(3)},30`)].join('\n'));
  const before = await tableHtml(page);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('csv');
  await page.locator('#csv').setInputFiles(file);
  await waitForResults(page, before);
  const upload = await page.locator('[data-command="results"] code').textContent();
  assert.match(upload, /^loratrack simulate --trajectory 'Pat'\\''s flight\.csv' /);
  assert.match(await page.locator('[data-command="results"] .command-files').textContent(), /run where Pat's flight\.csv is/);
  const fromFile = commandJson(upload, dir);
  for (const shown of await shownP75(page, models)) {
    assert.equal(shown.p75.toFixed(2), fromFile.results.find((r) => r.model === shown.model).error3d.p75.toFixed(2), shown.model);
  }
  assert.deepEqual(problems, []);
});

test("a flight faster than the payload's speed byte says which packets were sent at the range's edge, as the CLI counts them", async () => {
  // A minute straight east at 30 m/s: every packet's speed is sent as 25.5 m/s.
  const path = join(scratchDir(), 'fast.csv');
  const rows = ['t,x,y,z'];
  for (let i = 0; i <= 600; i++) rows.push(`${(i / 10).toFixed(1)},${(3 * i).toFixed(1)},0,50`);
  writeFileSync(path, rows.join('\n'));
  const { page, problems } = await open();
  assert.equal(await page.locator('#saturated-note').isVisible(), false, 'the synthetic flight stays within every range');
  const before = await tableHtml(page);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('csv');
  await page.locator('#csv').setInputFiles(path);
  await waitForResults(page, before);
  const cli = nativeJson(['simulate', '--trajectory', path]).results;
  assert.ok(cli.every((m) => m.packetsReceived > 0 && m.caveats.saturatedPackets === m.packetsReceived && m.caveats.saturated.join() === 'v'), JSON.stringify(cli.map((m) => m.caveats)));
  const note = await page.locator('#saturated-note').textContent();
  const counts = listed(cli.map((m) => `${LABELS[m.model]} ${m.caveats.saturatedPackets} of ${m.packetsReceived}`));
  assert.ok(note.startsWith(`Saturated: ${counts} received packets carried a value beyond the payload's range (speed, 0–25.5 m/s), sent as the range's edge.`), note);
  assert.equal(await page.locator('#saturated-note a').getAttribute('href'), 'docs/reference.html', 'the doc it names is a link');
  // The Results CSV carries the counts and the fields, row by row.
  const [header, ...body] = (await downloaded(page, page.getByRole('button', { name: 'Results (CSV)' }))).toString('utf8').trim().split('\n').map((l) => l.split(','));
  const [count, fields] = ['saturated_packets', 'saturated_fields'].map((name) => header.indexOf(name));
  assert.deepEqual(body.map((r) => [Number(r[count]), r[fields]]), cli.map((m) => [m.caveats.saturatedPackets, 'v']));
  // The table on a slide carries the note as well.
  const slide = (await downloaded(page, page.getByRole('button', { name: 'Download the results table as SVG' }))).toString('utf8').replace(/<[^>]+>/g, ' ').replace(/\s+/g, ' ');
  assert.ok(slide.includes(note.split('. ')[0]), `the slide's caption: ${slide.slice(-600)}`);
  assert.deepEqual(await axe(page), []);
  assert.deepEqual(problems, []);
});

test("a long uploaded flight's error chart and error series CSV say they are its envelope, with the CLI's series", async () => {
  // Ten minutes at 10 Hz: 6000 evaluation times a station, more than the 3000 a series keeps.
  const dir = scratchDir();
  const path = join(dir, 'long.csv');
  const rows = ['t,x,y,z'];
  for (let i = 0; i <= 6000; i++) {
    const t = i / 10;
    rows.push(`${t.toFixed(1)},${(300 * Math.cos(t / 60)).toFixed(3)},${(300 * Math.sin(t / 60)).toFixed(3)},${(40 + 10 * Math.sin(t / 90)).toFixed(3)}`);
  }
  writeFileSync(path, rows.join('\n'));
  const { page, problems } = await open();
  const before = await tableHtml(page);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('csv');
  await page.locator('#csv').setInputFiles(path);
  await waitForResults(page, before);
  // Not every panel: the distance and SF charts run the flight 12 times more.
  await page.waitForSelector('#chart-error .note');
  const cli = nativeJson(['simulate', '--trajectory', path, '--series']).series.models;
  assert.ok(cli.every((m) => m.samples > m.t.length), `the CLI's series: ${cli.map((m) => `${m.t.length} of ${m.samples}`)}`);
  const note = await page.locator('#chart-error .note').textContent();
  assert.match(note, new RegExp(`${Math.max(...cli.map((m) => m.samples)).toLocaleString('en')} samples a station are drawn as their envelope`));
  // Each station's line is thinned to at most two points a pixel of its axis (narrower than the
  // SVG), and its band's dashed edge to one, a step (two segments) each.
  const [axis, points, edges] = await page.evaluate(() => {
    const svg = [...document.querySelectorAll('#chart-error svg')].find((s) => Number(s.getAttribute('width')) > 100);
    const drawn = (attribute, value) => [...svg.querySelectorAll('path')].filter((p) => p.getAttribute(attribute) === value || p.parentElement?.getAttribute(attribute) === value);
    const vertices = (p) => (p.getAttribute('d').match(/L/g) ?? []).length + 1;
    return [Number(svg.getAttribute('width')), drawn('stroke-width', '1.4').map(vertices), drawn('stroke-dasharray', '3,3').map(vertices)];
  });
  assert.equal(points.length, cli.length, 'one line a station');
  assert.ok(points.every((n) => n <= 2 * axis), `points a line: ${points} on ${axis} px`);
  assert.equal(edges.length, cli.length, 'one band a station');
  assert.ok(edges.every((n) => n <= 2 * axis), `vertices a band's edge: ${edges} on ${axis} px`);
  // The CSV names itself an envelope: per stretch of time, each station's lowest and highest of
  // the samples the CLI's series keeps there.
  const [download] = await Promise.all([page.waitForEvent('download'), page.locator('#download-csv').click()]);
  assert.equal(download.suggestedFilename(), 'loratrack-error-envelope.csv');
  const [header, ...body] = readFileSync(await download.path(), 'utf8').trim().split('\n').map((r) => r.split(','));
  assert.deepEqual(header, ['t_from_s', 't_to_s', ...cli.flatMap((m) => [`${m.model}_min_error3d_m`, `${m.model}_max_error3d_m`])]);
  // Each row's times are the first and last kept evaluation time in its stretch, as printed.
  const within = (t, r) => Number(r[0]) <= Number(t.toFixed(2)) && Number(t.toFixed(2)) <= Number(r[1]);
  cli.forEach((m, k) => {
    const [lo, hi] = [2 + 2 * k, 3 + 2 * k];
    const filled = body.filter((r) => r[lo] !== '');
    assert.ok(filled.length >= m.t.length / 4, `${m.model}: ${filled.length} stretches for ${m.t.length} samples`);
    for (const r of filled) {
      const kept = m.error3d.filter((_, i) => within(m.t[i], r)).map((e) => e.toFixed(4));
      assert.ok(kept.includes(r[lo]) && kept.includes(r[hi]), `${m.model} ${r.slice(0, 2)}: ${r[lo]}, ${r[hi]} of ${kept}`);
    }
    // A sample on the printed edge of two stretches lies in one of them.
    m.t.forEach((t, i) => {
      const e = Number(m.error3d[i].toFixed(4));
      assert.ok(filled.some((r) => within(t, r) && Number(r[lo]) <= e && e <= Number(r[hi])), `${m.model} at ${t} s: ${e}`);
    });
    assert.equal(Math.max(...filled.map((r) => Number(r[hi]))).toFixed(4), Math.max(...m.error3d).toFixed(4), `${m.model}: the peak`);
  });
  assert.deepEqual(problems, []);
  await page.close();
});

test('an uploaded flight with its uploaded plan runs the mission station, with the CLI\'s numbers; a bad plan is refused next to its control', async () => {
  const { page, problems } = await open();
  const dir = scratchDir();
  // A 100 m square at 5 m/s and 30 m, flown once round with a 10 s hold at its far corner, and
  // its plan (the hold in its fifth column).
  const corner = (k) => [[0, 0], [100, 0], [100, 100], [0, 100]][k % 4];
  const rows = ['t,x,y,z'];
  for (let i = 0; i <= 900; i++) {
    const t = i * 0.1;
    const s = (t < 40 ? 5 * t : t < 50 ? 200 : 5 * (t - 10)) % 400;
    const [a, b] = [corner(Math.floor(s / 100)), corner(Math.floor(s / 100) + 1)];
    const w = (s % 100) / 100;
    rows.push(`${(i * 0.1).toFixed(1)},${(a[0] + w * (b[0] - a[0])).toFixed(3)},${(a[1] + w * (b[1] - a[1])).toFixed(3)},30`);
  }
  const flight = join(dir, 'square.csv');
  writeFileSync(flight, rows.join('\n') + '\n');
  const plan = join(dir, 'square-plan.csv');
  writeFileSync(plan, 'x,y,z,speed,hold\n0,0,30\n100,0,30,5\n100,100,30,5,10\n0,100,30,5\n0,0,30,5\n');

  let before = await tableHtml(page);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('csv');
  await page.getByLabel('CSV file').setInputFiles(flight);
  await waitForResults(page, before);
  // No plan yet: the mission station is not offered, and says why.
  assert.equal(await page.locator('#model option[value="3d-ctra,mission"]').isDisabled(), true);
  assert.match(await page.locator('#model-note').textContent(), /upload its plan too/);
  await page.getByLabel(/Flight plan/).setInputFiles(plan);
  await until(page, () => !document.querySelector('#model option[value="3d-ctra,mission"]').disabled);
  // The paper's stations read no plan: the results leave it out, and the CLI refuses it there.
  const unread = await page.locator('[data-command="results"] code').textContent();
  assert.equal(unread, 'loratrack simulate --trajectory square.csv');
  assert.match(await page.locator('#plan-help').textContent(), /Other stations read only its vehicle, and only bounded with Vehicle “As the plan says”; otherwise the results leave the plan out/);
  assert.throws(() => nativeText(['simulate', '--trajectory', flight, '--plan', plan]), (e) => e.status === 2 && /^error: --plan is read over a logged flight by the mission station alone/.test(e.stderr));
  before = await tableHtml(page);
  await page.getByLabel('Model').selectOption('3d-ctra,mission');
  await waitForResults(page, before);
  const cli = nativeJson(['simulate', '--trajectory', flight, '--plan', plan, '--model', '3d-ctra,mission']);
  for (const m of ['3d-ctra', 'mission']) {
    const r = cli.results.find((x) => x.model === m);
    assert.equal(number(await cell(page, m, 'p75')).toFixed(2), r.error3d.p75.toFixed(2), m);
  }
  // The page's command names both files, and run where they are prints the same results.
  const command = await page.locator('[data-command="results"] code').textContent();
  assert.equal(command, 'loratrack simulate --trajectory square.csv --plan square-plan.csv --model 3d-ctra,mission');
  assert.match(await page.locator('[data-command="results"] .command-files').textContent(), /run where square\.csv and square-plan\.csv are/);
  assert.deepStrictEqual(commandJson(command, dir).results, cli.results);
  // The 3D view draws the plan, whichever worker ran the mission station.
  await view3d(page);
  assert.match(await page.locator('#trajectory-legend').textContent(), /flight plan \(dashed\)/);
  assert.deepEqual(await axe(page), []);

  // The same square as QGroundControl saves a mission (`fileType: "Plan"`, its home in Canberra,
  // latitude and longitude about it): take-off at home, then the corners at 6 m/s, the far one's
  // hold as its waypoint's first parameter.
  const hold = ([x, y]) => (x === 100 && y === 100 ? 10 : 0);
  const home = [-35.3632, 149.1652, 584];
  const k = (Math.PI / 180) * 6371000;
  const at = ([x, y]) => [home[0] + y / k, home[1] + x / (k * Math.cos((home[0] * Math.PI) / 180))];
  const item = (command, params) => ({ type: 'SimpleItem', command, frame: 3, autoContinue: true, AMSLAltAboveTerrain: null, Altitude: params[6], AltitudeMode: 1, params });
  const items = [item(22, [0, 0, 0, null, ...at([0, 0]), 30]), item(178, [1, 6, -1, 0, 0, 0, 0]), ...[[100, 0], [100, 100], [0, 100], [0, 0]].map((c) => item(16, [hold(c), 0, 0, null, ...at(c), 30]))];
  const qgc = join(dir, 'square.plan');
  writeFileSync(qgc, JSON.stringify({ fileType: 'Plan', version: 1, groundStation: 'QGroundControl', geoFence: { circles: [], polygons: [], version: 2 }, rallyPoints: { points: [], version: 2 }, mission: { version: 2, firmwareType: 3, vehicleType: 2, cruiseSpeed: 15, hoverSpeed: 5, plannedHomePosition: home, items } }, null, 4));
  const fromQgc = nativeJson(['simulate', '--trajectory', flight, '--plan', qgc, '--model', '3d-ctra,mission']).results.find((x) => x.model === 'mission');
  assert.notEqual(fromQgc.error3d.p75, cli.results.find((x) => x.model === 'mission').error3d.p75);
  before = await tableHtml(page);
  await page.getByLabel(/Flight plan/).setInputFiles(qgc);
  await waitForResults(page, before);
  assert.equal(number(await cell(page, 'mission', 'p75')).toFixed(2), fromQgc.error3d.p75.toFixed(2));
  assert.doesNotMatch(await page.locator('#status').textContent(), /plane/);
  // The same square as a plane's plan: the station follows it round a plane's turns, and the status line says so.
  const planeSquare = join(dir, 'square-plane.plan');
  writeFileSync(planeSquare, readFileSync(qgc, 'utf8').replace('"vehicleType": 2', '"vehicleType": 1'));
  const fromPlane = nativeJson(['simulate', '--trajectory', flight, '--plan', planeSquare, '--model', '3d-ctra,mission']);
  assert.equal(fromPlane.config.planCornering, 'fixed-wing');
  before = await tableHtml(page);
  await page.getByLabel(/Flight plan/).setInputFiles(planeSquare);
  await waitForResults(page, before);
  assert.equal(number(await cell(page, 'mission', 'p75')).toFixed(2), fromPlane.results.find((x) => x.model === 'mission').error3d.p75.toFixed(2));
  assert.match(await page.locator('#status').textContent(), / The mission station follows the plan as a plane flies it \(ArduPlane’s wide turns\)\.$/);
  // And as Mission Planner saves it (a `QGC WPL 110` list, home as item 0), at 7 m/s.
  const wpl = join(dir, 'square.waypoints');
  const line = (i, frame, command, params) => [i, i === 0 ? 1 : 0, frame, command, ...params, 1].join('\t');
  writeFileSync(wpl, ['QGC WPL 110', line(0, 0, 16, [0, 0, 0, 0, ...home]), line(1, 3, 22, [0, 0, 0, 0, ...at([0, 0]), 30]), line(2, 3, 178, [1, 7, -1, 0, 0, 0, 0]), ...[[100, 0], [100, 100], [0, 100], [0, 0]].map((c, i) => line(3 + i, 3, 16, [hold(c), 0, 0, 0, ...at(c), 30]))].join('\n') + '\n');
  const fromList = nativeJson(['simulate', '--trajectory', flight, '--plan', wpl, '--model', '3d-ctra,mission']).results.find((x) => x.model === 'mission');
  assert.notEqual(fromList.error3d.p75, fromQgc.error3d.p75);
  before = await tableHtml(page);
  await page.getByLabel(/Flight plan/).setInputFiles(wpl);
  await waitForResults(page, before);
  assert.equal(number(await cell(page, 'mission', 'p75')).toFixed(2), fromList.error3d.p75.toFixed(2));
  // The flight as a GPS log (latitude, longitude, altitude above sea level) that starts on the
  // ground at that home and climbs to the square at 5 m/s: read in metres from its first row,
  // the list's frame.
  const gps = join(dir, 'square-gps.csv');
  const climb = Array.from({ length: 60 }, (_, i) => [i / 10, ...at([0, 0]), home[2] + i / 2]);
  const square = rows.slice(1).map((r) => { const [t, x, y, z] = r.split(',').map(Number); return [t + 6, ...at([x, y]), home[2] + z]; });
  writeFileSync(gps, ['time,Lat,Lng,Alt', ...[...climb, ...square].map((r) => r.join(','))].join('\n') + '\n');
  const fromGps = nativeJson(['simulate', '--trajectory', gps, '--plan', wpl, '--model', '3d-ctra,mission']).results.find((x) => x.model === 'mission');
  before = await tableHtml(page);
  await page.getByLabel('CSV file').setInputFiles(gps);
  await waitForResults(page, before);
  assert.equal(number(await cell(page, 'mission', 'p75')).toFixed(2), fromGps.error3d.p75.toFixed(2));

  const bad = join(dir, 'bad-plan.csv');
  writeFileSync(bad, '0,0,30\n100,zero,30\n');
  await page.getByLabel(/Flight plan/).setInputFiles(bad);
  await page.waitForSelector('#plan-error:not([hidden])');
  assert.match(await page.locator('#plan-error').textContent(), /plan line 2/);
  assert.equal(await page.locator('#results-table tbody tr').count(), 2);
  assert.deepEqual(problems, []);
});

test('a plan alone is flown: the page\'s numbers are the CLI\'s for --plan alone, its command says so, and a plan too long to fly is refused next to its control', async () => {
  const { page, problems } = await open();
  const dir = scratchDir();
  const plan = join(dir, 'survey.csv');
  writeFileSync(plan, 'x,y,z,speed,hold\n0,0,0\n0,0,30,3\n200,0,30,8,20\n200,150,40,6,10\n0,150,40\n0,0,30,8\n0,0,0,2\n');
  let before = await tableHtml(page);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('plan');
  // Nothing to fly yet: the page says what it needs, and the CSV flight's control is not shown.
  await until(page, () => /Choose a flight plan to fly it/.test(document.querySelector('#status').textContent));
  assert.equal(await page.locator('#csv').isVisible(), false);
  await page.getByLabel(/Flight plan/).setInputFiles(plan);
  await waitForResults(page, before);
  await until(page, () => !document.querySelector('#model option[value="3d-ctra,mission"]').disabled);
  before = await tableHtml(page);
  await page.getByLabel('Model').selectOption('3d-ctra,mission');
  await waitForResults(page, before);
  const cli = nativeJson(['simulate', '--plan', plan, '--model', '3d-ctra,mission']);
  assert.equal(cli.config.trajectory, `${plan} (flown)`);
  // What the numbers rest on: the plan flown as planned, by a multicopter (this CSV plan names no vehicle).
  assert.equal(cli.config.planCornering, 'multicopter');
  assert.match(await page.locator('#status').textContent(), /^survey\.csv \(flown\): 1 flight, \d+ s simulated .* The plan is flown as a multicopter flies it, exactly, without wind: the mission station’s best case\.$/);
  for (const m of ['3d-ctra', 'mission']) {
    const r = cli.results.find((x) => x.model === m);
    assert.equal(number(await cell(page, m, 'p75')).toFixed(2), r.error3d.p75.toFixed(2), m);
  }
  const command = await page.locator('[data-command="results"] code').textContent();
  assert.equal(command, 'loratrack simulate --plan survey.csv --model 3d-ctra,mission');
  assert.deepStrictEqual(commandJson(command, dir).results, cli.results);
  assert.deepEqual(await axe(page), []);

  // A plane's QGroundControl plan is flown with ArduPlane's turns, and the status line says so.
  const plane = join(dir, 'plane.plan');
  writeFileSync(plane, planePlan());
  before = await tableHtml(page);
  await page.getByLabel(/Flight plan/).setInputFiles(plane);
  await waitForResults(page, before);
  const flownAsPlane = nativeJson(['simulate', '--plan', plane, '--model', '3d-ctra,mission']);
  assert.equal(flownAsPlane.config.planCornering, 'fixed-wing');
  assert.match(await page.locator('#status').textContent(), /^plane\.plan \(flown\): .* The plan is flown as a plane flies it \(ArduPlane’s wide turns\), exactly/);
  for (const m of ['3d-ctra', 'mission']) {
    assert.equal(number(await cell(page, m, 'p75')).toFixed(2), flownAsPlane.results.find((x) => x.model === m).error3d.p75.toFixed(2), m);
  }
  // The 3D view draws the plan as the station follows it, round the turns, and says so.
  await page.locator('[data-panel="trajectory"]').scrollIntoViewIfNeeded();
  await until(page, () => /flight plan, round a plane’s turns \(dashed\)/.test(document.querySelector('#trajectory-legend')?.textContent ?? ''));
  // The Vehicle control overrides the file's: the plane's plan flown by a multicopter, then the
  // CSV plan, which names none, flown by a plane, each with the CLI's --vehicle numbers.
  for (const [file, vehicle, words] of [[plane, 'multicopter', 'a multicopter flies it'], [plan, 'fixed-wing', 'a plane flies it']]) {
    if (file === plan) {
      before = await tableHtml(page);
      await page.getByLabel(/Flight plan/).setInputFiles(plan);
      await waitForResults(page, before);
    }
    before = await tableHtml(page);
    await page.getByLabel('Vehicle').selectOption(vehicle);
    await waitForResults(page, before);
    const set = nativeJson(['simulate', '--plan', file, '--model', '3d-ctra,mission', '--vehicle', vehicle]);
    assert.equal(set.config.planCornering, vehicle);
    assert.match(await page.locator('#status').textContent(), new RegExp(`The plan is flown as ${words}`));
    for (const m of ['3d-ctra', 'mission']) {
      assert.equal(number(await cell(page, m, 'p75')).toFixed(2), set.results.find((x) => x.model === m).error3d.p75.toFixed(2), `${vehicle} ${m}`);
    }
    assert.match(await page.locator('[data-command="results"] code').textContent(), new RegExp(` --vehicle ${vehicle}$`));
  }
  assert.deepEqual(await axe(page), []);
  before = await tableHtml(page);
  await page.getByLabel('Vehicle').selectOption('auto');
  await waitForResults(page, before);
  // A CSV plan may say itself that a plane flies it: flown as the file says, with the CLI's
  // numbers for that file, and no --vehicle in the command.
  const marked = join(dir, 'plane-survey.csv');
  writeFileSync(marked, `# vehicle: fixed-wing\n${readFileSync(plan, 'utf8')}`);
  before = await tableHtml(page);
  await page.getByLabel(/Flight plan/).setInputFiles(marked);
  await waitForResults(page, before);
  const asTheFileSays = nativeJson(['simulate', '--plan', marked, '--model', '3d-ctra,mission']);
  assert.equal(asTheFileSays.config.planCornering, 'fixed-wing');
  assert.match(await page.locator('#status').textContent(), /The plan is flown as a plane flies it/);
  for (const m of ['3d-ctra', 'mission']) {
    assert.equal(number(await cell(page, m, 'p75')).toFixed(2), asTheFileSays.results.find((x) => x.model === m).error3d.p75.toFixed(2), `marked ${m}`);
  }
  assert.equal(await page.locator('[data-command="results"] code').textContent(), 'loratrack simulate --plan plane-survey.csv --model 3d-ctra,mission');

  const long = join(dir, 'loiter.csv');
  writeFileSync(long, 'x,y,z,speed,hold\n0,0,30\n30,0,30,3,86400\n');
  await page.getByLabel(/Flight plan/).setInputFiles(long);
  await page.waitForSelector('#plan-error:not([hidden])');
  assert.match(await page.locator('#plan-error').textContent(), /takes 86412 s to fly; a flown plan lasts at most 40000 s/);
  assert.equal(await page.locator('#results-table tbody tr').count(), 2);
  assert.deepEqual(problems, []);
});

test('the URL carries the state: a shared link reopens the same view; embed shows only chosen panels', async () => {
  const { page, problems } = await open();
  const before = await tableHtml(page);
  await page.getByLabel('Spreading factor', { exact: true }).selectOption('9');
  await page.getByLabel('Model').selectOption('3d-ctra');
  await waitForResults(page, before);
  const url = page.url();
  assert.match(url, /sf=9/);
  const again = await open(url.slice(playground.url.length));
  assert.equal(await again.page.getByLabel('Spreading factor', { exact: true }).inputValue(), '9');
  assert.equal(await again.page.locator('#results-table tbody tr').count(), 1);
  assert.equal(await cell(again.page, '3d-ctra', 'p75'), await cell(page, '3d-ctra', 'p75'));

  const embedded = await open('?embed=1&panels=results,error&sf=8');
  assert.equal(await embedded.page.locator('#controls').isVisible(), false);
  assert.equal(await embedded.page.locator('[data-panel="results"]').isVisible(), true);
  assert.equal(await embedded.page.locator('[data-panel="axes"]').isVisible(), false);
  await screenshot(embedded.page, 'embed');
  assert.deepEqual([...problems, ...again.problems, ...embedded.problems], []);
});

test('works on a phone-sized screen and by keyboard', async () => {
  const { page, problems } = await open('', { width: 390, height: 844 });
  const before = await tableHtml(page);
  await page.getByLabel('Spreading factor', { exact: true }).focus();
  await page.keyboard.press('ArrowDown');
  await waitForResults(page, before);
  assert.equal(await page.getByLabel('Spreading factor', { exact: true }).inputValue(), '8');
  await screenshot(page, 'phone');
  assert.deepEqual(problems, []);
});

test('every screen: the page does not jump as its results come, no sideways scrolling from a phone to a projector, and chart text stays legible and clear of other text', async () => {
  for (const [width, height, least] of [[360, 740, 11], [390, 844, 11], [768, 1024, 11], [1024, 768, 12], [1280, 800, 12], [1920, 1080, 12]]) {
    const { page, problems } = await open('', { width, height });
    await idle(page);
    // The table and the charts fill room kept for them (style.css): 0.09–0.15 at these screens
    // before, where Web Vitals call 0.1 poor; a setting that draws a box another height may move
    // the page once.
    const shift = await layoutShifts(page);
    console.log(`# ${width}x${height}: layout shift while loading ${shift.total.toFixed(4)}`);
    assert.ok(shift.total <= 0.03, `${width}x${height}: the page moved as its results came (layout shift ${shift.total.toFixed(3)}; the largest moved ${shift.moved.join(', ')})`);
    // `data-busy` gone means all in view is drawn: the 3D view too where it lies within a screen
    // of the viewport (at 1920×1080 once the panels above are drawn), and not elsewhere.
    const near = await page.evaluate(() => document.querySelector('[data-panel="trajectory"]').getBoundingClientRect().top < 2 * innerHeight);
    assert.equal(await page.locator('#chart-trajectory canvas').count(), near ? 1 : 0, `${width}x${height}: the 3D view ${near ? 'not drawn although' : 'drawn although not'} near when the page fell idle`);
    // The whole page, as a reader scrolls it: the 3D view is drawn once it comes near.
    await view3d(page);
    const m = await page.evaluate(() => {
      const sizes = [...document.querySelectorAll('.chart svg text')]
        .filter((t) => t.getBoundingClientRect().height > 0)
        .map((t) => {
          const svg = t.ownerSVGElement;
          const scale = svg.getBoundingClientRect().width / (svg.viewBox.baseVal?.width || svg.getBoundingClientRect().width);
          return parseFloat(getComputedStyle(t).fontSize) * scale;
        });
      return { scrollWidth: document.documentElement.scrollWidth, smallest: Math.min(...sizes), texts: sizes.length };
    });
    assert.ok(m.scrollWidth <= width, `${width}x${height}: the document is ${m.scrollWidth} px wide`);
    assert.ok(m.texts > 20, `${width}: chart text found`);
    assert.ok(m.smallest >= least, `${width}x${height}: chart text down to ${m.smallest.toFixed(1)} px`);
    console.log(`# ${width}x${height}: document ${m.scrollWidth} px wide, chart text >= ${m.smallest.toFixed(1)} px`);
    if (width <= 600) {
      // On a phone the headers stay on one line: no empty band above the columns in view.
      const [head, row] = await page.evaluate(() => ['thead', 'tbody tr'].map((s) => document.querySelector(`#results-table ${s}`).getBoundingClientRect().height));
      assert.ok(head <= 1.2 * row, `${width}x${height}: the results table's header is ${head} px tall, a row ${row} px`);
    }
    assert.deepEqual(await axisLabelOverlaps(page), [], `${width}x${height}: axis labels on other text`);
    assert.deepEqual(await tickLabelOverlaps(page), [], `${width}x${height}: tick labels on one another`);
    assert.deepEqual(await chartTextsCut(page), [], `${width}x${height}: chart text cut off`);
    // A table wider than the screen scrolls; what its numbers rest on (its caption) stays within
    // the visible width, scrolled or not.
    for (const scrolled of [0, 10_000]) {
      const cut = await page.evaluate((left) => {
        const out = [];
        for (const wrap of document.querySelectorAll('.table-wrap')) {
          const caption = wrap.querySelector('caption');
          if (!caption || wrap.getBoundingClientRect().width === 0) continue;
          wrap.scrollLeft = left;
          const [w, c] = [wrap.getBoundingClientRect(), caption.getBoundingClientRect()];
          if (c.left < w.left - 1 || c.right > w.right + 1) out.push(`${wrap.closest('[id]').id}: caption ${c.left}..${c.right} in ${w.left}..${w.right}`);
          // So do the row headers that name each row (the results' model; the time on air's SF and
          // bandwidth), side by side.
          let right = w.left;
          const headers = wrap.querySelectorAll('tbody tr:first-child th');
          const named = { 'results-table': 1, 'airtime-table': 2 }[wrap.closest('[id]').id];
          if (named !== undefined && headers.length !== named) out.push(`${wrap.closest('[id]').id}: ${headers.length} row headers, not ${named}`);
          for (const th of headers) {
            const r = th.getBoundingClientRect();
            if (r.left < right - 1 || r.right > w.right + 1) out.push(`${wrap.closest('[id]').id}: row header "${th.textContent}" at ${r.left}..${r.right}, the visible ${right}..${w.right}`);
            right = r.right;
          }
          wrap.scrollLeft = 0;
        }
        return out;
      }, scrolled);
      assert.deepEqual(cut, [], `${width}x${height}, scrolled ${scrolled}: a caption or a row header runs off its table's visible width`);
    }
    // From a tablet up the results do not scroll sideways at all: where one table would (831 px in
    // 702 at 768 px), the link's half goes under the tracking error's.
    if (width >= 768) {
      const over = await page.locator('#results-table .table-wrap').evaluateAll((wraps) => wraps.map((w) => w.scrollWidth - w.clientWidth));
      assert.ok(over.every((o) => o <= 1), `${width}x${height}: the results scroll sideways by ${over} px`);
    }
    // The headline p75 is on the table's first screen, not after a sideways scroll.
    const [p75, wrap] = [await page.locator('#results-table td[data-field="p75"]').first().boundingBox(), await page.locator('#results-table .table-wrap').first().boundingBox()];
    assert.ok(p75.x + p75.width <= wrap.x + wrap.width + 1, `${width}x${height}: p75 at ${p75.x}..${p75.x + p75.width}, the table shows up to ${wrap.x + wrap.width}`);
    // Every control can be reached: the last one is on the page, within its width.
    const last = await page.getByRole('button', { name: 'New seed' }).boundingBox();
    assert.ok(last.x >= 0 && last.x + last.width <= width, `${width}: New seed at ${last.x}`);
    assert.deepEqual(problems, []);
    await page.close();
  }
});

test('a page whose HTML arrives slowly does not move when the rest of it comes', async () => {
  // The settings form first, the results panel (which a narrow screen shows above it) 0.4 s later,
  // as a slow network or a busy device delivers it: painted in between, the form moved down by the
  // panel's height (0.29 at 1024x768 on a busy machine).
  const slow = await serveDist(undefined, { after: '</form>', ms: 400 });
  try {
    for (const [width, height] of [[390, 844], [1024, 768]]) {
      const { page, problems } = await openPage(playground.context, slow.origin, { width, height });
      await page.goto(slow.url);
      await waitForResults(page);
      const shift = await layoutShifts(page);
      assert.ok(shift.total <= 0.03, `${width}x${height}: layout shift ${shift.total.toFixed(3)} (${shift.moved.join(', ')})`);
      assert.deepEqual(problems, []);
    }
  } finally {
    slow.close();
  }
});

test('the JSON download equals the native CLI bit for bit, stations split over the worker pool', async () => {
  for (const [query, args] of [
    ['?flight=canberra&seed=7', ['--sample', 'canberra', '--seed', '7']],
    ['?model=dr%2Cctra-plus%2C3d-ctra%2Cimm&distance=3000&prediction=bounded', ['--synthetic', '1', '--model', 'dr,ctra-plus,3d-ctra,imm', '--distance', '3000', '--prediction', 'bounded']],
  ]) {
    const { page, problems } = await open(query);
    const download = await downloaded(page, page.getByRole('button', { name: /JSON/ }));
    const browserJson = JSON.parse(download.toString('utf8'));
    const cli = nativeJson(['simulate', ...args]);
    assert.deepStrictEqual(browserJson.results, cli.results, query);
    // The totals of the merged report add up every station's run, as the CLI's do.
    for (const key of ['packetsSent', 'packetsReceived', 'deliveryRatio', 'duplicates', 'gateways']) assert.deepStrictEqual(browserJson[key], cli[key], `${query}: ${key}`);
    assert.deepEqual(problems, []);
    await page.close();
  }
});

test('the bounded and IMM stations and error-triggered sending are one control away, and the URL keeps them', async () => {
  const { page, problems } = await open('?distance=3000');
  let before = await tableHtml(page);
  await page.getByLabel('Model').selectOption('dr,ctra-plus,3d-ctra,imm');
  await waitForResults(page, before);
  assert.equal(await page.locator('#results-table tbody tr').count(), 4);
  assert.match(await cell(page, 'imm', 'coverage'), /^\d+ %$/);
  const paperMean = number(await cell(page, '3d-ctra', 'mean'));
  before = await tableHtml(page);
  await page.getByLabel('Station prediction').selectOption('bounded');
  await waitForResults(page, before);
  assert.match(page.url(), /prediction=bounded/);
  assert.match(await page.locator('#results-table caption').first().textContent(), /bounded prediction/);
  const boundedMean = number(await cell(page, '3d-ctra', 'mean'));
  assert.ok(boundedMean <= paperMean, `bounded ${boundedMean} vs paper ${paperMean}`);

  assert.equal(await page.getByLabel('Threshold (m)').isVisible(), false);
  const periodicSent = number((await cell(page, '3d-ctra', 'packets')).split('/')[1]);
  before = await tableHtml(page);
  await page.getByLabel('Sending').selectOption('error');
  await waitForResults(page, before);
  assert.equal(await page.getByLabel('Threshold (m)').isVisible(), true);
  before = await tableHtml(page);
  await page.getByLabel('Threshold (m)').fill('5');
  await waitForResults(page, before);
  const errorSent = number((await cell(page, '3d-ctra', 'packets')).split('/')[1]);
  assert.ok(errorSent < periodicSent, `error-triggered sent ${errorSent}, periodic ${periodicSent}`);
  assert.match(page.url(), /sender=error/);
  assert.match(page.url(), /threshold=5/);
  // The table says what its numbers rest on: the sender, its threshold and heartbeat (not whether
  // it listens to its channel: a drone alone never hears another's frame).
  assert.match(await page.locator('#results-table caption').first().textContent(), /error-triggered sending \(5 m, heartbeat 10 s\)/);
  // At 3 km packets are lost: the results say what the drone's silence rests on.
  assert.equal(await page.locator('#silence-note').isVisible(), true);
  // A drone alone never hears another packet, so one that does not listen sends the same: the
  // results do not read it (the CLI refuses it in simulate) and stand; the link keeps it, for the
  // swarm panel, whose command line carries it.
  before = await tableHtml(page);
  const command = await page.locator('[data-command="results"] code').textContent();
  await page.getByLabel('Channel sensing').selectOption('off');
  await until(page, () => /channelSense=off/.test(location.href));
  assert.equal(await tableHtml(page), before);
  assert.equal(await page.locator('[data-command="results"] code').textContent(), command);
  assert.doesNotMatch(command, /--channel-sense/);
  assert.throws(() => nativeText(['simulate', '--synthetic', '1', '--sender', 'error', '--channel-sense', 'off']), (e) => e.status === 2 && /--channel-sense is a swarm setting/.test(e.stderr));
  // Back to periodic sending: the form keeps the threshold and listening (hidden) but does not
  // send them, which the core would refuse as settings nothing reads; the run and its command
  // line are periodic sending's.
  const listening = await tableHtml(page);
  await page.getByLabel('Sending').selectOption('periodic');
  await waitForResults(page, listening);
  assert.equal(number((await cell(page, '3d-ctra', 'packets')).split('/')[1]), periodicSent);
  await page.locator('[data-panel="results"] details.explain summary').click();
  const line = await page.locator('[data-command="results"] code').textContent();
  assert.doesNotMatch(line, /--threshold|--channel-sense|--sender/, line);
  assert.doesNotMatch(await page.locator('#status').textContent(), /threshold|channelSense/);
  assert.deepEqual(problems, []);
});

test('the bounded station offers an adaptive heading noise, with the CLI\'s numbers; the paper station neither offers nor sends it', async () => {
  const { page, problems } = await open('?prediction=bounded&model=3d-ctra');
  const noise = page.getByLabel('Heading noise');
  assert.equal(await noise.isVisible(), true);
  const before = await tableHtml(page);
  await noise.selectOption('adaptive');
  await waitForResults(page, before);
  assert.match(page.url(), /headingNoise=adaptive/);
  assert.match(await page.locator('#results-table caption').first().textContent(), /bounded prediction, adaptive heading noise/);
  const cli = nativeJson(['simulate', '--synthetic', '1', '--model', '3d-ctra', '--prediction', 'bounded', '--heading-noise', 'adaptive']);
  assert.equal((await cell(page, '3d-ctra', 'p75')).split(' ')[0], cli.results[0].error3d.p75.toFixed(2));
  assert.deepEqual(await axe(page), []);
  // The paper's station has no hedge to choose: the control goes, and the run does not fail.
  const adaptive = await tableHtml(page);
  await page.getByLabel('Station prediction').selectOption('paper');
  await waitForResults(page, adaptive);
  assert.equal(await noise.isVisible(), false);
  assert.match(await page.locator('#results-table caption').first().textContent(), /paper prediction$/);
  assert.doesNotMatch(await page.locator('#status').textContent(), /headingNoise/);
  assert.deepEqual(problems, []);
});

test('the tilt decay is offered and sent only where a station decays the tilt rate, as the core reads it', async () => {
  // A link with a tilt decay and DR alone: the core would refuse eta there, so the page keeps it
  // (hidden) without sending it, and the run and its command line are DR's.
  const { page, problems } = await open('?model=dr&eta=0.5');
  await page.locator('#advanced > summary').click();
  assert.equal(await page.getByLabel('Sensor rate (Hz)').isVisible(), true, 'the advanced settings are open');
  assert.equal(await page.getByLabel('Tilt decay eta').isVisible(), false);
  await page.locator('[data-panel="results"] details.explain summary').click();
  const command = () => page.locator('[data-command="results"] code').textContent();
  assert.doesNotMatch(await command(), /--eta/);
  const cli = nativeJson(['simulate', '--synthetic', '1', '--model', 'dr']);
  assert.equal((await cell(page, 'dr', 'p75')).split(' ')[0], cli.results[0].error3d.p75.toFixed(2));
  // 3D-CTRA decays it: the field shows and the run takes it, as the CLI does.
  const before = await tableHtml(page);
  await page.getByLabel('Model', { exact: true }).selectOption('3d-ctra');
  await waitForResults(page, before);
  assert.equal(await page.getByLabel('Tilt decay eta').isVisible(), true);
  assert.match(await command(), / --eta 0\.5/);
  const tilted = nativeJson(['simulate', '--synthetic', '1', '--model', '3d-ctra', '--eta', '0.5']);
  assert.equal((await cell(page, '3d-ctra', 'p75')).split(' ')[0], tilted.results[0].error3d.p75.toFixed(2));
  assert.deepEqual(problems, []);
});

test('where packets are lost, an error-triggered run says what its silence rests on, with the table\'s share of losses', async () => {
  const { page, problems } = await open('?sender=error&distance=3000&prediction=bounded&model=3d-ctra');
  await idle(page);
  const [received, sent] = (await cell(page, '3d-ctra', 'packets')).split('/').map(number);
  assert.ok(received < 0.95 * sent, `${received} of ${sent} received at 3 km`);
  // The bound that the losses let grow runs off the error chart, its peak written at the top, and
  // the scale stays the errors': at most twice the largest (the table's max, on this one flight).
  await page.waitForSelector('#chart-error svg');
  const peak = await page.locator('#chart-error svg text', { hasText: /95 % bound up to/ }).textContent();
  const bound = number(peak.match(/up to (\d+) m/)[1]);
  const largest = await cellNumber(page, '3d-ctra', 'max');
  // The y axis's tick labels: Plot sets them end-anchored in tabular figures (the x axis's are centred).
  const ticks = (await page.locator('#chart-error svg g[text-anchor="end"][font-variant="tabular-nums"] text').allTextContents()).map(number);
  const top = Math.max(...ticks);
  assert.ok(ticks.length > 1 && top <= 2 * largest && top < bound, `${ticks} against errors up to ${largest} m and a bound up to ${bound} m`);
  const note = await page.locator('#silence-note').textContent();
  assert.match(note, new RegExp(`^${Math.round(100 * (1 - received / sent))} % of the packets sent were lost\\. An error-triggered drone cannot tell a lost packet from a delivered one`), note);
  // The table on a slide, and an embed without the table, carry the note too.
  const download = await downloaded(page, page.getByRole('button', { name: 'Download the results table as SVG' }));
  const slide = download.toString('utf8').replace(/<[^>]+>/g, ' ').replace(/\s+/g, ' ');
  assert.ok(slide.includes(note.split('. ')[0]), `the slide's caption: ${slide.slice(-600)}`);
  const embedded = await open('?embed=1&panels=error&sender=error&distance=3000&prediction=bounded&model=3d-ctra');
  await idle(embedded.page);
  assert.ok((await embedded.page.locator('#embed-notices').textContent()).includes(note), 'the embed\'s notices');
  // Periodic sending at the same distance learns nothing from silence: no such note.
  const before = await tableHtml(page);
  await page.getByLabel('Sending').selectOption('periodic');
  await waitForResults(page, before);
  assert.equal(await page.locator('#silence-note').isVisible(), false);
  // Nor does error-triggered sending where every packet arrives (1 km).
  const near = await open('?sender=error&model=3d-ctra');
  await idle(near.page);
  assert.match(await cell(near.page, '3d-ctra', 'delivery'), /^100 %$/);
  assert.equal(await near.page.locator('#silence-note').isVisible(), false);
  assert.deepEqual([...problems, ...near.problems, ...embedded.problems], []);
});

test('adaptive data rate is one control away: from SF12 it speeds up and says where the packets went', async () => {
  const { page, problems } = await open('?flight=all&model=3d-ctra&sf=12&bw=125');
  assert.equal(await page.locator('#rate-use').isVisible(), false);
  const fixedReceived = number(await cell(page, '3d-ctra', 'packets'));
  const before = await tableHtml(page);
  await page.getByLabel('Adaptive data rate').selectOption('tracking');
  await waitForResults(page, before);
  assert.match(page.url(), /adr=tracking/);
  const note = await page.locator('#rate-use').textContent();
  assert.match(note, /DR6 \(SF7\/250\) \d+/, note);
  const adaptiveReceived = number(await cell(page, '3d-ctra', 'packets'));
  assert.ok(adaptiveReceived >= fixedReceived, `ADR received ${adaptiveReceived}, SF7 ${fixedReceived}`);
  // The table's caption names the adaptation its numbers rest on, and the status's range is the
  // starting rate's, not the one most packets went at.
  assert.match(await page.locator('#results-table caption').first().textContent(), /; tracking ADR from SF12, 125 kHz$/);
  assert.match(await page.locator('#status').textContent(), /Gateway range at SF12, 125 kHz, where ADR starts \(/);
  // The link budget's bold sensitivity is only where ADR starts the drone.
  await until(page, () => /the chosen SF's bold: where ADR starts the drone/.test(document.querySelector('#chart-link .note')?.textContent ?? ''));
  // The SF chart's points keep their SF: its note says so beside the table's ADR.
  await until(page, () => /Each point keeps its SF fixed; the results table's tracking ADR moves the rate/.test(document.querySelector('#sf-rests-on')?.textContent ?? ''));
  assert.deepEqual(problems, []);
});

// ---- Playground v2 defects: each test failed on the page before its fix ------------------------


test('axe finds no violation at all, on the full page and embedded', async () => {
  const { page, problems } = await open();
  await idle(page);
  await page.waitForSelector('#chart-distance svg');
  // Every panel drawn, the 3D view included (it waits until the reader comes near).
  await view3d(page);
  assert.deepEqual(await axe(page), []);
  await page.goto(`${playground.url}?embed=1&panels=results,error,distance`);
  await waitForResults(page);
  await idle(page);
  assert.deepEqual(await axe(page), []);
  assert.deepEqual(problems, []);
});

test('each row of the results CSV says what made it, in words, as a link that opens the page at the same numbers and as the command line that prints them', async () => {
  const { page, problems } = await open('?sf=9&bw=125&distance=2000');
  await idle(page);
  const text = (await downloaded(page, page.getByRole('button', { name: 'Results (CSV)' }))).toString('utf8');
  // Cells are quoted where they hold a comma (the settings in words do).
  const rows = text.trim().split('\n').map((line) => [...line.matchAll(/("(?:[^"]|"")*"|[^,]*)(?:,|$)/g)].map((m) => m[1].replace(/^"|"$/g, '').replace(/""/g, '"')).slice(0, -1));
  const [header, ...body] = rows;
  assert.deepEqual(header.slice(-3), ['settings', 'link', 'command']);
  assert.equal(body.length, 3);
  const col = (row, name) => row[header.indexOf(name)];
  for (const row of body) {
    assert.equal(row.length, header.length, row.join('|'));
    assert.match(col(row, 'settings'), /SF9, 125 kHz, 2\.0 km.*synthetic flight 1; seed 1; loratrack \d+\.\d+\.\d+/);
  }
  assert.ok(body.every((row) => col(row, 'command') === 'loratrack simulate --synthetic 1 --sf 9 --bw 125 --distance 2000'), body.map((r) => col(r, 'command')).join('|'));
  const cli = commandJson(col(body[0], 'command'));
  for (const row of body) assert.equal(col(row, 'p75_m'), String(cli.results.find((r) => r.model === row[0]).error3d.p75), row[0]);
  const link = new URL(col(body[0], 'link'));
  assert.deepEqual(Object.fromEntries(link.searchParams), { sf: '9', bw: '125', distance: '2000' });
  // The link opens the page at the same settings, whose table gives the file's numbers.
  await page.goto(link.href);
  await waitForResults(page);
  for (const s of await shownP75(page)) assert.equal(s.p75.toFixed(2), Number(col(body.find((r) => r[0] === s.model), 'p75_m')).toFixed(2), s.model);
  assert.deepEqual(problems, []);
});

test('every chart and both tables download ready for a slide: title, legend, caption with settings, seed and version; PNGs at least 1600 px wide', async () => {
  const { page, problems } = await open();
  await idle(page);
  const save = (locator) => downloaded(page, locator);
  for (const [panel, title] of [['error', 'Error over time'], ['distance', 'Error versus distance'], ['axes', 'Error along each axis'], ['link', 'Link budget'], ['airtime', 'Time on air']]) {
    const svg = (await save(page.getByRole('button', { name: new RegExp(`^Download the ${title.toLowerCase()}.* chart as SVG$`) }))).toString('utf8');
    const width = Number(/<svg[^>]*\swidth="(\d+)/.exec(svg)[1]);
    assert.ok(width > 250, `${panel}: an SVG ${width} px wide`);
    assert.match(svg, new RegExp(`>${title}`), `${panel}: titled`);
    assert.match(svg, /SF7, 250 kHz, 1\.0 km.*synthetic flight 1; seed 1; loratrack \d+\.\d+\.\d+/, `${panel}: captioned`);
    if (['error', 'distance', 'axes'].includes(panel)) assert.match(svg, />CTRA\+</, `${panel}: a legend`);
    assert.match(svg, /\((m|ms|km|dBm)[,)]/, `${panel}: axis units`);
    // What the marks mean, which the page says in the panel's "What this shows": the slide, with no
    // panel beside it, says it under the chart.
    const words = svg.replace(/<[^>]+>/g, ' ').replace(/\s+/g, ' ');
    const key = { error: /● packet arrived · ✕ packet lost · dashed band: the station's own 95 % bound/, distance: /whiskers: the furthest errors within 1\.5 box heights/, axes: /whiskers/, link: /Dashed lines: each SF's sensitivity/, airtime: /Lines: each SF at 250 kHz, the time on air of a payload plus 13 B of LoRaWAN overhead\. Black dots: the models' payloads/ }[panel];
    assert.match(words, key, `${panel}: its key`);
    // At these settings every band held (the CLI's underBound95, 95–100 %): no note on how often.
    if (panel === 'error') {
      assert.ok(nativeJson(['simulate', '--synthetic', '1']).results.every((x) => x.underBound95 >= 0.895));
      assert.ok(!words.includes('does not calibrate'), words.slice(-700));
    }
    // The legend, each entry once (the link budget draws one above each of its two charts), in
    // rows that stay on the slide.
    const legend = [...svg.matchAll(/<text x="([\d.]+)"[^>]*font-size="14"[^>]*>([^<]+)</g)].map((m) => ({ x: Number(m[1]), label: m[2] }));
    assert.ok(legend.length > 1, `${panel}: legend ${JSON.stringify(legend)}`);
    assert.equal(new Set(legend.map((e) => e.label)).size, legend.length, `${panel}: legend ${legend.map((e) => e.label)}`);
    for (const e of legend) assert.ok(e.x + 8 * e.label.length <= width, `${panel}: ${e.label} at ${e.x} px on a slide ${width} px wide`);
    const png = await save(page.getByRole('button', { name: new RegExp(`^Download the ${title.toLowerCase()}.* chart as PNG$`) }));
    assert.ok(png.readUInt32BE(16) >= 1600, `${panel}: a PNG ${png.readUInt32BE(16)} px wide`);
  }
  // The results table as a picture: the numbers on show, what they are and what they rest on.
  const table = (await save(page.getByRole('button', { name: 'Download the results table as SVG' }))).toString('utf8');
  assert.match(table, />Results</);
  // Its caption wraps over several lines: read as running text.
  const words = table.replace(/<[^>]+>/g, ' ').replace(/\s+/g, ' ');
  assert.match(words, /3D tracking error \(m\) at the station.*SF7, 250 kHz, 1\.0 km.*synthetic flight 1; seed 1; loratrack \d+\.\d+\.\d+/, 'results: captioned');
  for (const model of ['dr', 'ctra-plus', '3d-ctra']) assert.ok(table.includes(`>${(await cell(page, model, 'p75')).trim().split(/\s+/)[0]}<`), `results: ${model}'s p75 in the picture`);
  const tablePng = await save(page.getByRole('button', { name: 'Download the results table as PNG' }));
  assert.ok(tablePng.readUInt32BE(16) >= 1600, `results: a PNG ${tablePng.readUInt32BE(16)} px wide`);
  const shot = await save(page.getByRole('button', { name: 'Download the 3d trajectory chart as PNG' }));
  assert.ok(shot.readUInt32BE(16) >= 1600, `3D view: a PNG ${shot.readUInt32BE(16)} px wide`);
  const results = (await save(page.getByRole('button', { name: 'Results (CSV)' }))).toString('utf8').trim().split('\n');
  assert.equal(results.length, 4);
  assert.match(results[0], /^model,payload_bytes,.*p75_m,p75_lo_m,p75_hi_m/);
  const p75 = Number(results[1].split(',')[9]);
  assert.equal(p75.toFixed(2), number(await cell(page, 'dr', 'p75')).toFixed(2));
  // What the errors rest on: the share of the flight time after its first packet (SF7: most of it).
  const tracked = Number(results[1].split(',')[results[0].split(',').indexOf('tracked_share')]);
  assert.ok(tracked > 0.95 && tracked < 1, `tracked share ${tracked}`);
  // The time-on-air table as numbers a spreadsheet reads: one row per SF, bandwidth and payload,
  // in seconds, each the table's cell before it is rounded.
  const [airHead, ...airRows] = (await save(page.getByRole('button', { name: 'Time-on-air table (CSV)' }))).toString('utf8').trim().split('\n').map((l) => l.split(','));
  assert.deepEqual(airHead, ['sf', 'bandwidth_khz', 'data_rate', 'payload_bytes', 'model', 'time_on_air_s', 'interval_s', 'refused', 'settings']);
  assert.equal(airRows.length, 6 * 3 * 3);
  assert.deepEqual(airRows.find((r) => r[0] === '7' && r[1] === '250' && r[3] === '12').slice(0, 5), ['7', '250', 'DR6', '12', '3d-ctra'], "the plan names each pair's data rate");
  const tableRows = await page.locator('.airtime-table tbody tr').evaluateAll((rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));
  for (const [sf, bw, rate, ...cells] of tableRows) {
    const csv = airRows.filter((r) => `SF${r[0]}` === sf && `${r[1]} kHz` === bw);
    assert.deepEqual(csv.map((r) => r[2]), [rate, rate, rate], `${sf} ${bw}`);
    assert.deepEqual(csv.map((r) => `${(Number(r[5]) * 1e3).toFixed(1)} ms · ${Number(r[6]).toFixed(2)} s`), cells, `${sf} ${bw}`);
  }
  // The time-on-air table as a picture (Table II on a slide): each row as the page shows it, the
  // current data rate shaded, captioned with what the numbers are and the settings they follow.
  const airSvg = (await save(page.getByRole('button', { name: 'Download the time on air table as SVG' }))).toString('utf8');
  assert.match(airSvg, />Time on air</);
  assert.match(airSvg.replace(/<[^>]+>/g, ' ').replace(/\s+/g, ' '), /EU868 at a 1 % duty cycle: time on air · shortest interval.*SF7, 250 kHz.*13 B LoRaWAN overhead.*loratrack \d+\.\d+\.\d+/, 'time on air: captioned');
  // The page's caption names the overhead and coding rate beside the table; the slide's caption names
  // them with every other setting, so once.
  assert.equal(airSvg.split('overhead').length - 1, 1, 'time on air: the slide names the overhead once');
  const shown = await page.locator('.airtime-table tbody tr').evaluateAll((rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));
  assert.equal(shown.length, 18);
  for (const row of shown) for (const text of row) assert.ok(airSvg.includes(`>${text}<`), `time on air: "${text}" in the picture`);
  assert.equal((airSvg.match(/fill="#fff7d6"/g) ?? []).length, 1, 'time on air: the current data rate shaded');
  const airPng = await save(page.getByRole('button', { name: 'Download the time on air table as PNG' }));
  assert.ok(airPng.readUInt32BE(16) >= 1600, `time on air: a PNG ${airPng.readUInt32BE(16)} px wide`);
  // Before any swarm, and where no packet arrives, a download says why instead of doing nothing.
  await page.getByRole('button', { name: 'Download the swarm chart as PNG' }).click();
  await until(page, () => /run a swarm first/.test(document.querySelector('[data-panel="swarm"] .download-why')?.textContent ?? ''));
  const far = await open('?distance=9000');
  await idle(far.page);
  await far.page.getByRole('button', { name: 'Download the error over time chart as SVG' }).click();
  await until(far.page, () => /no packet reached the station/.test(document.querySelector('[data-panel="error"] .download-why')?.textContent ?? ''));
  // Once packets arrive the chart is drawn again, and the note, which spoke of the empty one, goes.
  await far.page.getByRole('slider', { name: /Distance/ }).fill('1000');
  await until(far.page, () => document.querySelector('[data-panel="error"] .download-why')?.textContent === '' && document.querySelector('#chart-error svg'));
  assert.deepEqual([...problems, ...far.problems], []);
});

test('a change leaves the charts it cannot change as drawn, their downloads naming the settings on show; a change of SF draws them again', async () => {
  const { page, problems } = await open();
  await idle(page);
  // Each chart on show is marked: a chart drawn again is a new element, without the mark.
  const panels = ['airtime', 'distance', 'link', 'error', 'axes'];
  const mark = () => page.evaluate((names) => names.forEach((n) => (document.querySelector(`#chart-${n}`).firstElementChild.dataset.seen = n)), panels);
  const kept = () => page.evaluate((names) => names.filter((n) => document.querySelector(`#chart-${n}`).firstElementChild.dataset.seen === n), panels);
  await mark();
  // Well within SF7's reach every packet still arrives: the same numbers (the CLI's at 1 and 1.5
  // km), so only the link budget's red line moves, and the distance chart's grey column, which
  // stood on its 1 km box and has none at 1.5 km.
  const at1km = await tableHtml(page);
  assert.equal(await page.locator('#chart-distance .chosen-column rect').count(), 1);
  await page.locator('#distance').fill('1500');
  await idle(page);
  assert.equal(await tableHtml(page), at1km);
  assert.deepEqual(await kept(), ['airtime', 'error', 'axes']);
  assert.equal(await page.locator('#chart-distance .chosen-column rect').count(), 0);
  await mark();
  const before = await tableHtml(page);
  // Far enough to lose packets: new numbers, but time on air and the distance sweep do not depend
  // on the distance, nor (at neither distance a box) the column.
  await page.locator('#distance').fill('3500');
  await waitForResults(page, before);
  await idle(page);
  assert.deepEqual(await kept(), ['airtime', 'distance']);
  for (const title of ['time on air', 'error versus distance']) {
    const svg = (await downloaded(page, page.getByRole('button', { name: new RegExp(`^Download the ${title}.* chart as SVG$`) }))).toString('utf8');
    assert.match(svg, /SF7, 250 kHz, 3\.5 km/, `${title}: captioned with the distance now set`);
  }
  // So do the time-on-air table's picture and CSV, whose numbers the distance leaves as they were.
  const tableSvg = (await downloaded(page, page.getByRole('button', { name: 'Download the time on air table as SVG' }))).toString('utf8');
  assert.match(tableSvg.replace(/<[^>]+>/g, ' ').replace(/\s+/g, ' '), /SF7, 250 kHz, 3\.5 km/, 'time-on-air table: captioned with the distance now set');
  const tableCsv = (await downloaded(page, page.getByRole('button', { name: 'Time-on-air table (CSV)' }))).toString('utf8');
  assert.match(tableCsv.split('\n')[1], /"SF7, 250 kHz, 3\.5 km/, 'time-on-air CSV: its settings the ones now set');
  await mark();
  const far = await tableHtml(page);
  await page.getByLabel('Spreading factor', { exact: true }).selectOption('8');
  await waitForResults(page, far);
  await idle(page);
  assert.deepEqual(await kept(), []);
  assert.equal(await page.locator('.airtime-table tr.current th').first().textContent(), 'SF8');
  assert.deepEqual(problems, []);
});

test('the error-series CSV has every model in its column', async () => {
  const { page, problems } = await open('?distance=3000');
  const download = await downloaded(page, page.getByRole('button', { name: /Error series/ }));
  const rows = download.toString('utf8').trim().split('\n').map((r) => r.split(','));
  assert.deepEqual(rows[0], ['t_s', 'dr_error3d_m', 'ctra-plus_error3d_m', '3d-ctra_error3d_m']);
  for (let k = 1; k <= 3; k++) assert.ok(rows.slice(1).filter((r) => r[k] !== '').length > 100, `column ${rows[0][k]} is empty`);
  assert.deepEqual(problems, []);
});

test('where no packet arrives, every panel says so instead of NaN or blanks, and log axes read in metres', async () => {
  for (const viewport of [undefined, { width: 360, height: 740 }]) {
    const { page, problems } = await open('?distance=5000', viewport);
    await idle(page);
    assert.doesNotMatch(await page.locator('#results-table').innerText(), /NaN/);
    assert.match(await page.locator('#chart-error').innerText(), /No packet arrives/);
    const distance = await chartTexts(page, '#chart-distance');
    assert.ok(distance.includes('no packet arrives'), distance.join(' | '));
    const ticks = await page.locator('#chart-distance svg text').allTextContents();
    assert.ok(!ticks.some((t) => /\d[mk]$/.test(t)), `SI-prefixed ticks: ${ticks.filter((t) => /\d[mk]$/.test(t))}`);
    // The note stays within its own distance's column, clear of the boxes beside it (on a phone a
    // column is ~45 px wide). The boxes (Q1–Q3) are the chart's rects; its grid and whiskers are lines.
    const overBoxes = await page.evaluate(() => {
      const svg = [...document.querySelectorAll('#chart-distance svg')].at(-1);
      const notes = [...svg.querySelectorAll('text')].filter((t) => t.textContent.replaceAll(' ', '') === 'nopacketarrives');
      // The chosen distance's grey column stands behind its note by design: not a box.
      const boxes = [...svg.querySelectorAll('rect')].filter((r) => !r.closest('.chosen-column')).map((r) => r.getBoundingClientRect()).filter((b) => b.width > 0 && b.height > 0);
      return notes.flatMap((t) => {
        const a = t.getBoundingClientRect();
        return boxes.filter((b) => a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom).map((b) => `${a.left}..${a.right} over a box at ${b.left}..${b.right}`);
      });
    });
    assert.deepEqual(overBoxes, [], `${viewport?.width ?? 1280} px: "no packet arrives" runs over the boxes`);
    assert.deepEqual(problems, []);
    await page.close();
  }
});

test('bad values in a shared link are explained and replaced by defaults', async () => {
  // One mangled link with five bad values: each is named, none hides another (one page load
  // instead of five).
  const { page, problems } = await open('?sf=13&bw=300&cr=9&distance=200000&gateways=1,2,3,4');
  const notice = await page.locator('#notice').textContent();
  for (const key of ['sf', 'bw', 'cr', 'distance', 'gateways']) assert.match(notice, new RegExp(`The link's ${key}=`), `${key}: ${notice}`);
  assert.match(await page.locator('#status').textContent(), /simulated in/);
  // The form shows what the notice says replaced each value.
  for (const key of ['sf', 'bw', 'cr']) {
    const replaced = notice.match(new RegExp(`The link's ${key}=\\S+ was replaced by ([\\d.]+):`))?.[1];
    assert.equal(await page.locator(`#${key}`).inputValue(), replaced, `${key}: ${notice}`);
  }
  assert.equal(await page.locator('#distance-value').textContent(), '1.0 km');
  assert.deepEqual(problems, []);
});

test('a distance the core accepts but the slider cannot show is said to be moved', async () => {
  const { page, problems } = await open('?distance=50000');
  assert.match(await page.locator('#notice').textContent(), /50000 m is shown and simulated as 10000 m/);
  assert.equal(await page.locator('#distance-value').textContent(), '10.0 km');
  assert.deepEqual(problems, []);
  await page.close();
});

test('an invalid field is marked beside itself, nothing runs, and the old results say they are old', async () => {
  const { page, problems } = await open();
  await page.locator('#advanced summary').click();
  const before = await tableHtml(page);
  await page.getByLabel('Path-loss exponent').fill('0.5');
  await page.waitForSelector('#pathLossExponent[aria-invalid="true"]');
  assert.match(await page.locator('#pathLossExponent-error').textContent(), /Path-loss exponent must be between 1.5 and 6/);
  assert.match(await page.locator('#status').textContent(), /Not simulated/);
  assert.equal(await page.locator('[data-panel="results"].stale').count(), 1);
  assert.equal(await tableHtml(page), before);
  // The dashed frame of old results is drawn outside the table's box: clear of the status's last line.
  const gap = await page.evaluate(() => {
    const table = document.querySelector('#results-table');
    const { outlineWidth, outlineOffset } = getComputedStyle(table);
    return table.getBoundingClientRect().top - parseFloat(outlineWidth) - parseFloat(outlineOffset) - document.querySelector('#status').getBoundingClientRect().bottom;
  });
  assert.ok(gap >= 0, `the frame crosses the status by ${-gap} px`);
  await page.getByLabel('Path-loss exponent').fill('3');
  await until(page, () => !document.querySelector('[data-panel="results"].stale'));
  assert.equal(await page.locator('#pathLossExponent[aria-invalid]').count(), 0);
  assert.equal(await page.locator('[data-panel="results"].stale').count(), 0);
  assert.deepEqual(problems, []);
});

test("the SF hint's and the link budget's reach per step is the core's link budget at the path-loss exponent set", async () => {
  const pkg = await import(join(process.cwd(), 'www', 'pkg', 'loratrack.js'));
  pkg.initSync({ module: readFileSync(join(process.cwd(), 'www', 'pkg', 'loratrack_bg.wasm')) });
  const further = (n) => {
    const [sf7, sf8] = pkg.linkBudget({ pathLossExponent: n }).sfs;
    return Math.round(100 * (sf8.rangeM / sf7.rangeM - 1));
  };
  const { page, problems } = await open('?pathLossExponent=2.7');
  assert.equal(await page.locator('#sf-help').textContent(), `Each step up about doubles the time on air (and the wait between packets) and reaches about ${further(2.7)} % further at path-loss exponent 2.7.`);
  // The link budget's explanation says the same (it said "about 15 % more range" whatever the exponent).
  assert.match(await page.locator('#link-title ~ details.explain').textContent(), new RegExp(`each SF step buys 2\\.5 dB, about ${further(2.7)} % more range at path-loss exponent 2\\.7, for about twice`));
  await page.locator('#advanced summary').click();
  await page.getByLabel('Path-loss exponent').fill('3.76');
  await until(page, () => !/exponent/.test(document.querySelector('#sf-help').textContent));
  assert.match(await page.locator('#sf-help').textContent(), new RegExp(`reaches about ${further(3.76)} % further\\.$`));
  assert.match(await page.locator('#link-title ~ details.explain').textContent(), new RegExp(`2\\.5 dB, about ${further(3.76)} % more range, for`));
  assert.notEqual(further(2.7), further(3.76));
  assert.deepEqual(problems, []);
});

test('a link whose settings the core refuses says why, shows no old results, and every download says there are none yet', async () => {
  // US915's DR0 (SF10/125 kHz) cannot carry 3D-CTRA's 25-byte frame within the 400 ms dwell time:
  // the form no longer offers it, but a link from before, or written by hand, still carries it.
  const { page, problems } = await openPage(playground.context, new URL(playground.url).origin);
  await page.goto(`${playground.url}?region=us915&sf=10&bw=125`);
  await until(page, () => /cannot be simulated/.test(document.querySelector('#status')?.textContent ?? ''));
  const text = await page.locator('#status').textContent();
  assert.match(text, /400 ms dwell time.*Change a setting to see results\.$/);
  assert.doesNotMatch(text, /previous settings/);
  assert.equal(await page.locator('[data-panel="results"].stale').count(), 0, 'no frame of old results around nothing');
  assert.equal(await page.locator('#results-table tbody tr').count(), 0);
  await idle(page);
  // The charts drawn from results say why they are empty.
  const empty = await page.evaluate(() => ['error', 'distance', 'sf', 'axes', 'trajectory'].map((n) => getComputedStyle(document.querySelector(`#chart-${n}`), '::before').content));
  assert.deepEqual(empty, Array(5).fill('"No chart: these settings are not simulated (Results says why)."'));
  // The form shows the link's choices, and that it would not offer them.
  assert.equal(await page.locator('#sf option[value="10"]:checked:disabled').count(), 1);
  assert.equal(await page.locator('#model option[value="all"]:checked:disabled').count(), 1);
  const why = (panel) => page.locator(`[data-panel="${panel}"] .download-why`).first();
  await page.getByRole('button', { name: 'Results (CSV)' }).click();
  assert.match(await why('results').textContent(), /^No results yet: nothing has been simulated at these settings/);
  // Not "no packet arrives" (the error chart) nor "needs WebGL" (the 3D view): there is no run.
  await page.getByRole('button', { name: 'Download the error over time chart as SVG' }).click();
  assert.match(await why('error').textContent(), /^No results yet/);
  await page.getByRole('button', { name: 'Download the 3d trajectory chart as PNG' }).click();
  assert.match(await why('trajectory').textContent(), /^No results yet/);
  // A setting the core accepts brings results, and the notes that there were none go.
  await page.getByLabel('Spreading factor', { exact: true }).selectOption('9');
  await waitForResults(page);
  await until(page, () => document.querySelector('#chart-error svg'));
  for (const panel of ['results', 'error', 'trajectory']) assert.equal(await why(panel).textContent(), '', panel);
  assert.equal(await page.locator('.chart[data-unrun]').count(), 0);
  // An embed of a chart alone has no status line and no settings to change: its caption says why.
  const embed = await openPage(playground.context, new URL(playground.url).origin);
  await embed.page.goto(`${playground.url}?embed=1&panels=error&region=us915&sf=10&bw=125`);
  await until(embed.page, () => /cannot be simulated/.test(document.querySelector('#embed-notices')?.textContent ?? ''));
  assert.doesNotMatch(await embed.page.locator('#embed-notices').textContent(), /Change a setting|previous settings/);
  await idle(embed.page);
  // Its caption says why, once: not again over the chart.
  assert.equal(await embed.page.locator('.chart[data-unrun]').count(), 0);
  await embed.page.getByRole('button', { name: 'Download the error over time chart as SVG' }).click();
  assert.match(await embed.page.locator('[data-panel="error"] .download-why').textContent(), /^No results yet: .*the caption at the top says why/);
  assert.deepEqual([...problems, ...embed.problems], []);
});

test('a whole set the core refuses after its first flight shows neither that flight nor old results as its own', async () => {
  // 20 seeds of the 44-minute set take more filter steps than one run may: the first flight alone
  // is accepted (and quick), the set is not.
  const { page, problems } = await openPage(playground.context, new URL(playground.url).origin);
  await page.goto(`${playground.url}?flight=all&seeds=20`);
  await until(page, () => /cannot be simulated: the run is too long/.test(document.querySelector('#status')?.textContent ?? ''));
  await idle(page);
  assert.match(await page.locator('#status').textContent(), /\(at most 18 seeds, or shorten the flight.*\)\. The setting it names is Seeds \(repeats\)\. Change a setting to see results\.$/);
  // The field to change is marked beside itself, Advanced opened to show it.
  assert.equal(await page.getByLabel('Seeds (repeats)').getAttribute('aria-invalid'), 'true');
  assert.match(await page.locator('#seeds-error').textContent(), /at most 18 seeds/);
  assert.ok(await page.locator('#seeds-error').isVisible());
  assert.equal(await page.locator('#results-table tbody tr').count(), 0, "the first flight's numbers do not stand for the set");
  assert.equal(await page.locator('#chart-error svg').count(), 0);
  assert.equal(await page.locator('[data-panel="results"].partial').count(), 0);
  await page.getByRole('button', { name: 'Results (CSV)' }).click();
  assert.match(await page.locator('[data-panel="results"] .download-why').first().textContent(), /^No results yet: nothing has been simulated at these settings/);
  // From a run on show, the same refusal leaves that run's numbers, marked as the previous settings'.
  await page.getByLabel('Seeds (repeats)').fill('2');
  await page.getByLabel('Seeds (repeats)').press('Tab');
  await waitForResults(page);
  await idle(page);
  const before = await tableHtml(page);
  await page.getByLabel('Seeds (repeats)').fill('20');
  await page.getByLabel('Seeds (repeats)').press('Tab');
  await until(page, () => /cannot be simulated: the run is too long/.test(document.querySelector('#status')?.textContent ?? ''));
  await idle(page);
  assert.match(await page.locator('#status').textContent(), /the results below are for the previous settings\.$/);
  assert.equal(await tableHtml(page), before);
  assert.match(await page.locator('#results-table caption').first().textContent(), /over 30 flights × 2 seeds/);
  assert.equal(await page.locator('[data-panel="results"].stale').count(), 1);
  assert.deepEqual(problems, []);
});

/** Once the page is idle: the run with `seeds` seeds of one flight was accepted, and its
 * numbers on show pool them. */
async function assertRanSeeds(page, seeds) {
  await idle(page);
  assert.equal(await page.getByLabel('Seeds (repeats)').inputValue(), String(seeds));
  assert.match(await page.locator('#results-table caption').first().textContent(), new RegExp(`over 1 flight × ${seeds} seeds`));
  assert.doesNotMatch(await page.locator('#status').textContent(), /cannot be simulated/);
}

test('Repeat with … seeds asks for no more seeds than the core takes at these rates, and the run it starts is accepted', async () => {
  // 1000 Hz sensors and a 1 ms station step: one 81 s flight is 162 000 filter steps, six fit.
  // The limit is per station, and two are the fewest the offer is made for (DR and CTRA+, quicker
  // than three).
  const { page, problems } = await open('?sensorRate=1000&step=0.001&model=dr,ctra-plus');
  const max = nativeJson(['simulate', '--synthetic', '1', '--sensor-rate', '1000', '--step', '0.001', '--model', 'dr,ctra-plus']).config.maxSeeds;
  assert.ok(max > 1 && max < 10, `maxSeeds ${max}`);
  const before = await tableHtml(page);
  await page.getByRole('button', { name: `Repeat with ${max} seeds` }).click();
  await waitForResults(page, before);
  await assertRanSeeds(page, max);
  // At the most seeds the flights take, it is not offered again.
  assert.equal(await page.locator('#repeat-seeds').isVisible(), false);
  assert.deepEqual(problems, []);
});

test('a run too long only for its seeds offers as many as the core takes at these rates, and that run is accepted', async () => {
  // 1000 Hz sensors and a 1 ms station step: one 81 s flight is 162 000 filter steps, six fit
  // (per station: one runs them a third as long as three).
  const { page, problems } = await openPage(playground.context, new URL(playground.url).origin);
  await page.goto(`${playground.url}?seeds=100&sensorRate=1000&step=0.001&model=dr`);
  const max = nativeJson(['simulate', '--synthetic', '1', '--sensor-rate', '1000', '--step', '0.001', '--model', 'dr']).config.maxSeeds;
  await until(page, () => /cannot be simulated/.test(document.querySelector('#status')?.textContent ?? ''));
  assert.match(await page.locator('#status').textContent(), new RegExp(`at most ${max} seeds`));
  // An uploaded flight too long for the seeds is refused for the seeds, not as a bad file.
  const csv = join(scratchDir(), 'minute.csv');
  writeFileSync(csv, ['t,x,y,z', ...Array.from({ length: 601 }, (_, i) => `${(i / 10).toFixed(1)},${i / 2},0,20`)].join('\n'));
  const fits = nativeJson(['simulate', '--trajectory', csv, '--sensor-rate', '1000', '--step', '0.001', '--model', 'dr']).config.maxSeeds;
  await page.getByLabel('Trajectory', { exact: true }).selectOption('csv');
  await page.getByLabel('CSV file').setInputFiles(csv);
  await page.getByRole('button', { name: `Use ${fits} seeds` }).waitFor();
  assert.match(await page.locator('#status').textContent(), new RegExp(`^These settings cannot be simulated: .*at most ${fits} seeds`));
  assert.equal(await page.locator('#csv-error').isVisible(), false);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('synthetic');
  await until(page, (m) => (document.querySelector('#status')?.textContent ?? '').includes(`at most ${m} seeds`), max);
  // One press sets the seeds and starts their run, which the core accepts: it reports progress.
  // Its end is the test above's (the same flight, rates and seeds), too long to wait for twice.
  await page.getByRole('button', { name: `Use ${max} seeds` }).click();
  assert.equal(await page.getByLabel('Seeds (repeats)').inputValue(), String(max));
  await until(page, () => document.querySelector('#progress').value > 0, null, { timeout: 60_000 });
  assert.doesNotMatch(await page.locator('#status').textContent(), /cannot be simulated/);
  assert.equal(new URL(page.url()).searchParams.get('seeds'), String(max));
  assert.equal(await page.locator('#fit-setting').isVisible(), false);
  assert.deepEqual(problems, []);
});

test('with Advanced open the page scrolls, not the settings, and the results table fits its box', async () => {
  const { page, problems } = await open('', { width: 1280, height: 800 });
  await page.locator('#advanced summary').click();
  const inner = await page.locator('#controls').evaluate((el) => el.scrollHeight - el.clientHeight);
  assert.equal(inner, 0, 'the settings scroll inside themselves');
  await page.getByLabel('Seed', { exact: true }).focus();
  const seed = await page.getByLabel('Seed', { exact: true }).boundingBox();
  assert.ok(seed.y >= 0 && seed.y + seed.height <= 800, `Seed at ${seed.y}`);
  const fits = await page.locator('#results-table .table-wrap').evaluate((el) => el.scrollWidth <= el.clientWidth + 1);
  assert.ok(fits, 'the results table scrolls sideways at 1280 px');
  assert.deepEqual(problems, []);
});

test('a wide p75 interval breaks after its dash at 1280 px instead of pushing the table sideways, and stays one line on the slide', async () => {
  // ADR at 5 km over eight seeds: p75 200 m, its interval 77–409 m, the widest cell of the row.
  const { page, problems } = await open('?adr=tracking&distance=5000&model=3d-ctra&seeds=8', { width: 1280, height: 800 });
  await idle(page);
  const cli = nativeJson(['simulate', '--synthetic', '1', '--adr', 'tracking', '--distance', '5000', '--model', '3d-ctra', '--seeds', '8']);
  const [shown] = await shownP75(page, ['3d-ctra']);
  assert.deepEqual(shown.ci, cli.results[0].ci95.p75.map((v) => Number(v.toFixed(2))));
  const box = await page.locator('#results-table .table-wrap').evaluate((el) => ({ scroll: el.scrollWidth, client: el.clientWidth }));
  assert.ok(box.scroll <= box.client + 1, `the table is ${box.scroll} px wide in a ${box.client} px box`);
  // The last column, the charge per uplink, is on screen without scrolling.
  const mc = await page.locator('#results-table tr[data-model="3d-ctra"] td:last-child').boundingBox();
  const wrap = await page.locator('#results-table .table-wrap').boundingBox();
  assert.ok(mc.x + mc.width <= wrap.x + wrap.width + 1, `the last cell ends at ${mc.x + mc.width}, the box at ${wrap.x + wrap.width}`);
  const picture = (await downloaded(page, page.getByRole('button', { name: 'Download the results table as SVG' }))).toString('utf8');
  const interval = `(${shown.ci[0].toFixed(2)}–${shown.ci[1].toFixed(2)})`;
  assert.ok(picture.includes(`>${interval}<`), `"${interval}" on one line of the picture`);
  // On a wider screen the interval has room again and stays on one line; back at 1280 px it breaks.
  const height = () => page.locator('#results-table tr[data-model="3d-ctra"] .ci').evaluate((el) => el.getBoundingClientRect().height);
  const breaks = (on) => until(page, (tight) => !!document.querySelector('#results-table .table-wrap.tight') === tight, on);
  const twoLines = await height();
  await page.setViewportSize({ width: 1920, height: 1080 });
  await breaks(false);
  assert.ok((await height()) < 0.7 * twoLines, `the interval ${await height()} px high on one line, ${twoLines} px on two`);
  await page.setViewportSize({ width: 1280, height: 800 });
  await breaks(true);
  assert.deepEqual(problems, []);
});

test('with ADR the interval and time on air are the mean over its packets and span the rates it sent at, as the CLI counts them, and the distance chart says ADR moved its runs too', async () => {
  const { page, problems } = await open('?adr=tracking&distance=3000&model=3d-ctra&flight=all');
  await idle(page);
  const cli = nativeJson(['simulate', '--synthetic', 'all', '--adr', 'tracking', '--distance', '3000', '--model', '3d-ctra']);
  const used = cli.results[0].dataRateUse;
  assert.ok(used.length > 1, 'ADR moved the rate at 3 km');
  // As the page rounds: three significant figures, at most two decimals.
  const short = (v) => v.toFixed(v < 10 ? 2 : v < 100 ? 1 : 0);
  const span = (values, unit) => `${short(Math.min(...values))}–${short(Math.max(...values))}\u00a0${unit}`;
  // The mean over the packets sent, each rate weighted by its packets, the span beneath.
  const sent = used.reduce((a, u) => a + u.packets, 0);
  const mean = (f) => used.reduce((a, u) => a + u.packets * f(u), 0) / sent;
  assert.equal(await cell(page, '3d-ctra', 'interval'), `${short(mean((u) => u.interval))} s ${span(used.map((u) => u.interval), 's')}`);
  assert.equal(await cell(page, '3d-ctra', 'toa'), `${short(mean((u) => u.timeOnAir) * 1e3)} ms ${span(used.map((u) => u.timeOnAir * 1e3), 'ms')}`);
  // Not the starting rate's: the slower rates' packets waited longer.
  assert.ok(mean((u) => u.interval) > cli.results[0].interval);
  const title = await page.locator('#results-table tr[data-model="3d-ctra"] td[data-field="interval"]').getAttribute('title');
  for (const u of used) assert.ok(title.includes(`DR${u.dr} ${u.packets} packet${u.packets === 1 ? '' : 's'}, ${(u.timeOnAir * 1e3).toFixed(1)} ms on air, every ${u.interval.toFixed(2)} s`), `${title} / DR${u.dr}`);
  assert.match(await page.locator('#rate-use').textContent(), /the interval and time on air above are the mean over the packets sent, their span beneath/);
  // The Results CSV spans them too, unrounded, beside the starting rate's.
  const [header, row] = (await downloaded(page, page.getByRole('button', { name: 'Results (CSV)' }))).toString('utf8').trim().split('\n').map((l) => l.split(','));
  const col = (name) => Number(row[header.indexOf(name)]);
  assert.equal(col('interval_s'), cli.results[0].interval);
  assert.equal(col('interval_mean_s'), cli.results[0].meanInterval);
  assert.equal(col('time_on_air_mean_s'), cli.results[0].meanTimeOnAir);
  assert.equal(col('interval_min_s'), Math.min(...used.map((u) => u.interval)));
  assert.equal(col('interval_max_s'), Math.max(...used.map((u) => u.interval)));
  assert.equal(col('time_on_air_min_s'), Math.min(...used.map((u) => u.timeOnAir)));
  assert.equal(col('time_on_air_max_s'), Math.max(...used.map((u) => u.timeOnAir)));
  // The Things Network's note counts what was sent by the packets' spacing, not by the starting rate.
  const ttn = nativeJson(['airtime', '--sf', '7', '--bw', '250', '--payload', '12']).ttnPacketsPerDay;
  assert.match(await page.locator('#ttn-note').textContent(), new RegExp(`— ${(86400 / cli.results[0].sentEvery / ttn).toFixed(0)}× fewer than sent here`));
  // The distance chart's runs move their rate too, and its axis says so.
  await page.waitForSelector('#chart-distance svg', { timeout: 30_000 });
  assert.ok((await chartTexts(page, '#chart-distance')).some((t) => t.includes('gateway distance (SF7, 250 kHz and tracking ADR)')));
  assert.deepEqual(await axe(page), []);
  assert.deepEqual(problems, []);
});

test('shadowing fixed in space is one Advanced control away, travels in the link, and its numbers are the CLI\'s', async () => {
  const { page, problems } = await open('?distance=3000');
  const before = await tableHtml(page);
  await page.locator('#advanced summary').click();
  await page.getByLabel('Shadowing varies').selectOption('field');
  await waitForResults(page, before);
  await idle(page);
  assert.match(page.url(), /shadowingModel=field/);
  const download = JSON.parse((await downloaded(page, page.getByRole('button', { name: /JSON/ }))).toString('utf8'));
  const cli = assertDownloadIsCli(download, ['--synthetic', '1', '--distance', '3000', '--shadowing-model', 'field']);
  // Other fades than along the path: the same settings without it lose other packets.
  const path = nativeJson(['simulate', '--synthetic', '1', '--distance', '3000']);
  assert.notDeepStrictEqual(cli.results.map((m) => m.packetsReceived), path.results.map((m) => m.packetsReceived));
  assert.deepEqual(await axe(page), []);
  assert.deepEqual(problems, []);
});

test('two sub-bands alternated: the Duty cycle control halves the intervals, the results and the time-on-air table are the CLI\'s, and listening before talk hides it', async () => {
  const { page, problems } = await open();
  await idle(page);
  let before = await tableHtml(page);
  await page.getByLabel('Duty cycle (0.01 = 1 %)').fill('0.02');
  await waitForResults(page, before);
  await idle(page);
  assert.match(page.url(), /dutyCycle=0\.02/);
  const download = JSON.parse((await downloaded(page, page.getByRole('button', { name: /JSON/ }))).toString('utf8'));
  const cli = assertDownloadIsCli(download, ['--synthetic', '1', '--duty-cycle', '0.02']);
  const one = nativeJson(['simulate', '--synthetic', '1']);
  // Half one sub-band's interval, and so more packets (each leaves on a whole sensor step).
  for (const [i, m] of cli.results.entries()) {
    assert.ok(Math.abs(2 * m.interval - one.results[i].interval) < 1e-9, `${m.model}: ${m.interval} s vs ${one.results[i].interval} s`);
    assert.ok(m.packetsSent > 1.8 * one.results[i].packetsSent, `${m.model}: ${m.packetsSent} vs ${one.results[i].packetsSent}`);
  }
  // The time-on-air table divides by the duty cycle set, says so, and gives the CLI's interval.
  const air = nativeJson(['airtime', '--sf', '7', '--bw', '250', '--payload', '12', '--duty-cycle', '0.02']);
  const tableCell = await page.locator('.airtime-table tr.current td').last().textContent();
  assert.equal(tableCell.split('·')[1].trim(), `${air.minInterval.toFixed(2)} s`);
  assert.match(await page.locator('.airtime-table caption').textContent(), /^EU868 at a 2 % duty cycle: /);
  // So does the results table's caption, above numbers that would otherwise read as 1 %'s.
  assert.match(await page.locator('#results-table caption').first().textContent(), /; overhead 13 B; EU868, 2 % duty cycle; paper prediction$/);
  assert.match(await page.locator('#results-table thead th', { hasText: /^interval$/ }).first().getAttribute('title'), /^Time between packets: time on air divided by the 2 % duty cycle/);
  assert.deepEqual(await axe(page), []);
  // Listening before talk replaces the duty cycle: the control goes, and so does the setting.
  before = await tableHtml(page);
  await page.getByLabel('Channel access').selectOption('lbt');
  await waitForResults(page, before);
  await idle(page);
  assert.equal(await page.locator('#dutyCycle').isVisible(), false);
  const lbt = JSON.parse((await downloaded(page, page.getByRole('button', { name: /JSON/ }))).toString('utf8'));
  assertDownloadIsCli(lbt, ['--synthetic', '1', '--access', 'lbt']);
  // A plan without a duty cycle has nothing for listening to replace: the control goes, and the
  // choice kept in it is not sent (the core refuses it there).
  before = await tableHtml(page);
  await page.getByLabel('Bandwidth').selectOption('125');
  await waitForResults(page, before);
  before = await tableHtml(page);
  await page.getByLabel('Region').selectOption('us915');
  await waitForResults(page, before);
  await idle(page);
  assert.equal(await page.locator('#access').isVisible(), false);
  const us = JSON.parse((await downloaded(page, page.getByRole('button', { name: /JSON/ }))).toString('utf8'));
  assertDownloadIsCli(us, ['--synthetic', '1', '--bw', '125', '--region', 'us915', '--interval', '1']);
  assert.deepEqual(problems, []);
});

test('the progress bar goes when the results come, and busy is cleared when all is drawn', async () => {
  const { page, problems } = await open();
  const before = await tableHtml(page);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('all');
  await waitForResults(page, before);
  assert.equal(await page.locator('#progress').isVisible(), false);
  await idle(page);
  assert.deepEqual(problems, []);
});

test('embedding: unknown panels are explained, spaces are forgiven, the credit and the full page stay reachable', async () => {
  const { page, problems } = await open('?embed=1&panels=foo');
  assert.match(await page.locator('#notice').textContent(), /foo/);
  assert.equal(await page.locator('[data-panel="results"]').isVisible(), true);
  await page.goto(`${playground.url}?embed=1&panels=results,%20error`);
  await waitForResults(page);
  assert.equal(await page.locator('[data-panel="error"]').isVisible(), true);
  assert.match(await page.locator('footer').innerText(), /CC BY-SA/);
  const full = await page.locator('#open-full').getAttribute('href');
  assert.doesNotMatch(full, /embed/);
  assert.equal(await page.locator('h1').count(), 1);
  assert.deepEqual(problems, []);
});

test('copying a link after a CSV upload says the link cannot carry the file', async () => {
  const dir = scratchDir();
  const path = join(dir, 'square.csv');
  writeFileSync(path, 't,x,y,z\n' + Array.from({ length: 400 }, (_, i) => `${(i * 0.1).toFixed(1)},${Math.sin(i / 40) * 50},${Math.cos(i / 40) * 50},20`).join('\n') + '\n');
  const { page, problems } = await open();
  await page.context().grantPermissions(['clipboard-read', 'clipboard-write']);
  const before = await tableHtml(page);
  await page.getByLabel('Trajectory', { exact: true }).selectOption('csv');
  await page.locator('#csv').setInputFiles(path);
  await waitForResults(page, before);
  await page.getByRole('button', { name: 'Copy link' }).click();
  // The clipboard answers asynchronously: wait for the message, never read right after the click.
  await until(page, () => document.querySelector('#copy-status')?.textContent !== '');
  assert.match(await page.locator('#copy-status').textContent(), /cannot carry it/);
  assert.deepEqual(problems, []);
});

test('the 3D view is drawn as the reader comes near it, keeps its camera across changes and has a legend, a gateway and a reset', async () => {
  const { page, problems } = await open('?distance=300');
  // Two screens below the results, the view waits until the reader comes near it.
  await idle(page);
  assert.equal(await page.locator('#chart-trajectory canvas').count(), 0, 'the 3D view was drawn before it came near the viewport');
  const canvas = await view3d(page);
  await canvas.focus();
  const snap = () => canvas.evaluate((c) => c.toDataURL());
  await idle(page);
  const initial = await snap();
  await page.keyboard.press('ArrowLeft');
  await page.keyboard.press('ArrowLeft');
  const turned = await snap();
  assert.notEqual(turned, initial, 'arrow keys rotate the view');
  const before = await tableHtml(page);
  await page.getByLabel('Spreading factor', { exact: true }).selectOption('8');
  await waitForResults(page, before);
  await idle(page);
  const after = await snap();
  assert.notEqual(after, initial, 'a settings change reset the camera');
  const legend = () => page.locator('[data-panel="trajectory"] .legend').textContent();
  assert.match(await legend(), /true flight, DR, CTRA\+, 3D-CTRA; grey cone: the gateway\. Grid squares [\d.]+ m\.$/);
  // With two seeds the view draws the first: its legend says so.
  const one = await tableHtml(page);
  await page.locator('#advanced summary').click();
  await page.getByLabel('Seeds (repeats)').fill('2');
  await page.getByLabel('Seeds (repeats)').blur();
  await waitForResults(page, one);
  await idle(page);
  await until(page, () => /This view is synthetic 1 with seed 1 alone; the results table pools 1 flight × 2 seeds\.$/.test(document.querySelector('[data-panel="trajectory"] .legend')?.textContent ?? ''));
  await page.getByRole('button', { name: 'Reset view' }).click();
  assert.deepEqual(problems, []);
});

test('the 3D view lets the page scroll past it, zooms once focused, and always shows the gateway with its distance', async () => {
  const { page, problems } = await open('?distance=3000');
  const canvas = await view3d(page);
  const snap = () => canvas.evaluate((c) => c.toDataURL());
  const box = await canvas.boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  const [y0, image0] = [await page.evaluate(() => scrollY), await snap()];
  await page.mouse.wheel(0, 200);
  await until(page, (y) => scrollY !== y, y0);
  assert.equal(await snap(), image0, 'the wheel zoomed a view without focus');
  await canvas.focus();
  // A reader zooming points at the view where it now is (the scroll moved it).
  const moved = await canvas.boundingBox();
  await page.mouse.move(moved.x + moved.width / 2, moved.y + moved.height / 2);
  const image1 = await snap();
  const y1 = await page.evaluate(() => scrollY);
  await page.mouse.wheel(0, -200);
  const zoomed = await until(page, (before) => document.querySelector('#chart-trajectory canvas').toDataURL() !== before, image1, { timeout: 10_000 }).then(
    () => true,
    () => false,
  );
  // Failed once in CI with nothing to go on: say what the wheel found.
  const state = await page.evaluate(
    ([x, y]) => ({
      focused: document.activeElement?.tagName,
      underMouse: document.elementFromPoint(x, y)?.tagName,
      scrollY,
      contextLost: document.querySelector('#chart-trajectory canvas').getContext('webgl2')?.isContextLost(),
    }),
    [moved.x + moved.width / 2, moved.y + moved.height / 2],
  );
  assert.ok(zoomed, `a focused view did not zoom: ${JSON.stringify({ ...state, scrollBefore: y1 })}`);
  assert.equal(state.scrollY, y1, 'a focused view zooms instead of scrolling the page');
  // 3 km away the gateway is off the flight's scale: a marker at the edge says where and how far.
  assert.match(await page.locator('.gateway-label').first().textContent(), /^gateway 3\.0 km →$/);
  assert.match(await page.locator('#trajectory-legend').textContent(), /grey cone at the edge: gateway beyond the view, with its distance/);
  assert.deepEqual(problems, []);
});

test('printed, the page shows the numbers and charts with the settings they rest on instead of the form', async () => {
  // At a phone's width the 3D view stays more than a screen away on paper too (on a wider page
  // the printed layout, without the form, brings it near, and it is drawn).
  // A distance between the slider's steps leaves a notice at the top of the form.
  const { page, problems } = await open('?sf=8&distance=2040', { width: 390, height: 844 });
  await idle(page);
  await page.emulateMedia({ media: 'print' });
  assert.equal(await page.locator('#controls').isVisible(), false, 'the form is printed');
  assert.equal(await page.getByRole('button', { name: 'Pin as baseline' }).isVisible(), false, 'buttons are printed');
  assert.match(await page.locator('#embed-settings').textContent(), /^Settings: SF8, 250 kHz, 2\.0 km, /);
  assert.equal(await page.locator('#embed-settings').isVisible(), true, 'the settings line is not printed');
  // The form's notices about the link are printed in the caption; the results' own notes where
  // they stand, not a second time.
  assert.equal(await page.locator('#embed-notices').isVisible(), true, 'the link\'s notice is not printed');
  const printed = await page.locator('#embed-notices').textContent();
  assert.match(printed, /^The link's distance 2040 m is shown and simulated as 2000 m/);
  assert.equal(printed, await page.locator('#notice').textContent(), 'the caption prints more than the form\'s notices');
  assert.equal(await page.locator('#results-table').isVisible(), true);
  // Not run, the swarm panel has nothing to print; not yet near, the 3D view says why it is blank.
  assert.equal(await page.locator('[data-panel="swarm"]').isVisible(), false);
  const why = await page.locator('#chart-trajectory').evaluate((el) => getComputedStyle(el, '::before').content);
  assert.match(why, /Not drawn: .*scroll there before printing/);
  // On paper the note alone, not the room the view keeps on screen until it is drawn.
  const blank = (await page.locator('#chart-trajectory').boundingBox()).height;
  assert.ok(blank < 100, `the undrawn 3D view takes ${blank} px on paper`);
  await page.emulateMedia({ media: 'screen' });
  assert.ok((await page.locator('#chart-trajectory').boundingBox()).height > 150, 'the undrawn 3D view keeps no room on screen');
  assert.equal(await page.locator('#controls').isVisible(), true);
  assert.equal(await page.locator('#embed-settings').isVisible(), false, 'the settings line shows on screen');
  assert.deepEqual(problems, []);
});

test('New seed draws a fresh seed, shows it and puts it in the link', async () => {
  const { page, problems } = await open();
  const before = await tableHtml(page);
  await page.getByRole('button', { name: 'New seed' }).click();
  await waitForResults(page, before);
  const seed = await page.locator('#seed').inputValue();
  assert.notEqual(seed, '1');
  assert.match(page.url(), new RegExp(`seed=${seed}`));
  assert.deepEqual(problems, []);
});

test('Reset puts every setting and the swarm panel\'s choices back: the link is a first visit\'s and the numbers the CLI\'s defaults', async () => {
  const { page, problems } = await open('?sf=9&distance=3000&model=dr&swarmDrones=100&swarmPlan=spread');
  await idle(page);
  assert.equal(await page.locator('#results-table tbody tr').count(), 1);
  const before = await tableHtml(page);
  await page.getByRole('button', { name: 'Reset', exact: true }).click();
  await waitForResults(page, before);
  await idle(page);
  assert.equal(await page.getByLabel('Spreading factor', { exact: true }).inputValue(), '7');
  assert.equal(await page.locator('#swarmDrones').inputValue(), '50');
  assert.equal(await page.locator('#swarmPlan').inputValue(), 'fixed');
  // Copy link after Reset opens the page as a first visit does.
  assert.equal(new URL(page.url()).search.replace(/^\?$/, ''), '');
  const cli = nativeJson(['simulate', '--synthetic', '1']);
  for (const s of await shownP75(page)) assert.equal(s.p75.toFixed(2), cli.results.find((r) => r.model === s.model).error3d.p75.toFixed(2), s.model);
  assert.deepEqual(problems, []);
});

test("where a band fails as a 95 % bound, the note under the error chart says how often it held, as the CLI counts it, and the slide carries it once", async () => {
  // The paper's station at SF8 / 125 kHz: its error stays under its band 86–87 % of the time on
  // synthetic flight 1.
  const { page, problems } = await open('?sf=8&bw=125');
  const held = nativeJson(['simulate', '--synthetic', '1', '--sf', '8', '--bw', '125']).results.map((x) => `${Math.round(100 * x.underBound95)} % (${LABELS[x.model]})`);
  const band = `The paper's station does not calibrate its band: the error stayed under it ${held.slice(0, -1).join(', ')} and ${held.at(-1)} of the time in the results' runs.`;
  await until(page, (text) => document.querySelector('#error-rests-on')?.textContent === text, band);
  assert.ok(await page.locator('#error-rests-on').isVisible());
  await page.waitForSelector('#chart-error svg');
  const svg = (await downloaded(page, page.getByRole('button', { name: /^Download the error over time.* chart as SVG$/ }))).toString('utf8');
  const words = svg.replace(/<[^>]+>/g, ' ').replace(/\s+/g, ' ');
  assert.equal(words.split('does not calibrate its band').length, 2, words.slice(-800));
  assert.ok(words.includes(band), words.slice(-800));
  assert.deepEqual(problems, []);
});

test('a laptop screen shows the results and two charts at once; a phone shows the numbers first', async () => {
  const started = Date.now();
  const { page, problems } = await open('', { width: 1280, height: 800 });
  const firstResults = Date.now() - started;
  // Wall-clock time is reported, not asserted (a loaded CI machine would make it flaky): the
  // benchmark of record is `npm run bench`. Only a hang fails here.
  console.log(`# first results after ${firstResults} ms (page, module and the workers loaded)`);
  assert.ok(firstResults < 20_000, `first results after ${firstResults} ms`);
  await idle(page);
  for (const panel of ['results', 'error', 'distance']) {
    const b = await page.locator(`[data-panel="${panel}"]`).boundingBox();
    assert.ok(b.y >= 0 && b.y + b.height <= 800, `${panel} spans ${b.y}..${b.y + b.height}`);
  }
  const phone = await open('', { width: 390, height: 844 });
  const results = await phone.page.locator('[data-panel="results"]').boundingBox();
  const controls = await phone.page.locator('#controls').boundingBox();
  assert.ok(results.y < controls.y && results.y < 844, `results at ${results.y}, settings at ${controls.y}`);
  assert.deepEqual([...problems, ...phone.problems], []);
});

test('the link-budget panel shows power, sensitivities and delivery, and follows the bandwidth', async () => {
  const { page, problems } = await open();
  await page.waitForSelector('#chart-link svg');
  assert.ok((await page.locator('#chart-link svg').count()) >= 2);
  const before = await page.locator('#chart-link .note').textContent();
  // Each SF is named with its EU868 data rate where it has one (SF7 at 250 kHz is DR6).
  assert.match(before, /SF7 \(DR6\) [\d.]+ km.*SF12 [\d.]+ km/);
  await page.getByLabel('Bandwidth').selectOption('125');
  await until(page, (old) => document.querySelector('#chart-link .note')?.textContent !== old, before);
  const sf7 = (t) => Number(/SF7(?: \(DR\d\))? ([\d.]+) km/.exec(t)[1]);
  const narrow = await page.locator('#chart-link .note').textContent();
  assert.ok(sf7(narrow) > sf7(before), 'a narrower band reaches further');
  // The power sent and the path-loss exponent set every curve: the note names them, and follows
  // them when the Advanced settings change them.
  assert.match(narrow, /^Range \(where the mean power, 14 dBm sent with a path-loss exponent of [\d.]+, meets the sensitivity\): /);
  await page.locator('#advanced summary').click();
  await page.getByLabel('Tx power (dBm)').fill('20');
  await page.getByLabel('Tx power (dBm)').blur();
  await until(page, (old) => document.querySelector('#chart-link .note')?.textContent !== old, narrow);
  const stronger = await page.locator('#chart-link .note').textContent();
  assert.match(stronger, /, 20 dBm sent with /);
  assert.ok(sf7(stronger) > sf7(narrow), '6 dB more reaches further');
  assert.deepEqual(problems, []);
});
