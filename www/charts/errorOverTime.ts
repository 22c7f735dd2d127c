// Paper Fig. "error over time": the station's 3D error on the first flight, with packet arrivals
// (dots on the axis) and lost packets (crosses), over the station's own 95 % bound (dashed band).
import * as Plot from '@observablehq/plot';
import { isThinned, MODEL_LABELS, type ModelSeries, type SimReport } from '../loratrack';
import { MODEL_COLORS, NOTE_GREY, chartFrame, chartFont, withKey, labelRoom } from './colors';
import { sendingLimit } from '../state';

/** What the error chart draws, computed from a report for a chart `width` px wide: the picked
 * samples, the packet marks and rate labels, the scale and the words around it. The page computes
 * it a task before Plot draws it ([`errorChart`]): on the long uploaded flight (10⁶ rows) these
 * numbers took 11–25 ms and the drawing 24–53 ms, one task of 54–84 ms together
 * (docs/performance.md). `note` alone, with nothing to draw, when no packet arrived. */
export type ErrorChartData =
  | { note: string }
  | {
      width: number;
      labels: string[];
      colors: string[];
      lines: PickedColumns;
      band: PickedColumns;
      arrivals: (PacketMark & { model: string })[];
      lost: (PacketMark & { model: string })[];
      changes: RateLabel[];
      top: number;
      offScale: string[];
      key: string;
      thinned: string;
    };

/** Why the first flight's station never had an estimate: its packets were lost on the way, or
 * none was sent, since the drone may send less often than the flight lasts (TTN's fair use at a
 * slow rate, a long interval set), which no gateway distance mends. */
function nothingArrived(report: SimReport): string {
  const flight = report.series?.flight ?? 'this flight';
  const sent = report.series?.models.some((m) => m.arrivals.length + m.lost.length > 0) ?? true;
  if (sent) return `No packet arrives at this distance on ${flight}: the station never has an estimate, so there is no error to plot. Move the gateway closer or raise the spreading factor.`;
  const every = Math.min(...report.results.map((m) => m.interval));
  // What would send sooner: where the plan has no duty cycle the interval set, not the rate.
  const sooner = [sendingLimit(report.config) === 'interval' ? 'with a shorter Interval' : 'at a faster data rate', ...(report.config.fairUse === 'off' ? [] : ['with Fair use off'])];
  return `No packet is sent on ${flight}: at these settings the drone may send once every ${every.toFixed(every >= 100 ? 0 : 1)} s, and no sending time fell within the flight, so the station never has an estimate. It sends sooner ${sooner.join(', or ')}.`;
}

export function errorChartData(report: SimReport, width: number): ErrorChartData {
  const models = report.series?.models ?? [];
  if (!models.some((m) => m.t.length > 0)) return { note: nothingArrived(report) };
  // A pixel of the time axis, s: packets less than a dot's width apart draw as one mark (a long
  // flight's tens of thousands would otherwise be as many SVG elements, one on top of another),
  // and a station's samples are thinned to the lowest and highest error in each pixel.
  const first = Math.min(...models.map((m) => m.t[0] ?? Infinity));
  const span = Math.max(...models.map((m) => m.t[m.t.length - 1] ?? -Infinity)) - first;
  const pixel = span / Math.max(1, width - 70);
  const lines = pickedColumns(models, models.map((m) => pixelPicks(m.t, m.error3d, first, pixel)));
  // The station's own 95 % bound on its error, as a faint band under each model's line.
  const band = pickedColumns(models, models.map((m) => pixelTops(m.t, m.bound95, first, pixel)));
  const dot = DOT_PX * pixel;
  const arrivals = models.flatMap((m) => packetMarks(m.arrivals, m.arrivalDr, dot).map((p) => ({ ...p, model: MODEL_LABELS[m.model] })));
  const lost = models.flatMap((m) => packetMarks(m.lost, m.lostDr, dot).map((p) => ({ ...p, model: MODEL_LABELS[m.model] })));
  // With ADR, label each change of data rate above the axis.
  const changes = rateLabels(
    report.config.adr === 'off' ? [] : models.flatMap((m) => rateChanges(m.arrivals, m.arrivalDr, MODEL_LABELS[m.model])),
    models.length,
    // A label's width (three characters and a space at ~0.6 em) in seconds of the plot (~width − 70 px).
    4 * 0.6 * chartFont() * pixel,
  );
  // The picks hold each pixel's largest error and bound, so their tops are the series' own.
  const scale = errorScale([lines.e], [band.b]);
  return {
    width,
    labels: models.map((m) => MODEL_LABELS[m.model]),
    colors: models.map((m) => MODEL_COLORS[m.model]),
    lines,
    band,
    arrivals,
    lost,
    changes,
    top: scale.top,
    offScale: scale.boundTop > scale.top ? [`95 % bound up to ${scale.boundTop.toFixed(0)} m ↑`] : [],
    // How often the band held is the note under the chart (`bandNote`), which its slide carries.
    key: `● packet arrived · ✕ packet lost · dashed band: the station's own 95 % bound on its error (an honest station's error stays under it 95 % of the time)${changes.length ? " · DRn: the data rate from that packet on (grey: every station's drone)" : ''}.`,
    thinned: thinnedNote(models),
  };
}

/** Paper Fig. "error over time" from [`errorChartData`]'s numbers. */
export function errorChart(data: ErrorChartData): SVGSVGElement | HTMLElement {
  if ('note' in data) {
    const note = document.createElement('p');
    note.className = 'empty-chart';
    note.textContent = data.note;
    return note;
  }
  const { lines, band } = data;
  const chart = Plot.plot({
    ...chartFrame(180),
    width: data.width,
    marginLeft: labelRoom(50),
    x: { label: 'time (s)' },
    y: { label: '3D error (m)', grid: true, domain: [0, data.top || 1], nice: true },
    color: { domain: data.labels, range: data.colors, legend: true },
    marks: [
      Plot.areaY(band.rows, { x: band.t, y1: 0, y2: band.b, fill: band.model, fillOpacity: 0.08, curve: 'step-after', clip: true }),
      Plot.lineY(band.rows, { x: band.t, y: band.b, stroke: band.model, strokeOpacity: 0.45, strokeDasharray: '3,3', strokeWidth: 1, curve: 'step-after', clip: true }),
      Plot.text(data.offScale, { frameAnchor: 'top-right', lineAnchor: 'bottom', dy: -4, fontSize: chartFont(), fill: '#555' }),
      Plot.lineY(lines.rows, { x: lines.t, y: lines.e, stroke: lines.model, strokeWidth: 1.4 }),
      Plot.dot(data.arrivals, { x: 't', y: 0, fill: 'model', r: 2.5, title: (d) => `${d.model}: ${packetsAt(d, 'arrived')}` }),
      Plot.dot(data.lost, { x: 't', y: 0, stroke: 'model', symbol: 'times', r: 4, title: (d) => `${d.model}: ${packetsAt(d, 'lost')}` }),
      ...rateMarks(data.changes),
      Plot.ruleY([0]),
      Plot.tip(lines.rows, Plot.pointerX({ x: lines.t, y: lines.e, stroke: lines.model })),
    ],
  });
  if (!data.thinned) return withKey(chart, data.key);
  // Under the chart, so that the page and a slide both say what a long flight's line rests on.
  const note = document.createElement('p');
  note.className = 'note';
  note.textContent = data.thinned;
  const box = document.createElement('div');
  box.append(withKey(chart, data.key), note);
  return box;
}

/** Packets less than this many pixels of the time axis apart draw as one mark: an arrival's dot
 * is 5 px across (r 2.5), so closer marks would only overlap. A long uploaded flight (10⁶ rows,
 * a packet every 3 s for 40 000 s) drew a mark in every pixel, ~1 100 dots with their titles,
 * and with them the chart took ~95 ms of the page's thread. */
const DOT_PX = 5;

/** A station's changes of data rate: each arrival whose rate differs from the one before. */
export function rateChanges(times: ArrayLike<number>, drs: ArrayLike<number | null> | undefined, model: string): { t: number; model: string; label: string }[] {
  const out: { t: number; model: string; label: string }[] = [];
  for (let i = 0; i < times.length; i++) {
    const dr = drs?.[i];
    if (dr !== null && dr !== undefined && (i === 0 || dr !== drs?.[i - 1])) out.push({ t: times[i], model, label: `DR${dr}` });
  }
  return out;
}

/** What a thinned series rests on (`ModelSeries.samples`): empty when every station's series is
 * whole, as on every synthetic flight. */
export function thinnedNote(models: Pick<ModelSeries, 't' | 'samples'>[]): string {
  const thinned = models.filter(isThinned);
  if (!thinned.length) return '';
  const [samples, kept] = [Math.max(...thinned.map((m) => m.samples)), Math.max(...thinned.map((m) => m.t.length))];
  return `This flight's ${samples.toLocaleString('en')} samples a station are drawn as their envelope: each stretch's lowest and highest error, ${kept.toLocaleString('en')} kept; the error series CSV gives that envelope stretch by stretch.`;
}

/**
 * The samples of one station's series (times `t`, s, in order; errors `e`, m) the chart draws
 * when a pixel of its time axis, starting at `start`, spans `pixel` s: every one where there
 * are at most four a pixel on average, otherwise the lowest and the highest error of each
 * pixel, in time order: the line a reader sees at that resolution, its peaks included (min-max
 * decimation, as plotting libraries thin a long series). A long uploaded flight's 3000 plotted
 * samples a station took four stations ~340 ms to draw at 1280 × 800, one long pause of the
 * page; a synthetic flight's (~800, at two or three a pixel on a phone) are drawn as they are.
 */
export function pixelPicks(t: ArrayLike<number>, e: ArrayLike<number>, start: number, pixel: number): number[] {
  if (!(pixel > 0) || t.length <= 4 * ((t[t.length - 1] - start) / pixel + 1)) return Array.from({ length: t.length }, (_, i) => i);
  const picks: number[] = [];
  const close = (low: number, high: number) => {
    picks.push(Math.min(low, high));
    if (high !== low) picks.push(Math.max(low, high));
  };
  let column = Math.floor((t[0] - start) / pixel);
  let low = 0;
  let high = 0;
  for (let i = 1; i < t.length; i++) {
    const c = Math.floor((t[i] - start) / pixel);
    if (c !== column) {
      close(low, high);
      column = c;
      low = high = i;
    } else if (e[i] < e[low]) low = i;
    else if (e[i] > e[high]) high = i;
  }
  if (t.length > 0) close(low, high);
  return picks;
}

/** The picked samples of every station (`picks[k]`: indices into `models[k]`'s series), as the
 * columns the chart's marks read: times `t` (s), errors `e` and bounds `b` (m), and the station's
 * label, with `rows` their count. Plot reads a column given as an array as it stands, instead of
 * building one row object per sample; the column of labels carries its name for the tip. */
export interface PickedColumns {
  rows: { length: number };
  t: Float64Array;
  e: Float64Array;
  b: Float64Array;
  model: { value: string[]; label: string };
}

export function pickedColumns(models: Pick<ModelSeries, 'model' | 't' | 'error3d' | 'bound95'>[], picks: number[][]): PickedColumns {
  const rows = picks.reduce((n, p) => n + p.length, 0);
  const [t, e, b] = [new Float64Array(rows), new Float64Array(rows), new Float64Array(rows)];
  const labels: string[] = new Array(rows);
  let row = 0;
  models.forEach((m, k) => {
    const label = MODEL_LABELS[m.model];
    for (const i of picks[k]) {
      t[row] = m.t[i];
      e[row] = m.error3d[i];
      b[row] = m.bound95[i];
      labels[row++] = label;
    }
  });
  return { rows: { length: rows }, t, e, b, model: { value: labels, label: 'model' } };
}

/**
 * The samples of one station's 95 % bound (times `t`, s, in order; bounds `b`, m) its band is
 * drawn through when a pixel of the time axis, starting at `start`, spans `pixel` s: every one
 * where there is at most one a pixel on average, otherwise the highest bound of each pixel. The
 * band is filled from zero with steps after each sample, so within a pixel only its top shows;
 * the line's picks ([`pixelPicks`]) took its area and dashed edge through twice the points.
 */
export function pixelTops(t: ArrayLike<number>, b: ArrayLike<number>, start: number, pixel: number): number[] {
  if (!(pixel > 0) || t.length <= (t[t.length - 1] - start) / pixel + 1) return Array.from({ length: t.length }, (_, i) => i);
  const tops: number[] = [];
  let column = Math.floor((t[0] - start) / pixel);
  let top = 0;
  for (let i = 1; i < t.length; i++) {
    const c = Math.floor((t[i] - start) / pixel);
    if (c !== column) {
      tops.push(top);
      column = c;
      top = i;
    } else if (b[i] > b[top] || Number.isNaN(b[top])) top = i;
  }
  if (t.length > 0) tops.push(top);
  return tops;
}

/** One mark of packets on the error chart's axis: the packets of one station within one pixel of
 * the time axis (nearly always one packet), at the first one's time `t` (s), with the last's time
 * `to` and each one's data rate where the run has them (`null`: an SF and bandwidth that form none). */
export interface PacketMark {
  t: number;
  to: number;
  count: number;
  drs: (number | null)[];
}

/**
 * The marks for packet times `times` (s, in order) with their data rates `drs`: one per packet,
 * except that packets less than `pixel` s after the first of a mark join it. A synthetic flight's
 * packets are seconds apart, one mark each; a long uploaded flight's (40 000 s, 13 000 packets a
 * station) would be tens of thousands of SVG elements drawn on one another, and their drawing a
 * 2 s pause of the page.
 */
export function packetMarks(times: ArrayLike<number>, drs: ArrayLike<number | null | undefined> | undefined, pixel: number): PacketMark[] {
  const marks: PacketMark[] = [];
  for (let i = 0; i < times.length; i++) {
    const t = times[i];
    const dr = drs?.[i] ?? null;
    const last = marks[marks.length - 1];
    if (last && t - last.t < pixel) {
      last.to = t;
      last.count += 1;
      if (!last.drs.includes(dr)) last.drs.push(dr);
    } else {
      marks.push({ t, to: t, count: 1, drs: [dr] });
    }
  }
  return marks;
}

/** A mark's title: "packet arrived at 12.3 s at DR5", or for several "37 packets arrived in
 * 1234.5–1290.2 s at DR3". */
function packetsAt(m: PacketMark, what: 'arrived' | 'lost'): string {
  const rates = m.drs.filter((dr) => dr !== null);
  const at = rates.length ? ` at ${rates.map((dr) => `DR${dr}`).join(', ')}` : '';
  return m.count === 1 ? `packet ${what} at ${m.t.toFixed(1)} s${at}` : `${m.count} packets ${what} in ${m.t.toFixed(1)}–${m.to.toFixed(1)} s${at}`;
}

/** A change of data rate written above the error chart's axis: its time (s), the rate, the
 * station it is that station's alone (undefined when every station's drone changed there: one
 * label in grey), and the row it is lifted to so that it clears the label before it. */
export interface RateLabel {
  t: number;
  label: string;
  model?: string;
  row: number;
}

/**
 * The labels of `changes` (each station's changes of data rate) as drawn: a change every station
 * makes written once, and each label lifted a row above one less than `clearance` s before it on
 * its row (a label's width on the time axis). With ADR the stations' drones change rate at
 * nearby packets: drawn as they came, three coloured labels lay on top of one another, and a
 * quick second change's label on the first, read as one garbled word.
 */
export function rateLabels(changes: { t: number; label: string; model: string }[], stations: number, clearance: number): RateLabel[] {
  // The stations' drones send different payloads, so the same change reaches each at a
  // slightly different packet: changes to one rate within a label's width count as one.
  const groups: { t: number; label: string; at: { t: number; model: string }[] }[] = [];
  for (const c of [...changes].sort((a, b) => a.t - b.t)) {
    const group = groups.find((g) => g.label === c.label && c.t - g.t < clearance && !g.at.some((a) => a.model === c.model));
    if (group) group.at.push(c);
    else groups.push({ t: c.t, label: c.label, at: [c] });
  }
  const labels = groups
    .flatMap((g) => (g.at.length === stations ? [{ t: g.t, label: g.label }] : g.at.map(({ t, model }) => ({ t, label: g.label, model }))))
    .sort((a, b) => a.t - b.t);
  const lastAt: number[] = [];
  return labels.map((l) => {
    let row = 0;
    while (lastAt[row] !== undefined && l.t - lastAt[row] < clearance) row++;
    lastAt[row] = l.t;
    return { ...l, row };
  });
}

/** The labels' marks: one per row (a row's lift is a constant offset), a shared change in grey
 * and a station's own in its colour. */
function rateMarks(labels: RateLabel[]): Plot.Markish[] {
  return [...new Set(labels.map((l) => l.row))].flatMap((row) => {
    const inRow = labels.filter((l) => l.row === row);
    const common = { x: 't', y: 0, text: 'label', dy: -10 - row * (chartFont() + 2), fontSize: chartFont() };
    return [Plot.text(inRow.filter((l) => !l.model), { ...common, fill: NOTE_GREY }), Plot.text(inRow.filter((l) => l.model), { ...common, fill: 'model' })];
  });
}

/**
 * The error chart's scale: its top, m, and the bound's peak. While packets are lost the station's
 * bound can grow far past its error (at 3 km to hundreds of metres against tens), and a scale set
 * by the bound would flatten the error lines: the top holds the bound to twice the largest error,
 * and above it the band runs off the chart. Without any error the bound sets it.
 */
export function errorScale(errors: ArrayLike<number>[], bounds: ArrayLike<number>[]): { top: number; boundTop: number } {
  const errorTop = largest(errors);
  const boundTop = largest(bounds);
  return { top: errorTop > 0 ? Math.max(errorTop, Math.min(boundTop, 2 * errorTop)) : boundTop, boundTop };
}

/** The largest finite number in `series`, or 0. */
function largest(series: ArrayLike<number>[]): number {
  let top = 0;
  for (const xs of series) for (let i = 0; i < xs.length; i++) if (Number.isFinite(xs[i]) && xs[i] > top) top = xs[i];
  return top;
}
