// Paper Table II (time on air and duty-cycle interval per SF, bandwidth and payload) and time on
// air versus payload size, computed by the Rust core for the current overhead and coding rate.
import { chartFrame, SF_COLORS, withKey, labelRoom } from './colors';
import * as Plot from '@observablehq/plot';
import { MODEL_LABELS, PAYLOAD_BYTES, timeOnAir } from '../loratrack';
import { airtimeRows, PAPER_STATIONS, SFS, type PlanOpts } from '../airtime';
import { percent } from '../format';

/** SF × bandwidth × payload table in the plan's words: each pair's data rate (or that the plan
 * lacks it), and for each payload its time on air and interval, or why the plan refuses it (the
 * core decides). The current SF/bandwidth row is highlighted. */
export function airtimeTable(opts: { overhead: number; cr: number; sf: number; bw: number } & PlanOpts): HTMLTableElement {
  const table = document.createElement('table');
  table.className = 'airtime-table';
  const caption = table.createCaption();
  // The duty cycle the intervals divide by, where the drone keeps one (not with listen before talk).
  const label = `${opts.region.toUpperCase()}${opts.dutyCycle === undefined ? '' : ` at a ${percent(opts.dutyCycle)} duty cycle`}`;
  // What every number rests on besides the plan: the bytes on air and the coding rate, which the
  // form may have changed (the paper's Table II has no overhead). The slide's caption names them
  // with the other settings, so it reads only the first part (`.what`).
  const what = document.createElement('span');
  what.className = 'what';
  what.textContent = `${label}: time on air · shortest interval between packets; refused where the plan does not carry the packet.`;
  const restsOn = document.createElement('span');
  restsOn.className = 'rests-on';
  const bytes = opts.overhead > 0 ? `each payload plus ${opts.overhead} B of LoRaWAN overhead` : 'each payload alone (no LoRaWAN overhead, as the paper\'s Table II)';
  restsOn.textContent = ` ${bytes.charAt(0).toUpperCase()}${bytes.slice(1)}, coding rate 4/${4 + opts.cr}.`;
  caption.append(what, restsOn);
  const head = table.createTHead().insertRow();
  for (const h of ['SF', 'bandwidth', 'data rate', ...PAPER_STATIONS.map((m) => `${PAYLOAD_BYTES[m]} B (${MODEL_LABELS[m]})`)]) {
    const th = document.createElement('th');
    th.textContent = h;
    head.appendChild(th);
  }
  const body = table.createTBody();
  for (const { sf, bw, dataRate, cells } of airtimeRows(opts)) {
    const row = body.insertRow();
    if (sf === opts.sf && bw === opts.bw) row.className = 'current';
    // SF and bandwidth name the row (row headers, kept in view as the table scrolls sideways).
    for (const name of [`SF${sf}`, `${bw} kHz`]) {
      const th = document.createElement('th');
      th.scope = 'row';
      th.textContent = name;
      row.appendChild(th);
    }
    row.insertCell().textContent = dataRate;
    for (const c of cells) {
      const cell = row.insertCell();
      // Two pieces, so that where the table is too wide (`tighten`) the interval goes under the
      // time on air rather than out of sight: presentation mode at 1024×768 cut off 3D-CTRA's.
      const [air, interval] = [`${(c.timeOnAir * 1e3).toFixed(1)} ms ·`, c.interval === null ? 'refused' : `${c.interval.toFixed(2)} s`].map((text) => {
        const piece = document.createElement('span');
        piece.textContent = text;
        return piece;
      });
      cell.append(air, ' ', interval);
      if (c.refused) {
        cell.className = 'refused';
        cell.title = c.refused;
      }
    }
  }
  return table;
}

/** Time on air (ms) against application payload for every SF at the current bandwidth, which
 * its key says. */
export function airtimeVsPayloadChart(opts: { overhead: number; cr: number; sf: number; bw: number; width: number }): SVGSVGElement | HTMLElement {
  const data = SFS.flatMap((sf) =>
    Array.from({ length: 64 }, (_, i) => i + 1).map((payload) => ({
      sf: `SF${sf}`,
      payload,
      ms: timeOnAir({ sf, bw: opts.bw, payload, overhead: opts.overhead, cr: opts.cr }).timeOnAir * 1e3,
    })),
  );
  const ours = PAPER_STATIONS.map((m) => PAYLOAD_BYTES[m]).map((payload) => ({ payload, ms: timeOnAir({ sf: opts.sf, bw: opts.bw, payload, overhead: opts.overhead, cr: opts.cr }).timeOnAir * 1e3 }));
  const chart = Plot.plot({
    // Below the time-on-air table, which fills its presentation screen already: never taller.
    ...chartFrame(300, Infinity),
    width: opts.width,
    marginLeft: labelRoom(55),
    x: { label: 'application payload (bytes)' },
    y: { label: 'time on air (ms)', type: 'log', grid: true },
    color: { legend: true, domain: SFS.map((sf) => `SF${sf}`), range: SFS.map((sf) => SF_COLORS[sf - 7]) },
    marks: [
      Plot.line(data, { x: 'payload', y: 'ms', stroke: 'sf', curve: 'step-after' }),
      Plot.dot(ours, { x: 'payload', y: 'ms', r: 4, fill: 'black', title: (d) => `${d.payload} B at SF${opts.sf}: ${d.ms.toFixed(1)} ms` }),
      Plot.tip(data, Plot.pointer({ x: 'payload', y: 'ms', stroke: 'sf' })),
    ],
  });
  // The lines' bandwidth and the bytes added to each payload, which neither axis says: at 250 kHz
  // SF12's line lies at half the time on air of LoRaWAN's SF12 (EU868's DR0, at 125 kHz).
  const added = opts.overhead > 0 ? ` plus ${opts.overhead} B of LoRaWAN overhead` : '';
  return withKey(chart, `Lines: each SF at ${opts.bw} kHz, the time on air of a payload${added}. Black dots: the models' payloads (9, 11 and 12 B) at SF${opts.sf}, ${opts.bw} kHz.`);
}
