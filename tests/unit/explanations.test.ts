// The page's "What this shows" texts quote numbers the core gives at stated settings: each is
// computed here and looked for in index.html, so that an explanation cannot drift from the
// simulation it explains. Needs the WebAssembly package (`npm run build`).
import { readFileSync } from 'node:fs';
import { beforeAll, expect, test } from 'vitest';
import type { Prediction } from '../../www/loratrack';
import { api, loadCore } from './core';

/** index.html's text, each run of whitespace one space, so that a sentence may wrap anywhere. */
const page = readFileSync(new URL('../../index.html', import.meta.url), 'utf8').replace(/\s+/g, ' ');

/** Fails, naming `claim` (not the whole page), where the page does not say it. */
const says = (claim: string) => expect(page.includes(claim), `index.html no longer says: ${claim}`).toBe(true);

/** "lo–hi %" of `shares` (0..1) in whole per cent. */
const percentRange = (shares: number[]) => `${(100 * Math.min(...shares)).toFixed(0)}–${(100 * Math.max(...shares)).toFixed(0)} %`;

/** Each station's `underBound95`, how often its error stayed under the error chart's band, over
 * the whole synthetic set with the bounded station. */
const underBand = (model: string, sf: number, bw: number) =>
  api.simulate({ synthetic: 'all', model, prediction: 'bounded', sf, bw }).results.map((m) => m.underBound95 ?? Number.NaN);

beforeAll(loadCore);

test("the error chart's explanation gives how often the bounded station's error stays under its band as the core measures it", () => {
  says(`the bounded station's error stays under its band ${percentRange(underBand('all,imm', 7, 250))} of the time at SF7/250 kHz`);
  // Every slower rate: SF8 and SF9 at both bandwidths, and every rate at 125 kHz.
  const slow = [[7, 125], [8, 250], [8, 125], [9, 250], [9, 125], [10, 125], [11, 125], [12, 125]].map(([sf, bw]) => underBand('all,imm', sf, bw));
  const single = percentRange(slow.flatMap((c) => c.slice(0, 3)));
  const imm = percentRange(slow.map((c) => c[3]));
  says(`DR's, CTRA+'s and 3D-CTRA's ${single} (the IMM's ${imm})`);
}, 60_000);

test("the swarm's explanation gives how much longer a slotted drone waits than its duty cycle asks", () => {
  // The panel's defaults: the form's (3D-CTRA's frame at 250 kHz with LoRaWAN's overhead), SFs in turn.
  const r = api.swarm({ drones: 12, duration: 120, schedule: 'slotted', sfPlan: 'spread' });
  const longer = r.drones.filter((d) => d.sf > 7).map((d) => (d.frameLength ?? Number.NaN) / d.dataRateUse[0].interval - 1);
  says(`(at the defaults with SFs in turn, SF8–SF12 wait ${percentRange(longer)} longer)`);
});

test("the bounded station's explanation gives its gain at 3 km as the core measures it", () => {
  // SF7 / 250 kHz, 3 km, the whole synthetic set over 8 seeds, with and without LoRaWAN's overhead.
  const run = (prediction: Prediction, overhead: number) =>
    api.simulate({ synthetic: 'all', model: '3d-ctra', prediction, distance: 3000, seeds: 8, overhead }).results[0];
  const [paper, bounded, bare, bareBounded] = [run('paper', 13), run('bounded', 13), run('paper', 0), run('bounded', 0)];
  const m = (x: number | null) => (x ?? Number.NaN).toPrecision(3);
  const lost = 1 - (paper.deliveryRatio ?? Number.NaN);
  expect(lost).toBeGreaterThan(0.2);
  expect(lost).toBeLessThan(0.3);
  says(`where about a quarter of the packets are lost, 3D-CTRA's mean error over 8 seeds falls from ${m(paper.error3d.mean)} to ${m(bounded.error3d.mean)} m and its p95 from ${m(paper.error3d.p95)} to ${m(bounded.error3d.p95)} m (without LoRaWAN's overhead, as the paper sends: ${m(bare.error3d.mean)} → ${m(bareBounded.error3d.mean)} m, where the paper reports under 5 m)`);
}, 60_000);
