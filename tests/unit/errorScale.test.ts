// The error chart's scale follows the errors, not a bound that lost packets let run away.
import { expect, test } from 'vitest';
import { errorScale } from '../../www/charts/errorOverTime';

test('a bound far past the errors is held to twice the largest error and reported', () => {
  expect(errorScale([[1, 10], [4]], [[30, 700], [12]])).toEqual({ top: 20, boundTop: 700 });
});

test('a bound within twice the errors sets the top itself, so its band is whole', () => {
  expect(errorScale([[1, 10]], [[15]])).toEqual({ top: 15, boundTop: 15 });
  expect(errorScale([[1, 10]], [[3]])).toEqual({ top: 10, boundTop: 3 });
});

test('non-finite values are skipped, and without errors the bound sets the top', () => {
  expect(errorScale([[Number.NaN, 0]], [[Number.POSITIVE_INFINITY, 5]])).toEqual({ top: 5, boundTop: 5 });
});
