// The swarm strip draws a dot per drone with a p75: a drone that received no packet has none. The
// note must count those, not read "4 of 4 drones" for a swarm of 50 whose 46 others were silent.
import { beforeAll, expect, test } from 'vitest';
import { stripCounts } from '../../www/charts/swarm';
import { api, loadCore } from './core';

beforeAll(loadCore);

test('a swarm whose drones all have a p75 counts only the hollow ones, of all', () => {
  expect(stripCounts(50, 50, 0)).toBe('');
  expect(stripCounts(50, 50, 3)).toBe('; 3 of 50 drones (hollow) received too few packets for their own p75 to compare');
});

test('drones that received nothing are counted apart from the hollow ones, as the core reports them', () => {
  // TTN's fair use at SF12: one packet per 4270 s, so in two minutes only the drones whose random
  // start falls early send at all.
  const r = api.swarm({ drones: 50, duration: 120, sf: 12, bw: 125, fairUse: 'ttn', sfPlan: 'fixed' });
  const drawn = r.drones.filter((d) => d.error3d.p75 !== null);
  const silent = r.drones.filter((d) => d.error3d.count === 0).length;
  const thin = drawn.filter((d) => d.caveats.fewPackets).length;
  expect(silent).toBeGreaterThan(0);
  expect(drawn.length).toBeGreaterThan(0);
  expect(stripCounts(r.drones.length, drawn.length, thin)).toBe(`; ${silent} of 50 drones received no packet (no dot)${thin ? ` and ${thin} (hollow) too few for their own p75 to compare` : ''}`);
});
