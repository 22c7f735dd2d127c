// The link budget: why packets stop arriving. Mean received power against distance with the
// shadowing band, each SF's sensitivity as a line, each gateway's distance from the flight's start
// marked; and each SF's
// delivery ratio against distance. The numbers come from the core's linkBudget().
import { chartFrame, chartFont, SF_COLORS, labelRoom } from './colors';
import * as Plot from '@observablehq/plot';
import type { LinkBudgetReport } from '../loratrack';

/** The charts, in the plan's words: only the SFs the plan allows at this bandwidth, each named
 * with its data rate (`SF9 (DR1)`); the note says which the plan lacks. */
export function linkBudgetCharts(r: LinkBudgetReport, opts: { width: number; distances: number[]; sf: number; plan: string; adr?: boolean }): HTMLElement {
  const km = (d: number) => d / 1000;
  const band = r.distances.map((d, i) => ({ d: km(d), lo: r.meanRxDbm[i] - 1.645 * r.shadowing, hi: r.meanRxDbm[i] + 1.645 * r.shadowing, mean: r.meanRxDbm[i] }));
  const shown = r.sfs.filter((s) => s.inPlan);
  const name = (s: LinkBudgetReport['sfs'][number]) => (s.dataRate === null ? `SF${s.sf}` : `SF${s.sf} (DR${s.dataRate})`);
  const chosen = shown.find((s) => s.sf === opts.sf);
  const current = chosen ? name(chosen) : '';
  const sens = shown.map((s) => ({ sf: name(s), dbm: s.sensitivityDbm, range: km(s.rangeM) }));
  const color = { domain: sens.map((s) => s.sf), range: shown.map((s) => SF_COLORS[s.sf - 7]), legend: true };
  const far = km(Math.max(...r.distances));
  const gateways = opts.distances.map((d, i) => ({ d: km(d), label: opts.distances.length > 1 ? `gateway ${i + 1}` : 'gateway distance' }));
  const power = Plot.plot({
    ...chartFrame(240, 440),
    width: opts.width,
    marginLeft: labelRoom(50),
    x: { label: 'distance (km)' },
    y: { label: 'received power (dBm)', grid: true },
    color,
    marks: [
      Plot.areaY(band, { x: 'd', y1: 'lo', y2: 'hi', fill: '#888', fillOpacity: 0.15 }),
      Plot.lineY(band, { x: 'd', y: 'mean', stroke: '#222', strokeWidth: 1.6 }),
      Plot.ruleY(sens, { y: 'dbm', stroke: 'sf', strokeDasharray: '4,3', strokeWidth: (s) => (s.sf === current ? 2.2 : 1) }),
      Plot.ruleX(opts.distances.map(km), { stroke: '#b00020', strokeWidth: 1.5 }),
      // Each label beside its line, on the side away from the curve's steep start (centred on a
      // gateway at 1 km it lay on the curve), and inward near the chart's right end.
      ...(['start', 'end'] as const).map((side) =>
        Plot.text(
          gateways.filter((g) => (g.d < 0.6 * far) === (side === 'start')),
          { x: 'd', text: 'label', frameAnchor: 'top', dy: 6, dx: side === 'start' ? 4 : -4, textAnchor: side, fill: '#b00020', fontSize: chartFont() },
        ),
      ),
    ],
  });
  const curves = shown.flatMap((s) => s.delivery.map((p, i) => ({ d: km(r.distances[i]), p: 100 * p, sf: name(s) })));
  const delivery = Plot.plot({
    ...chartFrame(200, 440),
    width: opts.width,
    marginLeft: labelRoom(50),
    x: { label: 'distance (km)' },
    y: { label: 'packets delivered (%)', domain: [0, 100], grid: true },
    // The chart above shows the SFs' colours; a second legend, the same, only pushed this chart
    // and the ranges under it down (in presentation mode at 1024×768, past the screen).
    color: { ...color, legend: false },
    marks: [
      Plot.lineY(curves, { x: 'd', y: 'p', stroke: 'sf', strokeWidth: (c) => (c.sf === current ? 2.4 : 1.2) }),
      Plot.ruleX(opts.distances.map(km), { stroke: '#b00020', strokeWidth: 1.5 }),
      Plot.tip(curves, Plot.pointerX({ x: 'd', y: 'p', stroke: 'sf', title: (c) => `${c.sf} at ${c.d.toFixed(1)} km: ${c.p.toFixed(0)} % delivered` })),
    ],
  });
  const ranges = document.createElement('p');
  ranges.className = 'note';
  const missing = r.sfs.filter((s) => !s.inPlan).map((s) => `SF${s.sf}`);
  // The power sent and the path-loss exponent set every curve here: the Advanced settings may
  // have changed them, and the form may be a screen away.
  ranges.textContent = `Range (where the mean power, ${r.txPower} dBm sent with a path-loss exponent of ${r.pathLossExponent}, meets the sensitivity): ${sens.map((s) => `${s.sf} ${s.range.toFixed(1)} km`).join(', ')}. Dashed lines: each SF's sensitivity (the chosen SF's bold${opts.adr ? ': where ADR starts the drone, which it then moves' : ''}); ${opts.distances.length > 1 ? 'red lines: each gateway\'s distance' : 'red line: the gateway\'s distance'}; grey band: 90 % of packets (shadowing σ ${r.shadowing} dB).${missing.length ? ` ${opts.plan} has no uplink data rate at ${missing.join(', ')} with this bandwidth.` : ''}`;
  const box = document.createElement('div');
  box.append(power, delivery, ranges);
  return box;
}
