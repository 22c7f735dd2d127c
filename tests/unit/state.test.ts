// The page's settings and its URL: every shareable view must come back exactly as it was, and a
// link asking for something the core refuses must be explained, never silently used.
import { describe, expect, test } from 'vitest';
import { adrCanStart, DEFAULTS, fromQuery, gatewaysFromText, gatewaysToText, invalid, LIMITS, modelChoiceOf, planAllows, planKnown, sendingLimit, uploaded, simulateRequest, toParams, toQuery, type Settings } from '../../www/state';
import type { Region } from '../../www/loratrack';
import { baselineIsLessons, changedFromLesson, LESSONS, lessonQuery, lessonSettings } from '../../www/lessons';

/** A deterministic stream of settings that differ from the defaults in many ways. */
function* variedSettings(): Generator<Settings> {
  let x = 12345;
  const rand = () => ((x = (x * 1103515245 + 12345) % 2 ** 31) / 2 ** 31);
  const pick = <T>(list: readonly T[]) => list[Math.floor(rand() * list.length)];
  for (let i = 0; i < 200; i++) {
    const sf = pick([7, 8, 9, 10, 11, 12]);
    const bw = pick([125, 250, 500]);
    yield {
      ...DEFAULTS,
      sf,
      bw,
      distance: 100 * Math.ceil(rand() * 100),
      model: pick(['all', 'dr', 'ctra-plus', '3d-ctra', 'imm', 'dr,ctra-plus,3d-ctra,imm'] as const),
      prediction: pick(['paper', 'bounded'] as const),
      sender: pick(['periodic', 'error'] as const),
      threshold: pick([0.5, 2, 7.5]),
      maxInterval: pick([10, 60, 150]),
      dutyCycleMode: pick(['per-packet', 'budget'] as const),
      ...(() => {
        // A plan that has this SF and bandwidth; ADR only in EU868, listen-before-talk only where
        // the plan has a duty cycle.
        const region = pick((['eu868', 'us915', 'au915', 'as923', 'in865'] as Region[]).filter((r) => planAllows(r, sf, bw)));
        const dutyCycled = region === 'eu868' || region === 'as923';
        return {
          adr: region === 'eu868' && adrCanStart(sf, bw) ? pick(['off', 'lorawan', 'tracking'] as const) : 'off',
          region,
          interval: pick([0.5, 1, 30]),
          access: dutyCycled ? pick(['duty-cycle', 'lbt'] as const) : 'duty-cycle',
          dutyCycle: pick([0.01, 0.02, 0.0001, 1]),
          fairUse: pick(['off', 'ttn'] as const),
        };
      })(),
      flight: pick(['synthetic', 'all', 'canberra'] as const),
      flightNumber: 1 + Math.floor(rand() * 30),
      lorawan: rand() < 0.5,
      cr: pick([1, 2, 3, 4]),
      txPower: pick([-10, 0, 14, 20]),
      shadowingModel: pick(['path', 'field'] as const),
      seed: Math.floor(rand() * 1e9),
      seeds: pick([1, 10, 100]),
      gateways: rand() < 0.5 ? [] : [{ east: 5000, north: -250 }, { east: 0, north: 0, height: 30 }],
    };
  }
}

describe('the URL', () => {
  test('carries every setting: a shared link reopens exactly the same settings, with nothing to explain', () => {
    for (const s of variedSettings()) {
      const back = fromQuery(`?${toQuery(s)}`);
      expect(back.problems).toEqual([]);
      expect(back.settings).toEqual(s);
    }
  });

  test('holds only what differs from the defaults', () => {
    expect(toQuery(DEFAULTS)).toBe('');
    expect(toQuery({ ...DEFAULTS, sf: 9 })).toBe('sf=9');
  });

  test('explains and replaces every value the core would refuse', () => {
    const { settings, problems } = fromQuery('?sf=13&bw=300&seeds=0&distance=abc&adr=lorawan&model=nonsense');
    expect(settings.sf).toBe(DEFAULTS.sf);
    expect(settings.bw).toBe(DEFAULTS.bw);
    expect(settings.seeds).toBe(1);
    expect(settings.model).toBe('all');
    expect(problems.join(' ')).toMatch(/sf=13 was replaced by 7: Spreading factor must be/);
    expect(problems.join(' ')).toMatch(/seeds=0 was replaced by 1/);
    expect(problems.join(' ')).toMatch(/model=nonsense was replaced by all/);
    expect(problems.length).toBe(5);
  });

  test('never opens a plan without the SF and bandwidth, or listen-before-talk without a duty cycle, and says why', () => {
    const a = fromQuery('?region=us915&sf=12&bw=125');
    expect(a.settings.region).toBe('eu868');
    expect(a.problems.join(' ')).toMatch(/region=us915 was replaced by eu868: SF12 \/ 125 kHz is not in it. US915 offers only DR0 SF10\/125/);
    const b = fromQuery('?region=in865&sf=7&bw=125&access=lbt');
    expect(b.settings.access).toBe('duty-cycle');
    expect(b.problems.join(' ')).toMatch(/IN865 has none/);
    expect(fromQuery('?region=us915&sf=9&bw=125').problems).toEqual([]);
    expect(toParams({ ...DEFAULTS, region: 'us915', sf: 9, bw: 125, interval: 2 })).toMatchObject({ region: 'us915', interval: 2 });
    // The interval is not sent where the plan has a duty cycle (the core would refuse it).
    expect(toParams({ ...DEFAULTS, interval: 2 })).not.toHaveProperty('interval');
  });

  test('sends the duty cycle only where the drone keeps one: not where the plan has none, nor with listen before talk', () => {
    const twoSubBands = { ...DEFAULTS, dutyCycle: 0.02 };
    expect(toParams(twoSubBands)).toMatchObject({ dutyCycle: 0.02 });
    expect(toParams({ ...twoSubBands, region: 'as923' })).toMatchObject({ dutyCycle: 0.02 });
    expect(toParams({ ...twoSubBands, access: 'lbt' })).not.toHaveProperty('dutyCycle');
    expect(toParams({ ...twoSubBands, region: 'us915', sf: 9, bw: 125 })).not.toHaveProperty('dutyCycle');
    expect(fromQuery('?dutyCycle=0.02').settings.dutyCycle).toBe(0.02);
    const refused = fromQuery('?dutyCycle=2');
    expect(refused.settings.dutyCycle).toBe(DEFAULTS.dutyCycle);
    expect(refused.problems.join(' ')).toMatch(/dutyCycle=2 was replaced by 0.01: Duty cycle must be between 0.0001 and 1/);
  });

  test('opens a link’s model written as the CLI takes it as the page’s choice of the same stations', () => {
    expect(modelChoiceOf('all,imm')).toBe('dr,ctra-plus,3d-ctra,imm');
    expect(modelChoiceOf('IMM, 3d-ctra,DR,ctra-plus')).toBe('dr,ctra-plus,3d-ctra,imm');
    expect(modelChoiceOf('3d-ctra,ctra-plus,dr')).toBe('all');
    expect(modelChoiceOf('mission,3d-ctra')).toBe('3d-ctra,mission');
    // Sets the page does not offer, and names it does not know, are refused.
    expect(modelChoiceOf('imm,dr')).toBeNull();
    expect(modelChoiceOf('dr,kalman')).toBeNull();
    expect(modelChoiceOf(',')).toBeNull();
    const { settings, problems } = fromQuery('?model=all%2Cimm');
    expect(settings.model).toBe('dr,ctra-plus,3d-ctra,imm');
    expect(problems).toEqual([]);
    expect(fromQuery('?model=imm,dr').problems.join(' ')).toMatch(/model=imm,dr was replaced by all: expected one of/);
  });

  test('never opens the mission station without a known plan, and says why', () => {
    const { settings, problems } = fromQuery('?flight=canberra&model=3d-ctra%2Cmission');
    expect(settings.model).toBe('3d-ctra');
    expect(problems.join(' ')).toMatch(/model=3d-ctra,mission was replaced by 3d-ctra: The mission station follows the drone’s flight plan/);
    expect(fromQuery('?flight=all&model=mission').problems).toEqual([]);
  });

  test('never opens ADR where it cannot start, and says why', () => {
    const { settings, problems } = fromQuery('?sf=9&bw=250&adr=tracking');
    expect(settings.adr).toBe('off');
    expect(problems.join(' ')).toMatch(/adr=tracking was replaced by off: ADR starts at an EU868 data rate/);
    expect(fromQuery('?sf=9&bw=125&adr=tracking').settings.adr).toBe('tracking');
  });
});

describe('limits', () => {
  test('come from the core table and say the range in the form’s words', () => {
    expect(LIMITS.seeds).toMatchObject({ min: 1, max: 100, integer: true });
    expect(invalid('seeds', 101)).toBe('Seeds must be between 1 and 100.');
    expect(invalid('seeds', 2.5)).toBe('Seeds must be a whole number.');
    expect(invalid('txPower', NaN)).toMatch(/enter a number/);
    expect(invalid('sf', 12)).toBeNull();
  });

  test('ADR starts only at an EU868 data rate', () => {
    expect([7, 8, 9, 10, 11, 12].every((sf) => adrCanStart(sf, 125))).toBe(true);
    expect([7, 8, 12].map((sf) => adrCanStart(sf, 250))).toEqual([true, false, false]);
    expect(adrCanStart(7, 500)).toBe(false);
  });
});

describe('gateways', () => {
  test('round-trip through their URL text, heights optional', () => {
    const g = [{ east: 5000, north: -250 }, { east: -1.5, north: 2600, height: 30 }];
    expect(gatewaysFromText(gatewaysToText(g))).toEqual(g);
    expect(gatewaysFromText('1,2,3,4')).toBeNull();
    expect(gatewaysFromText('')).toEqual([]);
  });
});

describe('simulate() parameters', () => {
  test('name the flight once and carry the repeats', () => {
    expect(toParams({ ...DEFAULTS, flight: 'all', seeds: 10 })).toMatchObject({ synthetic: 'all', seeds: 10 });
    expect(toParams({ ...DEFAULTS, flight: 'canberra' })).toMatchObject({ sample: 'canberra' });
    const csv = toParams({ ...DEFAULTS, flight: 'csv' }, { name: 'mine.csv' });
    expect(csv).toMatchObject({ trajectoryName: 'mine.csv' });
    expect(csv).not.toHaveProperty('synthetic');
    // The text comes to the worker as the upload's Blob, read there.
    const file = new Blob(['t,x,y,z']);
    const request = simulateRequest(1, { ...DEFAULTS, flight: 'csv' }, { file, name: 'mine.csv' });
    expect(request.trajectoryFile).toBe(file);
    expect(request.params).not.toHaveProperty('trajectory');
    expect(simulateRequest(1, DEFAULTS, { file, name: 'mine.csv' })).not.toHaveProperty('trajectoryFile');
    expect(toParams({ ...DEFAULTS, lorawan: false }).overhead).toBe(0);
    // An uploaded plan goes with its file name, for the command line that reruns the run, where
    // a station reads it (the paper's stations do not: hiddenSettings.test.ts).
    expect(toParams({ ...DEFAULTS, flight: 'csv', model: 'mission' }, { name: 'mine.csv' }, { text: '0,0,10', name: 'mine.plan' })).toMatchObject({ plan: '0,0,10', planName: 'mine.plan' });
    // A plan flown is the flight: no other flight goes with it, and the page knows its plan.
    const flown = toParams({ ...DEFAULTS, flight: 'plan' }, undefined, { text: '0,0,10', name: 'mine.plan' });
    expect(flown).toMatchObject({ plan: '0,0,10', planName: 'mine.plan' });
    for (const other of ['synthetic', 'sample', 'trajectoryName']) expect(flown).not.toHaveProperty(other);
    expect(planKnown('plan', true)).toBe(true);
    expect(planKnown('plan', false)).toBe(false);
    expect((['synthetic', 'all', 'canberra', 'csv', 'plan'] as const).filter(uploaded)).toEqual(['csv', 'plan']);
  });

  test('name what sets how often a drone sends: the interval where the plan has no duty cycle, else listen before talk or the duty cycle', () => {
    expect(sendingLimit({ region: 'eu868', access: 'duty-cycle' })).toBe('dutyCycle');
    expect(sendingLimit({ region: 'eu868', access: 'lbt' })).toBe('lbt');
    expect(sendingLimit({ region: 'us915', access: 'duty-cycle' })).toBe('interval');
    expect(sendingLimit({ region: 'as923', access: 'lbt' })).toBe('lbt');
  });
});

describe('lessons', () => {
  test('a lesson names the settings the form has left, and nothing while it shows its own', () => {
    const crowd = LESSONS.find((l) => l.id === 'crowd-sends-less')!;
    expect(changedFromLesson(crowd, lessonSettings(crowd))).toEqual([]);
    // The lesson's own second step: the paper's drone.
    expect(changedFromLesson(crowd, { ...lessonSettings(crowd), sender: 'periodic', dutyCycleMode: 'per-packet' })).toEqual(['sender', 'dutyCycleMode']);
    // A link typed by hand: ?lesson=crowd-sends-less over the defaults.
    expect(changedFromLesson(crowd, DEFAULTS)).toEqual(['bw', 'prediction', 'sender', 'threshold', 'maxInterval', 'channelSense', 'dutyCycleMode']);
    expect(changedFromLesson(crowd, { ...lessonSettings(crowd), gateways: [{ east: 500, north: 0 }] })).toEqual(['gateways']);
  });

  test("a lesson's baseline counts only when the one pinned has the lesson's settings", () => {
    const adr = LESSONS.find((l) => l.id === 'adr-chases-the-link')!;
    const own = { ...DEFAULTS, ...adr.baseline };
    expect(baselineIsLessons(adr, own)).toBe(true);
    expect(baselineIsLessons(adr, undefined)).toBe(false);
    expect(baselineIsLessons(adr, { ...own, sf: 11 })).toBe(false);
    const wall = LESSONS.find((l) => !l.baseline)!;
    expect(baselineIsLessons(wall, undefined)).toBe(true);
    expect(baselineIsLessons(wall, DEFAULTS)).toBe(true);
  });

  test('each opens a link the page reads back without a problem, baseline included', () => {
    expect(LESSONS.length).toBeGreaterThanOrEqual(5);
    for (const l of LESSONS) {
      const q = new URLSearchParams(lessonQuery(l));
      expect(q.get('lesson')).toBe(l.id);
      const { settings, problems } = fromQuery(`?${q}`);
      expect(problems).toEqual([]);
      expect(settings).toMatchObject(l.settings);
      if (l.baseline) {
        const base = fromQuery(`?${q.get('baseline')}`);
        expect(base.problems).toEqual([]);
        expect(base.settings).toMatchObject(l.baseline);
      }
    }
  });
});
