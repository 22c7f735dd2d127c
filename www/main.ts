// The playground: reads the controls, asks the worker to simulate, renders numbers and charts.
import { linkBudget, load, MODEL_LABELS, stationsOf, timeOnAir, type GatewaySite, type ModelResult, type SimReport, type SwarmParams } from './loratrack';
import { linkBudgetCharts } from './charts/linkBudget';
import { swarmCharts } from './charts/swarm';
import { ADR_START_REASON, adrCanStart, DEFAULTS, fromQuery, GATEWAY_LIMITS, invalid, invalidGateways, isNumericKey, LIMITS, overheadBytes, toParams, toQuery, type Settings } from './state';
import type { Request, Response, SimulateRequest } from './worker';
import { SimulationPool } from './pool';
import { airtimeTable, airtimeVsPayloadChart } from './charts/airtime';
import { boxplotChart, type BoxRow } from './charts/boxplot';
import { p75BySfChart } from './charts/p75BySf';
import { LESSONS, lessonQuery } from './lessons';
import { errorOverTimeChart } from './charts/errorOverTime';
import type { Trajectory3d } from './charts/trajectory3d';
import { chartSvg, downloadErrorCsv, downloadJson, downloadPicturePng, downloadPng, downloadResultsCsv, downloadSvg, downloadTableCsv, MIN_PNG_WIDTH } from './export';
import { MODEL_COLORS, TRUTH_COLOR } from './charts/colors';

const DISTANCES = [500, 1000, 2000, 3000, 4000, 5000];
const SFS = [7, 8, 9, 10, 11, 12];
/** The largest CSV the core reads (MAX_CSV_BYTES in src/trajectory/csv.rs). */
const MAX_CSV_BYTES = 64 * 2 ** 20;
const $ = <T extends HTMLElement>(sel: string) => document.querySelector<T>(sel)!;
const form = $<HTMLFormElement>('#controls');
const status = $('#status');
const progress = $<HTMLProgressElement>('#progress');
const csvError = $('#csv-error');
const query = new URLSearchParams(location.search);
const embed = query.get('embed') === '1';
const PANELS = ['controls', 'results', 'trajectory', 'error', 'axes', 'distance', 'sf', 'link', 'swarm', 'airtime'];

const parsed = fromQuery(location.search);
let settings: Settings = parsed.settings;
const notices: string[] = [...parsed.problems];
let csv: { text: string; name: string } | undefined;
let report: SimReport | undefined;
/** The settings that made `report` (the form may have moved on since). */
let reportSettings: Settings = settings;
let trajectory3d: Trajectory3d | undefined;
const charts: Record<string, { chart: Element; caption: string }> = {};

// ---- embedding: ?embed=1&panels=results,error shows only those panels --------------------------
let panels = 'results,error';
if (embed) {
  document.body.classList.add('embed');
  const asked = (query.get('panels') ?? panels).split(',').map((p) => p.trim()).filter(Boolean);
  const known = asked.filter((p) => PANELS.includes(p));
  if (known.length < asked.length || known.length === 0) {
    notices.push(`Unknown panel${asked.length - known.length === 1 ? '' : 's'} in the link (${asked.filter((p) => !PANELS.includes(p)).join(', ') || 'none named'}); the panels are ${PANELS.join(', ')}.`);
  }
  panels = (known.length ? known : panels.split(',')).join(',');
  for (const el of document.querySelectorAll<HTMLElement>('[data-panel]')) el.hidden = !panels.split(',').includes(el.dataset.panel!);
  // The heading stays for screen readers, the credit and a way to the full page stay visible.
  for (const el of document.querySelectorAll<HTMLElement>('[data-chrome]')) el.classList.add('visually-hidden');
  const full = $<HTMLAnchorElement>('#open-full');
  const url = new URL(location.href);
  url.searchParams.delete('embed');
  url.searchParams.delete('panels');
  full.href = url.toString();
  full.hidden = false;
  // An embed says which settings it shows; Pin compares runs, which an embed does not make.
  $('#embed-caption').hidden = false;
  $('#pin').hidden = true;
  // The host page can grow the frame to its content (README: the snippet that listens).
  if (window.parent !== window) {
    let last = 0;
    new ResizeObserver(() => {
      const height = Math.ceil(document.documentElement.scrollHeight);
      if (height === last) return;
      last = height;
      window.parent.postMessage({ loratrackHeight: height }, '*');
    }).observe(document.body);
  }
}

/** In an embed: the settings behind the numbers, and every notice (the form is not shown). */
function updateEmbedCaption(): void {
  if (!embed) return;
  $('#embed-settings').textContent = `Settings: ${caption(reportSettings)}.`;
  const lines = [...notices];
  if (!$('#rests-on').hidden) lines.push($('#rests-on-text').textContent ?? '');
  if ($('[data-panel="results"]').classList.contains('stale')) lines.push('The numbers shown are for the previous settings.');
  $('#embed-notices').hidden = lines.length === 0;
  $('#embed-notices').textContent = lines.join(' ');
}

// ---- controls <-> settings ---------------------------------------------------------------------
function field(name: string): HTMLInputElement | HTMLSelectElement {
  return form.elements.namedItem(name) as HTMLInputElement | HTMLSelectElement;
}

/** The form's min and max come from the core's table, as the URL's checks do; the distance
 * slider keeps its teaching range (0.1–10 km), and a link beyond it is said to be moved. */
for (const [key, l] of Object.entries(LIMITS)) {
  const el = field(key);
  if (el instanceof HTMLInputElement && el.type !== 'checkbox' && el.type !== 'range' && !l.values) {
    el.min = String(l.min);
    el.max = String(l.max);
  }
  if (el && l.help) el.title = `${l.help} Accepted: ${l.min}–${l.max}${l.unit ? ` ${l.unit}` : ''}.`;
}

// ---- gateways: rows of east, north and height, none for the one default gateway --------------
const gatewayRows = $('#gateway-rows');
function writeGateways(list: GatewaySite[]): void {
  const heading = document.createElement('div');
  heading.className = 'gateway-heading';
  heading.setAttribute('aria-hidden', 'true');
  heading.innerHTML = '<span></span><span>east (m)</span><span>north (m)</span><span>height (m)</span>';
  gatewayRows.replaceChildren(
    ...(list.length ? [heading] : []),
    ...list.map((g, i) => {
      const row = document.createElement('div');
      row.className = 'gateway-row';
      const input = (name: string, label: string, value: number | undefined, min: number, max: number) => {
        const el = document.createElement('input');
        el.type = 'number';
        el.name = `gateway-${name}`;
        el.dataset.gateway = name;
        el.min = String(min);
        el.max = String(max);
        el.step = '10';
        el.value = value === undefined ? '' : String(value);
        el.setAttribute('aria-label', `Gateway ${i + 1} ${label}`);
        // A blank height is the default antenna height (the core's table).
        if (name === 'height') el.placeholder = String(GATEWAY_LIMITS.height.default ?? '');
        return el;
      };
      const c = GATEWAY_LIMITS.coordinate;
      const h = GATEWAY_LIMITS.height;
      const remove = document.createElement('button');
      remove.type = 'button';
      remove.textContent = 'Remove';
      remove.setAttribute('aria-label', `Remove gateway ${i + 1}`);
      remove.addEventListener('click', () => {
        settings.gateways = settings.gateways.filter((_, k) => k !== i);
        writeGateways(settings.gateways);
        onChange();
      });
      const label = document.createElement('span');
      label.textContent = `${i + 1}`;
      label.className = 'gateway-number';
      row.append(label, input('east', 'east (m)', g.east, c.min, c.max), input('north', 'north (m)', g.north, c.min, c.max), input('height', 'height (m)', g.height, h.min, h.max), remove);
      return row;
    }),
  );
  $<HTMLButtonElement>('#add-gateway').disabled = list.length >= GATEWAY_LIMITS.count.max;
}

/** The gateways in the form, and why they cannot be simulated (null when they can). */
function readGateways(): { list: GatewaySite[]; why: string | null } {
  const list = [...gatewayRows.querySelectorAll<HTMLElement>('.gateway-row')].map((row) => {
    const v = (name: string) => row.querySelector<HTMLInputElement>(`[data-gateway="${name}"]`)!.value.trim();
    const g: GatewaySite = { east: v('east') === '' ? NaN : Number(v('east')), north: v('north') === '' ? NaN : Number(v('north')) };
    if (v('height') !== '') g.height = Number(v('height'));
    return g;
  });
  return { list, why: invalidGateways(list) };
}

$('#add-gateway').addEventListener('click', () => {
  // The first added gateway keeps the default one where it was, so adding never moves it.
  const list = settings.gateways.length ? [...settings.gateways] : [{ east: settings.distance, north: 0 }];
  list.push({ east: 0, north: 0 });
  settings.gateways = list;
  writeGateways(list);
  onChange();
});

function writeControls(s: Settings): void {
  writeGateways(s.gateways);
  for (const [key, value] of Object.entries(s)) {
    if (key === 'gateways') continue;
    const el = field(key);
    if (!el) continue;
    if (el instanceof HTMLInputElement && el.type === 'checkbox') el.checked = Boolean(value);
    else el.value = String(value);
  }
  showConditional();
}

/** The form's settings, and the fields whose values are not acceptable (marked next to them). */
function readControls(): { next: Settings; errors: string[] } {
  const s: Settings = { ...settings };
  const errors: string[] = [];
  const gateways = readGateways();
  if (gateways.why) errors.push(gateways.why);
  else s.gateways = gateways.list;
  for (const key of Object.keys(DEFAULTS) as (keyof Settings)[]) {
    if (key === 'gateways') continue;
    const el = field(key);
    if (!el) continue;
    if (el instanceof HTMLInputElement && el.type === 'checkbox') (s as unknown as Record<string, unknown>)[key] = el.checked;
    else if (isNumericKey(key)) {
      const v = el.value.trim() === '' ? NaN : Number(el.value);
      const why = invalid(key, v);
      markField(el, why);
      if (why) errors.push(why);
      else (s as unknown as Record<string, unknown>)[key] = v;
    } else (s as unknown as Record<string, unknown>)[key] = el.value;
  }
  return { next: s, errors };
}

/** Shows (or clears) a field's problem beside it, for eyes and for screen readers. */
function markField(el: HTMLInputElement | HTMLSelectElement, why: string | null): void {
  const id = `${el.id}-error`;
  let message = document.getElementById(id);
  if (!why) {
    el.removeAttribute('aria-invalid');
    message?.remove();
    el.setAttribute('aria-describedby', (el.getAttribute('aria-describedby') ?? '').replace(id, '').trim());
    if (!el.getAttribute('aria-describedby')) el.removeAttribute('aria-describedby');
    return;
  }
  el.setAttribute('aria-invalid', 'true');
  if (!message) {
    message = document.createElement('p');
    message.id = id;
    message.className = 'error field-error';
    el.insertAdjacentElement('afterend', message);
    el.setAttribute('aria-describedby', `${el.getAttribute('aria-describedby') ?? ''} ${id}`.trim());
  }
  message.textContent = why;
}

function showConditional(): void {
  for (const el of document.querySelectorAll<HTMLElement>('[data-when]')) el.hidden = el.dataset.when !== field('flight').value;
  for (const el of document.querySelectorAll<HTMLElement>('[data-when-sender]')) el.hidden = el.dataset.whenSender !== field('sender').value;
  const km = `${(Number(field('distance').value) / 1000).toFixed(1)} km`;
  $('#distance-value').textContent = km;
  // Screen readers hear the distance with its unit, not a bare number of metres.
  field('distance').setAttribute('aria-valuetext', `${km} to the gateway`);
  showAdrChoices();
}

/** Settings the core would refuse are not offered: ADR starts only at an EU868 data rate, so
 * with ADR on the other SF/bandwidth pairs are disabled, and with such a pair ADR is. */
function showAdrChoices(): void {
  const sf = Number(field('sf').value);
  const bw = Number(field('bw').value);
  const adrOn = field('adr').value !== 'off';
  const offer = (select: HTMLSelectElement, ok: (o: HTMLOptionElement) => boolean) => {
    let any = false;
    for (const o of select.options) {
      o.disabled = !ok(o);
      o.title = o.disabled ? ADR_START_REASON : '';
      any ||= o.disabled;
    }
    return any;
  };
  const adrBlocked = offer(field('adr') as HTMLSelectElement, (o) => o.value === 'off' || adrCanStart(sf, bw));
  // Both lists are updated (no short-circuit).
  const sfBlocked = offer(field('sf') as HTMLSelectElement, (o) => !adrOn || adrCanStart(Number(o.value), bw));
  const bwBlocked = offer(field('bw') as HTMLSelectElement, (o) => !adrOn || adrCanStart(sf, Number(o.value)));
  const rateBlocked = sfBlocked || bwBlocked;
  const note = $('#adr-note');
  note.hidden = !adrBlocked && !rateBlocked;
  note.textContent = adrBlocked ? `ADR is not offered at SF${sf} / ${bw} kHz. ${ADR_START_REASON}` : rateBlocked ? `With ADR on, only EU868 data rates can be chosen. ${ADR_START_REASON}` : '';
}

// ---- the workers: latest request wins; a long whole-set run is interrupted by the next change --
let pool: SimulationPool;
let nextId = 0;
let running: { id: number; long: boolean; started: number; settings: Settings } | undefined;
let queued: { request: SimulateRequest; settings: Settings } | undefined;
/** The next run draws a fresh seed (New seed), which then becomes the setting. */
let freshSeed = false;

function submit(): void {
  const sweep = [...DISTANCES.map((distance) => ({ distance })), ...SFS.map((sf) => ({ sf }))];
  const request: SimulateRequest = { id: ++nextId, params: toParams(settings, csv), sweep };
  if (freshSeed) request.params.seed = 'random';
  if (settings.flight === 'csv' && !csv) {
    status.textContent = 'Choose a CSV file to simulate it.';
    return;
  }
  if (running?.long) {
    // A whole-set run takes about a second: stop it rather than make the user wait for stale numbers.
    pool.restart();
    running = undefined;
  }
  if (running) {
    queued = { request, settings: { ...settings } };
    return;
  }
  send(request, { ...settings });
}

function send(request: SimulateRequest, made: Settings): void {
  const long = made.flight === 'all' || made.flight === 'csv' || made.seeds > 1;
  running = { id: request.id, long, started: performance.now(), settings: made };
  updateBusy();
  progress.hidden = !long;
  progress.value = 0;
  const repeats = made.seeds > 1 ? `, ${made.seeds} seeds each` : '';
  if (made.flight === 'all') status.textContent = `Simulating 30 flights (44 min of flight${repeats})… change any setting to interrupt.`;
  else if (made.seeds > 1) status.textContent = `Simulating ${made.seeds} seeds… change any setting to interrupt.`;
  else if (settings.flight === 'csv' && csv) status.textContent = `Simulating ${csv.name} (${(csv.text.length / 1024).toFixed(0)} KB)… change any setting to interrupt.`;
  pool.run(request, onResponse);
}

/** The results on show belong to other settings (or to none yet). */
function markStale(stale: boolean): void {
  $('[data-panel="results"]').classList.toggle('stale', stale);
  updateEmbedCaption();
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
  if ('sweep' in r) {
    renderSweep(r.sweep, { ...(running?.settings ?? reportSettings), seeds: 1 });
    running = undefined;
    progress.hidden = true;
    updateBusy();
    sendQueued();
    return;
  }
  if ('error' in r) {
    const failed = running.settings;
    running = undefined;
    progress.hidden = true;
    updateBusy();
    markStale(true);
    if (failed.flight === 'csv') {
      csvError.textContent = r.error;
      csvError.hidden = false;
      status.textContent = 'The CSV could not be simulated; the results below are for the previous settings.';
    } else {
      status.textContent = `These settings cannot be simulated: ${r.error}. Change a setting; the results below are for the previous settings.`;
    }
    sendQueued();
    return;
  }
  if (!('report' in r)) return;
  csvError.hidden = true;
  progress.hidden = true;
  report = r.report;
  reportSettings = { ...running.settings };
  if (freshSeed) {
    // The drawn seed becomes the setting: the link and the form repeat this run.
    freshSeed = false;
    settings.seed = report.config.seed;
    reportSettings.seed = report.config.seed;
    field('seed').value = String(settings.seed);
    history.replaceState(null, '', `?${pageQuery()}`);
  }
  // Typing may have moved the form on while this ran: the numbers say so.
  markStale(typing !== undefined || JSON.stringify(reportSettings) !== JSON.stringify(settings));
  const c = report.config;
  status.textContent = `${c.trajectory}: ${c.flights} flight${c.flights > 1 ? 's' : ''}, ${c.flightTime.toFixed(0)} s simulated in ${r.millis.toFixed(0)} ms. Gateway range (mean power = sensitivity ${c.sensitivityDbm.toFixed(1)} dBm): ${(c.rangeM / 1000).toFixed(2)} km.`;
  renderResults(report);
}

// ---- rendering ---------------------------------------------------------------------------------
const fmt = (v: number | null, digits = 2) => (v === null || v === undefined ? '—' : v.toFixed(digits));

/** The station whose p75 is lowest, when its 95 % interval lies below every other station's
 * (docs/reference.md §12); undefined when no difference is clear. */
function clearlyLowest(r: SimReport): ModelResult | undefined {
  const withData = r.results.filter((m) => m.error3d.count > 0);
  const lowest = withData.reduce<ModelResult | undefined>((a, m) => (!a || (m.error3d.p75 ?? Infinity) < (a.error3d.p75 ?? Infinity) ? m : a), undefined);
  if (r.results.length < 2 || withData.length < r.results.length || !lowest?.ci95) return undefined;
  const below = lowest.ci95.p75[1];
  return withData.every((m) => m === lowest || (m.ci95 !== null && below < m.ci95.p75[0])) ? lowest : undefined;
}

const names = (list: ModelResult[]) => list.map((m) => MODEL_LABELS[m.model]).join(list.length === 2 ? ' and ' : ', ');

/** How many packets and runs the numbers rest on, and whether the models differ clearly. */
function renderVerdict(r: SimReport, best: ModelResult | undefined): void {
  const few = r.results.filter((m) => m.packetsReceived < 10);
  $('#rests-on').hidden = few.length === 0;
  $('#use-whole-set').hidden = reportSettings.flight === 'all';
  if (few.length) {
    $('#rests-on-text').textContent = `Too few packets to compare: ${names(few)} ${few.length === 1 ? 'rests' : 'rest'} on ${few.map((m) => m.packetsReceived).join(few.length === 2 ? ' and ' : ', ')} received packet${few.every((m) => m.packetsReceived === 1) ? '' : 's'} (under 10).`;
  }
  const text = $('#verdict-text');
  const repeat = $<HTMLButtonElement>('#repeat-seeds');
  const runs = r.results.find((m) => m.ci95)?.ci95?.runs;
  repeat.hidden = reportSettings.seeds >= 10 || r.results.length < 2;
  if (r.results.length < 2) text.textContent = runs ? `p75's 95 % interval rests on ${runs} runs (flights × seeds).` : '';
  else if (best) text.textContent = `${MODEL_LABELS[best.model]} has the lowest p75, clearly: its 95 % interval lies below every other model's (${runs} runs).`;
  else if (!runs) text.textContent = 'One flight with one seed cannot tell whether these differences are larger than chance: no model is named best.';
  else text.textContent = `No clear difference in p75: the 95 % intervals overlap (${runs} runs). More seeds or flights narrow them.`;
}

function renderResults(r: SimReport): void {
  const best = clearlyLowest(r);
  renderVerdict(r, best);
  updateEmbedCaption();
  const rows = r.results
    .map((m) => {
      const ratio = m.packetsSent ? m.packetsReceived / m.packetsSent : 0;
      const isBest = m === best;
      return `<tr class="${isBest ? 'best' : ''}" data-model="${m.model}">
        <th scope="row">${MODEL_LABELS[m.model]}${isBest ? ' <span class="badge">lowest p75</span>' : ''}</th>
        <td>${m.payloadBytes} B</td><td data-field="toa">${(m.timeOnAir * 1e3).toFixed(1)} ms</td><td data-field="interval">${m.interval.toFixed(2)} s</td>
        <td data-field="packets" title="${m.airtime.toFixed(1)} s on air">${m.packetsReceived} / ${m.packetsSent}${delta(m, 'packets')}</td><td data-field="delivery">${(ratio * 100).toFixed(0)} %</td>
        <td data-field="mean">${fmt(m.error3d.mean)}${delta(m, 'mean')}</td><td data-field="p50">${fmt(m.error3d.p50)}${delta(m, 'p50')}</td><td data-field="p75">${fmt(m.error3d.p75)}${interval(m)}${delta(m, 'p75')}</td>
        <td data-field="p95">${fmt(m.error3d.p95)}${delta(m, 'p95')}</td><td data-field="max">${fmt(m.error3d.max, 1)}${delta(m, 'max')}</td>
        <td data-field="coverage" title="${probabilities(m)}">${m.coverage95 === null ? '—' : `${(m.coverage95 * 100).toFixed(0)} %`}</td>
        <td data-field="energy" title="${m.energy.chargePerHour.toFixed(3)} mAh per hour of tracking">${m.energy.chargePerUplink.toFixed(2)}</td></tr>`;
    })
    .join('');
  $('#results-table').innerHTML = `<div class="table-wrap" tabindex="0" role="region" aria-label="Results table"><table class="results">
    <caption>3D tracking error (m) at the station, every ${r.config.step ?? 0.1} s after the first packet, over ${r.config.flights} flight${r.config.flights === 1 ? '' : 's'} × ${r.config.seeds} seed${r.config.seeds === 1 ? '' : 's'}; overhead ${r.config.overhead} B; ${r.config.prediction} prediction</caption>
    <thead><tr><th scope="col">model</th><th scope="col" title="Bytes of state in each packet (before the LoRaWAN overhead)">payload</th><th scope="col" title="How long one packet occupies the channel (Semtech's formula)">time on air</th><th scope="col" title="Time between packets: time on air divided by the 1 % duty cycle">interval</th>
    <th scope="col" title="Packets the gateway received out of those sent, over all flights">received / sent</th><th scope="col" title="Share of packets received">delivery</th><th scope="col" title="Mean 3D distance between the station's estimate and the truth">mean</th><th scope="col" title="Half the time the error is below this">median</th><th scope="col" title="75th percentile: 3 times in 4 the error is below this (the paper's headline statistic)">p75</th><th scope="col" title="95th percentile: the bad moments, typically long gaps">p95</th><th scope="col">max</th>
    <th scope="col" title="Share of the time the true position lay inside the station's own 95 % ellipsoid: about 95 % when the station's uncertainty is honest, more when it is too cautious, less when it is overconfident">in 95 % bound</th>
    <th scope="col" title="The drone radio's charge per uplink with its receive windows (Semtech SX1276 currents), mC; the tooltip gives mAh per hour">mC / uplink</th></tr></thead>
    <tbody>${rows}</tbody></table></div>`;
  $('#ttn').innerHTML = ttnNote(r);
  // One gateway and no downlink: the table's delivery column already says it all. Each station's
  // run is its own (the drone sends that station's payload): the note tells the first station's.
  const first = r.results[0];
  const networkShown = first.gateways.length > 1 || first.gateways.some((g) => g.downlinksSent + g.downlinksDropped > 0);
  $('#network-note').hidden = !networkShown;
  $('#network-note').textContent = networkShown ? networkNote(first, r.results.length > 1) : '';

  renderRateUse(r);
  const width = (id: string) => Math.max(300, $(id).clientWidth || 600);
  place('error', errorOverTimeChart(r, width('#chart-error')), reportSettings);
  const axisRows: BoxRow[] = r.results.flatMap((m) => [
    { group: 'x', model: m.model, box: m.boxplot.errorX },
    { group: 'y', model: m.model, box: m.boxplot.errorY },
    { group: 'z', model: m.model, box: m.boxplot.errorZ },
  ]);
  place('axes', boxplotChart(axisRows, { groupLabel: 'axis', width: width('#chart-axes') }), reportSettings);
  if (!$('[data-panel="trajectory"]').hidden) void render3d(r);
}

/** p75's 95 % interval, when the run has one. */
function interval(m: ModelResult): string {
  const c = m.ci95;
  return c ? ` <span class="ci" data-field="p75-interval" title="95 % interval over ${c.runs} runs (flights × seeds)">(${fmt(c.p75[0])}–${fmt(c.p75[1])})</span>` : '';
}

/** The pinned baseline, if any, and what it was. */
let baseline: { report: SimReport; settings: Settings } | undefined;

/** The page's URL query: the settings, the pinned baseline's settings, and the embed choice. */
function pageQuery(): string {
  const extra: Record<string, string> = embed ? { embed: '1', panels } : {};
  if (document.body.classList.contains('present')) extra.present = '1';
  if (baseline) extra.baseline = toQuery(baseline.settings);
  return toQuery(settings, extra);
}

/** The change of statistic `key` against the baseline's same station, as a small signed number. */
function delta(m: ModelResult, key: 'mean' | 'p50' | 'p75' | 'p95' | 'max' | 'packets'): string {
  const base = baseline?.report.results.find((x) => x.model === m.model);
  if (!base) return '';
  const [b, v] = key === 'packets' ? [base.packetsReceived, m.packetsReceived] : [base.error3d[key], m.error3d[key]];
  if (b === null || v === null) return '';
  const d = v - b;
  // Fewer metres of error is better; more packets received is better. The arrow and the
  // (screen-reader) word carry the direction without colour.
  const digits = key === 'packets' ? 0 : 2;
  const same = Math.abs(d) < (key === 'packets' ? 0.5 : 0.005);
  const better = key === 'packets' ? d > 0 : d < 0;
  const cls = same ? 'same' : better ? 'better' : 'worse';
  const arrow = same ? '=' : d > 0 ? '▲' : '▼';
  const word = same ? 'unchanged' : better ? 'better' : 'worse';
  return ` <span class="delta ${cls}" data-delta="${key}" title="against the baseline (${b.toFixed(digits)}${key === 'packets' ? ' packets' : ' m'})">${arrow}\u2009${d >= 0 ? '+' : '−'}${Math.abs(d).toFixed(digits)}<span class="visually-hidden"> (${word} than the baseline)</span></span>`;
}

function describe(s: Settings): string {
  return `SF${s.sf}, ${s.bw} kHz, ${(s.distance / 1000).toFixed(1)} km, ${s.prediction} prediction, ${s.sender} sending${s.adr === 'off' ? '' : `, ${s.adr} ADR`}`;
}

function renderBaseline(): void {
  const note = $('#baseline-note');
  note.hidden = !baseline;
  $('#pin').textContent = baseline ? 'Clear baseline' : 'Pin as baseline';
  if (baseline) note.textContent = `Differences are against the pinned baseline: ${caption(baseline.settings)}. ▼ lower, ▲ higher; lower error and more packets received are better (green).`;
}

/** With ADR: how many packets each model sent at each data rate. */
function renderRateUse(r: SimReport): void {
  const note = $('#rate-use');
  note.hidden = r.config.adr === 'off';
  if (note.hidden) return;
  const rate = (u: ModelResult['dataRateUse'][number]) => `${u.dr === null ? `SF${u.sf}/${u.bw}` : `DR${u.dr} (SF${u.sf}/${u.bw})`} ${u.received}/${u.packets}`;
  const lines = r.results.map((m) => `${MODEL_LABELS[m.model]}: ${[...m.dataRateUse].reverse().map(rate).join(', ')}`);
  note.textContent = `Packets received / sent per data rate (${r.config.adr === 'lorawan' ? 'LoRaWAN' : 'tracking-aware'} ADR, interval and time on air above are the starting rate's) — ${lines.join('; ')}.`;
}

/** What each gateway heard, and the copies the network server removed. */
function networkNote(m: ModelResult, named: boolean): string {
  const { packetsSent: sent, packetsReceived: received, duplicates, gateways } = m;
  const each = gateways
    .map((g, i) => `gateway ${i + 1} at (${(g.east / 1000).toFixed(1)}, ${(g.north / 1000).toFixed(1)}) km heard ${g.heard}${gateways.length > 1 ? ` (${g.onlyHeard} only it)` : ''}${g.downlinksSent + g.downlinksDropped ? `, ${g.downlinksSent} downlinks sent, ${g.downlinksDropped} dropped by its duty cycle` : ''}`)
    .join('; ');
  return `Network${named ? ` (${MODEL_LABELS[m.model]}'s packets)` : ''}: ${received} of ${sent} packets delivered (${sent ? ((100 * received) / sent).toFixed(0) : 0} %)${gateways.length > 1 ? `, ${duplicates} duplicate copies removed` : ''} — ${each}.`;
}

/** The IMM's mean member probabilities, as a tooltip. */
function probabilities(m: ModelResult): string {
  const p = m.modelProbability;
  if (!p) return "Share of the time the truth lay inside the station's 95 % ellipsoid";
  return `Mean IMM probability: DR ${fmt(p.dr ?? null)}, CTRA+ ${fmt(p['ctra-plus'] ?? null)}, 3D-CTRA ${fmt(p['3d-ctra'] ?? null)}`;
}

/** The Things Network's fair-use limit, shown for information (the simulation uses the duty cycle). */
function ttnNote(r: SimReport): string {
  const m = r.results[r.results.length - 1];
  const a = timeOnAir({ sf: settings.sf, bw: settings.bw, payload: m.payloadBytes, overhead: overheadBytes(settings), cr: settings.cr });
  const perDay = 86400 / a.minInterval;
  return `<p class="note" id="ttn-note">On The Things Network, fair use allows 30 s of airtime a day: ${a.ttnPacketsPerDay} packets of ${m.payloadBytes} B
    (${MODEL_LABELS[m.model]}) at this setting, one every ${(86400 / Math.max(1, a.ttnPacketsPerDay)).toFixed(0)} s — ${(perDay / Math.max(1, a.ttnPacketsPerDay)).toFixed(0)}× fewer than the duty cycle allows. Not applied here.</p>`;
}

/** three.js is most of the page's JavaScript: load it only once there is a trajectory to draw. */
/** Drawings still under way (the 3D view loads three.js on first use) and swarm runs. */
let drawing = 0;
let swarming = false;

/** `<body data-busy>` while anything visible is still being computed or drawn (tests wait on it). */
function updateBusy(): void {
  if (running || drawing > 0 || swarming) document.body.dataset.busy = '';
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

async function draw3d(r: SimReport): Promise<void> {
  if (!trajectory3d) {
    const { createTrajectory3d } = await import('./charts/trajectory3d');
    trajectory3d ??= createTrajectory3d($('#chart-trajectory'));
  }
  if (r !== report) return;
  const drawn = trajectory3d.update(r);
  if (!drawn) return;
  // The legend lists what is drawn: the truth, each station, the gateways, and the grid's scale.
  const swatch = (color: string) => `<span class="swatch" style="background:${color}"></span>`;
  const stations = (r.series?.models ?? []).map((m) => `${swatch(MODEL_COLORS[m.model])}${MODEL_LABELS[m.model]}`).join(', ');
  const gateways = r.series?.gateways.length ?? 1;
  const far = drawn.farGateways ? `; orange cone${drawn.farGateways > 1 ? 's' : ''} at the edge: ${drawn.farGateways === gateways ? '' : 'the other '}gateway${drawn.farGateways > 1 ? 's' : ''} beyond the view, with ${drawn.farGateways > 1 ? 'their' : 'its'} distance` : '';
  const near = gateways - drawn.farGateways;
  $('#trajectory-legend').innerHTML = `${swatch(TRUTH_COLOR)}true flight, ${stations}${near ? `; grey cone${near > 1 ? 's' : ''}: the gateway${near > 1 ? 's' : ''}` : ''}${far}. Grid squares ${drawn.gridStep >= 10 ? drawn.gridStep.toFixed(0) : drawn.gridStep.toFixed(1)} m.`;
}

function renderSfs(sweep: { sf: number; report: SimReport }[], made: Settings): void {
  const rows = sweep.flatMap(({ sf, report: r }) => r.results.map((m) => ({ sf, model: m.model, p75: m.error3d.p75, received: m.packetsReceived })));
  place('sf', p75BySfChart(rows, { bw: made.bw, distance: made.distance, width: Math.max(300, $('#chart-sf').clientWidth || 600) }), made);
}

/** The last sweep and swarms drawn, to draw again at another size (presentation mode). */
let lastSweep: Extract<Response, { sweep: unknown }>['sweep'] | undefined;
let lastSwarm: (() => void) | undefined;

function renderSweep(sweep: Extract<Response, { sweep: unknown }>['sweep'], made: Settings): void {
  lastSweep = sweep;
  renderDistance(sweep.flatMap(({ point, report: rep }) => ('distance' in point ? [{ distance: point.distance, report: rep }] : [])), made);
  renderSfs(sweep.flatMap(({ point, report: rep }) => ('sf' in point ? [{ sf: point.sf, report: rep }] : [])), made);
}

function renderDistance(sweep: { distance: number; report: SimReport }[], made: Settings): void {
  const rows: BoxRow[] = sweep.flatMap(({ distance, report: r }) => r.results.map((m) => ({ group: `${distance / 1000} km`, model: m.model, box: m.boxplot.error3d })));
  place('distance', boxplotChart(rows, { log: true, groupLabel: `gateway distance (SF${settings.sf}, ${settings.bw} kHz)`, width: Math.max(300, $('#chart-distance').clientWidth || 600) }), made);
}

function renderLink(): void {
  const r = linkBudget({ bw: settings.bw, txPower: settings.txPower, pathLossExponent: settings.pathLossExponent, shadowing: settings.shadowing });
  // Each gateway's distance from the flight's start (the default one: the distance setting).
  const distances = settings.gateways.length ? settings.gateways.map((g) => Math.hypot(g.east, g.north)) : [settings.distance];
  place('link', linkBudgetCharts(r, { width: Math.max(300, $('#chart-link').clientWidth || 600), distances, sf: settings.sf }));
}

function renderAirtime(): void {
  const opts = { overhead: overheadBytes(settings), cr: settings.cr, sf: settings.sf, bw: settings.bw };
  $('#airtime-table').replaceChildren(airtimeTable(opts));
  place('airtime', airtimeVsPayloadChart({ ...opts, width: Math.max(300, $('#chart-airtime').clientWidth || 600) }));
}

/** One line for a download's caption: the settings, flight, seed and version behind a chart. */
function caption(s: Settings, extra = ''): string {
  const flight = s.flight === 'all' ? 'whole synthetic set' : s.flight === 'canberra' ? 'real flight (Canberra)' : s.flight === 'csv' ? (csv?.name ?? 'uploaded CSV') : `synthetic flight ${s.flightNumber}`;
  const seeds = s.seeds > 1 ? ` to ${s.seed + s.seeds - 1}` : '';
  return `${describe(s)}, ${s.lorawan ? '13 B' : 'no'} LoRaWAN overhead; ${flight}; seed ${s.seed}${seeds}${extra}; loratrack ${__LORATRACK_VERSION__}`;
}

function place(name: string, chart: Element, made: Settings = settings, extra = ''): void {
  charts[name] = { chart, caption: caption(made, extra) };
  // Plot labels its mark groups; an unlabelled role-less <g> may not carry aria-label, so the
  // chart is one image named by its panel's title instead.
  for (const g of chart.querySelectorAll('g[aria-label]')) g.removeAttribute('aria-label');
  const main = chartSvg(chart);
  main?.setAttribute('role', 'img');
  main?.setAttribute('aria-label', document.getElementById(`${name}-title`)?.textContent ?? name);
  $(`#chart-${name}`).replaceChildren(chart);
}

// ---- events ------------------------------------------------------------------------------------
function onChange(): void {
  const { next, errors } = readControls();
  showConditional();
  if (errors.length) {
    // Nothing runs on a value the core would refuse; the numbers on show are marked as old.
    markStale(true);
    status.textContent = `Not simulated: ${errors.join(' ')} The results below are for the previous settings.`;
    return;
  }
  settings = next;
  history.replaceState(null, '', `?${pageQuery()}`);
  renderAirtime();
  renderLink();
  submit();
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
  if ((e.target as HTMLElement).id === 'csv') return;
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

$<HTMLInputElement>('#csv').addEventListener('change', async (e) => {
  const file = (e.target as HTMLInputElement).files?.[0];
  if (!file) return;
  if (file.size > MAX_CSV_BYTES) {
    // The core refuses more than 64 MiB too; say so before reading the file into memory.
    csvError.textContent = `${file.name} is ${(file.size / 2 ** 20).toFixed(1)} MiB; at most 64 MiB is read.`;
    csvError.hidden = false;
    return;
  }
  csv = { text: await file.text(), name: file.name };
  csvError.hidden = true;
  onChange();
});

$('#copy-link').addEventListener('click', async () => {
  const url = location.href;
  // An uploaded file stays on this computer: say what the link will open instead.
  const caveat = settings.flight === 'csv' ? ' It opens one synthetic flight: an uploaded CSV never leaves this computer, so a link cannot carry it.' : '';
  try {
    await navigator.clipboard.writeText(url);
    $('#copy-status').textContent = `Link copied.${caveat}`;
  } catch {
    $('#copy-status').textContent = `Copy this link: ${url}${caveat}`;
  }
});

$('#reset').addEventListener('click', () => {
  settings = { ...DEFAULTS };
  writeControls(settings);
  onChange();
});

$('#reset-view').addEventListener('click', () => trajectory3d?.resetView());

// ---- the swarm panel: its own worker, so a swarm never holds up the single-drone results ----
let swarmWorker: Worker | undefined;
$('#run-swarm').addEventListener('click', () => {
  swarmWorker?.terminate();
  swarmWorker = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
  const n = Number($<HTMLSelectElement>('#swarmDrones').value);
  const sizes = [...new Set([2, Math.round(n / 8), Math.round(n / 4), Math.round(n / 2), n])].filter((k) => k >= 1);
  // The swarm takes every setting of the single drone; its drones chain synthetic flights around
  // the centre, and run one station (a list of models runs 3D-CTRA, as `all` does).
  const { synthetic: _s, sample: _m, trajectory: _t, trajectoryName: _n, ...shared } = toParams(settings, csv);
  const params: SwarmParams = {
    ...shared,
    model: stationsOf(settings.model).length === 1 ? settings.model : 'all',
    duration: 120,
    channels: Number($<HTMLSelectElement>('#swarmChannels').value),
    sfPlan: $<HTMLSelectElement>('#swarmPlan').value as 'fixed' | 'spread',
  };
  const made = { ...settings };
  const bar = $<HTMLProgressElement>('#swarm-progress');
  bar.hidden = false;
  bar.value = 0;
  $('#swarm-status').textContent = `Simulating swarms of ${sizes.join(', ')} drones…`;
  swarming = true;
  updateBusy();
  swarmWorker.onmessage = (e: MessageEvent<Response>) => {
    const r = e.data;
    if ('progress' in r) {
      bar.value = r.progress;
      return;
    }
    bar.hidden = true;
    swarming = false;
    updateBusy();
    if ('error' in r) {
      $('#swarm-status').textContent = r.error;
      return;
    }
    if ('swarms' in r) {
      const rates = r.swarms.map((w) => `${w.config.drones} drones ${(100 * w.collisionRate).toFixed(1)} %`).join(', ');
      $('#swarm-status').textContent = `${sizes.length} swarms simulated in ${(r.millis / 1000).toFixed(1)} s. Packets collided: ${rates}.`;
      const swarms = r.swarms;
      lastSwarm = () => place('swarm', swarmCharts(swarms, Math.max(300, $('#chart-swarm').clientWidth || 600)), made, `; swarms of ${sizes.join(', ')} drones, ${params.channels} channel${params.channels === 1 ? '' : 's'}, ${params.sfPlan} SFs, ${params.duration} s each`);
      lastSwarm();
    }
  };
  swarmWorker.postMessage({ id: 1, swarm: { sizes, params } } satisfies Request);
});

$('#pin').addEventListener('click', () => {
  baseline = baseline || !report ? undefined : { report, settings: { ...reportSettings } };
  renderBaseline();
  history.replaceState(null, '', `?${pageQuery()}`);
  if (report) renderResults(report);
});

$('#repeat-seeds').addEventListener('click', () => {
  field('seeds').value = '10';
  onChange();
});

$('#use-whole-set').addEventListener('click', () => {
  field('flight').value = 'all';
  onChange();
});

$('#new-seed').addEventListener('click', () => {
  freshSeed = true;
  submit();
});

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

$('#download-csv').addEventListener('click', () => report && downloadErrorCsv(report));
$('#download-json').addEventListener('click', () => report && downloadJson(report, reportSettings));
$('#download-results-csv').addEventListener('click', () => report && downloadResultsCsv(report));
$('#download-airtime-csv').addEventListener('click', () => {
  const table = document.querySelector<HTMLTableElement>('#airtime-table table');
  if (table) downloadTableCsv(table, 'loratrack-time-on-air');
});
for (const button of document.querySelectorAll<HTMLButtonElement>('[data-download]')) {
  const name = button.dataset.download!;
  const title = document.getElementById(`${name}-title`)?.textContent ?? name;
  button.setAttribute('aria-label', `Download the ${title.replace(/:.*/, '').toLowerCase()} chart as ${button.dataset.format!.toUpperCase()}`);
  button.addEventListener('click', () => {
    const slide = (c: string) => ({ title, caption: c });
    if (name === 'trajectory') {
      const shot = trajectory3d?.snapshot(MIN_PNG_WIDTH);
      if (!shot) return downloadWhy(button, 'Nothing to save: the 3D view needs WebGL, which this browser does not offer.');
      const legend = [{ color: TRUTH_COLOR, label: 'true flight' }, ...(report?.series?.models ?? []).map((m) => ({ color: MODEL_COLORS[m.model], label: MODEL_LABELS[m.model] }))];
      downloadPicturePng(shot.canvas, shot.scale, `loratrack-${name}`, slide(caption(reportSettings)), legend);
      return downloadWhy(button, '');
    }
    const entry = charts[name];
    const saved = entry && (button.dataset.format === 'svg' ? downloadSvg : downloadPng)(entry.chart, `loratrack-${name}`, slide(entry.caption));
    downloadWhy(button, saved ? '' : name === 'swarm' && !entry ? 'Nothing to save yet: run a swarm first.' : 'Nothing to save: this chart has no data at these settings (no packet arrives).');
  });
}

// ---- the Embed dialog: pick panels, copy a snippet that sizes its frame ------------------------
const embedDialog = $<HTMLDialogElement>('#embed-dialog');
for (const name of PANELS) {
  const label = document.createElement('label');
  const box = document.createElement('input');
  box.type = 'checkbox';
  box.value = name;
  box.checked = ['results', 'error'].includes(name);
  label.append(box, ` ${name}`);
  $('#embed-panels').append(label);
}

function embedSnippet(): string {
  const chosen = [...document.querySelectorAll<HTMLInputElement>('#embed-panels input:checked')].map((b) => b.value);
  const url = new URL(location.href);
  url.search = `?${toQuery(settings, { embed: '1', panels: (chosen.length ? chosen : ['results']).join(',') })}`;
  return `<iframe id="loratrack" src="${url.toString().replace(/&/g, '&amp;')}" title="loratrack: LoRa tracking playground (${describe(settings)})" style="width: 100%; border: 0" height="600" loading="lazy"></iframe>
<script>
  // The frame posts its content height; grow it to fit.
  addEventListener('message', (e) => {
    const frame = document.getElementById('loratrack');
    if (e.source === frame.contentWindow && e.data && e.data.loratrackHeight) frame.style.height = e.data.loratrackHeight + 'px';
  });
</script>`;
}

$('#embed-open').addEventListener('click', () => {
  $<HTMLTextAreaElement>('#embed-snippet').value = embedSnippet();
  $('#embed-status').textContent = '';
  embedDialog.showModal();
});
$('#embed-panels').addEventListener('change', () => ($<HTMLTextAreaElement>('#embed-snippet').value = embedSnippet()));
$('#embed-close').addEventListener('click', () => embedDialog.close());
$('#embed-copy').addEventListener('click', async () => {
  const snippet = $<HTMLTextAreaElement>('#embed-snippet').value;
  try {
    await navigator.clipboard.writeText(snippet);
    $('#embed-status').textContent = 'Snippet copied.';
  } catch {
    $<HTMLTextAreaElement>('#embed-snippet').select();
    $('#embed-status').textContent = 'Select the snippet and copy it (the clipboard is not available here).';
  }
});

// ---- presentation mode: large type, one panel per screen, arrow keys step ---------------------
function setPresent(on: boolean): void {
  document.documentElement.classList.toggle('present', on);
  document.body.classList.toggle('present', on);
  $('#present-toggle').setAttribute('aria-pressed', String(on));
  history.replaceState(null, '', `?${pageQuery()}`);
  // Charts are drawn at their box's width with text in px: draw them again at the new size.
  renderAirtime();
  renderLink();
  if (report) renderResults(report);
  if (lastSweep) renderSweep(lastSweep, { ...reportSettings, seeds: 1 });
  lastSwarm?.();
}

$('#present-toggle').addEventListener('click', () => setPresent(!document.body.classList.contains('present')));
document.addEventListener('keydown', (e) => {
  const target = e.target as HTMLElement;
  if (e.ctrlKey || e.metaKey || e.altKey || target.closest('input, select, textarea, canvas, dialog, [contenteditable]')) return;
  if (e.key === 'p' || e.key === 'P') {
    e.preventDefault();
    setPresent(!document.body.classList.contains('present'));
    return;
  }
  const step = { ArrowDown: 1, ArrowRight: 1, PageDown: 1, ArrowUp: -1, ArrowLeft: -1, PageUp: -1 }[e.key];
  if (!step || !document.body.classList.contains('present')) return;
  e.preventDefault();
  const shown = [...document.querySelectorAll<HTMLElement>('.panel')].filter((p) => p.offsetParent !== null).sort((a, b) => a.getBoundingClientRect().top - b.getBoundingClientRect().top);
  const next = step > 0 ? shown.find((p) => p.getBoundingClientRect().top > 5) : [...shown].reverse().find((p) => p.getBoundingClientRect().top < -5);
  next?.scrollIntoView({ block: 'start' });
});

// ---- lessons: guided scenarios, each a URL state with what to notice ---------------------------
for (const l of LESSONS) {
  const item = document.createElement('li');
  const link = document.createElement('a');
  link.href = `?${lessonQuery(l)}`;
  link.textContent = l.title;
  item.append(link);
  $('#lesson-list').append(item);
}
const lesson = embed ? undefined : LESSONS.find((l) => l.id === query.get('lesson'));
if (lesson) {
  $('#lesson').hidden = false;
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

// ---- start -------------------------------------------------------------------------------------
writeControls(settings);
// The form is the truth: a value the slider cannot show (a distance between its steps) is what it shows.
const shown = readControls().next;
if (shown.distance !== settings.distance) {
  notices.push(`The link's distance ${settings.distance} m is shown and simulated as ${shown.distance} m, the slider's nearest step.`);
  settings = shown;
}
/** Adds a sentence to the notices at the top of the settings (and of an embed). */
function showNotice(text: string): void {
  if (text) notices.push(text);
  const box = $('#notice');
  box.textContent = notices.join(' ');
  box.hidden = notices.length === 0;
  updateEmbedCaption();
}
showNotice('');
pool = new SimulationPool();
// A shared link may carry a pinned baseline: its settings are simulated again (the same seed
// gives the same numbers) in a worker of its own, then pinned.
const pinned = query.get('baseline');
if (pinned !== null) {
  const b = fromQuery(`?${pinned}`);
  if (b.problems.length) showNotice(`The link's baseline: ${b.problems.join(' ')}`);
  const w = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
  drawing++;
  updateBusy();
  w.onmessage = (e: MessageEvent<Response>) => {
    if (!('report' in e.data) && !('error' in e.data)) return;
    if ('report' in e.data) baseline = { report: e.data.report, settings: b.settings };
    else showNotice(`The link's baseline could not be simulated: ${e.data.error}.`);
    w.terminate();
    drawing--;
    renderBaseline();
    if (report) renderResults(report);
    updateBusy();
  };
  w.postMessage({ id: 1, params: toParams(b.settings) } satisfies Request);
}
if (query.get('present') === '1') {
  document.documentElement.classList.add('present');
  document.body.classList.add('present');
  $('#present-toggle').setAttribute('aria-pressed', 'true');
}
await load();
renderAirtime();
renderLink();
submit();
if (lesson?.swarm) {
  // The lesson's swarm runs as if its button were pressed with these choices.
  $<HTMLSelectElement>('#swarmDrones').value = String(lesson.swarm.drones);
  $<HTMLSelectElement>('#swarmChannels').value = String(lesson.swarm.channels);
  $<HTMLSelectElement>('#swarmPlan').value = lesson.swarm.plan;
  $('#run-swarm').click();
}
