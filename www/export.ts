// Downloads: error series and results (CSV), settings and results (JSON), every chart as SVG or
// PNG ready for a slide (title, legend, axis labels, a caption with the settings, seed and
// version; PNGs at least 1600 px wide), and tables as CSV. Everything is made in the page from
// data it already has: no request leaves it.
import type { AirtimeRow } from './airtime';
import { isThinned, type ModelSeries, type SimReport } from './loratrack';

/** What a slide needs besides the chart: a title, a one-line caption of what made it and what
 * the page writes beside the chart (outside its element) that the picture needs, such as the
 * spreading factors it could not simulate. */
export interface SlideText {
  title: string;
  caption: string;
  notes?: string[];
}

/** The narrowest PNG a download gives, px: sharp on a 1080p projector at full width. */
export const MIN_PNG_WIDTH = 1600;

function save(blob: Blob, name: string): void {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  // The browser fetches the file after the click returns; revoked a second later, a busy machine
  // (a phone, a laptop presenting) had not always started to, and the download never came.
  setTimeout(() => URL.revokeObjectURL(a.href), 60_000);
}

const csvCell = (v: string) => (/[",\n]/.test(v) ? `"${v.replace(/"/g, '""')}"` : v);
const csvText = (rows: string[][]) => rows.map((r) => r.map(csvCell).join(',')).join('\n') + '\n';

type Series = Pick<ModelSeries, 'model' | 't' | 'error3d' | 'samples'>;

/** The first flight's error series as CSV rows, header first, and the file's name: one row per
 * evaluation time, one column per model; a flight thinned to its envelope, that envelope stretch
 * by stretch ({@link envelopeRows}). */
export function errorCsv(models: Series[]): { rows: string[][]; name: string } {
  if (models.some(isThinned)) return { rows: envelopeRows(models), name: 'loratrack-error-envelope.csv' };
  const header = ['t_s', ...models.map((m) => `${m.model}_error3d_m`)];
  // Each station starts at its own first packet: join the series on time, empty before it.
  const byTime = new Map<number, string[]>();
  models.forEach((m, k) =>
    m.t.forEach((t, i) => {
      const row = byTime.get(t) ?? models.map(() => '');
      row[k] = m.error3d[i].toFixed(4);
      byTime.set(t, row);
    }),
  );
  const rows = [...byTime.entries()].sort((a, b) => a[0] - b[0]).map(([t, cells]) => [t.toFixed(2), ...cells]);
  return { rows: [header, ...rows], name: 'loratrack-error-series.csv' };
}

/**
 * A flight of more than 3000 evaluation times comes as each station's envelope
 * (`ModelSeries.samples`: the lowest and highest error of each of its runs, at their own times,
 * which differ from station to station). Joined on time, many rows would miss a station's cell
 * (a third of the cells on a 600 s flight); instead the flight is cut into stretches of equal
 * time, as many as the runs (half the kept samples), and each row gives a stretch's first and last
 * kept evaluation time and each station's lowest and highest kept error in it: the same envelope,
 * at that stretch's resolution, with a cell for every station that has started.
 */
function envelopeRows(models: Series[]): string[][] {
  const header = ['t_from_s', 't_to_s', ...models.flatMap((m) => [`${m.model}_min_error3d_m`, `${m.model}_max_error3d_m`])];
  const times = models.flatMap((m) => (m.t.length ? [m.t[0], m.t[m.t.length - 1]] : []));
  const [from, to] = [Math.min(...times), Math.max(...times)];
  const count = Math.max(1, Math.ceil(Math.max(...models.map((m) => m.t.length)) / 2));
  const width = (to - from) / count || 1;
  const stretch = (t: number) => Math.min(count - 1, Math.floor((t - from) / width));
  // Per stretch: its first and last kept time, and each station's lowest and highest error.
  const first = new Array<number>(count).fill(Infinity);
  const last = new Array<number>(count).fill(-Infinity);
  const lows = models.map(() => new Array<number>(count).fill(Infinity));
  const highs = models.map(() => new Array<number>(count).fill(-Infinity));
  models.forEach((m, k) =>
    m.t.forEach((t, i) => {
      const s = stretch(t);
      [first[s], last[s]] = [Math.min(first[s], t), Math.max(last[s], t)];
      lows[k][s] = Math.min(lows[k][s], m.error3d[i]);
      highs[k][s] = Math.max(highs[k][s], m.error3d[i]);
    }),
  );
  const rows: string[][] = [];
  for (let s = 0; s < count; s++) {
    if (first[s] > last[s]) continue;
    const cells = models.flatMap((_, k) => (lows[k][s] <= highs[k][s] ? [lows[k][s].toFixed(4), highs[k][s].toFixed(4)] : ['', '']));
    rows.push([first[s].toFixed(2), last[s].toFixed(2), ...cells]);
  }
  return [header, ...rows];
}

/** Saves the first flight's error series ({@link errorCsv}). */
export function downloadErrorCsv(report: SimReport): void {
  const { rows, name } = errorCsv(report.series?.models ?? []);
  save(new Blob([csvText(rows)], { type: 'text/csv' }), name);
}

/** One row per station: the numbers of the results table, unrounded, with the 95 % intervals,
 * and what made them: the settings in words (the charts' caption) and a link that opens the page
 * at them, in each row so that rows pasted beside another run's keep theirs.
 * `time_on_air_s` and `interval_s` are the starting rate's; the `_mean_s` columns average over the
 * packets sent and the `_min_s` / `_max_s` ones span the data rates used, as the table's cells
 * show them where ADR moved the rate; `sent_every_s` is the mean time between the packets sent
 * (the core's `sentEvery`, empty where no flight sent two), whether or not the table shows it.
 * `lowest_p75_model` and the `p75_over_lowest` columns are the verdict's: this station's p75 over
 * the lowest one's and its interval with the same runs resampled for both (the core's
 * `p75VsLowest`, empty for the lowest itself and where there is nothing to pair).
 * `too_few_packets` and `silence_after_loss` are the notes under the table (the core's caveats),
 * true or false: a spreadsheet sorted by p75 keeps them; `saturated_packets` the received packets
 * that carried a value beyond the payload's range and `saturated_fields` those fields' names
 * (`omega psi`), the saturated note's. */
export function downloadResultsCsv(report: SimReport, made: { settings: string; link: string; command: string }): void {
  const header = ['model', 'payload_bytes', 'time_on_air_s', 'interval_s', 'packets_sent', 'packets_received', 'delivery_ratio', 'mean_m', 'p50_m', 'p75_m', 'p75_lo_m', 'p75_hi_m', 'lowest_p75_model', 'p75_over_lowest', 'p75_over_lowest_lo', 'p75_over_lowest_hi', 'p95_m', 'max_m', 'samples', 'tracked_share', 'runs', 'coverage95', 'under_bound95', 'nees', 'charge_per_uplink_mC', 'lean_packets', 'lean_time_on_air_s', 'lean_interval_s', 'time_on_air_mean_s', 'time_on_air_min_s', 'time_on_air_max_s', 'interval_mean_s', 'interval_min_s', 'interval_max_s', 'sent_every_s', 'too_few_packets', 'silence_after_loss', 'saturated_packets', 'saturated_fields', 'settings', 'link', 'command'];
  const n = (v: number | null | undefined) => (v === null || v === undefined ? '' : String(v));
  const span = (values: number[]) => (values.length ? [n(Math.min(...values)), n(Math.max(...values))] : ['', '']);
  const rows = report.results.map((m) => [m.model, n(m.payloadBytes), n(m.timeOnAir), n(m.interval), n(m.packetsSent), n(m.packetsReceived), n(m.deliveryRatio), n(m.error3d.mean), n(m.error3d.p50), n(m.error3d.p75), n(m.ci95?.p75[0]), n(m.ci95?.p75[1]), m.p75VsLowest?.lowest ?? '', n(m.p75VsLowest?.ratio), n(m.p75VsLowest?.interval[0]), n(m.p75VsLowest?.interval[1]), n(m.error3d.p95), n(m.error3d.max), n(m.error3d.count), n(m.wholeFlight.tracked), n(m.ci95?.runs ?? 1), n(m.coverage95), n(m.underBound95), n(m.nees), n(m.energy.chargePerUplink), n(m.leanPackets), n(m.leanFrame?.timeOnAir), n(m.leanFrame?.interval), n(m.meanTimeOnAir), ...span(m.dataRateUse.map((u) => u.timeOnAir)), n(m.meanInterval), ...span(m.dataRateUse.map((u) => u.interval)), n(m.sentEvery), String(m.caveats.fewPackets), String(m.caveats.silenceAfterLoss), n(m.caveats.saturatedPackets), m.caveats.saturated.join(' '), made.settings, made.link, made.command]);
  save(new Blob([csvText([header, ...rows])], { type: 'text/csv' }), 'loratrack-results.csv');
}

/** The time-on-air table as CSV, one row per SF, bandwidth and payload, its numbers in seconds as
 * the core gives them (the table rounds them): `interval_s` empty and `refused` the plan's reason
 * where the plan does not carry the packet; `settings` the ones the table follows, in words. */
export function downloadAirtimeCsv(rows: AirtimeRow[], settings: string): void {
  const header = ['sf', 'bandwidth_khz', 'data_rate', 'payload_bytes', 'model', 'time_on_air_s', 'interval_s', 'refused', 'settings'];
  const body = rows.flatMap((r) => r.cells.map((c) => [String(r.sf), String(r.bw), r.dataRate, String(c.payload), c.station, String(c.timeOnAir), c.interval === null ? '' : String(c.interval), c.refused ?? '', settings]));
  save(new Blob([csvText([header, ...body])], { type: 'text/csv' }), 'loratrack-time-on-air.csv');
}

/** Configuration and results, without the bulky series; `command` the CLI's command line that
 * gives the same results. */
export function downloadJson(report: SimReport, settings: unknown, command?: string): void {
  const { series: _series, ...rest } = report;
  save(new Blob([JSON.stringify({ settings, command, ...rest }, null, 2)], { type: 'application/json' }), 'loratrack-results.json');
}

/** The chart's own drawings, top to bottom: every SVG but a legend's small swatches. */
export function chartSvgs(chart: Element): SVGSVGElement[] {
  if (chart instanceof SVGSVGElement) return [chart];
  return [...chart.querySelectorAll('svg')].filter((s) => !isSwatch(s) && !s.parentElement?.closest('svg'));
}

/** The chart itself: the largest SVG (a figure also holds the legend's small swatches). */
export function chartSvg(chart: Element): SVGSVGElement | null {
  const area = (s: SVGSVGElement) => Number(s.getAttribute('width') ?? 0) * Number(s.getAttribute('height') ?? 0);
  return chartSvgs(chart).reduce<SVGSVGElement | null>((best, s) => (!best || area(s) > area(best) ? s : best), null);
}

/** Plot draws a legend as HTML: one `<span class="plot-…-swatch">` per entry, each a small SVG
 * square and its label. */
const isSwatch = (svg: SVGSVGElement) => /-swatch\b/.test(svg.parentElement?.getAttribute('class') ?? '');

/** A legend's entries: colour and label, each once (were two charts in a panel to draw the same
 * legend, the slide would draw it once). */
function legendOf(chart: Element): { color: string; label: string }[] {
  const entries = [...chart.querySelectorAll('svg')].filter(isSwatch).map((svg) => ({
    color: svg.getAttribute('fill') ?? svg.querySelector('rect')?.getAttribute('fill') ?? '#888',
    label: (svg.parentElement?.textContent ?? '').trim(),
  }));
  return entries.filter((e, i) => entries.findIndex((f) => f.label === e.label && f.color === e.color) === i);
}

/** The index of the first of `parts` that the legend's swatches come before, as on the page the
 * legend stands above it: 0 for a chart under its legend; 1 for the swarm panel, whose legend
 * names the SFs of its strip of p75s, under the collision chart it does not describe (on a slide
 * with the legend at the top the collision chart's blue dots seemed to be an SF). 0 where no
 * part follows a swatch. */
function legendAbove(chart: Element, parts: SVGSVGElement[]): number {
  const swatches = [...chart.querySelectorAll('svg')].filter(isSwatch);
  const after = parts.findIndex((part) => swatches.some((s) => s.compareDocumentPosition(part) & Node.DOCUMENT_POSITION_FOLLOWING));
  return Math.max(0, after);
}

/** What a slide writes under the chart: its key (`withKey` in `charts/colors.ts`: what the dots,
 * crosses, bands and whiskers mean) and what the page writes under it (the link budget's ranges,
 * the swarm's numbers). */
function notesOf(chart: Element): string[] {
  const keyed = chart.matches('[data-key]') ? chart : chart.querySelector('[data-key]');
  const notes = [...chart.querySelectorAll('.note')].map((n) => n.textContent ?? '');
  return [keyed?.getAttribute('data-key') ?? '', ...notes].map((n) => n.replace(/\s+/g, ' ').trim()).filter(Boolean);
}

const SVG_NS = 'http://www.w3.org/2000/svg';
const FONT = 'system-ui, -apple-system, "Segoe UI", sans-serif';

function text(x: number, y: number, content: string, size: number, attrs: Record<string, string> = {}): SVGTextElement {
  const t = document.createElementNS(SVG_NS, 'text');
  t.setAttribute('x', String(x));
  t.setAttribute('y', String(y));
  t.setAttribute('font-size', String(size));
  t.setAttribute('font-family', FONT);
  for (const [k, v] of Object.entries(attrs)) t.setAttribute(k, v);
  t.textContent = content;
  return t;
}

/** The width of `content` in the slides' font at `size` px (`weight` as CSS's), px, as the page's
 * canvas measures it: estimated at 8 px a character of 14 px type, a legend's "CTRA+" was 49 px
 * wide, not 40, and left 4 px before the next swatch instead of 13. Where there is no canvas (a
 * unit test), about 0.57 em a character. */
function textWidth(content: string, size: number, weight = 'normal'): number {
  measurer ??= typeof document === 'undefined' ? null : document.createElement('canvas').getContext('2d');
  if (!measurer) return content.length * size * 0.57;
  measurer.font = `${weight} ${size}px ${FONT}`;
  return measurer.measureText(content).width;
}
let measurer: CanvasRenderingContext2D | null | undefined;

/** Whether a line fits in `width` px at `size` px (`weight`): a test for [`wrap`]. */
const fitsIn =
  (width: number, size: number, weight?: string) =>
  (line: string): boolean =>
    textWidth(line, size, weight) <= width;

/** Where a slide's legend entries go, left to right in rows from `left` to `right`: each entry
 * `widths[i]` wide (its swatch and label), `gap` after it; an entry that would pass `right` starts
 * the next row (unless it is a row's first: one too wide for any row stands alone). */
export function legendPlaces(widths: number[], left: number, right: number, gap: number): { x: number; row: number }[] {
  let [x, row] = [left, 0];
  return widths.map((width) => {
    if (x > left && x + width > right) [x, row] = [left, row + 1];
    const place = { x, row };
    x += width + gap;
    return place;
  });
}

/** Draws `legend` into `out` from `top` down, its entries in rows between `left` and `right`;
 * returns where the next drawing starts, px. */
function drawLegend(out: SVGSVGElement, legend: { color: string; label: string }[], top: number, left: number, right: number): number {
  const places = legendPlaces(
    legend.map(({ label }) => 17 + textWidth(label, 14)),
    left,
    right,
    13,
  );
  legend.forEach(({ color, label }, i) => {
    const { x, row } = places[i];
    const swatch = document.createElementNS(SVG_NS, 'rect');
    for (const [k, v] of Object.entries({ x: String(x), y: String(top + 22 * row + 3), width: '12', height: '12', fill: color })) swatch.setAttribute(k, v);
    out.append(swatch, text(x + 17, top + 22 * row + 14, label, 14, { fill: '#1b1f24' }));
  });
  return top + 22 * places[places.length - 1].row + 26;
}

/** The distance between two lines of a slide's title, px (its type is 20 px). */
const TITLE_LINE = 24;

/** One standalone SVG for a slide: title, the chart(s) stacked with the legend above the one it
 * stands above on the page, and the caption. */
export function slideSvg(chart: Element, slide: SlideText): SVGSVGElement | null {
  const parts = chartSvgs(chart);
  if (!parts.length) return null;
  const pad = 16;
  const width = Math.max(...parts.map((p) => p.getBoundingClientRect().width || Number(p.getAttribute('width')) || 600)) + 2 * pad;
  const out = document.createElementNS(SVG_NS, 'svg');
  out.setAttribute('xmlns', SVG_NS);
  const background = document.createElementNS(SVG_NS, 'rect');
  background.setAttribute('width', '100%');
  background.setAttribute('height', '100%');
  background.setAttribute('fill', 'white');
  out.append(background);
  // The title wraps at the slide's width too: a phone's swarm slide, 356 px wide, cut "Swarm:
  // many drones, one gateway" off after "gate".
  const title = wrap(slide.title, fitsIn(width - 2 * pad, 20, '600'));
  title.forEach((line, i) => out.append(text(pad, pad + 18 + TITLE_LINE * i, line, 20, { 'font-weight': '600', fill: '#1b1f24' })));
  let y = pad + 30 + TITLE_LINE * (title.length - 1);
  const legend = legendOf(chart);
  const legendAt = legendAbove(chart, parts);
  parts.forEach((part, index) => {
    if (index === legendAt && legend.length) y = drawLegend(out, legend, y, pad, width - pad);
    const clone = part.cloneNode(true) as SVGSVGElement;
    const w = part.getBoundingClientRect().width || Number(part.getAttribute('width'));
    const h = part.getBoundingClientRect().height || Number(part.getAttribute('height'));
    if (!clone.getAttribute('viewBox')) clone.setAttribute('viewBox', `0 0 ${part.getAttribute('width') ?? w} ${part.getAttribute('height') ?? h}`);
    clone.setAttribute('x', String(pad));
    clone.setAttribute('y', String(y));
    clone.setAttribute('width', String(w));
    clone.setAttribute('height', String(h));
    clone.removeAttribute('style');
    out.append(clone);
    y += h + 8;
  });
  // The chart's notes, then the caption, wrap at the chart's width; a gap between them.
  const below = linesBelow([...notesOf(chart), ...(slide.notes ?? [])], slide.caption, fitsIn(width - 2 * pad, 12));
  for (const { lines, fill } of below.slice(0, -1)) {
    lines.forEach((line, i) => out.append(text(pad, y + 14 + 16 * i, line, 12, { fill })));
    y += 16 * lines.length + 6;
  }
  const { lines, fill } = below[below.length - 1];
  lines.forEach((line, i) => out.append(text(pad, y + 14 + 16 * i, line, 12, { fill })));
  const height = y + 14 + 16 * (lines.length - 1) + pad;
  out.setAttribute('width', String(Math.ceil(width)));
  out.setAttribute('height', String(Math.ceil(height)));
  out.setAttribute('viewBox', `0 0 ${Math.ceil(width)} ${Math.ceil(height)}`);
  return out;
}

/**
 * A table as the page shows it, drawn as an SVG for a slide (through [`slideSvg`]): its header and
 * rows in columns, a cell's lines (a p75 with its interval below) one under another, the columns
 * of row headers (the results' model; the time on air's SF and bandwidth) bold and left-aligned
 * and the numbers right-aligned, the highlighted row shaded as on the page (the lowest p75 green,
 * the current data rate yellow), a refused cell red. Its `<caption>` is left to the slide's
 * caption. Column widths follow the longest line, measured in the type it is drawn in.
 * Where the page shows a table in parts, one under another (the results' tracking error and its
 * link where one table would not fit), so does the slide: each later part under its caption.
 */
export function tableSvg(...tables: HTMLTableElement[]): SVGSVGElement {
  const out = document.createElementNS(SVG_NS, 'svg');
  out.setAttribute('xmlns', SVG_NS);
  let [width, y] = [0, 0];
  tables.forEach((table, i) => {
    if (i > 0) {
      y += TABLE_LINE;
      out.append(text(TABLE_PAD, y + TABLE_LINE - 4, table.caption?.textContent?.trim() ?? '', TABLE_SIZE - 1, { fill: '#3a3f45' }));
      y += TABLE_LINE + TABLE_PAD / 2;
    }
    const drawn = drawTable(table, out, y);
    width = Math.max(width, drawn.width);
    y = drawn.bottom;
  });
  out.setAttribute('width', String(Math.ceil(width)));
  out.setAttribute('height', String(Math.ceil(y + 1)));
  return out;
}

const TABLE_SIZE = 13;
const TABLE_LINE = 17;
const TABLE_PAD = 8;

/** Draws `table`'s header and rows into `out` from `top` down ([`tableSvg`]); its width and the
 * bottom of its last rule. */
function drawTable(table: HTMLTableElement, out: SVGSVGElement, top: number): { width: number; bottom: number } {
  const SIZE = TABLE_SIZE;
  const LINE = TABLE_LINE;
  const PAD = TABLE_PAD;
  // As read on the page: innerText keeps a block's line break (the p75's interval); what is there
  // for screen readers alone ("lower than the baseline") is left out.
  const linesOf = (cell: Element) =>
    [...cell.querySelectorAll('.visually-hidden')]
      .reduce((t, hidden) => t.replace((hidden.textContent ?? '').trim(), ''), cell instanceof HTMLElement && cell.closest('tbody') ? cell.innerText : (cell.textContent ?? ''))
      .split('\n')
      // Runs of white space become one space; a thin space (between a difference's arrow and
      // its number) stays as drawn.
      .map((l) => l.replace(/[^\S\u2009]+/g, ' ').trim())
      .filter(Boolean);
  // A difference against the baseline keeps its colour (better green, worse red), as on the page.
  const deltaOf = (cell: Element) => {
    const d = cell.querySelector('.delta');
    const colour = d?.classList.contains('better') ? '#1b7a2b' : d?.classList.contains('worse') ? '#b00020' : '#5a6068';
    return d ? { text: linesOf(d).join(' '), colour } : undefined;
  };
  const shadeOf = (row: HTMLTableRowElement) => (row.closest('thead') ? '#f6f7f9' : row.classList.contains('best') ? '#e8f5e9' : row.classList.contains('current') ? '#fff7d6' : undefined);
  const rows = [...table.rows]
    .filter((row) => row.closest('thead, tbody'))
    .map((row) => ({
      head: !!row.closest('thead'),
      shade: shadeOf(row),
      cells: [...row.cells].map(linesOf),
      deltas: [...row.cells].map(deltaOf),
      refused: [...row.cells].map((c) => c.classList.contains('refused')),
    }));
  const columns = Math.max(...rows.map((r) => r.cells.length));
  // Columns of row headers, as the first row of the body has them.
  const named = [...(table.tBodies[0]?.rows[0]?.cells ?? [])].map((c) => c.tagName === 'TH');
  // Each column as wide as its widest line, measured in the type it is drawn in (a header's and a
  // row header's bold, a second line's smaller).
  const widths = Array.from({ length: columns }, (_, c) => PAD * 2 + Math.max(1, ...rows.flatMap((r) => (r.cells[c] ?? []).map((l, i) => textWidth(l, i > 0 ? SIZE - 2 : SIZE, r.head || named[c] ? '600' : 'normal')))));
  const width = widths.reduce((a, b) => a + b, 0);
  let y = top;
  for (const row of rows) {
    const height = PAD + LINE * Math.max(1, ...row.cells.map((c) => c.length));
    if (row.shade) {
      const shade = document.createElementNS(SVG_NS, 'rect');
      for (const [k, v] of Object.entries({ x: '0', y: String(y), width: String(width), height: String(height), fill: row.shade })) shade.setAttribute(k, v);
      out.append(shade);
    }
    let x = 0;
    row.cells.forEach((lines, c) => {
      const left = named[c];
      const fill = row.refused[c] ? '#a40000' : '#1b1f24';
      lines.forEach((line, i) => {
        const t = text(left ? x + PAD : x + widths[c] - PAD, y + PAD / 2 + LINE * (i + 1) - 4, line, i > 0 ? SIZE - 2 : SIZE, { fill: i > 0 ? '#5a6068' : fill, 'text-anchor': left ? 'start' : 'end', ...(row.head || left ? { 'font-weight': '600' } : {}) });
        const delta = i === 0 ? row.deltas[c] : undefined;
        if (delta && line.endsWith(delta.text)) colourTail(t, delta);
        out.append(t);
      });
      x += widths[c];
    });
    y += height;
    const rule = document.createElementNS(SVG_NS, 'line');
    for (const [k, v] of Object.entries({ x1: '0', x2: String(width), y1: String(y), y2: String(y), stroke: '#d8dde3' })) rule.setAttribute(k, v);
    out.append(rule);
  }
  return { width, bottom: y };
}

/** Splits `t`'s text so that its last `tail.text` is a tspan of its own, in `tail.colour`. */
function colourTail(t: SVGTextElement, tail: { text: string; colour: string }): void {
  const line = t.textContent ?? '';
  const head = document.createElementNS(SVG_NS, 'tspan');
  head.textContent = line.slice(0, line.length - tail.text.length);
  const coloured = document.createElementNS(SVG_NS, 'tspan');
  coloured.setAttribute('fill', tail.colour);
  coloured.textContent = tail.text;
  t.replaceChildren(head, coloured);
}

/** What a slide writes under its picture, each block wrapped by `fits` with its colour: the
 * notes (its key, what the page writes beside it) in grey, then the caption, darker. */
function linesBelow(notes: string[], caption: string, fits: (text: string) => boolean): { lines: string[]; fill: string }[] {
  return [...notes.filter(Boolean).map((n) => ({ lines: wrap(n, fits), fill: '#5a6068' })), { lines: wrap(caption, fits), fill: '#3a3f45' }];
}

/** A number ending a word and a unit after it (`95 %`, `13 B`, `1.0 km`, `250 kHz,`): the space
 * between them is no place to break a line. */
const NUMBER_END = /\d$/;
const UNIT = /^(%|[A-Za-zµ°Ω]{1,3})[),.;:]?$/;

/** `line`'s words, each number kept with the unit after it (a slide that wraps "95" and "%" onto
 * two lines reads as a typo). */
export function unbreakable(line: string): string[] {
  const groups: string[] = [];
  for (const word of line.split(' ')) {
    const last = groups.length - 1;
    if (last >= 0 && NUMBER_END.test(groups[last]) && UNIT.test(word)) groups[last] += ` ${word}`;
    else groups.push(word);
  }
  return groups;
}

/** `line` broken at spaces into the longest lines that `fits` (a word that does not fit alone
 * stands alone), never between a number and its unit ([`unbreakable`]): by characters in an SVG,
 * by measured width on a canvas. */
export function wrap(line: string, fits: (text: string) => boolean): string[] {
  const out: string[] = [];
  let current = '';
  for (const word of unbreakable(line)) {
    const next = current ? `${current} ${word}` : word;
    if (current && !fits(next)) {
      out.push(current);
      current = word;
    } else current = next;
  }
  return [...out, current];
}

const serialize = (svg: SVGSVGElement) => new XMLSerializer().serializeToString(svg);

/** Saves the slide SVG; false when the chart has nothing drawn to save. */
export function downloadSvg(chart: Element, name: string, slide: SlideText): boolean {
  const svg = slideSvg(chart, slide);
  if (!svg) return false;
  save(new Blob([serialize(svg)], { type: 'image/svg+xml' }), `${name}.svg`);
  return true;
}

/** The slide pictures being decoded for a PNG, held until they load or fail: nothing else
 * refers to them while the browser decodes. */
const decoding = new Set<HTMLImageElement>();

/** Encodes `canvas` as `name`.png and saves it; `failed` is told why where the browser makes no
 * file, which would otherwise end the download without a word. */
function savePng(canvas: HTMLCanvasElement, name: string, failed: (why: string) => void): void {
  canvas.toBlob((b) => (b ? save(b, `${name}.png`) : failed('The PNG could not be made: the browser encoded no image. The SVG download holds the same slide.')));
}

/** Saves the slide as a PNG at least [`MIN_PNG_WIDTH`] px wide (2× or more); false when the
 * chart has nothing drawn to save. The picture is drawn once the browser has decoded the slide's
 * SVG; `failed` is told why where it cannot. */
export function downloadPng(chart: Element, name: string, slide: SlideText, failed: (why: string) => void): boolean {
  const svg = slideSvg(chart, slide);
  if (!svg) return false;
  const width = Number(svg.getAttribute('width'));
  const height = Number(svg.getAttribute('height'));
  const scale = Math.max(2, MIN_PNG_WIDTH / width);
  const img = new Image();
  const url = URL.createObjectURL(new Blob([serialize(svg)], { type: 'image/svg+xml' }));
  const done = () => {
    decoding.delete(img);
    URL.revokeObjectURL(url);
  };
  img.onload = () => {
    done();
    const canvas = document.createElement('canvas');
    canvas.width = Math.ceil(width * scale);
    canvas.height = Math.ceil(height * scale);
    const ctx = canvas.getContext('2d')!;
    ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
    savePng(canvas, name, failed);
  };
  img.onerror = () => {
    done();
    failed('The PNG could not be made: the browser could not draw the slide. The SVG download holds the same slide.');
  };
  decoding.add(img);
  img.src = url;
  return true;
}

/** Saves a rendered picture (the 3D view), drawn at `scale` device pixels per CSS pixel, with
 * the slide's title and legend above and its key (`notes`) and caption below, wrapped at the
 * picture's width. */
export function downloadPicturePng(picture: HTMLCanvasElement, scale: number, name: string, slide: SlideText, legend: { color: string; label: string }[], notes: string[], failed: (why: string) => void): void {
  const px = (v: number) => v * scale;
  const pad = px(16);
  const canvas = document.createElement('canvas');
  const ctx = canvas.getContext('2d')!;
  canvas.width = picture.width + 2 * pad;
  const title = wrap(slide.title, fitsIn(picture.width, px(20), '600'));
  // The legend's entries in rows within the picture's width, as a chart's slide places them (on a
  // phone the 3D view's seven entries ran off the picture's right edge in one row after "DR").
  const places = legendPlaces(
    legend.map(({ label }) => px(17) + textWidth(label, px(14))),
    pad,
    pad + picture.width,
    px(13),
  );
  const rows = places.length ? places[places.length - 1].row + 1 : 0;
  const top = pad + px(30) + px(TITLE_LINE) * (title.length - 1) + (rows ? px(26) + px(22) * (rows - 1) : 0);
  const below = linesBelow(notes, slide.caption, fitsIn(picture.width, px(12)));
  const lineHeight = px(16);
  canvas.height = top + picture.height + below.reduce((h, b) => h + b.lines.length * lineHeight + px(6), 0) + pad;
  ctx.fillStyle = 'white';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = '#1b1f24';
  ctx.font = `600 ${px(20)}px ${FONT}`;
  title.forEach((line, i) => ctx.fillText(line, pad, pad + px(18) + px(TITLE_LINE) * i));
  const legendTop = pad + px(TITLE_LINE) * (title.length - 1);
  ctx.font = `${px(14)}px ${FONT}`;
  for (const [i, { color, label }] of legend.entries()) {
    const { x, row } = places[i];
    const y = legendTop + px(22) * row;
    ctx.fillStyle = color;
    ctx.fillRect(x, y + px(33), px(12), px(12));
    ctx.fillStyle = '#1b1f24';
    ctx.fillText(label, x + px(17), y + px(44));
  }
  ctx.drawImage(picture, pad, top);
  ctx.font = `${px(12)}px ${FONT}`;
  let y = top + picture.height;
  for (const { lines, fill } of below) {
    ctx.fillStyle = fill;
    for (const line of lines) ctx.fillText(line, pad, (y += lineHeight));
    y += px(6);
  }
  savePng(canvas, name, failed);
}

