// Boxplot marks drawn from statistics the Rust core computed (quartiles, whiskers at 1.5 IQR),
// so the chart shows exactly the numbers in the tables and the JSON.
import * as Plot from '@observablehq/plot';
import type { Boxplot, ModelName } from '../loratrack';
import { MODEL_LABELS } from '../loratrack';
import { CHOSEN_COLUMN, MODEL_COLORS, chartFrame, chartFont, NOTE_GREY, fitLabel, withKey, labelRoom, noneSent } from './colors';
import { plainNumber } from './logAxis';

/** The plot's left margin at the page's type size, px: room for the y axis's labels. */
const MARGIN_LEFT = 50;
const MARGIN_RIGHT = 20;

export interface BoxRow {
  group: string;
  model: ModelName;
  box: Boxplot;
  /** Too few packets received to compare the stations (the core's `caveats.fewPackets`): a
   * dashed, paler box, which the note under the chart explains (`fewPacketsNote`). */
  few?: boolean;
  /** Packets sent: 0 where the drone sent none within the flight (TTN's fair use at a slow rate),
   * which the chart says instead of "no packet arrives", since no distance mends it. */
  sent?: number;
}

/** `opts.chosen`: the group the results' run is (the distance chart's chosen distance), drawn on a
 * grey column that `chosen.key` names in the slide's key; none where the run is none of them. */
export function boxplotChart(rows: BoxRow[], opts: { groupLabel: string[]; width: number; yLabel?: string; log?: boolean; chosen?: { group: string; key: string } }): SVGSVGElement | HTMLElement {
  const data = rows
    .filter((r) => r.box.count > 0 && (!opts.log || (r.box.whiskerLow ?? 0) > 0))
    .map((r) => ({ group: r.group, label: MODEL_LABELS[r.model], model: r.model, few: r.few ?? false, ...r.box }));
  // Every station keeps its place and colour, in the order of the rows (the stations' order), even
  // where none of its packets arrived.
  const stations = [...new Set(rows.map((r) => r.model))];
  const models = stations.map((m) => MODEL_LABELS[m]);
  const groups = [...new Set(rows.map((r) => r.group))];
  const empty = groups
    .filter((g) => !data.some((d) => d.group === g))
    .map((group) => ({ group, text: noneSent(rows.filter((r) => r.group === group)) ? 'no packet sent' : 'no packet arrives' }));
  // A station none of whose packets arrived where others' did: "none" in its place, not a gap
  // that reads as a station left out (the real flight at 5 km: one CTRA+ and one 3D-CTRA packet,
  // no DR packet).
  const none = rows
    .filter((r) => r.box.count === 0 && data.some((d) => d.group === r.group))
    .map((r) => ({ group: r.group, label: MODEL_LABELS[r.model], why: r.sent === 0 ? 'no packet sent' : 'no packet arrived' }));
  const floor = opts.log ? logFloor(data) : {};
  const chosen = opts.chosen && groups.includes(opts.chosen.group) ? opts.chosen : undefined;
  const chart = Plot.plot({
    ...chartFrame(180),
    width: opts.width,
    marginLeft: labelRoom(MARGIN_LEFT),
    marginRight: MARGIN_RIGHT,
    fx: { label: fitLabel(opts.width, ...opts.groupLabel), domain: groups },
    x: { axis: null, domain: models, paddingInner: 0.25 },
    // A log scale keeps the boxes near the gateway readable beside the metres-to-kilometres ones beyond its range.
    // Plain numbers at the powers of ten ("0.1", not "100m", which reads as 100 metres).
    y: opts.log ? { label: opts.yLabel ?? 'error (m, log scale)', grid: true, type: 'log', tickFormat: decade, ...floor } : { label: opts.yLabel ?? 'error (m)', grid: true, zero: true },
    color: { domain: models, range: stations.map((m) => MODEL_COLORS[m]), legend: true },
    marks: [
      // Without x or y channels a rect fills its facet's frame: the chosen group's whole column.
      Plot.rect(chosen ? [chosen.group] : [], { fx: (g: string) => g, ...CHOSEN_COLUMN }),
      // A group where nothing arrived says so instead of staying blank, wrapped within its own
      // column (on a phone a column is ~45 px, and one line ran over the boxes beside it).
      Plot.text(empty, { fx: 'group', text: 'text', lineWidth: groupEms(opts.width, groups.length), frameAnchor: 'middle', fill: NOTE_GREY, fontSize: chartFont() }),
      // Upright from the axis (a slot is about a third of a group's column), the station named and
      // in the notes' grey: its colour would be small text at 3:1 contrast for DR and 3D-CTRA.
      Plot.text(none, { fx: 'group', x: 'label', text: (d: { label: string }) => `${d.label}: none`, rotate: -90, textAnchor: 'start', frameAnchor: 'bottom', dy: -4, fill: NOTE_GREY, fontSize: chartFont(), title: (d: { group: string; label: string; why: string }) => `${d.label}, ${d.group}: ${d.why}` }),
      Plot.ruleX(data, { fx: 'group', x: 'label', y1: 'whiskerLow', y2: 'whiskerHigh', stroke: 'label' }),
      Plot.barY(data.filter((d) => !d.few), { fx: 'group', x: 'label', y1: 'q1', y2: 'q3', fill: 'label', fillOpacity: 0.35, stroke: 'label' }),
      Plot.barY(data.filter((d) => d.few), { fx: 'group', x: 'label', y1: 'q1', y2: 'q3', fill: 'label', fillOpacity: 0.12, stroke: 'label', strokeDasharray: '4,3' }),
      Plot.tickY(data, { fx: 'group', x: 'label', y: 'median', stroke: 'label', strokeWidth: 2.5 }),
      Plot.tip(data, Plot.pointerX({ fx: 'group', x: 'label', y: 'median', title: (d) => `${d.label}\nmedian ${d.median.toFixed(2)} m\nQ1–Q3 ${d.q1.toFixed(2)}–${d.q3.toFixed(2)} m\nwhiskers ${d.whiskerLow.toFixed(2)}–${d.whiskerHigh.toFixed(2)} m\n${d.outliers} outliers of ${d.count}${d.few ? '\ntoo few packets to compare' : ''}` })),
    ],
  });
  const clamped = floor.domain ? ` Whiskers that reach below ${plainNumber(floor.domain[0])} m end at the axis's bottom edge.` : '';
  const silent = none.length ? ' "DR: none" (or another station) in its place: none of its packets arrived there.' : '';
  return withKey(chart, `Box: the middle half of the errors (quartiles), thick line the median; whiskers: the furthest errors within 1.5 box heights of the box (any beyond, the outliers, are not drawn).${clamped}${silent}${chosen ? ` ${chosen.key}` : ''}`);
}

/** The width of one group's column in ems of the chart's type, a little inside it: `width` px
 * less the plot's margins, shared by `groups`. */
function groupEms(width: number, groups: number): number {
  return (0.95 * (width - labelRoom(MARGIN_LEFT) - MARGIN_RIGHT)) / Math.max(1, groups) / chartFont();
}

/** The smallest error a log axis shows, m: a centimetre, below the sensors' noise and the
 * tables' two decimals. Without it the mission station's whiskers at 4–5 km on the whole set (a
 * flight that keeps its plan, forecast along it to a micrometre) took the axis down to 0.000001,
 * six decades that squashed every box, with labels cut off at the chart's edge. */
const LOG_FLOOR = 0.01;

/** Where a whisker reaches below [`LOG_FLOOR`], a log axis from the floor (a decade below the
 * highest whisker, where every error lies under it) to the highest whisker, lower whiskers clamped
 * to its bottom edge (their tooltips keep the numbers); otherwise the data's own extent. */
function logFloor(data: { whiskerLow: number | null; whiskerHigh: number | null }[]): { domain?: [number, number]; clamp?: boolean } {
  const lows = data.map((d) => d.whiskerLow ?? NaN).filter((v) => v > 0);
  const high = Math.max(...data.map((d) => d.whiskerHigh ?? NaN).filter((v) => v > 0));
  const floor = Math.min(LOG_FLOOR, high / 10);
  if (!lows.length || !(high > 0) || Math.min(...lows) >= floor) return {};
  return { domain: [floor, high], clamp: true };
}

/** Labels only the powers of ten of a log axis, as plain numbers. */
function decade(d: number): string {
  const e = Math.log10(d);
  return Math.abs(e - Math.round(e)) < 1e-9 ? plainNumber(d) : '';
}
