// The playground's wiring: reads the form, asks the worker pool to simulate, hands the numbers
// to the panels that draw them. The state lives in ./store, the form in ./form, the results
// table in ./results, embeds in ./embed, presentation mode in ./present.
import { changedEarly, pool } from './boot';
import { runSwarms, spawnWorker, type SwarmRun } from './pool';
import { linkBudget, load, MODEL_LABELS, settingOf, stationsOf, TOP_SPEEDS, valueThatFits, type ModelName, type SimReport, type SimulateParams, type SwarmParams } from './loratrack';
import { MODEL_COLORS, PLAN_COLOR, TRUTH_COLOR } from './charts/colors';
import type { BoxRow } from './charts/plots';
import type { SfRow } from './charts/p75BySf';
import type { Trajectory3d } from './charts/trajectory3d';
import { $, fitOnWidth, linkDocs, presenting, tighten } from './dom';
import { airtimeRows } from './airtime';
import { chartSvg, downloadAirtimeCsv, downloadErrorCsv, downloadJson, downloadPicturePng, downloadPng, downloadResultsCsv, downloadSvg, MIN_PNG_WIDTH, tableSvg, type SlideText } from './export';
import { field, form, markField, onFormChange, readControls, settingWords, showConditional, writeControls } from './form';
import { setUpEmbed, setUpEmbedDialog, updateEmbedCaption } from './embed';
import { adrName, bandNote, caption, fewPacketsNote, fixedRateNote, noLineNote, offChartNote, oneGatewayNote, oneSeedNote, refusedNote, seriesNote, type SwarmOf } from './format';
import { later, drawingLater, nextTask, onDrawing } from './later';
import { baselineIsLessons, changedFromLesson, LESSONS, lessonQuery, lessonSettings, type Lesson } from './lessons';
import { clearTable, renderBaseline, renderTable, restingNotes, resultsWhat } from './results';
import { commandOf, setUpCopyCommand, showCommand } from './command';
import { setUpPresent } from './present';
import { DEFAULTS, fromQuery, isNumericKey, packetPlan, plan, planAllows, planReason, simulateRequest, swarmRequest as swarmRequestOf, swarmSettings, toParams, toQuery, uploaded, type Settings } from './state';
import { pageQuery, store } from './store';
import { readSwarmQuery, resetSwarmChoices, swarmSelects } from './swarmChoices';
import type { Request, Response, SimulateRequest } from './worker';

/** The largest CSV the core reads (MAX_CSV_BYTES in src/trajectory/csv.rs). */
const MAX_CSV_BYTES = 64 * 2 ** 20;
const status = $('#status');
const progress = $<HTMLProgressElement>('#progress');
const csvError = $('#csv-error');
const planError = $('#plan-error');

let trajectory3d: Trajectory3d | undefined;
let plotsLoading: Promise<typeof import('./charts/plots')> | undefined;
/** The Plot charts (./charts/plots), loaded on first use. The charts' code (Plot and d3) is
 * evaluated in one task, Plot's first run is paid in a few more (./charts/warmUp), and the first
 * chart is drawn after them: short tasks between which the page answers input, instead of one
 * long one (docs/performance.md). Loading them while the first results are computed instead cost
 * those results 43–132 ms on two cores (three comparisons), so they wait until asked for. */
const plots = () =>
  (plotsLoading ??= import('./charts/plots').then(async (m) => {
    for (const warm of m.warmUps) {
      await nextTask();
      try {
        warm();
      } catch (e) {
        // A warm-up only saves time: one that fails costs the first chart that time, nothing else.
        console.error('warming up the charts:', e);
      }
    }
    await nextTask();
    return m;
  }));
const charts: Record<string, { chart: Element; caption: string }> = {};

setUpEmbed();
setUpEmbedDialog();
setUpPresent(() => {
  renderSettingsCharts();
  if (store.report) renderResults(store.report);
  if (lastSweep) renderSweep(lastSweep, { ...store.reportSettings, seeds: 1 });
  if (lastSwarm) later('swarm', lastSwarm);
});

// ---- the workers: latest request wins; a long whole-set run is interrupted by the next change --
let nextId = 0;
let running: { id: number; long: boolean; started: number; settings: Settings; params: SimulateParams } | undefined;
let queued: { request: SimulateRequest; settings: Settings } | undefined;
/** The next run draws a fresh seed (New seed), which then becomes the setting. */
let freshSeed = false;

function submit(): void {
  const request = simulateRequest(++nextId, store.settings, store.csv, store.plan);
  if (freshSeed) request.params.seed = 'random';
  const missing = store.settings.flight === 'csv' && !store.csv ? 'a CSV file to simulate it' : store.settings.flight === 'plan' && !store.plan ? 'a flight plan to fly it' : undefined;
  if (missing) {
    // Nothing runs until a file is chosen: the numbers on show are the previous flight's.
    markStale(store.report !== undefined);
    markChartsUnrun(true);
    status.textContent = `Choose ${missing}${store.report ? '; the results below are for the previous settings.' : '.'}`;
    return;
  }
  if (running?.long) {
    // A whole-set run takes about a second: stop it rather than make the user wait for stale numbers.
    pool.interrupt();
    running = undefined;
    // A first flight on show belongs to the run just stopped.
    if (showPartial(false)) markStale(true);
  }
  if (running) {
    queued = { request, settings: { ...store.settings } };
    return;
  }
  send(request, { ...store.settings });
}

/** The id of the request last sent to the pool: the run whose answers the page shows. */
let lastSent = 0;

function send(request: SimulateRequest, made: Settings): void {
  lastSent = request.id;
  offerFit($('#fit-setting'), undefined, undefined);
  const long = made.flight === 'all' || uploaded(made.flight) || made.seeds > 1;
  running = { id: request.id, long, started: performance.now(), settings: made, params: request.params };
  updateBusy();
  progress.hidden = !long;
  progress.value = 0;
  const repeats = made.seeds > 1 ? `, ${made.seeds} seeds each` : '';
  if (made.flight === 'all') status.textContent = `Simulating 30 flights (44 min of flight${repeats})… change any setting to interrupt.`;
  else if (made.seeds > 1) status.textContent = `Simulating ${made.seeds} seeds… change any setting to interrupt.`;
  else if (made.flight === 'csv' && store.csv) status.textContent = `Simulating ${store.csv.name} (${(store.csv.file.size / 1024).toFixed(0)} KB)… change any setting to interrupt.`;
  else if (made.flight === 'plan' && store.plan) status.textContent = `Flying ${store.plan.name} and simulating it… change any setting to interrupt.`;
  pool.run(request, onResponse);
}

/** What the status line says of the run's plan: which vehicle it is flown (or followed) as, read
 * from the file or set (`config.planCornering`, `vehicle`, reference §16), and that a flown plan
 * is the mission station's best case; of a plane's log without a plan, that it is bounded as one. */
function planNote(c: SimReport['config']): string {
  if (c.planCornering === null) return c.vehicle === 'fixed-wing' ? ` The drone is a plane: a bounded station lets it reach ${TOP_SPEEDS['fixed-wing']} m/s.` : '';
  const vehicle = c.planCornering === 'fixed-wing' ? 'a plane flies it (ArduPlane’s wide turns)' : 'a multicopter flies it';
  if (store.reportSettings.flight === 'plan') return ` The plan is flown as ${vehicle}, exactly, without wind: the mission station’s best case.`;
  return c.planCornering === 'fixed-wing' && c.models.includes('mission') ? ` The mission station follows the plan as ${vehicle}.` : '';
}

/** The results on show are a whole set's first flight while the set runs (`.partial`); returns
 * whether they were. */
function showPartial(partial: boolean): boolean {
  const panel = $('[data-panel="results"]');
  const was = panel.classList.contains('partial');
  panel.classList.toggle('partial', partial);
  // A "still running" note beside the results' buttons is out of date once the set's report is on show.
  if (was && !partial) clearDownloadWhy(panel);
  updateEmbedCaption();
  return was;
}

/** The run whose whole set the core refused: its first flight's numbers, if not yet shown, are not. */
let refusedRun: number | undefined;

/** A whole set refused after its first flight was shown (more seeds than the core's step limit
 * takes): that flight's numbers stand for neither these settings nor the previous ones, so the
 * table and the error chart go back to the previous results, or to none. */
function unshowPartial(): void {
  if (store.report) {
    renderTable(store.report);
    drawErrorChart(store.report, store.reportSettings);
    return;
  }
  clearTable();
  restsOn('error');
  later('error', () => {
    $('#chart-error').replaceChildren();
    delete charts.error;
    delete drawnFrom.error;
  });
}

/** The whole set's first flight while the other flights run: its table (whose caption says one
 * flight) and its error chart, which is the one the whole set's report draws too. */
function renderPartial(r: SimReport, made: Settings): void {
  markStale(typing !== undefined || JSON.stringify(made) !== JSON.stringify(store.settings));
  markChartsUnrun(false);
  // The first flight draws the error chart alone; the others wait for the set (its report, then
  // its sweep), and say so if that takes a while.
  clearTimeout(sweepWait);
  sweepWait = setTimeout(() => setPending(SET_PANELS, true), SWEEP_PATIENCE_MS);
  showPartial(true);
  renderTable(r);
  updateEmbedCaption();
  drawErrorChart(r, made);
  status.textContent = 'Flight 1 of the 30 shown, its numbers alone; simulating the rest of the set… change any setting to interrupt.';
  if (settingsChartsWait) renderSettingsCharts();
}

/** The error chart, in a later task. A whole set's report draws the chart its first flight
 * already drew (the series is always the first flight's), so that second drawing is skipped; the
 * note under it, which says how often the band held over the runs (`bandNote`), follows the set. */
function drawErrorChart(r: SimReport, made: Settings): void {
  restsOn('error', r.series ? seriesNote(r.config, r.series.flight) : '', r.series ? noLineNote(r.series.models, r.series.flight) : '', bandNote(r.config.prediction, r.results));
  later('error', () => {
    const width = chartWidth('error');
    // What the chart reads: the stations' series and the words of its key, not where the gateway
    // stood. Its numbers and Plot's drawing of them each take a task: on a long flight each is
    // tens of milliseconds.
    return drawPanel('error', [width, r.series?.flight, r.series?.models, r.config.adr], async (p) => {
      const data = p.errorChartData(r, width);
      await nextTask();
      return p.errorChart(data);
    }, made);
  });
}

/** Whether `a` and `b` hold the same data: plain values, arrays and objects compared in depth, and
 * the series' Float64Arrays number by number (JSON.stringify would write each as an object keyed
 * by index). */
function sameData(a: unknown, b: unknown): boolean {
  if (a === b) return true;
  if (typeof a !== 'object' || typeof b !== 'object' || a === null || b === null) return false;
  if (ArrayBuffer.isView(a) || ArrayBuffer.isView(b) || Array.isArray(a) || Array.isArray(b)) {
    const [xs, ys] = [a as ArrayLike<unknown>, b as ArrayLike<unknown>];
    if (Array.isArray(a) !== Array.isArray(b) || xs.length !== ys.length) return false;
    for (let i = 0; i < xs.length; i++) if (!sameData(xs[i], ys[i])) return false;
    return true;
  }
  const keys = Object.keys(a);
  return keys.length === Object.keys(b).length && keys.every((k) => sameData((a as Record<string, unknown>)[k], (b as Record<string, unknown>)[k]));
}

/** The results on show belong to other settings (or to none yet). */
function markStale(stale: boolean): void {
  $('[data-panel="results"]').classList.toggle('stale', stale);
  updateEmbedCaption();
}

/** The panels whose charts are drawn from the results (the distance and SF charts from the runs
 * that follow them). */
const RESULT_CHARTS = ['error', 'distance', 'sf', 'axes', 'trajectory'];

/** The panels drawn from the settings alone: the form's last valid ones. */
const SETTINGS_CHARTS = ['link', 'airtime'];

/** Marks charts `names` (by default those drawn from the results) while the settings on show are not
 * simulated (`unrun`: the core refused them, the form holds a value it would refuse, or a CSV is
 * still to be chosen), as the table is marked: one drawn for the previous settings says so, an
 * empty one why it is empty. An embed, whose settings its reader cannot change, says so in its
 * caption. */
function markChartsUnrun(unrun: boolean, names = RESULT_CHARTS): void {
  // The SF chart's offer fitted the settings it was drawn for, which may not be these.
  if (unrun) offerFit($('#sf-fit'), undefined, undefined);
  for (const name of names) {
    const chart = $(`#chart-${name}`);
    if (!unrun || store.embed) delete chart.dataset.unrun;
    else chart.dataset.unrun = chart.childElementCount ? 'Old chart: for the previous settings (Results says why).' : 'No chart: these settings are not simulated (Results says why).';
  }
}

function sendQueued(): void {
  if (!queued) return;
  const q = queued;
  queued = undefined;
  send(q.request, q.settings);
}

function onResponse(r: Response): void {
  if (r.id !== running?.id) return;
  if ('progress' in r) {
    progress.value = r.progress;
    return;
  }
  if ('partial' in r) {
    const made = running.settings;
    const id = r.id;
    // Not once the core has refused the whole set (its first flight is quick to accept and the
    // set quick to refuse, so the refusal may come before this task).
    inNextTask(id, () => refusedRun !== id && renderPartial(r.partial, made));
    return;
  }
  if ('report' in r) {
    const made = { ...running.settings };
    const params = running.params;
    inNextTask(r.id, () => showReport(r.report, made, r.millis, params));
    // The sweep follows the report (the pool merges the workers' reports before their sweeps).
    clearTimeout(sweepWait);
    sweepWait = setTimeout(() => sweepPending(true), SWEEP_PATIENCE_MS);
    return;
  }
  const hadPartial = showPartial(false);
  sweepPending(false);
  if ('sweep' in r) {
    renderSweep(r.sweep, { ...(running?.settings ?? store.reportSettings), seeds: 1 });
    running = undefined;
    progress.hidden = true;
    updateBusy();
    sendQueued();
    return;
  }
  if ('error' in r) {
    const failed = running.settings;
    refusedRun = r.id;
    if (hadPartial) unshowPartial();
    running = undefined;
    progress.hidden = true;
    updateBusy();
    if (r.setting === 'plan') {
      planError.textContent = r.error;
      planError.hidden = false;
      status.textContent = `The flight plan could not be read${store.report ? '; the results below are for the previous settings.' : '.'}`;
    } else if (failed.flight === 'csv' && !numericControl(r.setting)) {
      // The file's fault, not a number's set beside it (too many seeds for its length).
      csvError.textContent = r.error;
      csvError.hidden = false;
      status.textContent = `The CSV could not be simulated${store.report ? '; the results below are for the previous settings.' : '.'}`;
    } else {
      // An embed has no settings to change: its author chose them.
      const next = store.report ? ' Change a setting; the results below are for the previous settings.' : store.embed ? '' : ' Change a setting to see results.';
      status.textContent = `These settings cannot be simulated: ${r.error}.${namesSetting(r.setting)}${next}`;
      // Where the core knows the value of the setting it names that lets the run go ahead (the
      // seeds that fit, the heartbeat the slowest data rate needs), offer it (not in an embed,
      // whose settings are its author's).
      offerFit($('#fit-setting'), r.setting, store.embed ? undefined : r.valueThatFits);
      // The core names the setting it refuses (`maxInterval` shorter than the data rate's
      // interval, a limit the form cannot check alone): mark that control as the form marks its
      // own (the next change of any setting checks every control afresh and clears it).
      const control = numericControl(r.setting);
      if (control) markField(control, `${r.error}.`);
    }
    // Without results on show the refusal stands for them (an embed of charts alone shows it in
    // its caption, which markStale brings up to date).
    if (!store.report) store.refused = status.textContent ?? '';
    markStale(store.report !== undefined);
    markChartsUnrun(true);
    if (settingsChartsWait) renderSettingsCharts();
    sendQueued();
    return;
  }
}

/** The form's control of the numeric setting the core names by its key (`maxInterval`), if any. */
const numericControl = (key?: string) => (key && isNumericKey(key) ? field(key) : null);

/** The control a refusal's setting names: a numeric field of the form, or for a swarm's
 * `drones` the swarm panel's select of sizes. */
const fitControl = (setting?: string): HTMLInputElement | HTMLSelectElement | null => (setting === 'drones' ? $<HTMLSelectElement>('#swarmDrones') : numericControl(setting));

/** The core names a setting it refuses by its key (`maxInterval`), the page by its label:
 * " The setting it names is Heartbeat (s)." for a status line, or '' where it names none. */
function namesSetting(key?: string): string {
  const label = fitControl(key)?.labels?.[0]?.textContent?.trim();
  return label ? ` The setting it names is ${label}.` : '';
}

/** Calls `show` in the next task, the page busy until it has: the message that brought a report
 * (its data copied out of the workers and merged) and the table that shows it are each a task of
 * their own, not one long one (docs/performance.md). Not called if a run other than `id` has been
 * sent in between: that run has taken over the status line and the progress bar. */
function inNextTask(id: number, show: () => void): void {
  drawing++;
  void nextTask().then(() => {
    try {
      if (id === lastSent) show();
    } finally {
      drawing--;
      updateBusy();
    }
  });
}

/** The report of a run of `made` on show: the table, the status line and every chart. */
function showReport(report: SimReport, made: Settings, millis: number, params: SimulateParams): void {
  showPartial(false);
  csvError.hidden = true;
  planError.hidden = true;
  progress.hidden = true;
  store.report = report;
  store.reportSettings = made;
  store.refused = undefined;
  markChartsUnrun(false);
  // Drawn from this report now (the distance and SF charts wait on for its sweep).
  setPending(['axes', 'trajectory'], false);
  // A note that there were no results yet, beside the buttons of panels that draw no Plot chart
  // (the others' go as their chart is placed), is out of date.
  for (const panel of ['results', 'trajectory']) clearDownloadWhy($(`[data-panel="${panel}"]`));
  if (freshSeed) {
    // The drawn seed becomes the setting: the link and the form repeat this run.
    freshSeed = false;
    store.settings.seed = report.config.seed;
    store.reportSettings.seed = report.config.seed;
    field('seed').value = String(store.settings.seed);
    history.replaceState(null, '', `?${pageQuery()}`);
    renderLessonChanges();
  }
  // Typing may have moved the form on while this ran: the numbers say so.
  markStale(typing !== undefined || JSON.stringify(store.reportSettings) !== JSON.stringify(store.settings));
  const c = report.config;
  status.textContent = `${c.trajectory}: ${c.flights} flight${c.flights > 1 ? 's' : ''}, ${c.flightTime.toFixed(0)} s simulated in ${millis.toFixed(0)} ms. Gateway range${c.adr === 'off' ? '' : ` at SF${c.sf}, ${c.bw} kHz, where ADR starts`} (mean power = sensitivity ${c.sensitivityDbm.toFixed(1)} dBm): ${(c.rangeM / 1000).toFixed(2)} km.${planNote(c)}`;
  renderResults(report);
  showCommand('results', { ...params, seed: report.config.seed });
  if (settingsChartsWait) renderSettingsCharts();
}

/** How long the sweep that follows a report (the distance and SF charts: 12 more runs of the
 * flight) may take before those panels say that they still show the previous settings, ms. Most
 * sweeps come within it, so the charts do not flicker as a slider moves; a long uploaded flight's
 * took 90 s, its old charts on show all along. */
const SWEEP_PATIENCE_MS = 600;
let sweepWait: ReturnType<typeof setTimeout> | undefined;

/** The panels drawn from the sweep that follows a report. */
const SWEEP_PANELS = ['distance', 'sf'];
/** The panels a whole set's first flight does not draw: the sweep's, and those drawn from the
 * set's report. */
const SET_PANELS = [...SWEEP_PANELS, 'axes', 'trajectory'];

/** Marks the distance and SF panels as waiting for the sweep of the numbers on show (`on`), or
 * none as waiting. */
function sweepPending(on: boolean): void {
  clearTimeout(sweepWait);
  sweepWait = undefined;
  setPending(on ? SWEEP_PANELS : SET_PANELS, on);
}

/** Marks panels `names` as waiting for runs of the settings on show (`on`), or not: the chart
 * dimmed, a note over it (on a page still without them, the note alone). */
function setPending(names: string[], on: boolean): void {
  // The SF chart's heartbeat offer fitted the chart now dimmed; its sweep offers its own.
  if (on && names.includes('sf')) offerFit($('#sf-fit'), undefined, undefined);
  for (const name of names) {
    const panel = $(`[data-panel="${name}"]`);
    panel.classList.toggle('pending', on);
    const drawn = panel.querySelector('.chart')!.childElementCount > 0;
    if (on) panel.querySelector('.pending-note')!.textContent = `Computing this chart for the current settings${drawn ? '; until then it shows the previous ones.' : '…'}`;
  }
}

// ---- rendering ---------------------------------------------------------------------------------

/** The table at once; the charts each in a later task, so the numbers are painted first. */
function renderResults(r: SimReport): void {
  renderTable(r);
  updateEmbedCaption();
  const made = store.reportSettings;
  drawErrorChart(r, made);
  later('axes', () => {
    const axisRows: BoxRow[] = r.results.flatMap((m) => [
      { group: 'x', model: m.model, box: m.boxplot.errorX },
      { group: 'y', model: m.model, box: m.boxplot.errorY },
      { group: 'z', model: m.model, box: m.boxplot.errorZ },
    ]);
    const opts = { groupLabel: ['axis'], width: chartWidth('axes') };
    return drawPanel('axes', [axisRows, opts], (p) => p.boxplotChart(axisRows, opts), made);
  });
  if (!trajectoryPanel.hidden && trajectoryNear) later('trajectory', () => render3d(r));
}

/** Whether the 3D view has come within a screen of the viewport. Until then it is not drawn: its
 * first drawing (three.js, a WebGL context, the first frame) is the page's costliest, and at
 * 1280×800 the panel starts 2.5 screens down, so drawing it on load delayed every panel in view
 * by ~250 ms (docs/performance.md). Once near, it is drawn as every other panel is. */
let trajectoryNear = false;
/** Whether the watch has answered once: until then, whether the view is in view (and so still to
 * be drawn) is unknown, and the page stays busy. At 1920×1080 the view is near once the panels
 * above are drawn; `data-busy` cleared before that answer came would be set again at once, and a
 * caller waiting for it (a screenshot of an embed) would take the view blank. */
let trajectoryAnswered = false;
const trajectoryPanel = $('[data-panel="trajectory"]');
const nearTrajectory = new IntersectionObserver(
  (entries) => {
    trajectoryAnswered = true;
    if (!entries.some((e) => e.isIntersecting)) return updateBusy();
    nearTrajectory.disconnect();
    trajectoryNear = true;
    const r = store.report;
    if (r && !trajectoryPanel.hidden) later('trajectory', () => render3d(r));
  },
  { rootMargin: '100% 0px' },
);

/** Watches for the 3D view once the first results and the panels above it are drawn: before that
 * the empty panels above are short, and the view would seem near on every screen. Observing a
 * panel already observed does nothing, so this may run whenever the page falls idle. */
function watchTrajectory(): void {
  if (!trajectoryNear && store.report) nearTrajectory.observe(trajectoryPanel);
}
// A reader who scrolls is watched from then on, busy or not: a whole set's distance and SF charts
// run it again twelve times (seconds), and a reader who scrolled down to the 3D view meanwhile
// found it blank until they were done. On load, without a scroll, the watch still waits for them.
addEventListener('scroll', watchTrajectory, { passive: true });

/** The panels that need no simulation wait for a run's first answer (a whole set's first flight
 * included): on load, since drawn at once they would take the cores the first results need (about
 * 200 ms later on 2 cores), and after a change to a quick run, whose answer would wait for them. */
let settingsChartsWait = false;

/** The panels that follow the settings alone (time on air, link budget), drawn at once or, while a run is under way, after its first answer (`settingsChartsWait`). */
function renderSettingsCharts(): void {
  settingsChartsWait = false;
  markChartsUnrun(false, SETTINGS_CHARTS);
  later('airtime', renderAirtime);
  later('link', renderLink);
}

/** Drawings still under way (the 3D view loads three.js on first use) and a linked baseline being simulated; `swarming`: a swarm run. */
let drawing = 0;
let swarming = false;

/** `<body data-busy>` while anything visible is still being computed or drawn (tests wait on it). */
function updateBusy(): void {
  const working = running || drawing > 0 || swarming || drawingLater();
  if (!working) watchTrajectory();
  // Watched from here on once there are results (the line above); its first answer is pending.
  const unknown = store.report !== undefined && !trajectoryAnswered && !trajectoryNear;
  if (working || unknown) document.body.dataset.busy = '';
  else delete document.body.dataset.busy;
}

async function render3d(r: SimReport): Promise<void> {
  drawing++;
  try {
    await draw3d(r);
  } finally {
    drawing--;
    updateBusy();
  }
}

/** The lines the 3D view draws for `r`, in the legend's order: the truth, the plan, each station
 * (the page's legend and the PNG's). A plane's plan is drawn as the mission station follows it,
 * round its turns' arcs (reference §16), and its label says so. */
function tracksDrawn(r: SimReport | undefined): { color: string; label: string }[] {
  const series = r?.series;
  const plan = r?.config.planCornering === 'fixed-wing' ? 'flight plan, round a plane’s turns (dashed)' : 'flight plan (dashed)';
  return [{ color: TRUTH_COLOR, label: 'true flight' }, ...(series?.plan ? [{ color: PLAN_COLOR, label: plan }] : []), ...(series?.models ?? []).map((m) => ({ color: MODEL_COLORS[m.model], label: MODEL_LABELS[m.model] }))];
}

/** The 3D view as a PNG for slides. Until the panel has come near the viewport the view is not
 * kept up to date (its button reached without scrolling there): it is drawn from the results on
 * show first. */
async function download3d(button: HTMLButtonElement, title: string): Promise<void> {
  if (!store.report) return downloadWhy(button, noResults());
  if (!trajectoryNear) await render3d(store.report);
  const shot = trajectory3d?.snapshot(MIN_PNG_WIDTH);
  if (!shot) return downloadWhy(button, 'Nothing to save: the 3D view needs WebGL, which this browser does not offer.');
  downloadWhy(button, '');
  downloadPicturePng(shot.canvas, shot.scale, 'loratrack-trajectory', { title, caption: caption(store.reportSettings) }, tracksDrawn(store.report), [trajectoryKey], (why) => downloadWhy(button, why));
}

/** What the 3D view's cones and grid mean, as its legend on the page says it. */
let trajectoryKey = '';

async function draw3d(r: SimReport): Promise<void> {
  if (!trajectory3d) {
    const { createTrajectory3d } = await import('./charts/trajectory3d');
    // three.js is evaluated in one task, the WebGL context made in the next and the view drawn in
    // a third, as the Plot charts' first drawing is (`plots`): a reader scrolling to the view
    // meets short tasks, not one long one.
    await nextTask();
    trajectory3d ??= createTrajectory3d($('#chart-trajectory'));
    // Without a view there is nothing to rotate or reset; the PNG button stays and says why.
    if (!trajectory3d.webgl) for (const control of [$('#reset-view'), $('#trajectory-controls')]) control.hidden = true;
    await nextTask();
  }
  if (r !== store.report) return;
  const drawn = trajectory3d.update(r);
  if (!drawn) return;
  // The legend lists what is drawn: the truth, each station, the gateways, and the grid's scale.
  const swatch = (color: string) => `<span class="swatch" style="background:${color}"></span>`;
  const gateways = r.series?.gateways.length ?? 1;
  const far = drawn.farGateways ? `grey cone${drawn.farGateways > 1 ? 's' : ''} at the edge: ${drawn.farGateways === gateways ? '' : 'the other '}gateway${drawn.farGateways > 1 ? 's' : ''} beyond the view, with ${drawn.farGateways > 1 ? 'their' : 'its'} distance` : '';
  const near = gateways - drawn.farGateways;
  const tracks = tracksDrawn(r).map((t) => `${swatch(t.color)}${t.label}`).join(', ');
  const cones = [near ? `grey cone${near > 1 ? 's' : ''}: the gateway${near > 1 ? 's' : ''}` : '', far].filter(Boolean);
  const grid = `Grid squares ${drawn.gridStep >= 10 ? drawn.gridStep.toFixed(0) : drawn.gridStep.toFixed(1)} m.`;
  // Which flight and seed, where the results pool more.
  const which = r.series ? [seriesNote(r.config, r.series.flight, 'view'), noLineNote(r.series.models, r.series.flight, 'view')].filter(Boolean).join(' ') : '';
  $('#trajectory-legend').innerHTML = `${[tracks, ...cones].join('; ')}. ${grid}${which ? ` ${which}` : ''}`;
  // A slide lists the tracks as swatches; the cones, the grid's scale and the flight go under the picture.
  const coneKey = cones.join('; ');
  trajectoryKey = `${coneKey ? `${coneKey[0].toUpperCase()}${coneKey.slice(1)}. ${grid}` : grid}${which ? ` ${which}` : ''}`;
}

/** The note under chart `name` on what it rests on, from its `parts` (hidden where all are
 * empty): the error chart's one flight and seed; a sweep chart's points over too few packets and
 * its one seed ([`sweepRestsOn`]). A slide of the chart carries it. */
function restsOn(name: 'error' | 'sf' | 'distance', ...parts: string[]): void {
  const text = parts.filter(Boolean).join(' ');
  $(`#${name}-rests-on`).hidden = !text;
  $(`#${name}-rests-on`).textContent = text;
}

/** A sweep chart's note: its points over too few packets (`few`), its one seed where the table
 * pools more, and what else its runs fix that the table's do not (`fixed`: one gateway, one SF). */
function sweepRestsOn(name: 'sf' | 'distance', few: string, made: Settings, fixed: string): void {
  restsOn(name, few, oneSeedNote(store.reportSettings.seeds, made.seed), fixed);
}

/** The SF chart from the sweep's SF points: each station's p75 where it ran, and where the core
 * refused it (the note under the chart says why) a row that says so. */
async function renderSfs(sweep: { sf: number; report?: SimReport }[], asked: ModelName[], made: Settings): Promise<void> {
  const rows: SfRow[] = sweep.flatMap(({ sf, report: r }) => {
    const ran = r?.results ?? [];
    const refused = asked.filter((model) => !ran.some((m) => m.model === model));
    return [
      ...ran.map((m) => ({ sf, model: m.model, p75: m.error3d.p75, received: m.packetsReceived, sent: m.packetsSent, few: m.caveats.fewPackets, wholeFlight: m.wholeFlight })),
      ...refused.map((model) => ({ sf, model, p75: null, received: 0, few: false, wholeFlight: { tracked: 0, partlyTracked: false }, refused: true })),
    ];
  });
  sweepRestsOn('sf', fewPacketsNote(rows.filter((r) => r.p75 !== null).map((r) => ({ at: `SF${r.sf}`, received: r.received, few: r.few })), 'Hollow points', made.flight), made, fixedRateNote(made.adr));
  const opts = { bw: made.bw, distance: made.distance, sf: made.sf, adr: made.adr !== 'off', width: chartWidth('sf') };
  await drawPanel('sf', [rows, opts], (p) => p.p75BySfChart(rows, opts), made);
}

/** The last sweep and swarms drawn, to draw again at another size (presentation mode). */
let lastSweep: Extract<Response, { sweep: unknown }>['sweep'] | undefined;
let lastSwarm: (() => Promise<void>) | undefined;

function renderSweep(sweep: Extract<Response, { sweep: unknown }>['sweep'], made: Settings): void {
  lastSweep = sweep;
  later('distance', () => renderDistance(sweep.flatMap(({ point, report: rep }) => ('distance' in point && rep ? [{ distance: point.distance, report: rep }] : [])), made));
  // An SF, or a station at an SF, the core refuses at these settings is marked in the chart, and
  // the note says why; the SFs the plan lacks under one reason (the core names each SF).
  const asked = stationsOf(made.model);
  const sfs = sweep.flatMap(({ point, report: rep, error, setting, valueThatFits: fits }) => ('sf' in point ? [{ sf: point.sf, report: rep, error, setting, valueThatFits: fits }] : []));
  later('sf', () => renderSfs(sfs, asked, made));
  // Each refusal with the label of the setting it names, as the status line gives it.
  const why = (sf: number, error?: string, setting?: string) =>
    error && (!planAllows(made.region, sf, made.bw) ? planReason(made.region) : `${error.replace(/\.$/, '')}.${namesSetting(setting)}`);
  const note = refusedNote(sfs.map(({ sf, report: rep, error, setting }) => ({ at: `SF${sf}`, asked, ran: rep?.results.map((r) => r.model) ?? [], error: why(sf, error, setting) })));
  $('#sf-note').hidden = !note;
  $('#sf-note').textContent = note;
  // Named apart from the results' and the swarm panel's offers, which may give the same value.
  offerFit($('#sf-fit'), 'maxInterval', store.embed ? undefined : heartbeatThatFits(sfs), ' for every SF');
}

/** The heartbeat with which every SF the core refused for its heartbeat would run: the
 * largest value it named (the slowest data rate's duty-cycle interval, since each point's is a
 * least heartbeat), or undefined where none was refused for it. */
function heartbeatThatFits(sweep: { setting?: string; valueThatFits?: number }[]): number | undefined {
  const fits = sweep.flatMap(({ setting, valueThatFits: v }) => (setting === 'maxInterval' && v !== undefined ? [v] : []));
  return fits.length ? Math.max(...fits) : undefined;
}

/** What each panel drawn by `drawPanel` was last drawn from, with the page's type size then. */
const drawnFrom: Record<string, unknown> = {};

/**
 * Draws panel `name` with `draw` (given the Plot charts) from `inputs`, everything the drawing
 * reads, unless it is on show drawn from the same data (`sameData`): a change of distance, model
 * or station leaves the time-on-air panel as it was (drawn again, 54–64 ms of the page's thread on
 * two cores), a change of model the link budget, a change between distances at which the
 * error-versus-distance chart has no box that chart (its points do not move with the distance,
 * and its grey column stands only at a box), and a change that leaves the numbers as they were
 * (a distance within the link's reach, where every packet arrives) the charts of those numbers.
 * Either way its download's caption names the settings (`made`) now on show.
 */
async function drawPanel(name: string, inputs: unknown, draw: (p: Awaited<ReturnType<typeof plots>>) => Element | Promise<Element>, made: Settings = store.settings): Promise<void> {
  // Presentation mode draws the same inputs larger.
  const from = [inputs, presenting()];
  const drawn = charts[name];
  if (drawn && sameData(drawnFrom[name], from)) {
    drawn.caption = caption(made);
    return;
  }
  place(name, await draw(await plots()), made);
  drawnFrom[name] = from;
}

async function renderDistance(sweep: { distance: number; report: SimReport }[], made: Settings): Promise<void> {
  const rows: BoxRow[] = sweep.flatMap(({ distance, report: r }) => r.results.map((m) => ({ group: `${distance / 1000} km`, model: m.model, box: m.boxplot.error3d, few: m.caveats.fewPackets, sent: m.packetsSent })));
  const received = sweep.flatMap(({ distance, report: r }) => r.results.filter((m) => m.error3d.count > 0).map((m) => ({ at: `${distance / 1000} km`, received: m.packetsReceived, few: m.caveats.fewPackets })));
  const swept = sweep.map(({ distance }) => distance);
  const fixed = [oneGatewayNote(made.gateways.length), offChartNote(made.distance, swept, made.gateways.length)].filter(Boolean).join(' ');
  sweepRestsOn('distance', fewPacketsNote(received, 'Dashed boxes', made.flight), made, fixed);
  // With ADR the runs start at the chosen rate and the network moves them (the SF chart's do not).
  const adr = made.adr === 'off' ? '' : ` and ${adrName(made.adr)}`;
  const rate = `SF${made.sf}, ${made.bw} kHz${adr}`;
  // A column where the results' one gateway stands at one of the chart's distances (listed
  // gateways have no one distance); a distance between them or beyond leaves the chart as drawn.
  const group = `${made.distance / 1000} km`;
  const chosen = made.gateways.length || !swept.includes(made.distance) ? undefined : { group, key: `Grey column: ${group}, the chosen distance, where the results' run is.` };
  const opts = { log: true, groupLabel: [`gateway distance (${rate})`, `distance (${rate})`, `distance (${rate.replace(' and ', ', ')})`], width: chartWidth('distance'), chosen };
  await drawPanel('distance', [rows, opts], (p) => p.boxplotChart(rows, opts), made);
}

async function renderLink(): Promise<void> {
  const s = store.settings;
  const params = { bw: s.bw, txPower: s.txPower, pathLossExponent: s.pathLossExponent, shadowing: s.shadowing, region: s.region };
  // Each gateway's distance from the flight's start (the default one: the distance setting).
  const distances = s.gateways.length ? s.gateways.map((g) => Math.hypot(g.east, g.north)) : [s.distance];
  const opts = { width: chartWidth('link'), distances, sf: s.sf, plan: plan(s.region).label, adr: s.adr !== 'off' };
  await drawPanel('link', [params, opts], (p) => p.linkBudgetCharts(linkBudget(params), opts));
}

/** What the time-on-air table on show follows: its CSV gives the same rows, with these settings
 * (set also where the table is left as drawn, its numbers the same: a new distance). */
let airtimeDrawn: { opts: ReturnType<typeof packetPlan> & { sf: number; bw: number }; settings: Settings } | undefined;

async function renderAirtime(): Promise<void> {
  const s = store.settings;
  const opts = { sf: s.sf, bw: s.bw, ...packetPlan(s) };
  const width = chartWidth('airtime');
  airtimeDrawn = { opts, settings: { ...s } };
  await drawPanel('airtime', [opts, width], (p) => {
    $('#airtime-table').replaceChildren(p.airtimeTable(opts));
    fitAirtimeTable();
    return p.airtimeVsPayloadChart({ ...opts, width });
  });
}

/**
 * Lets the time-on-air table's intervals go under their times where it is too wide for its box,
 * if that makes it fit: presentation mode at 1024×768 cut off 3D-CTRA's column (now one row
 * breaks), and a tablet or an embed in a documentation column (601–767 px) hid it behind a
 * sideways scroll (now most rows break: 1023 px tall at 650 px against 660, every column in
 * view). Again whenever the box changes width. On a phone, where it would not fit either way, the
 * table stays one line a row and scrolls sideways with its rows' names in view.
 */
const fitAirtimeTable = fitOnWidth($('#airtime-table'), () => {
  if (!tighten([$('#airtime-table')])) $('#airtime-table').classList.remove('tight');
});

/** A chart's drawing width, px: its box's, at least 300 (600 before the box is laid out). */
function chartWidth(name: string): number {
  return Math.max(300, $(`#chart-${name}`).clientWidth || 600);
}

function place(name: string, chart: Element, made: Settings = store.settings, extra = '', swarm?: SwarmOf): void {
  charts[name] = { chart, caption: caption(made, extra, swarm) };
  // Plot labels its mark groups; an unlabelled role-less <g> may not carry aria-label, so the
  // chart is one image named by its panel's title instead.
  for (const g of chart.querySelectorAll('g[aria-label]')) g.removeAttribute('aria-label');
  const main = chartSvg(chart);
  main?.setAttribute('role', 'img');
  main?.setAttribute('aria-label', document.getElementById(`${name}-title`)?.textContent ?? name);
  const box = $(`#chart-${name}`);
  box.replaceChildren(chart);
  // A note under the chart that cites the docs (the swarm's saturated drones) links them.
  linkDocs(box);
  // A note on why a download did nothing spoke of the chart this one replaces.
  clearDownloadWhy(box.closest('[data-panel]') ?? box);
}

// ---- events ------------------------------------------------------------------------------------
function onChange(): void {
  const { next, errors } = readControls();
  showConditional();
  if (errors.length) {
    // Nothing runs on a value the core would refuse; the numbers on show are marked as old.
    markStale(store.report !== undefined);
    // The link budget and time on air, too, are drawn from the last valid settings.
    markChartsUnrun(true, [...RESULT_CHARTS, ...SETTINGS_CHARTS]);
    status.textContent = `Not simulated: ${errors.join(' ')}${store.report ? ' The results below are for the previous settings.' : ''}`;
    return;
  }
  store.settings = next;
  history.replaceState(null, '', `?${pageQuery()}`);
  renderLessonChanges();
  markSwarmStale();
  submit();
  // A quick run's numbers first: drawn ahead of them, the airtime and link charts (~60 and ~30
  // ms on two cores) held a changed SF's results back by ~100 ms (docs/performance.md). A long
  // run (the whole set, a CSV, several seeds) would leave them showing the old settings for seconds.
  if (running && !running.long) settingsChartsWait = true;
  else renderSettingsCharts();
}

/** A pending run of a number being typed (a half-typed −1 of −15 must not run). */
let typing: number | undefined;
const TYPING_PAUSE_MS = 800;
const isTyped = (t: EventTarget | null) => t instanceof HTMLInputElement && t.type === 'number';

function commitTyping(): void {
  clearTimeout(typing);
  typing = undefined;
  onChange();
}

form.addEventListener('input', (e) => {
  if (['csv', 'plan-file'].includes((e.target as HTMLElement).id)) return;
  if (isTyped(e.target)) {
    // The numbers on show no longer match the form: say so at once, run after a pause or when
    // the field is left.
    clearTimeout(typing);
    markStale(true);
    typing = window.setTimeout(commitTyping, TYPING_PAUSE_MS);
    return;
  }
  onChange();
});
form.addEventListener('change', (e) => {
  if (isTyped(e.target) && typing !== undefined) commitTyping();
});
form.addEventListener('submit', (e) => e.preventDefault());
// Adding or removing a gateway changes the settings as typing does.
onFormChange(onChange);

/** Gives the file chosen in `input` to `keep` and runs; a file over the core's 64 MiB is
 * refused in `error` before it is read. */
function onUpload(input: string, error: HTMLElement, keep: (file: File) => void | Promise<void>): void {
  $<HTMLInputElement>(input).addEventListener('change', async (e) => {
    const file = (e.target as HTMLInputElement).files?.[0];
    if (!file) return;
    if (file.size > MAX_CSV_BYTES) {
      error.textContent = `${file.name} is ${(file.size / 2 ** 20).toFixed(1)} MiB; at most 64 MiB is read.`;
      error.hidden = false;
      return;
    }
    await keep(file);
    error.hidden = true;
    onChange();
  });
}
// Its bytes, held in memory: a File is read from disk at each use, and a file edited or removed
// after its upload would then fail the next run.
onUpload('#csv', csvError, async (f) => {
  store.csv = { file: new Blob([await f.arrayBuffer()]), name: f.name };
});
onUpload('#plan-file', planError, async (f) => {
  store.plan = { text: await f.text(), name: f.name };
});

setUpCopyCommand();

$('#copy-link').addEventListener('click', async () => {
  const url = location.href;
  // An uploaded file stays on this computer: say what the link will open instead.
  const caveat = uploaded(store.settings.flight) ? ` It opens one synthetic flight: an uploaded ${store.settings.flight === 'csv' ? 'CSV' : 'plan'} never leaves this computer, so a link cannot carry it.` : '';
  try {
    await navigator.clipboard.writeText(url);
    $('#copy-status').textContent = `Link copied.${caveat}`;
  } catch {
    $('#copy-status').textContent = `Copy this link: ${url}${caveat}`;
  }
});

// Every setting of the link, the swarm panel's choices too: after Reset, Copy link opens the page
// as a first visit does (a pinned baseline stays: Clear baseline is its own button).
$('#reset').addEventListener('click', () => {
  store.settings = { ...DEFAULTS };
  writeControls(store.settings);
  resetSwarmChoices();
  onChange();
});

$('#reset-view').addEventListener('click', () => trajectory3d?.resetView());

// ---- the swarm panel: workers of its own, so a swarm never holds up the single-drone results --
let swarmRun: SwarmRun | undefined;

/** The swarms the panel would run now (`swarmRequest`: the drone's settings and the panel's
 * choices). */
function swarmRequest(): { sizes: number[]; params: SwarmParams } {
  const value = (id: string) => $<HTMLSelectElement>(`#${id}`).value;
  return swarmRequestOf(store.settings, {
    drones: Number(value('swarmDrones')),
    channels: value('swarmChannels') === '1' ? '1' : 'plan',
    sfPlan: value('swarmPlan') === 'fixed' ? 'fixed' : 'spread',
    schedule: value('swarmSchedule') === 'slotted' ? 'slotted' : 'aloha',
    duration: Number(value('swarmDuration')),
  });
}

/** The request of the swarms on show, to tell when the settings have moved on from them. */
let swarmShown: string | undefined;

/** Marks the swarms on show as old where the panel would now run other swarms (a setting of the
 * drone or a choice of the panel changed since): they run only when asked, so nothing else would
 * say that their numbers are not the settings' on show. */
function markSwarmStale(): void {
  const now = JSON.stringify(swarmRequest());
  const stale = swarmShown !== undefined && now !== swarmShown;
  $('[data-panel="swarm"]').classList.toggle('stale', stale);
  // Before any swarm is on show, an embed's caption says what Run swarm would run.
  updateEmbedCaption();
  // A refusal's offered value fits the swarms it refused, not others.
  if (swarmRefused !== now) offerFit($('#swarm-fit'), undefined, undefined);
}

/** The swarms the core refused last (their request), whose refusal is on show. */
let swarmRefused: string | undefined;

/** Stops the swarms under way and says so (the panel's Stop button, shown while they run): a
 * 200-drone swarm of 20-minute flights takes a minute or more, and Run swarm was the only way
 * out of one started by mistake. */
let stopSwarms: (() => void) | undefined;
$('#stop-swarm').addEventListener('click', () => stopSwarms?.());

$('#run-swarm').addEventListener('click', () => {
  swarmRun?.stop();
  const { sizes, params } = swarmRequest();
  const made = swarmSettings(store.settings);
  const bar = $<HTMLProgressElement>('#swarm-progress');
  bar.hidden = false;
  bar.value = 0;
  $('#swarm-status').textContent = `Simulating swarms of ${sizes.join(', ')} drones…`;
  offerFit($('#swarm-fit'), undefined, undefined);
  // Before the first swarm's chart, the placeholder says it is on its way, not that none was run.
  const placeholder = document.querySelector('#chart-swarm > .empty-chart');
  const unrun = placeholder?.textContent ?? '';
  if (placeholder) placeholder.textContent = 'The swarms are running; their chart appears here when all are done.';
  swarming = true;
  updateBusy();
  const run = (swarmRun = runSwarms(sizes, params, (done) => (bar.value = done)));
  const stopButton = $<HTMLButtonElement>('#stop-swarm');
  stopButton.hidden = false;
  const end = () => {
    bar.hidden = true;
    // Focus on the Stop button would be lost with it: it goes to Run swarm.
    if (document.activeElement === stopButton) $<HTMLButtonElement>('#run-swarm').focus();
    stopButton.hidden = true;
    stopSwarms = undefined;
    swarming = false;
    updateBusy();
    // "Still running" no longer holds, whether the chart follows or an error.
    clearDownloadWhy($('[data-panel="swarm"]'));
  };
  stopSwarms = () => {
    run.stop();
    end();
    if (placeholder) placeholder.textContent = unrun;
    $('#swarm-status').textContent = `Stopped: the swarms of ${sizes.join(', ')} drones were not run to the end.${swarmShown === undefined ? '' : ' The chart is of the swarms run before.'}`;
  };
  run.done.then(
    ({ swarms, millis }) => {
      end();
      const rates = swarms.map((w) => `${w.config.drones} drones ${w.collisionRate === null ? '— (none sent)' : `${(100 * w.collisionRate).toFixed(1)} %`}`).join(', ');
      $('#swarm-status').textContent = `${sizes.length} swarms simulated in ${(millis / 1000).toFixed(1)} s. Packets collided: ${rates}.`;
      swarmShown = JSON.stringify({ sizes, params });
      const shown = (store.swarm = { settings: made, fixedSf: params.sfPlan === 'fixed' });
      showCommand('swarm', { ...params, drones: sizes[sizes.length - 1] });
      markSwarmStale();
      lastSwarm = async () => {
        const p = await plots();
        const channels = swarms[0]?.drones[0]?.channelUse.length ?? params.channels ?? 1;
        const largest = swarms[swarms.length - 1];
        place('swarm', p.swarmCharts(swarms, chartWidth('swarm')), made, `; swarms of ${sizes.join(', ')} drones, ${channels} channel${channels === 1 ? '' : 's'}, ${p.sfPlanWords(largest)}, ${params.schedule === 'slotted' ? 'slotted' : 'ALOHA'}, ${Math.round(largest.flightTime)} s each`, shown);
      };
      later('swarm', lastSwarm);
    },
    (e: Error) => {
      end();
      if (placeholder) placeholder.textContent = unrun;
      $('#swarm-status').textContent = `These swarms cannot be simulated: ${e.message}.${namesSetting(settingOf(e))}`;
      swarmRefused = JSON.stringify({ sizes, params });
      offerFit($('#swarm-fit'), settingOf(e), store.embed ? undefined : valueThatFits(e));
    },
  );
});

$('#pin').addEventListener('click', () => {
  const report = store.baseline ? undefined : shownReport($('#pin'));
  store.baseline = report && { report, settings: { ...store.reportSettings } };
  history.replaceState(null, '', `?${pageQuery()}`);
  renderLessonChanges();
  // The table draws the baseline's note with its differences; without one, the note alone.
  if (store.report) renderResults(store.report);
  else renderBaseline();
});

$('#repeat-seeds').addEventListener('click', () => {
  field('seeds').value = $('#repeat-seeds').dataset.seeds ?? '10';
  onChange();
});

/** The words of the button that sets `setting` to `value`: "Use 18 seeds", "Use a heartbeat of
 * 148.3 s", or the control's label and the value. */
function fitWords(setting: string, value: number): string {
  if (setting === 'seeds') return `Use ${value} seed${value === 1 ? '' : 's'}`;
  if (setting === 'maxInterval') return `Use a heartbeat of ${value} s`;
  if (setting === 'drones') return `Use ${value} drones`;
  return `Set ${numericControl(setting)?.labels?.[0]?.textContent?.trim() ?? setting} to ${value}`;
}

/** The value `control` can take for the core's `value`: a number as it is; for a select of
 * sizes, the largest of its options within it (a swarm of at most 29 drones: 20), if any. */
function fitFor(control: HTMLInputElement | HTMLSelectElement, value: number): number | undefined {
  if (!(control instanceof HTMLSelectElement)) return value;
  const within = [...control.options].map((o) => Number(o.value)).filter((v) => v <= value);
  return within.length ? Math.max(...within) : undefined;
}

/** Shows `button` under a refusal, to set the setting it names to the value with which the run
 * would go ahead (the core's `valueThatFits`), or hides it where there is none; `what` says what
 * it lets run where the page offers the same value for more than one thing (" for every SF"). */
function offerFit(button: HTMLButtonElement, setting: string | undefined, value: number | undefined, what = ''): void {
  const control = fitControl(setting);
  const fit = control && value !== undefined ? fitFor(control, value) : undefined;
  button.hidden = fit === undefined;
  if (setting === undefined || fit === undefined) return;
  button.dataset.setting = setting;
  button.dataset.value = String(fit);
  button.textContent = `${fitWords(setting, fit)}${what}`;
}

/** Sets the control `button` was offered for to its value, as if typed or chosen, and runs the
 * form (a swarm size: the panel's choice, which its own button runs). */
function useFit(button: HTMLElement): void {
  const control = fitControl(button.dataset.setting);
  if (!control || button.dataset.value === undefined) return;
  control.value = button.dataset.value;
  if (control instanceof HTMLSelectElement) control.dispatchEvent(new Event('change'));
  else onChange();
}

$('#fit-setting').addEventListener('click', () => useFit($('#fit-setting')));
$('#sf-fit').addEventListener('click', () => useFit($('#sf-fit')));

// The swarms asked for again at once: the reader pressed Run swarm to see them.
$('#swarm-fit').addEventListener('click', () => {
  useFit($('#swarm-fit'));
  $('#run-swarm').click();
});

$('#use-whole-set').addEventListener('click', () => {
  field('flight').value = 'all';
  onChange();
});

$('#new-seed').addEventListener('click', () => {
  freshSeed = true;
  submit();
});

/** Empties the notes in `panel` that said why a download did nothing. */
function clearDownloadWhy(panel: Element): void {
  for (const note of panel.querySelectorAll('.download-why')) note.textContent = '';
}

/** Says beside a download's buttons why it could not happen (or clears the message). */
function downloadWhy(button: HTMLElement, why: string): void {
  const group = button.closest('.buttons') ?? button.parentElement!;
  let note = group.querySelector<HTMLElement>('.download-why');
  if (!note) {
    note = document.createElement('span');
    note.className = 'note download-why';
    note.setAttribute('role', 'status');
    group.append(note);
  }
  note.textContent = why;
}

/** The report behind the numbers on show, for a download or Pin; none while a whole set's first
 * flight stands in for it (the table is not that report), which is said beside `button`. */
function shownReport(button: HTMLElement): SimReport | undefined {
  const waiting = $('[data-panel="results"]').classList.contains('partial');
  downloadWhy(button, waiting ? 'The whole set is still running: its results can be saved or pinned when it ends.' : (store.report ? '' : noResults()));
  return waiting ? undefined : store.report;
}

/** Why a download or Pin finds no results at all: the first run has not ended, or the page has
 * none to show (a link whose settings the core refuses: the status says why). */
function noResults(): string {
  const where = store.embed && $('[data-panel="results"]').hidden ? 'the caption at the top' : 'the status above the results';
  return running ? 'No results yet: the first run is still under way.' : `No results yet: nothing has been simulated at these settings (${where} says why).`;
}

for (const [id, save] of [
  ['download-csv', (r: SimReport) => downloadErrorCsv(r)],
  ['download-json', (r: SimReport) => downloadJson(r, store.reportSettings, commandOf('results'))],
  // An uploaded flight never leaves this computer: no link opens it.
  ['download-results-csv', (r: SimReport) => downloadResultsCsv(r, { settings: caption(store.reportSettings), link: uploaded(store.reportSettings.flight) ? '' : `${location.origin}${location.pathname}?${toQuery(store.reportSettings)}`, command: commandOf('results') ?? '' })],
] as const) {
  $(`#${id}`).addEventListener('click', () => {
    const report = shownReport($(`#${id}`));
    if (report) save(report);
  });
}
/** The notes on show right after `chart` in its panel (the SF chart's SFs not simulated, and
 * why): a slide of the chart carries them. */
function notesAfter(chart: Element): string[] {
  const notes: string[] = [];
  for (let e = chart.nextElementSibling; e instanceof HTMLElement && e.matches('.note'); e = e.nextElementSibling) if (!e.hidden && e.textContent) notes.push(e.textContent);
  return notes;
}
/** Saves `picture` on a slide in the format `button` names (SVG or PNG); false when it has
 * nothing drawn to save. */
function saveSlide(button: HTMLButtonElement, picture: Element, name: string, slide: SlideText): boolean {
  if (button.dataset.format === 'svg') return downloadSvg(picture, name, slide);
  return downloadPng(picture, name, slide, (why) => downloadWhy(button, why));
}
/** The results table as drawn (in the pieces the page splits it into), for a slide: whether a
 * station's p75 is clearly the lowest (the verdict under the table: the slide's "lowest p75" mark
 * means that, and where there is none, the slide says why), what the numbers are, the settings they
 * rest on and, with a baseline pinned, what the differences are against. None while a whole set's
 * first flight stands in for the set. */
function downloadResultsPicture(button: HTMLButtonElement): void {
  const [table, ...rest] = document.querySelectorAll<HTMLTableElement>('#results-table table');
  if (!shownReport(button) || !table) return;
  const what = resultsWhat();
  const against = $('#baseline-note').hidden ? '' : ` ${$('#baseline-note').textContent ?? ''}`;
  const notes = restingNotes().map((n) => `${n} `).join('');
  const verdict = ($('#verdict-text').textContent ?? '').trim();
  const slide = { title: 'Results', caption: `${what ? `${what}. ` : ''}${notes}${caption(store.reportSettings)}.${against}`, notes: verdict ? [verdict] : [] };
  saveSlide(button, tableSvg(table, ...rest), 'loratrack-results', slide);
}
/** The time-on-air table as drawn, for a slide: its caption (what the numbers are and what the plan
 * refuses) and the settings it follows (the overhead and coding rate among them). */
function downloadAirtimePicture(button: HTMLButtonElement): void {
  const table = document.querySelector<HTMLTableElement>('#airtime-table table');
  if (!table) return;
  // The caption's first part: its second (overhead, coding rate) is among the settings named after it.
  const what = table.caption?.querySelector('.what')?.textContent?.trim() ?? '';
  const slide = { title: 'Time on air', caption: `${what} ${caption(airtimeDrawn?.settings ?? store.settings)}.` };
  saveSlide(button, tableSvg(table), 'loratrack-time-on-air', slide);
}
$('#download-airtime-csv').addEventListener('click', () => {
  if (airtimeDrawn) downloadAirtimeCsv(airtimeRows(airtimeDrawn.opts), caption(airtimeDrawn.settings));
});
for (const button of document.querySelectorAll<HTMLButtonElement>('[data-download]')) {
  const name = button.dataset.download!;
  // `airtime-table` is the time-on-air panel's table, beside its chart (`airtime`).
  const table = name === 'results' || name === 'airtime-table';
  const title = document.getElementById(`${name.replace(/-table$/, '')}-title`)?.textContent ?? name;
  button.setAttribute('aria-label', `Download the ${title.replace(/:.*/, '').toLowerCase()} ${table ? 'table' : 'chart'} as ${button.dataset.format!.toUpperCase()}`);
  button.addEventListener('click', () => {
    const slide = (c: string): SlideText => ({ title, caption: c, notes: notesAfter($(`#chart-${name}`)) });
    if (name === 'trajectory') return void download3d(button, title);
    if (name === 'results') return void downloadResultsPicture(button);
    if (name === 'airtime-table') return void downloadAirtimePicture(button);
    const entry = charts[name];
    const saved = entry && saveSlide(button, entry.chart, `loratrack-${name}`, slide(entry.caption));
    downloadWhy(button, saved ? '' : name === 'swarm' && !entry ? `Nothing to save yet: ${swarming ? 'the swarms are still running' : 'run a swarm first'}.` : !entry ? noResults() : 'Nothing to save: this chart has no data at these settings (no packet reached the station).');
  });
}

// ---- lessons: guided scenarios, each a URL state with what to notice ---------------------------
for (const l of LESSONS) {
  const item = document.createElement('li');
  const link = document.createElement('a');
  link.href = `?${lessonQuery(l)}`;
  link.textContent = l.title;
  item.append(link);
  $('#lesson-list').append(item);
}
// The link's swarm choices first: a lesson with a swarm sets its own over them.
store.notices.push(...readSwarmQuery(store.query));
const asked = store.query.get('lesson');
const lesson = store.embed ? undefined : LESSONS.find((l) => l.id === asked);
if (asked !== null && !store.embed && !lesson) store.notices.push(`The link's lesson=${asked.slice(0, 40)} is not one of the lessons; the Lessons menu lists them.`);
if (lesson) {
  store.lesson = lesson.id;
  $('#lesson').hidden = false;
  $<HTMLAnchorElement>('#lesson-restore').href = `?${lessonQuery(lesson)}`;
  if (lesson.swarm) for (const [id, , value] of swarmChoices(lesson.swarm)) $<HTMLSelectElement>(`#${id}`).value = value;
  $('#lesson-title').textContent = `Lesson: ${lesson.title}`;
  $('#lesson-text').textContent = lesson.text;
  $('#lesson-notice').replaceChildren(
    ...lesson.notice.map((n) => {
      const li = document.createElement('li');
      li.textContent = n;
      return li;
    }),
  );
}
/** While the link's baseline is simulated, none is pinned yet: not a change from the lesson's. */
let baselineLoading = store.query.get('baseline') !== null;
/** The lesson's text speaks of its own settings: where the form or the pinned baseline has left
 * them (a step the lesson asks for, a link typed by hand), the panel names what changed. */
function renderLessonChanges(): void {
  if (!lesson) return;
  // A setting whose control the form hides (a threshold while sending periodically) shapes nothing.
  const words = changedFromLesson(lesson, store.settings).filter((k) => !field(k)?.hidden).map((k) => {
    const now = settingWords(k, store.settings);
    return `${now.label}: ${now.value} instead of ${settingWords(k, lessonSettings(lesson)).value}`;
  });
  if (lesson.swarm) words.push(...swarmChanges(lesson.swarm));
  if (!baselineLoading && !baselineIsLessons(lesson, store.baseline?.settings)) words.push(store.baseline ? "a pinned baseline other than the lesson's" : 'no pinned baseline (the lesson pins one)');
  $('#lesson-changed').hidden = words.length === 0;
  $('#lesson-changed-text').textContent = `Not the lesson's settings: ${words.join('; ')}. “What to notice” speaks of the lesson's own settings and of the steps it asks for.`;
}
/** A lesson's swarm as the swarm panel's choices: each select's id, its name in a sentence and the
 * value the lesson picks (ALOHA and 2-minute flights, the panel's own). The lesson sets them, and
 * names any the reader has since changed. */
function swarmChoices(own: NonNullable<Lesson['swarm']>): [string, string, string][] {
  return [
    ['swarmDrones', 'Swarm drones', String(own.drones)],
    ['swarmChannels', 'Swarm channels', own.channels === 1 ? '1' : 'plan'],
    ['swarmPlan', 'Swarm SF plan', own.plan],
    ['swarmSchedule', 'Swarm schedule', 'aloha'],
    ['swarmDuration', 'Swarm flights', '120'],
  ];
}
/** The swarm panel's choices that are not the lesson's swarm, in the panel's words. */
function swarmChanges(own: NonNullable<Lesson['swarm']>): string[] {
  return swarmChoices(own).flatMap(([id, name, value]) => {
    const select = $<HTMLSelectElement>(`#${id}`);
    const text = (v: string) => [...select.options].find((o) => o.value === v)?.textContent ?? v;
    return select.value === value ? [] : [`${name}: ${text(select.value)} instead of ${text(value)}`];
  });
}
// Every choice of the swarm panel, as the panel has them: a new one cannot be left out.
for (const select of swarmSelects())
  select.addEventListener('change', () => {
    history.replaceState(null, '', `?${pageQuery()}`);
    renderLessonChanges();
    markSwarmStale();
  });
// The help texts and the lesson name the docs their numbers come from: links to their pages.
linkDocs(document.body);

// ---- start -------------------------------------------------------------------------------------
writeControls(store.settings);
keepEarlyChoices();
// The form is the truth: a value the slider cannot show (a distance between its steps) is what it shows.
const shown = readControls().next;
if (shown.distance !== store.settings.distance) {
  store.notices.push(`The link's distance ${store.settings.distance} m is shown and simulated as ${shown.distance} m, the slider's nearest step.`);
  store.settings = shown;
}
renderLessonChanges();
/** A setting changed in the form before this script ran (boot.ts `changedEarly`) keeps the value
 * chosen, the others show the link's; where the choices together are not valid, the link's stand. */
function keepEarlyChoices(): void {
  if (!changedEarly.size) return;
  for (const [name, value] of changedEarly) {
    const el = field(name);
    if (!el) continue;
    if (typeof value === 'boolean') (el as HTMLInputElement).checked = value;
    else el.value = value;
  }
  const { next, errors } = readControls();
  if (!errors.length) {
    store.settings = next;
    history.replaceState(null, '', `?${pageQuery()}`);
  }
  writeControls(store.settings);
}
/** Adds a sentence to the notices at the top of the settings (and of an embed). */
function showNotice(text: string): void {
  if (text) store.notices.push(text);
  const box = $('#notice');
  box.textContent = store.notices.join(' ');
  box.hidden = store.notices.length === 0;
  updateEmbedCaption();
}
showNotice('');
// A shared link may carry a pinned baseline: its settings are simulated again (the same seed
// gives the same numbers) in a worker of its own, then pinned.
const pinned = store.query.get('baseline');
if (pinned !== null) {
  const b = fromQuery(`?${pinned}`);
  if (b.problems.length) showNotice(`The link's baseline: ${b.problems.join(' ')}`);
  const w = spawnWorker();
  drawing++;
  updateBusy();
  w.onmessage = (e: MessageEvent<Response>) => {
    if (!('report' in e.data) && !('error' in e.data)) return;
    if ('report' in e.data) store.baseline = { report: e.data.report, settings: b.settings };
    else showNotice(`The link's baseline could not be simulated: ${e.data.error}.`);
    w.terminate();
    drawing--;
    baselineLoading = false;
    renderLessonChanges();
    if (store.report) renderResults(store.report);
    else renderBaseline();
    updateBusy();
  };
  w.postMessage({ id: 1, params: toParams(b.settings) } satisfies Request);
}
onDrawing(updateBusy);
await load();
submit();
// The choices whose frames the plan cannot carry are known now (form.ts `frameRefusal`).
showConditional();
if (running) settingsChartsWait = true;
else renderSettingsCharts();
// The lesson's swarm runs as if its button were pressed with its choices (set with the lesson),
// and so does an embed's: its reader came for the chart its author chose.
if (lesson?.swarm || (store.embed && store.panels.split(',').includes('swarm'))) $('#run-swarm').click();
