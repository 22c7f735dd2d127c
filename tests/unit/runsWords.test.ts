// What the verdict under the results table says its intervals rest on.
import { expect, test } from 'vitest';
import { runsWords } from '../../www/results';
import type { SimReport } from '../../www/loratrack';

const report = (runs: (number | null)[], flights = 30, seeds = 1) =>
  ({ config: { flights, seeds }, results: runs.map((n) => ({ ci95: n === null ? null : { runs: n } })) }) as unknown as Pick<SimReport, 'results' | 'config'>;

test('every station over every run: the count alone', () => {
  expect(runsWords(report([30, 30, 30]))).toBe('30 runs');
  expect(runsWords(report([20, 20], 2, 10))).toBe('20 runs');
});

test('where runs without a packet leave stations fewer, the span of what they rest on and why', () => {
  expect(runsWords(report([29, 27, 27]))).toBe('27–29 of 30 runs: a run in which no packet arrived has no errors');
  expect(runsWords(report([28, 28]))).toBe('28 of 30 runs: a run in which no packet arrived has no errors');
});

test('no intervals (one run): nothing to say', () => {
  expect(runsWords(report([null, null], 1, 1))).toBe('');
});
