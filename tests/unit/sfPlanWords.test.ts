// The swarm panel's note and slide caption name the SFs the core dealt the drones, and say why
// where "SF7–SF12 in turn" dealt fewer: a lecturer who chose it must not read "all on SF7" unexplained.
import { beforeAll, expect, test } from 'vitest';
import { sfPlanWords } from '../../www/charts/swarm';
import type { SwarmParams } from '../../www/loratrack';
import { api, loadCore } from './core';

beforeAll(loadCore);

const words = (params: SwarmParams) => sfPlanWords(api.swarm({ drones: 6, duration: 60, ...params }));

test('a spread plan names the SFs it dealt, and why where it dealt fewer than it had drones for', () => {
  expect(words({})).toBe('SF7–SF12 in turn');
  expect(words({ drones: 2 })).toBe('SF7–SF8 in turn');
  // Three drones take three SFs whatever the plan carries beyond them: no reason to give.
  expect(words({ drones: 3, region: 'us915', bw: 125 })).toBe('SF7–SF9 in turn');
  expect(words({ region: 'us915', bw: 125 })).toBe('SF7–SF9 in turn (at 125 kHz US915 carries the frame at no other SF)');
  // IN865 has no duty cycle: drones send at the interval set, which SF12's frame outlasts.
  expect(words({ region: 'in865', bw: 125 })).toBe('SF7–SF11 in turn (at 125 kHz a slower SF’s frame outlasts the 1 s interval set)');
  expect(words({ region: 'in865', bw: 125, interval: 2 })).toBe('SF7–SF12 in turn');
  // ADR starts only at an EU868 data rate: at 250 kHz that is SF7's alone.
  expect(words({ adr: 'tracking' })).toBe('all starting on SF7 (at 250 kHz ADR can start at no other SF)');
  expect(words({ adr: 'tracking', bw: 125 })).toBe('SF7–SF12 in turn at the start');
});

test('a fixed plan puts every drone on the chosen SF, where ADR then moves them', () => {
  expect(words({ sfPlan: 'fixed', sf: 9 })).toBe('all on SF9');
  expect(words({ sfPlan: 'fixed', sf: 9, bw: 125, adr: 'lorawan' })).toBe('all starting on SF9');
});
