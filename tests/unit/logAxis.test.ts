// The log axes label their ticks as numbers a reader can read the lines off.
import { expect, test } from 'vitest';
import { logAxis, plainNumber } from '../../www/charts/logAxis';

test('a range of two decades is labelled at 1, 2 and 5 of each and rounded out to labels', () => {
  expect(logAxis([1.18, 3.7, 150])).toEqual({ domain: [1, 200], ticks: [1, 2, 5, 10, 20, 50, 100, 200] });
});

test('below one metre the labels go on down without rounding noise', () => {
  expect(logAxis([0.13, 0.9])).toEqual({ domain: [0.1, 1], ticks: [0.1, 0.2, 0.5, 1] });
});

test('more than three decades are labelled at the powers of ten alone', () => {
  expect(logAxis([0.5, 2000])?.ticks).toEqual([0.1, 1, 10, 100, 1000, 10000]);
});

test('values on a label keep it as the bound; no positive value gives no axis', () => {
  expect(logAxis([2, 20])?.domain).toEqual([2, 20]);
  expect(logAxis([0, -1, Number.NaN])).toBeNull();
});

test('tick labels are plain numbers, not SI prefixes that read as units', () => {
  expect([0.5, 20, 1000].map(plainNumber)).toEqual(['0.5', '20', '1,000']);
});

test('given the axis length, 1-2-5 labels that would run into each other give way to the powers of ten', () => {
  // A swarm's p75s from 6 m to 2.1 km: on a phone's 250 px "1,000" and "2,000" lie 25 px apart.
  expect(logAxis([6, 2100], { px: 250, font: 13 })?.ticks).toEqual([1, 10, 100, 1000, 10000]);
  // Presenting at 1024 px the same labels have room.
  expect(logAxis([6, 2100], { px: 838, font: 18 })?.ticks).toEqual([5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000]);
  // Short labels fit where long ones do not.
  expect(logAxis([2, 50], { px: 250, font: 13 })?.ticks).toEqual([2, 5, 10, 20, 50]);
});
