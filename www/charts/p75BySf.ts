// The classic lesson chart: p75 tracking error against the spreading factor (SF7–SF12 at the
// chosen bandwidth and distance), one line per model. A higher SF reaches further but sends less
// often: at short range the error grows with SF, beyond SF7's range a higher SF is what arrives.
import * as Plot from '@observablehq/plot';
import { MODEL_LABELS, type ModelName, type WholeFlightError } from '../loratrack';
import { CHOSEN_COLUMN, chartFrame, chartFont, NOTE_GREY, fitLabel, MODEL_COLORS, labelRoom, noneSent, withKey } from './colors';
import { counted, trackedPercent } from '../format';
import { logAxis, plainNumber } from './logAxis';

export interface SfRow {
  sf: number;
  model: ModelName;
  /** null where no packet arrived (no error to measure). */
  p75: number | null;
  received: number;
  /** Packets sent: 0 where the drone sent none within the flight (TTN's fair use at a slow SF),
   * which the chart says instead of "none arrives", since no distance mends it. */
  sent?: number;
  /** Too few packets received to compare the stations (the core's `caveats.fewPackets`): drawn
   * hollow, and the note under the chart says so (`fewPacketsNote`). */
  few: boolean;
  /** The share of the flight time after each flight's first packet (all the p75 covers), and
   * whether that is worth saying. */
  wholeFlight: Pick<WholeFlightError, 'tracked' | 'partlyTracked'>;
  /** Not simulated: the core refused this station at this SF (its frame over the plan's dwell
   * time, a heartbeat shorter than the interval, …); the note under the chart says why. */
  refused?: boolean;
}

/** "errors over 62 % of the flight time (before a flight's first packet there is none)". */
function covered({ tracked, partlyTracked }: SfRow['wholeFlight']): string {
  const why = partlyTracked ? ' (before a flight\'s first packet there is none)' : '';
  return `errors over ${trackedPercent(tracked)} % of the flight time${why}`;
}

/** The dots' radius, px. */
const DOT_R = 3.5;

/** `opts.sf` is the chosen SF, where the results table's run is (with ADR, where it starts): a
 * grey column behind it, which the slide's key names, so that a reader finds the table's SF among
 * the six. */
export function p75BySfChart(rows: SfRow[], opts: { bw: number; distance: number; sf: number; width: number; adr?: boolean }): SVGSVGElement | HTMLElement {
  const data = rows.filter((r) => r.p75 !== null && !r.refused).map((r) => ({ ...r, label: MODEL_LABELS[r.model] }));
  const ran = rows.filter((r) => !r.refused);
  if (!data.length) {
    const note = document.createElement('p');
    note.className = 'empty-chart';
    note.textContent = noneSent(ran)
      ? `No packet is sent within the flight at any SF with ${opts.bw} kHz: at these settings the drone sends less often than the flight lasts.`
      : `No packet arrives at ${(opts.distance / 1000).toFixed(1)} km at any SF with ${opts.bw} kHz: move the gateway closer.`;
    return note;
  }
  // The stations in the rows' order (their order everywhere on the page), each with its colour,
  // also where none of its packets arrived at some SF.
  const stations = [...new Set(rows.map((r) => r.model))];
  const models = stations.map((m) => MODEL_LABELS[m]);
  const sfs = [...new Set(rows.map((r) => r.sf))];
  // An SF where no station's packet arrived says so once, as does one the core refused for every
  // station; where only some stations' packets arrived, or the core refused only some stations,
  // each of the others says so by name ("DR: none", "3D-CTRA: refused"), upright from the axis,
  // in the notes' grey (a station's colour would be small text at 3:1 contrast).
  const refusedAt = sfs.filter((sf) => rows.every((r) => r.sf !== sf || r.refused));
  const silent = sfs.filter((sf) => !refusedAt.includes(sf) && !data.some((d) => d.sf === sf));
  const marked = [...refusedAt, ...silent];
  const none = rows
    .filter((r) => r.p75 === null && !marked.includes(r.sf))
    .map((r) => ({ sf: r.sf, label: MODEL_LABELS[r.model], kind: r.refused ? 'refused' : 'none', why: r.refused ? 'not simulated: the note under the chart says why' : r.sent === 0 ? 'no packet sent' : 'no packet arrived' }));
  // The named ones stand beside their SF's dots, not across them (a label centred on the SF ran
  // through a low dot): from just clear of a dot to the right, in the stations' order, and at
  // SF12, the chart's right edge, to the left. Where an SF's labels would reach the next SF's
  // marks (a phone, three stations refused), those of one kind are counted in one: "3 stations:
  // refused".
  const [marginLeft, marginRight] = [labelRoom(56), 20];
  const pxPerSf = (opts.width - marginLeft - marginRight) / 6;
  // A rotated label's box is about 1.25 em across, and Plot's centring of its line moves it 0.32 em
  // to the left, toward the dots it stands right of: 2 px between box and dot.
  const clear = DOT_R + chartFont() * 0.95 + 2;
  const step = chartFont() * 1.35;
  const room = pxPerSf - clear - chartFont() * 1.25;
  const named = sfs.flatMap((sf) => {
    const here = none.filter((d) => d.sf === sf);
    const labels =
      (here.length - 1) * step <= room
        ? here.map((d) => ({ sf, text: `${d.label}: ${d.kind}`, title: `${d.label}, SF${sf}: ${d.why}` }))
        : (['none', 'refused'] as const).flatMap((kind) => {
            const of = here.filter((d) => d.kind === kind);
            const text = of.length === 1 ? `${of[0].label}: ${kind}` : `${of.length} stations: ${kind}`;
            return of.length ? [{ sf, text, title: `${of.map((d) => d.label).join(', ')}, SF${sf}: ${of[0].why}` }] : [];
          });
    return labels.map((l, j) => ({ ...l, x: sf + (sf === 12 ? -(clear + (labels.length - 1 - j) * step) : clear + j * step) / pxPerSf }));
  });
  // "none arrives" stands in two lines on its SF; where an SF's column is narrower than
  // "arrives" (about 4.2 em; 41 px on a phone, where neighbours' ran into one another), upright.
  const upright = pxPerSf < 4.2 * chartFont() + 4;
  const wrap = upright ? ' ' : '\n';
  const km = (opts.distance / 1000).toFixed(1);
  const title = (d: (typeof data)[number]) => `${d.label}, SF${d.sf}: p75 ${d.p75!.toFixed(2)} m over ${counted(d.received, 'packet')}${d.few ? ', too few to compare' : ''}, ${covered(d.wholeFlight)}`;
  const chart = Plot.plot({
    ...chartFrame(220),
    width: opts.width,
    marginLeft,
    marginRight,
    x: { label: fitLabel(opts.width, `spreading factor (${opts.bw} kHz, gateway at ${km} km)`, `spreading factor (${opts.bw} kHz, ${km} km)`, `SF (${opts.bw} kHz, ${km} km)`), domain: [6.5, 12.5], ticks: [7, 8, 9, 10, 11, 12], tickFormat: (d: number) => `SF${d}` },
    y: { label: 'p75 3D error (m, log scale)', type: 'log', grid: true, ...logAxis(data.map((d) => d.p75!)), tickFormat: plainNumber },
    color: { domain: models, range: stations.map((m) => MODEL_COLORS[m]), legend: true },
    marks: [
      Plot.rect([opts.sf], { x1: (d: number) => d - 0.5, x2: (d: number) => d + 0.5, ...CHOSEN_COLUMN }),
      Plot.line(data, { x: 'sf', y: 'p75', stroke: 'label', z: 'label' }),
      Plot.dot(data.filter((d) => !d.few), { x: 'sf', y: 'p75', fill: 'label', r: DOT_R, title }),
      Plot.dot(data.filter((d) => d.few), { x: 'sf', y: 'p75', fill: 'white', stroke: 'label', strokeWidth: 1.5, r: DOT_R, title }),
      Plot.text(silent, { x: (d: number) => d, frameAnchor: 'bottom', dy: -4, text: (d: number) => (noneSent(ran.filter((r) => r.sf === d)) ? `none${wrap}sent` : `none${wrap}arrives`), fill: NOTE_GREY, fontSize: chartFont(), ...(upright ? { rotate: -90, textAnchor: 'start' as const } : {}) }),
      // Upright: side by side, two SFs' "not simulated" ran into each other on a phone.
      Plot.text(refusedAt, { x: (d: number) => d, text: () => 'not simulated', rotate: -90, textAnchor: 'start', frameAnchor: 'bottom', dy: -4, fill: NOTE_GREY, fontSize: chartFont(), title: (d: number) => `SF${d}: not simulated: the note under the chart says why` }),
      Plot.text(named, { x: 'x', text: 'text', rotate: -90, textAnchor: 'start', frameAnchor: 'bottom', dy: -4, fill: NOTE_GREY, fontSize: chartFont(), title: 'title' }),
    ],
  });
  return withKey(chart, `Grey column: SF${opts.sf}, the chosen SF, ${opts.adr ? 'where the results\' run starts before ADR moves it' : 'where the results\' run is'}.`);
}
