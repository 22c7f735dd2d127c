// The results panel: the table of statistics with their intervals, the verdict on which station
// is best (only when the same runs, resampled together, say so), the baseline's differences, and
// the notes under the table. Reads the page's state from the store.
import { deliverySpread, MODEL_LABELS, timeOnAir, type ModelResult, type RunConfig, type SimReport } from './loratrack';
import { $, fitOnWidth, linkDocs, tighten } from './dom';
import { adrFrom, adrName, advancedChanged, beyondRange, caption, counted, downlinkCounts, downlinksWanted, fmt, listed, names, percent, planLimit, prediction, sending, sendsAsPublished, trackedPercent } from './format';
import { DEFAULTS, overheadBytes, plan, sendingLimit } from './state';
import { store } from './store';

/** The results table, the verdict on it, and the notes under it (network, data rates, TTN). */
export function renderTable(r: SimReport): void {
  renderBaseline(r);
  const best = clearlyLowest(r);
  renderVerdict(r, best);
  renderUntracked(r);
  renderSilenceNote(r);
  renderSaturatedNote(r);
  renderSpreadNote(r);
  // What limits sending, where it is not the paper's 1 % duty cycle: the intervals rest on it.
  const limit = planLimit(r.config);
  // The tracking error first, then what the link spent on it: on a phone the table scrolls
  // sideways, and the headline p75 must be within the first screen, not after the link's columns
  // (which the time-on-air and link panels show too); a little wider, the link's half goes under
  // it (fitTable).
  shown = {
    what: `3D tracking error (m) at the station, every ${r.config.step ?? 0.1} s after the first packet, over ${r.config.flights} flight${r.config.flights === 1 ? '' : 's'} × ${r.config.seeds} seed${r.config.seeds === 1 ? '' : 's'}`,
    setup: `overhead ${r.config.overhead} B; ${limit ? `${limit}; ` : ''}${prediction(r.config)}${sendsAsPublished(r.config) ? '' : `; ${sending(r.config)}`}${adrFrom(r.config)}${advancedSetup(r.config)}`,
    packetsHead: `<th scope="col" title="Share of packets received">delivery</th><th scope="col" title="Packets the gateway received out of those sent, over all flights">received / sent</th>`,
    framesHead: `<th scope="col" title="${intervalRule(r.config)}">interval</th><th scope="col" title="How long one packet occupies the channel (Semtech's formula)">time on air</th><th scope="col" title="Bytes of state in each packet (before the LoRaWAN overhead)">payload</th><th scope="col" title="The drone radio's charge per uplink with its receive windows (Semtech SX1276 currents), mC; the tooltip gives mAh per hour">mC / uplink</th>`,
    rows: r.results.map((m) => {
      // A drone that sent nothing (TTN's fair use at SF12 in a short flight) has no delivery
      // share and no charge per uplink (the core's null): a dash, not "0 %" (every packet lost)
      // or "0.00" (free).
      return {
        model: m.model,
        best: m === best,
        errors: `<td data-field="mean">${fmt(m.error3d.mean)}${delta(m, 'mean')}</td><td data-field="p50">${fmt(m.error3d.p50)}${delta(m, 'p50')}</td><td data-field="p75">${fmt(m.error3d.p75)}${interval(m)}${delta(m, 'p75')}</td>
        <td data-field="p95">${fmt(m.error3d.p95)}${delta(m, 'p95')}</td><td data-field="max">${fmt(m.error3d.max, 1)}${delta(m, 'max')}</td>
        <td data-field="coverage" title="${probabilities(m)}">${m.coverage95 === null ? '—' : `${(m.coverage95 * 100).toFixed(0)} %`}</td>`,
        packets: `<td data-field="delivery">${m.deliveryRatio === null ? '—' : `${(m.deliveryRatio * 100).toFixed(0)} %`}</td><td data-field="packets" title="${m.airtime.toFixed(1)} s on air">${m.packetsReceived} / ${m.packetsSent}${delta(m, 'packets')}</td>`,
        frames: `${frameCells(m)}<td data-field="payload"${leanTitle(m)}>${m.payloadBytes} B${lean(m.leanPackets > 0 && `${m.leanPackets} lean`)}</td>
        <td data-field="energy" title="${m.energy.chargePerUplink === null ? 'No uplink was sent' : `${fmt(m.energy.chargePerHour, 3)} mAh per hour of tracking`}">${fmt(m.energy.chargePerUplink)}</td>`,
      };
    }),
  };
  fitTable();
  $('#ttn').innerHTML = ttnNote(r);
  // One gateway and no downlink: the table's delivery column already says it all. Each station's
  // run is its own (the drone sends that station's payload): the note tells the first station's.
  const first = r.results[0];
  const networkShown = first.gateways.length > 1 || first.gateways.some((g) => downlinksWanted(g) > 0);
  $('#network-note').hidden = !networkShown;
  $('#network-note').textContent = networkShown ? networkNote(first, r.results.length > 1) : '';

  renderRateUse(r);
}

/** The advanced settings the run changed from their defaults, as the caption's last clause
 * (`; Tx power 10 dBm, shadowing sigma 6 dB`): where the form sits under the results (1024×768,
 * a phone) the caption is the one place beside the numbers that says what they rest on. */
function advancedSetup(config: RunConfig): string {
  const changed = advancedChanged(config);
  return changed.length ? `; ${changed.join(', ')}` : '';
}

/** The results on show, as the table's pieces: laid out as one table, two or three by `fitTable`. */
let shown: {
  /** What the numbers are (the error, how often it was taken, over which runs). */
  what: string;
  /** The settings the table's caption names beside them; a slide's caption names every setting. */
  setup: string;
  /** The link's columns in two groups: what arrived, and what each packet cost. */
  packetsHead: string;
  framesHead: string;
  rows: { model: ModelResult['model']; best: boolean; errors: string; packets: string; frames: string }[];
} | null = null;

/** What the results on show are, without the settings their table's caption adds: a slide's
 * caption names the settings in full ([`caption`]), so they would be said twice. */
export function resultsWhat(): string {
  return shown?.what ?? '';
}

/** No results on show, as before the first run: the table and every note it wrote emptied (a
 * whole set refused after its first flight's numbers were shown, and no earlier run to go back to). */
export function clearTable(): void {
  shown = null;
  $('#results-table').replaceChildren();
  for (const id of ['rests-on', 'untracked', 'silence-note', 'saturated-note', 'spread-note', 'network-note', 'rate-use']) $(`#${id}`).hidden = true;
  $('#verdict-text').textContent = '';
  $('#repeat-seeds').hidden = true;
  renderBaseline(undefined);
}

const ERROR_HEAD = `<th scope="col" title="Mean 3D distance between the station's estimate and the truth">mean</th><th scope="col" title="Half the time the error is below this">median</th><th scope="col" title="75th percentile: 3 times in 4 the error is below this (the paper's headline statistic)">p75</th><th scope="col" title="95th percentile: the bad moments, typically long gaps">p95</th><th scope="col">max</th><th scope="col" title="Share of the time the true position lay inside the station's own 95 % ellipsoid: about 95 % when the station's uncertainty is honest, more when it is too cautious, less when it is overconfident">in 95 % region</th>`;

/** How many tables the results are laid out in: one; the tracking error, and under it what the
 * link spent on it; or that link half in two, what arrived and what each packet cost. */
type Parts = 1 | 2 | 3;

/** The results as `parts` tables, each row named by its station. */
function layoutTable(parts: Parts): void {
  if (!shown) return;
  const { packetsHead, framesHead, rows } = shown;
  const caption = `${shown.what}; ${shown.setup}`;
  const table = (label: string, what: string, head: string, cells: (row: (typeof rows)[number]) => string, badge: boolean) =>
    `<div class="table-wrap" tabindex="0" role="region" aria-label="${label}"><table class="results">
    <caption>${what}</caption>
    <thead><tr><th scope="col">model</th>${head}</tr></thead>
    <tbody>${rows
      .map(
        (row) => `<tr class="${row.best ? 'best' : ''}" data-model="${row.model}">
        <th scope="row">${MODEL_LABELS[row.model]}${row.best && badge ? ' <span class="badge">lowest p75</span>' : ''}</th>${cells(row)}</tr>`,
      )
      .join('')}</tbody></table></div>`;
  const spent = 'What the link spent on those errors, for each station';
  const error = () => table('Results table: tracking error', caption, ERROR_HEAD, (row) => row.errors, true);
  $('#results-table').innerHTML =
    parts === 1
      ? table('Results table', caption, `${ERROR_HEAD}\n    ${packetsHead}${framesHead}`, (row) => `${row.errors}\n        ${row.packets}${row.frames}`, true)
      : parts === 2
        ? error() + table('Results table: the link', spent, packetsHead + framesHead, (row) => row.packets + row.frames, false)
        : error() +
          table('Results table: the packets', `${spent}: the packets`, packetsHead, (row) => row.packets, false) +
          table('Results table: each packet', `${spent}: each packet`, framesHead, (row) => row.frames, false);
  $('#results-table').classList.toggle('split', parts > 1);
}

/** Lays the results out to fit their box ([`layOutToFit`]), now and whenever the box changes width. */
function fitTable(): void {
  fitResults ??= fitOnWidth($('#results-table'), layOutToFit);
  fitResults();
}
// Made on first use, not when the module loads: tests/unit imports this module where there is no
// page to observe.
let fitResults: (() => void) | undefined;

/**
 * Lays the results out so that nothing scrolls sideways where that can be helped. First as one
 * table; where it is too wide, the p75's interval and an ADR run's spans (`frameCells`) may break
 * after their dash (`tighten`): a wide interval (ADR at 5 km over eight seeds, "(76.52–408.85)")
 * pushed the charge per uplink out of a 1280 px window (always allowed, the breaks stacked short
 * intervals on two lines where the headers alone made room: the default table at 1024 px). Where
 * it is still too wide, the link's half goes under the tracking error's (presentation mode at
 * 1024×768: 1186 px in 940, the time on air cut off on a projector; a tablet at 768 px), and where
 * that half is too wide too, it goes in two (presenting on a tablet held upright, 768×1024, with
 * p75 intervals: 1193 px in 684, everything after the delivery out of sight). On a phone not even
 * the tracking error's table fits, and the one table scrolls with its station names in view.
 */
function layOutToFit(): void {
  layoutTable(1);
  if (tightenResults()) return;
  const overflow = errorColumnsOverflow();
  if (overflow > NEARLY_FITS) return;
  for (const parts of [2, 3] as const) {
    layoutTable(parts);
    // Where the error's columns nearly fit (a baseline's differences under each number, presenting
    // on a tablet held upright: 702 px in 684), the link's parts fitting is enough: only the
    // error's table then scrolls, by a few columns' edge, not the whole link (1312 px in 684).
    if (tightenResults() || (overflow > 0 && linkPartsFit())) return;
  }
  layoutTable(1);
  tightenResults();
}

/** How far past its box the error's columns of the one table may reach, as a share of the box's
 * width, for the link's half still to go under them: a tablet's few pixels, not a phone's half
 * again. */
const NEARLY_FITS = 0.15;

/** How far the one table's tracking-error columns (station to bound) reach past its box, as a
 * share of its width (0 where they fit): where the table overflows, every column is at its
 * narrowest, so these are as wide as the error's table alone would be, and where they reach far
 * past it (a phone) no split helps. Read from the layout just made: on a phone the results were
 * laid out three times per result, now once. */
function errorColumnsOverflow(): number {
  const wrap = document.querySelector<HTMLElement>('#results-table .table-wrap');
  const last = wrap?.querySelector('tbody td[data-field="coverage"]');
  if (!wrap || !last) return 0;
  const right = last.getBoundingClientRect().right - wrap.getBoundingClientRect().left + wrap.scrollLeft;
  return Math.max(0, right - wrap.clientWidth - 1) / Math.max(1, wrap.clientWidth);
}

/** Whether every table after the tracking error's (the link's parts) fits its box. */
const linkPartsFit = () => [...document.querySelectorAll<HTMLElement>('#results-table .table-wrap')].slice(1).every((w) => w.scrollWidth <= w.clientWidth + 1);

/** Tightens the results' tables where they are too wide; whether they all fit then. */
const tightenResults = () => tighten(document.querySelectorAll<HTMLElement>('#results-table .table-wrap'));

/** What the interval column rests on under the run's plan and sending (its header's tooltip): the
 * duty cycle set, listen before talk's airtime, or the interval set where the plan has none; never
 * less than fair use leaves (the core's `AccessSettings::duty_cycle_for`). With the paper's exact
 * timing (no clock drift, no random delay) a packet leaves on a sensor step, carrying its estimate
 * (`Flier::next_uplink`), so the time between packets is that rounded up to whole steps: at 1 Hz
 * SF7's 3.08 s are 4 s. */
export function intervalRule(c: Pick<RunConfig, 'region' | 'access' | 'fairUse' | 'interval' | 'dutyCycle' | 'sender' | 'dutyCycleMode' | 'sensorRate' | 'clockDrift' | 'jitter'>): string {
  const p = plan(c.region);
  const fair = c.fairUse === 'off' ? '' : `, or longer where ${c.fairUse.toUpperCase()} fair use leaves less airtime`;
  const rule = {
    interval: `the ${c.interval ?? DEFAULTS.interval} s set (${p.label} has no duty cycle)`,
    lbt: "time on air divided by listen before talk's share of the air (100 s per hour)",
    dutyCycle: `time on air divided by the ${percent(c.dutyCycle)} duty cycle`,
  }[sendingLimit(c)];
  const steps = !c.clockDrift && !c.jitter ? `, then rounded up to whole sensor steps (${+(1 / c.sensorRate).toPrecision(3)} s): a packet carries the estimate of the step it leaves on` : '';
  const error = c.sender === 'error' ? '. The shortest: error-triggered sending waits longer while the station’s forecast holds' : '';
  const budget = c.dutyCycleMode === 'budget' ? '. On average: the budget rule lets saved airtime go sooner, in a burst' : '';
  return `Time between packets: ${rule}${fair}${steps}${error}${budget}`;
}

/** The interval and time on air cells: one packet's at the run's rate, or with ADR that moved the
 * rate, their mean over the packets sent (the starting rate's alone said 148 s for a drone that
 * sent every 3 s after its first packet, or 3 s for one whose packets waited minutes) and, on a
 * second line, their span over the rates used, each rate's in the title. */
function frameCells(m: ModelResult): string {
  const used = [...m.dataRateUse].reverse();
  if (used.length > 1) {
    const title = ` title="Mean over the ${counted(m.packetsSent, 'packet')} sent; ADR sent at ${used.length} data rates: ${used.map((u) => `${rateName(u)} ${counted(u.packets, 'packet')}, ${(u.timeOnAir * 1e3).toFixed(1)} ms on air, every ${u.interval.toFixed(2)} s`).join('; ')}"`;
    // Where the table is tight (fitTable) the span may break after its dash, not before its unit.
    const span = (values: number[], unit: string) => ` <span class="sub" data-span>${short(Math.min(...values))}–${short(Math.max(...values))}\u00a0${unit}</span>`;
    // The means to three figures, as the spans: an average over rates claims no more.
    const mean = (v: number | null, scale: number, unit: string) => (v === null ? '—' : `${short(v * scale)} ${unit}`);
    return `<td data-field="interval"${title}>${mean(m.meanInterval, 1, 's')}${span(used.map((u) => u.interval), 's')}${sentLine(m)}</td><td data-field="toa"${title}>${mean(m.meanTimeOnAir, 1e3, 'ms')}${span(used.map((u) => u.timeOnAir * 1e3), 'ms')}</td>`;
  }
  return `<td data-field="interval"${leanTitle(m)}>${m.interval.toFixed(2)} s${lean(m.leanFrame && `lean ${m.leanFrame.interval.toFixed(2)} s`)}${sentLine(m)}</td><td data-field="toa"${leanTitle(m)}>${(m.timeOnAir * 1e3).toFixed(1)} ms${lean(m.leanFrame && `lean ${(m.leanFrame.timeOnAir * 1e3).toFixed(1)} ms`)}</td>`;
}

/** The duty-cycle interval the table shows, s: the mean over the packets sent (ADR), or the
 * starting rate's where none was sent (the core's `ModelResult::interval_shown`). */
function intervalShown(m: ModelResult): number {
  return m.meanInterval ?? m.interval;
}

/** Under the interval, where the drone's packets went notably less often (the core's
 * `sentSlower`, which the CLI's line under the station reads too): how often they did go. At
 * 1 Hz SF7's 3.08 s are 4 s, since a packet leaves on a sensor step; error-triggered sending
 * waits for its threshold. Nothing otherwise. */
function sentLine(m: ModelResult): string {
  if (!m.sentSlower || m.sentEvery === null) return '';
  return ` <span class="sub" data-sent title="The mean time between two packets the drone sent in a flight; the interval above is what the plan allows">sent every ${short(m.sentEvery)}\u00a0s</span>`;
}

/** A data rate by its EU868 name, `DR3`, or `SF8/500` where it has none. */
function rateName(u: ModelResult['dataRateUse'][number]): string {
  return u.dr === null ? `SF${u.sf}/${u.bw}` : `DR${u.dr}`;
}

/** Three significant figures, at most two decimals: 3.08, 41.2, 148. */
function short(v: number): string {
  return v.toFixed(v < 10 ? 2 : v < 100 ? 1 : 0);
}

/** A cell's second line, under a full packet's number, for what lean packets did (as the p75's
 * interval sits under it): nothing without them. */
function lean(text: string | false | null): string {
  return text ? ` <span class="sub" data-lean>${text}</span>` : '';
}

/** With lean payloads, what the interval, time on air and payload cells rest on: the shortest
 * lean frame and the full one. */
function leanTitle(m: ModelResult): string {
  if (!m.leanPackets) return '';
  const frame = m.leanFrame;
  const shortest = frame ? `, as short as ${(frame.timeOnAir * 1e3).toFixed(1)} ms on air with the next allowed ${frame.interval.toFixed(2)} s later` : '';
  return ` title="${m.leanPackets} of ${counted(m.packetsSent, 'packet')} left out small manoeuvre fields (DR's 9 or CTRA+'s 11 bytes)${shortest}; a full packet: ${(m.timeOnAir * 1e3).toFixed(1)} ms, ${m.interval.toFixed(2)} s"`;
}

/** The station with the lowest p75 and every other station's p75 against it, paired over the
 * same runs (`p75VsLowest`, docs/reference.md §12); undefined where the core could pair none. */
function pairedWithLowest(r: SimReport): { lowest: ModelResult; others: ModelResult[] } | undefined {
  const others = r.results.filter((m) => m.p75VsLowest !== null);
  const lowest = r.results.find((m) => m.model === others[0]?.p75VsLowest?.lowest);
  return lowest ? { lowest, others } : undefined;
}

/** The station whose p75 is lowest, when on the same runs resampled together every other
 * station's is clearly higher (its ratio's 95 % interval wholly above 1); undefined when no
 * difference is clear. */
function clearlyLowest(r: SimReport): ModelResult | undefined {
  const v = pairedWithLowest(r);
  if (!v || v.others.length !== r.results.length - 1) return undefined;
  return v.others.every((m) => m.p75VsLowest!.interval[0] > 1) ? v.lowest : undefined;
}

/** "DR's 1.47× (1.39–1.58)": a station's p75 over the lowest's, with its paired interval. */
function ratioWords(m: ModelResult): string {
  const v = m.p75VsLowest!;
  return `${MODEL_LABELS[m.model]}’s ${v.ratio.toFixed(2)}× (${v.interval[0].toFixed(2)}–${v.interval[1].toFixed(2)})`;
}

/** Why no station is named best: the stations the runs cannot tell from the lowest, those
 * clearly above it, and those with too few runs with errors to compare. */
function noClearLowest(r: SimReport, runs: string): string {
  const v = pairedWithLowest(r);
  if (!v) return `Too few runs with errors to compare the stations (${runs}): no model is named best.`;
  const tied = v.others.filter((m) => m.p75VsLowest!.interval[0] <= 1);
  const above = v.others.filter((m) => !tied.includes(m));
  const unpaired = r.results.filter((m) => m !== v.lowest && !v.others.includes(m));
  // Each ratio with its verb: "CTRA+’s 1.02× (0.99–1.05) as high is within chance".
  const are = (ms: ModelResult[]) => `${listed(ms.map(ratioWords))} as high ${ms.length === 1 ? 'is' : 'are'}`;
  const parts = [
    `${MODEL_LABELS[v.lowest.model]}’s is lowest${tied.length ? `, but ${are(tied)} within chance` : ''}`,
    above.length ? `${are(above)} clearly above` : '',
    unpaired.length ? `${names(unpaired)} ${unpaired.length === 1 ? 'has' : 'have'} errors in too few runs to compare` : '',
  ].filter(Boolean);
  return `No clear lowest p75: ${parts.join('; ')} (the same runs resampled together: 95 % intervals, ${runs}). More seeds or flights narrow them.`;
}

/** How many runs (flights × seeds) the stations' p75 intervals rest on: "30 runs", or where a run
 * in which no packet arrived gives some station no errors (a flight shorter than the wait for its
 * first packet), "27–29 of 30 runs" and why; '' for none. */
export function runsWords(r: Pick<SimReport, 'results' | 'config'>): string {
  const counts = r.results.flatMap((m) => (m.ci95 ? [m.ci95.runs] : []));
  if (!counts.length) return '';
  const [lo, hi] = [Math.min(...counts), Math.max(...counts)];
  const total = r.config.flights * r.config.seeds;
  const span = lo === hi ? `${lo}` : `${lo}–${hi}`;
  return lo === total && hi === total ? `${total} runs` : `${span} of ${total} runs: a run in which no packet arrived has no errors`;
}

/** The seeds "Repeat with … seeds" asks for: enough for an interval that can tell models apart. */
const REPEAT_SEEDS = 10;

/** How many packets and runs the numbers rest on, and whether the models differ clearly. */
function renderVerdict(r: SimReport, best: ModelResult | undefined): void {
  const few = r.results.filter((m) => m.caveats.fewPackets);
  $('#rests-on').hidden = few.length === 0;
  $('#use-whole-set').hidden = store.reportSettings.flight === 'all';
  if (few.length) {
    const counts = [...new Set(few.map((m) => m.packetsReceived))];
    const packets = `${counts.length === 1 ? counts[0] : listed(few.map((m) => String(m.packetsReceived)))} received packet${counts.length === 1 && counts[0] === 1 ? '' : 's'}${counts.length === 1 && few.length > 1 ? ' each' : ''}`;
    $('#rests-on-text').textContent = `Too few packets to compare: ${names(few)} ${few.length === 1 ? 'rests' : 'rest'} on ${packets}.`;
  }
  const text = $('#verdict-text');
  const repeat = $<HTMLButtonElement>('#repeat-seeds');
  const runs = runsWords(r);
  // Ten seeds, or as many as the core takes for these flights at these rates (`maxSeeds`).
  const seeds = Math.min(REPEAT_SEEDS, r.config.maxSeeds);
  // No station has an error when no packet arrived (or none was sent): nothing to compare, and
  // more seeds of the same flight bring none.
  const measured = r.results.some((m) => m.error3d.count > 0);
  repeat.hidden = store.reportSettings.seeds >= seeds || r.results.length < 2 || !measured;
  repeat.dataset.seeds = String(seeds);
  repeat.textContent = `Repeat with ${seeds} seeds`;
  if (!measured) text.textContent = `No station has an error to compare: ${r.results.every((m) => m.packetsSent === 0) ? 'the drone sent no packet' : 'no packet arrived'}.`;
  else if (r.results.length < 2) text.textContent = runs ? `p75's 95 % interval rests on ${runs} (flights × seeds).` : '';
  else if (best) text.textContent = `${MODEL_LABELS[best.model]} has the lowest p75, clearly: on the same runs resampled together, ${listed(r.results.filter((m) => m !== best).map(ratioWords))} as high (95 % intervals, ${runs}).`;
  else if (!runs) text.textContent = 'One flight with one seed cannot tell whether these differences are larger than chance: no model is named best.';
  else text.textContent = noClearLowest(r, runs);
}

/** How much of the flight time the statistics cover, when a flight's first packet comes late
 * (SF11-12, long range): before it the station has no estimate and no error is counted
 * (`wholeFlight`, docs/reference.md §12). */
function renderUntracked(r: SimReport): void {
  const note = $('#untracked');
  const share = (m: ModelResult) => trackedPercent(m.wholeFlight.tracked);
  note.hidden = !r.results.some((m) => m.wholeFlight.partlyTracked);
  if (note.hidden) return;
  const shares = new Set(r.results.map(share));
  const cover = shares.size === 1 ? `${share(r.results[0])} %` : r.results.map((m) => `${share(m)} % (${MODEL_LABELS[m.model]})`).join(', ');
  note.textContent = `These errors cover ${cover} of the flight time: until a flight's first packet arrives the station has no estimate, so that time has no error to count.`;
}

/** The notes under the table that say what its numbers rest on (too few packets, untracked time,
 * an error-triggered drone's lost packets), as shown: an embed's caption and the table's slide
 * carry them too. */
export function restingNotes(): string[] {
  return [
    ['#rests-on', '#rests-on-text'],
    ['#untracked', '#untracked'],
    ['#silence-note', '#silence-note'],
    ['#saturated-note', '#saturated-note'],
    ['#spread-note', '#spread-note'],
  ].flatMap(([box, text]) => ($(box).hidden ? [] : [$(text).textContent ?? '']));
}

/** Where an error-triggered drone's packets are lost (the core's `caveats.silenceAfterLoss`: over
 * 5 %), what its results rest on: the drone never learns of a loss, so it stays silent while the
 * station drifts (docs/senders.md, README "Beyond the paper, at a glance"). */
function renderSilenceNote(r: SimReport): void {
  const note = $('#silence-note');
  note.hidden = !r.results.some((m) => m.caveats.silenceAfterLoss);
  if (note.hidden) return;
  const sent = r.results.reduce((n, m) => n + m.packetsSent, 0);
  const lost = 1 - r.results.reduce((n, m) => n + m.packetsReceived, 0) / sent;
  note.textContent = `${(lost * 100).toFixed(0)} % of the packets sent were lost. An error-triggered drone cannot tell a lost packet from a delivered one: after a loss it stays silent while the station drifts. Where packets are lost it can track worse than periodic sending at the same airtime (at 3 km its p95 up to 1.23× on the synthetic set and 2.12× on the real flight; docs/senders.md).`;
  linkDocs(note);
}

/** Where a station's received packets carried a value beyond the payload's range (the core's
 * `caveats.saturatedPackets`: a speed over 25.5 m/s, a turn rate over 2 rad/s, a position 6.5 km
 * from the start): sent as the range's edge, so the station started from a state other than the
 * drone's estimate, and part of its error is the payload's (docs/reference.md §5). */
function renderSaturatedNote(r: SimReport): void {
  const note = $('#saturated-note');
  const hit = r.results.filter((m) => m.caveats.saturatedPackets > 0);
  note.hidden = hit.length === 0;
  if (note.hidden) return;
  const counts = listed(hit.map((m) => `${MODEL_LABELS[m.model]} ${m.caveats.saturatedPackets} of ${m.packetsReceived}`));
  note.textContent = `Saturated: ${counts} received packets ${beyondRange(hit.flatMap((m) => m.caveats.saturated), false)}`;
  linkDocs(note);
}

/** Where the stations' packets arrived at rates more than 5 points apart (the core's
 * `DeliverySpread`): stations whose frames differ in length send at other moments and lose other
 * packets, so part of the difference in their errors is the link's (docs/paper-reproduction.md). */
function renderSpreadNote(r: SimReport): void {
  const note = $('#spread-note');
  const d = r.results.length > 1 ? deliverySpread(r.results) : null;
  note.hidden = d === null;
  if (d === null) return;
  const pct = (x: number) => `${(x * 100).toFixed(0)} %`;
  note.textContent = `${MODEL_LABELS[d.highest]}’s packets arrived ${pct(d.highestRatio)} of the time, ${MODEL_LABELS[d.lowest]}’s ${pct(d.lowestRatio)}. Stations whose frames differ in length send at other moments, and the link’s fades took other packets from each: part of the difference in their errors is the link’s, not the model’s (docs/paper-reproduction.md).`;
  linkDocs(note);
}

/** p75's 95 % interval, when the run has one. */
function interval(m: ModelResult): string {
  const c = m.ci95;
  return c ? ` <span class="ci" data-field="p75-interval" title="95 % interval over ${c.runs} runs (flights × seeds)">(${fmt(c.p75[0])}–${fmt(c.p75[1])})</span>` : '';
}

/** The change of statistic `key` against the baseline's same station, as a small signed number. */
function delta(m: ModelResult, key: 'mean' | 'p50' | 'p75' | 'p95' | 'max' | 'packets'): string {
  const base = store.baseline?.report.results.find((x) => x.model === m.model);
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

/** The baseline's note under the table and Pin's label: what the differences are against, and
 * the stations of `shown` (the report in the table) that have none: not run in the baseline, or
 * without a packet received there. */
export function renderBaseline(shown: SimReport | undefined = store.report): void {
  const note = $('#baseline-note');
  note.hidden = !store.baseline;
  $('#pin').textContent = store.baseline ? 'Clear baseline' : 'Pin as baseline';
  if (!store.baseline) return;
  // A station the baseline did not run has no differences: its row must not read as unchanged.
  const pinned = store.baseline.report.results.map((m) => m.model);
  const unpinned = (shown?.results ?? []).filter((m) => !pinned.includes(m.model));
  const alone = unpinned.length ? ` ${names(unpinned)} ${unpinned.length === 1 ? 'was' : 'were'} not in the baseline: no differences in ${unpinned.length === 1 ? 'its row' : 'their rows'}.` : '';
  // Nor has a station whose packets all failed to arrive in the baseline any error to differ from.
  const silent = (shown?.results ?? []).filter((m) => store.baseline!.report.results.some((b) => b.model === m.model && b.error3d.p75 === null) && m.error3d.p75 !== null);
  const unmeasured = silent.length ? ` ${names(silent)} received no packet in the baseline: no differences in ${silent.length === 1 ? 'its errors' : 'their errors'}.` : '';
  note.textContent = `Differences are against the pinned baseline: ${caption(store.baseline.settings)}. ▼ lower, ▲ higher; lower error and more packets received are better (green).${alone}${unmeasured}`;
}

/** With ADR: how many packets each model sent at each data rate. */
function renderRateUse(r: SimReport): void {
  const note = $('#rate-use');
  note.hidden = r.config.adr === 'off';
  if (note.hidden) return;
  const rate = (u: ModelResult['dataRateUse'][number]) => `${rateName(u)}${u.dr === null ? '' : ` (SF${u.sf}/${u.bw})`} ${u.received}/${u.packets}`;
  const lines = r.results.map((m) => `${MODEL_LABELS[m.model]}: ${[...m.dataRateUse].reverse().map(rate).join(', ')}`);
  note.textContent = `Packets received / sent per data rate (${adrName(r.config.adr)}; the interval and time on air above are the mean over the packets sent, their span beneath) — ${lines.join('; ')}.`;
}

/** What each gateway heard, and the copies the network server removed. */
function networkNote(m: ModelResult, named: boolean): string {
  const { packetsSent: sent, packetsReceived: received, duplicates, gateways } = m;
  const each = gateways
    .map((g, i) => `gateway ${i + 1} at (${(g.east / 1000).toFixed(1)}, ${(g.north / 1000).toFixed(1)}) km heard ${g.heard}${gateways.length > 1 ? ` (${g.onlyHeard} only it)` : ''}${downlinksWanted(g) ? `, ${downlinkCounts([g])}` : ''}${g.missedWhileTransmitting ? `, ${counted(g.missedWhileTransmitting, 'uplink')} missed while it sent` : ''}`)
    .join('; ');
  return `Network${named ? ` (${MODEL_LABELS[m.model]}'s packets)` : ''}: ${received} of ${counted(sent, 'packet')} delivered (${sent ? ((100 * received) / sent).toFixed(0) : 0} %)${gateways.length > 1 ? `, ${counted(duplicates, 'duplicate copy', 'duplicate copies')} removed` : ''} — ${each}.`;
}

/** The IMM's mean member probabilities, as a tooltip. */
function probabilities(m: ModelResult): string {
  const nees = m.nees === null ? '' : `; mean NEES ${m.nees.toFixed(1)} (3 when the station's uncertainty is honest)`;
  const under = m.underBound95 === null ? '' : `; its error stayed under its 95 % bound (the error chart's band) ${(100 * m.underBound95).toFixed(0)} % of the time`;
  const p = m.modelProbability;
  if (!p) return `Share of the time the truth lay inside the station's 95 % ellipsoid${under}${nees}`;
  return `Mean IMM probability: DR ${fmt(p.dr ?? null)}, CTRA+ ${fmt(p['ctra-plus'] ?? null)}, 3D-CTRA ${fmt(p['3d-ctra'] ?? null)}${under}${nees}`;
}

/** The Things Network's fair-use limit: what it sets when chosen, otherwise what it would. "Sent
 * here" counts by the mean time between the packets sent where there were two, else by the mean
 * interval over the packets sent: the starting rate's interval would miscount ADR, and any
 * interval a drone that waits for sensor steps or a threshold. */
function ttnNote(r: SimReport): string {
  const m = r.results[r.results.length - 1];
  const interval = intervalShown(m);
  // The settings that made these results, not the form's (which may have moved on).
  const made = store.reportSettings;
  const who = `${m.payloadBytes} B (${MODEL_LABELS[m.model]})`;
  if (made.fairUse === 'ttn') {
    return `<p class="note" id="ttn-note">The Things Network's fair use (30 s of airtime a day, spread evenly) sets the interval here: one packet of ${who} every ${interval.toFixed(0)} s.</p>`;
  }
  const a = timeOnAir({ sf: made.sf, bw: made.bw, payload: m.payloadBytes, overhead: overheadBytes(made), cr: made.cr });
  const perDay = 86400 / (m.sentEvery ?? interval);
  return `<p class="note" id="ttn-note">On The Things Network, fair use allows 30 s of airtime a day: ${a.ttnPacketsPerDay} packets of ${who}
    at this setting, one every ${(86400 / Math.max(1, a.ttnPacketsPerDay)).toFixed(0)} s — ${(perDay / Math.max(1, a.ttnPacketsPerDay)).toFixed(0)}× fewer than sent here. Not applied (choose it under Fair use).</p>`;
}
