// The error chart's scale follows the errors, not a bound that lost packets let run away.
import { expect, test } from 'vitest';
import { errorScale, rateLabels } from '../../www/charts/errorOverTime';

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

test("a change of data rate every station makes within a label's width is labelled once, and a label near the one before it is lifted a row", () => {
  const at = (t: number, label: string, model: string) => ({ t, label, model });
  // Each station's drone sends its own payload: the same change reaches each a little apart.
  const changes = [at(20, 'DR5', 'DR'), at(20.5, 'DR5', 'CTRA+'), at(21, 'DR5', '3D-CTRA'), at(23, 'DR3', 'DR'), at(24, 'DR3', 'CTRA+'), at(23.5, 'DR3', '3D-CTRA'), at(70, 'DR4', 'DR')];
  const labels = rateLabels(changes, 3, 7.6);
  expect(labels).toEqual([
    { t: 20, label: 'DR5', row: 0 },
    { t: 23, label: 'DR3', row: 1 },
    { t: 70, label: 'DR4', model: 'DR', row: 0 },
  ]);
  // On a chart so wide that the stations' changes stand apart, each is its own, on one row.
  expect(rateLabels(changes, 3, 0.4).map((l) => [l.label, l.model, l.row])).toEqual([
    ['DR5', 'DR', 0], ['DR5', 'CTRA+', 0], ['DR5', '3D-CTRA', 0], ['DR3', 'DR', 0], ['DR3', '3D-CTRA', 0], ['DR3', 'CTRA+', 0], ['DR4', 'DR', 0],
  ]);
});
