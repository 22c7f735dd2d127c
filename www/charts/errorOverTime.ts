// Paper Fig. "error over time": the station's 3D error on the first flight, with packet arrivals
// (dots on the axis) and lost packets (crosses), over the station's own 95 % bound (dashed band).
import * as Plot from '@observablehq/plot';
import { MODEL_LABELS, type SimReport } from '../loratrack';
import { MODEL_COLORS, chartFrame, chartFont } from './colors';

export function errorOverTimeChart(report: SimReport, width: number): SVGSVGElement | HTMLElement {
  const models = report.series?.models ?? [];
  if (!models.some((m) => m.t.length > 0)) {
    // Nothing arrived on this flight: the station never had an estimate, so there is no error to draw.
    const note = document.createElement('p');
    note.className = 'empty-chart';
    note.textContent = `No packet arrives at this distance on ${report.series?.flight ?? 'this flight'}: the station never has an estimate, so there is no error to plot. Move the gateway closer or raise the spreading factor.`;
    return note;
  }
  const lines = models.flatMap((m) => m.t.map((t, i) => ({ t, e: m.error3d[i], model: MODEL_LABELS[m.model] })));
  const rate = (dr: number | null | undefined) => (dr === null || dr === undefined ? '' : ` at DR${dr}`);
  const arrivals = models.flatMap((m) => m.arrivals.map((t, i) => ({ t, model: MODEL_LABELS[m.model], dr: rate(m.arrivalDr?.[i]) })));
  const lost = models.flatMap((m) => m.lost.map((t, i) => ({ t, model: MODEL_LABELS[m.model], dr: rate(m.lostDr?.[i]) })));
  // With ADR, label each change of data rate above the axis.
  const changes = models.flatMap((m) =>
    m.arrivals
      .map((t, i) => ({ t, dr: m.arrivalDr?.[i], before: i > 0 ? m.arrivalDr?.[i - 1] : undefined, model: MODEL_LABELS[m.model] }))
      .filter((d) => report.config.adr !== 'off' && d.dr !== d.before && d.dr !== null && d.dr !== undefined)
      .map((d) => ({ ...d, label: `DR${d.dr}` })),
  );
  const labels = models.map((m) => MODEL_LABELS[m.model]);
  // The station's own 95 % bound on its error, as a faint band under each model's line.
  const bounds = models.flatMap((m) => m.t.map((t, i) => ({ t, b: m.bound95[i], model: MODEL_LABELS[m.model] })));
  return Plot.plot({
    ...chartFrame(180),
    width,
    marginLeft: 50,
    x: { label: 'time (s)' },
    y: { label: '3D error (m)', grid: true, zero: true },
    color: { domain: labels, range: models.map((m) => MODEL_COLORS[m.model]), legend: true },
    marks: [
      Plot.areaY(bounds, { x: 't', y1: 0, y2: 'b', fill: 'model', fillOpacity: 0.08, curve: 'step-after' }),
      Plot.lineY(bounds, { x: 't', y: 'b', stroke: 'model', strokeOpacity: 0.45, strokeDasharray: '3,3', strokeWidth: 1, curve: 'step-after' }),
      Plot.lineY(lines, { x: 't', y: 'e', stroke: 'model', strokeWidth: 1.4 }),
      Plot.dot(arrivals, { x: 't', y: 0, fill: 'model', r: 2.5, title: (d) => `${d.model}: packet arrived at ${d.t.toFixed(1)} s${d.dr}` }),
      Plot.dot(lost, { x: 't', y: 0, stroke: 'model', symbol: 'times', r: 4, title: (d) => `${d.model}: packet lost at ${d.t.toFixed(1)} s${d.dr}` }),
      Plot.text(changes, { x: 't', y: 0, text: 'label', fill: 'model', dy: -10, fontSize: chartFont() }),
      Plot.ruleY([0]),
      Plot.tip(lines, Plot.pointerX({ x: 't', y: 'e', stroke: 'model' })),
    ],
  });
}
