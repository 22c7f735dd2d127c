// Plot's code runs for the first time in the page's first chart, the error chart: that drawing
// was one task of 96–120 ms on a cold load (2 cores), 27–49 ms when drawn again. These small
// charts of four points each use the marks, scales, axes, legend and tip that chart uses, one
// group at a time, so that most of the first-run cost is paid in several short tasks (main.ts
// `plots`) instead of one long one; the charts themselves are thrown away.
import * as Plot from '@observablehq/plot';

const rows = [0, 1, 2, 3].map((t) => ({ t, e: t, model: 'a' }));
const frame = { width: 300, height: 100 };

/** Steps that each draw a throw-away chart, to be called in separate tasks before the first real one. */
export const warmUps: (() => unknown)[] = [
  // The frame, linear scales, axes and grid, a grouped line.
  () => Plot.plot({ ...frame, y: { grid: true, nice: true, domain: [0, 3] }, marks: [Plot.lineY(rows, { x: 't', y: 'e', stroke: 'model' }), Plot.ruleY([0])] }),
  // The colour legend, a stepped area and a dashed line, both clipped.
  () =>
    Plot.plot({
      ...frame,
      color: { legend: true, domain: ['a'], range: ['#000'] },
      marks: [
        Plot.areaY(rows, { x: 't', y1: 0, y2: 'e', fill: 'model', fillOpacity: 0.08, curve: 'step-after', clip: true }),
        Plot.lineY(rows, { x: 't', y: 'e', stroke: 'model', strokeDasharray: '3,3', curve: 'step-after', clip: true }),
      ],
    }),
  // Dots with titles, crosses, and text anchored to the frame.
  () =>
    Plot.plot({
      ...frame,
      marks: [
        Plot.dot(rows, { x: 't', y: 0, fill: 'model', r: 2.5, title: (d: (typeof rows)[number]) => d.model }),
        Plot.dot(rows, { x: 't', y: 0, stroke: 'model', symbol: 'times', r: 4 }),
        Plot.text(['a'], { frameAnchor: 'top-right', lineAnchor: 'bottom', dy: -4 }),
      ],
    }),
  // The tip that follows the pointer.
  () => Plot.plot({ ...frame, marks: [Plot.tip(rows, Plot.pointerX({ x: 't', y: 'e', stroke: 'model' }))] }),
];
