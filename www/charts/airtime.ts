// Paper Table II (time on air and duty-cycle interval per SF, bandwidth and payload) and time on
// air versus payload size, computed by the Rust core for the current overhead and coding rate.
import { chartStyle } from './colors';
import * as Plot from '@observablehq/plot';
import { timeOnAir } from '../loratrack';

const SFS = [7, 8, 9, 10, 11, 12];
const BWS = [125, 250, 500];
const PAYLOADS = [9, 11, 12];

/** SF × bandwidth × payload table; the current SF/bandwidth row is highlighted. */
export function airtimeTable(opts: { overhead: number; cr: number; sf: number; bw: number }): HTMLTableElement {
  const table = document.createElement('table');
  table.className = 'airtime-table';
  const head = table.createTHead().insertRow();
  for (const h of ['SF', 'bandwidth', '9 B (DR)', '11 B (CTRA+)', '12 B (3D-CTRA)']) {
    const th = document.createElement('th');
    th.textContent = h;
    head.appendChild(th);
  }
  const body = table.createTBody();
  for (const sf of SFS) {
    for (const bw of BWS) {
      const row = body.insertRow();
      if (sf === opts.sf && bw === opts.bw) row.className = 'current';
      row.insertCell().textContent = `SF${sf}`;
      row.insertCell().textContent = `${bw} kHz`;
      for (const payload of PAYLOADS) {
        const r = timeOnAir({ sf, bw, payload, overhead: opts.overhead, cr: opts.cr });
        row.insertCell().textContent = `${(r.timeOnAir * 1e3).toFixed(1)} ms · ${r.minInterval.toFixed(2)} s`;
      }
    }
  }
  return table;
}

/** Time on air (ms) against application payload for every SF at the current bandwidth. */
export function airtimeVsPayloadChart(opts: { overhead: number; cr: number; sf: number; bw: number; width: number }): SVGSVGElement | HTMLElement {
  const data = SFS.flatMap((sf) =>
    Array.from({ length: 64 }, (_, i) => i + 1).map((payload) => ({
      sf: `SF${sf}`,
      payload,
      ms: timeOnAir({ sf, bw: opts.bw, payload, overhead: opts.overhead, cr: opts.cr }).timeOnAir * 1e3,
    })),
  );
  const ours = PAYLOADS.map((payload) => ({ payload, ms: timeOnAir({ sf: opts.sf, bw: opts.bw, payload, overhead: opts.overhead, cr: opts.cr }).timeOnAir * 1e3 }));
  return Plot.plot({
    style: chartStyle(),
    width: opts.width,
    height: 300,
    marginLeft: 55,
    x: { label: 'application payload (bytes)' },
    y: { label: 'time on air (ms)', type: 'log', grid: true },
    color: { legend: true, scheme: 'viridis', domain: SFS.map((sf) => `SF${sf}`) },
    marks: [
      Plot.line(data, { x: 'payload', y: 'ms', stroke: 'sf', curve: 'step-after' }),
      Plot.dot(ours, { x: 'payload', y: 'ms', r: 4, fill: 'black', title: (d) => `${d.payload} B at SF${opts.sf}: ${d.ms.toFixed(1)} ms` }),
      Plot.tip(data, Plot.pointer({ x: 'payload', y: 'ms', stroke: 'sf' })),
    ],
  });
}
