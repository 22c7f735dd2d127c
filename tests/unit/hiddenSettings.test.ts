// The form keeps a setting whose control it hides (the threshold while sending periodically, the
// tilt decay with DR alone), and the core refuses such a setting where nothing would read it: every
// request the form makes must leave those out, whatever was left in the hidden fields.
import { beforeAll, expect, test } from 'vitest';
import { caption, describe } from '../../www/format';
import type { SimulateParams } from '../../www/loratrack';
import { DEFAULTS, MODEL_CHOICES, packetPlan, swarmRequest, toParams } from '../../www/state';
import { decaysTilt } from '../../www/stations';
import { api, loadCore } from './core';

beforeAll(loadCore);

/** Settings with every hidden field changed from its default. */
const leftBehind = { ...DEFAULTS, eta: 0.5, threshold: 5, maxInterval: 30, channelSense: 'off' as const };

test('each station choice runs with every hidden setting changed, sending periodically and on error', () => {
  for (const model of MODEL_CHOICES) {
    for (const sender of ['periodic', 'error'] as const) {
      const params = toParams({ ...leftBehind, model, sender });
      expect(() => api.simulate(params), `${model}, ${sender}`).not.toThrow();
      expect('threshold' in params, `${model}, ${sender}`).toBe(sender === 'error');
    }
  }
});

test('the tilt decay is sent exactly where the core reads it', () => {
  for (const model of MODEL_CHOICES) {
    const withEta = { ...toParams({ ...DEFAULTS, model }), eta: 0.5 };
    const reads = (() => {
      try {
        api.simulate(withEta);
        return true;
      } catch (e) {
        expect(String(e)).toMatch(/eta is 3D-CTRA's/);
        return false;
      }
    })();
    expect(decaysTilt(model), model).toBe(reads);
  }
});

test('the distance is sent exactly where no gateway is listed, which the core reads it for', () => {
  const far = { ...DEFAULTS, model: 'dr' as const, distance: 3000 };
  const listed = toParams({ ...far, gateways: [{ east: 500, north: 0 }] });
  expect('distance' in listed).toBe(false);
  expect(() => api.simulate(listed)).not.toThrow();
  expect(() => api.simulate({ ...listed, distance: 3000 })).toThrow(/distance is where the one default gateway stands/);
  expect(toParams(far).distance).toBe(3000);
});

test('a listen before talk kept under a plan without a duty cycle, which hides the choice, is not sent', () => {
  // Chosen under EU868, then the region changed to US915, where it has no duty cycle to replace.
  const kept = { ...DEFAULTS, sf: 9, bw: 125, access: 'lbt' as const, region: 'us915' as const };
  expect(() => api.simulate(toParams(kept))).not.toThrow();
  expect(() => api.timeOnAir({ sf: 9, bw: 125, payload: 12, ...packetPlan(kept) })).not.toThrow();
  expect(() => api.simulate({ ...toParams(kept), access: 'lbt' })).toThrow(/lbt replaces a duty cycle/);
  // Under EU868 it is sent, and the duty cycle it replaces is not.
  const eu = toParams({ ...kept, region: 'eu868' });
  expect([eu.access, 'dutyCycle' in eu]).toEqual(['lbt', false]);
});

/** Whether the core runs `params` (else the refusal must match `refusal`). */
function runs(params: SimulateParams, refusal: RegExp, what: string): boolean {
  try {
    api.simulate(params);
    return true;
  } catch (e) {
    expect(String(e), what).toMatch(refusal);
    return false;
  }
}

test('an uploaded plan beside a CSV flight, and the vehicle, are sent exactly where the core reads them', () => {
  // A drone flying 300 m east at 5 m/s, 30 m up, and the plan it flew.
  const log = ['t,x,y,z', ...Array.from({ length: 601 }, (_, i) => `${i / 10},${i / 2},0,30`)].join('\n');
  const plan = { text: 'x,y,z\n0,0,30\n300,0,30\n', name: 'route.csv' };
  for (const model of MODEL_CHOICES) {
    for (const prediction of ['paper', 'bounded'] as const) {
      for (const vehicle of ['auto', 'multicopter', 'fixed-wing'] as const) {
        const s = { ...DEFAULTS, flight: 'csv' as const, model, prediction, vehicle };
        const params = { ...toParams(s, { name: 'log.csv' }, plan), trajectory: log };
        const what = `${model}, ${prediction}, ${vehicle}`;
        expect(() => api.simulate(params), what).not.toThrow();
        const withPlan = runs({ ...params, plan: plan.text, vehicle: params.vehicle ?? 'auto' }, /plan is read over a logged flight by the mission station alone/, what);
        expect('plan' in params, what).toBe(withPlan);
        const withVehicle = runs({ ...params, vehicle }, /vehicle is read only where a plan is flown or followed/, what);
        expect('vehicle' in params, what).toBe(withVehicle);
        // The download's caption names a vehicle only where the run reads one.
        expect(/ as a (plane|multicopter);/.test(caption(s)), what).toBe(vehicle !== 'auto' && withVehicle);
      }
    }
  }
});

test('the shadowing model is sent, and named, only where there is shadowing for it to place', () => {
  const none = { ...DEFAULTS, shadowing: 0, shadowingModel: 'field' as const };
  const params = toParams(none);
  expect('shadowingModel' in params).toBe(false);
  expect(() => api.simulate(params)).not.toThrow();
  expect(() => api.simulate({ ...params, shadowingModel: 'field' })).toThrow(/shadowingModel is a shadowing's/);
  expect(describe(none)).not.toMatch(/fixed in space/);
  const some = { ...none, shadowing: 4 };
  expect(toParams(some).shadowingModel).toBe('field');
  expect(describe(some)).toMatch(/shadowing fixed in space/);
});

test('a download caption names the tilt decay only where a station reads it', () => {
  expect(describe({ ...DEFAULTS, model: '3d-ctra', eta: 0.5 })).toMatch(/eta 0\.5/);
  expect(describe({ ...DEFAULTS, model: 'dr', eta: 0.5 })).not.toMatch(/eta/);
});

test('the swarm panel asks the core for nothing its swarms would not read, at every choice of station, sender, SF plan and flight', () => {
  const choices = { drones: 2, channels: 'plan', schedule: 'aloha', duration: 30 } as const;
  for (const model of MODEL_CHOICES) {
    for (const sender of ['periodic', 'error'] as const) {
      for (const sfPlan of ['fixed', 'spread'] as const) {
        for (const flight of ['synthetic', 'canberra', 'csv'] as const) {
          const what = `${model}, ${sender}, ${sfPlan}, ${flight}`;
          const { sizes, params } = swarmRequest({ ...leftBehind, model, sender, flight }, { ...choices, sfPlan });
          expect(sizes, what).toEqual([2, 1]);
          // One station; a list, like the mission station, flies 3D-CTRA's.
          const several = model === 'all' || model.includes(',');
          expect(params.model, what).toBe(several || model === 'mission' ? 'all' : model);
          expect('sf' in params, what).toBe(sfPlan === 'fixed');
          expect('channelSense' in params, what).toBe(sender === 'error');
          expect('duration' in params, what).toBe(flight !== 'canberra');
          // The core refuses a setting a swarm does not read: every request runs.
          expect(() => api.swarm({ ...params, drones: 1 }), what).not.toThrow();
        }
      }
    }
  }
  // 108 swarms (the real flight's 162 s each): seconds on a machine busy with the other suites.
}, 60_000);
