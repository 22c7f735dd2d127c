// The results table's interval header says what its number rests on under the run's plan: the core
// divides the time on air by the plan's duty cycle, listen before talk's share, or time on air over
// the interval set where the plan has none, capped by fair use (AccessSettings::duty_cycle_for).
import { expect, test } from 'vitest';
import { intervalRule } from '../../www/results';
import { DEFAULTS } from '../../www/state';

// With a random delay before each uplink packets leave when the rule allows, not on a sensor step.
const eu = { region: DEFAULTS.region, access: DEFAULTS.access, fairUse: DEFAULTS.fairUse, interval: undefined, dutyCycle: 0.01, sender: DEFAULTS.sender, dutyCycleMode: DEFAULTS.dutyCycleMode, sensorRate: 10, jitter: 1 };

test('EU868 names its duty cycle as set', () => {
  expect(intervalRule(eu)).toBe('Time between packets: time on air divided by the 1 % duty cycle');
  expect(intervalRule({ ...eu, dutyCycle: 0.001 })).toMatch(/the 0\.1 % duty cycle$/);
});

test('a plan without a duty cycle names the interval set, listen before talk its share, fair use its cap', () => {
  expect(intervalRule({ ...eu, region: 'us915', interval: 2.5 })).toBe('Time between packets: the 2.5 s set (US915 has no duty cycle)');
  expect(intervalRule({ ...eu, region: 'us915' })).toMatch(new RegExp(`the ${DEFAULTS.interval} s set`));
  expect(intervalRule({ ...eu, access: 'lbt' })).toMatch(/listen before talk's share of the air \(100 s per hour\)$/);
  expect(intervalRule({ ...eu, fairUse: 'ttn' })).toMatch(/1 % duty cycle, or longer where TTN fair use leaves less airtime$/);
});

test('under error-triggered sending or the budget rule the number is a shortest average, and says so', () => {
  const periodic = { ...eu, sender: 'periodic', dutyCycleMode: 'per-packet' } as const;
  expect(intervalRule(periodic)).toBe('Time between packets: time on air divided by the 1 % duty cycle');
  expect(intervalRule({ ...periodic, sender: 'error' })).toMatch(/duty cycle\. The shortest: error-triggered sending waits longer while the station’s forecast holds$/);
  expect(intervalRule({ ...periodic, dutyCycleMode: 'budget' })).toMatch(/duty cycle\. On average: the budget rule lets saved airtime go sooner, in a burst$/);
});

test('with the paper\'s exact timing packets leave on sensor steps, and the rule rounds up to them', () => {
  const exact = { ...eu, jitter: undefined, clockDrift: 0 };
  expect(intervalRule(exact)).toBe('Time between packets: time on air divided by the 1 % duty cycle, then rounded up to whole sensor steps (0.1 s): a packet carries the estimate of the step it leaves on');
  expect(intervalRule({ ...exact, sensorRate: 1 })).toMatch(/whole sensor steps \(1 s\)/);
  expect(intervalRule({ ...exact, sensorRate: 3 })).toMatch(/whole sensor steps \(0\.333 s\)/);
  expect(intervalRule({ ...exact, clockDrift: 20 })).not.toMatch(/sensor steps/);
  expect(intervalRule({ ...exact, region: 'us915', interval: 2.5 })).toMatch(/US915 has no duty cycle\), then rounded up to whole sensor steps/);
});
