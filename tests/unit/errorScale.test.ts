// The error chart's scale follows the errors, not a bound that lost packets let run away.
import { expect, test } from 'vitest';
import { errorScale, packetMarks, pickedColumns, pixelPicks, pixelTops, rateChanges, rateLabels, thinnedNote } from '../../www/charts/errorOverTime';

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

test('packets seconds apart are a mark each; packets within one pixel of the time axis are one mark, with their count, span and rates', () => {
  // A synthetic flight's packets, 2-3 s apart on a chart of 0.15 s a pixel: one mark each, at its own time.
  const sparse = packetMarks(Float64Array.from([2.1, 4.2, 7.3]), [6, null, 5], 0.15);
  expect(sparse).toEqual([
    { t: 2.1, to: 2.1, count: 1, drs: [6] },
    { t: 4.2, to: 4.2, count: 1, drs: [null] },
    { t: 7.3, to: 7.3, count: 1, drs: [5] },
  ]);
  // A 40 000 s flight on ~600 px: 66 s a pixel, a packet every 3 s: about 22 packets a mark.
  const times = Float64Array.from({ length: 13_000 }, (_, i) => 3 * i);
  const dense = packetMarks(times, undefined, 66);
  expect(dense.length).toBeLessThan(700);
  expect(dense.reduce((n, m) => n + m.count, 0)).toBe(13_000);
  expect(dense[0]).toEqual({ t: 0, to: 63, count: 22, drs: [null] });
  // Every mark starts at or after a pixel from the one before, so marks never pile up.
  expect(dense.every((m, i) => i === 0 || m.t - dense[i - 1].t >= 66)).toBe(true);
  // A mark that spans a change of data rate names both.
  expect(packetMarks([10, 10.05, 10.1], [5, 5, 4], 1)[0].drs).toEqual([5, 4]);
});

test("a series of at most four samples a pixel is drawn whole; a denser one keeps each pixel's lowest and highest error, in time order", () => {
  // A synthetic flight's 875 samples at 10 Hz on a phone's 290 px of axis: every one.
  const t = Float64Array.from({ length: 875 }, (_, i) => i / 10);
  const saw = Float64Array.from(t, (s) => 1 + (s % 3));
  expect(pixelPicks(t, saw, 0, 87.4 / 290)).toEqual([...t.keys()]);
  // Five a pixel: thinned to at most two.
  expect(pixelPicks(t, saw, 0, 87.4 / 174).length).toBeLessThanOrEqual(2 * 175);
  // An hour at 10 Hz on the same axis: 6.8 s a pixel, a saw-tooth of 3 s teeth.
  const hour = Float64Array.from({ length: 36_000 }, (_, i) => i / 10);
  const teeth = Float64Array.from(hour, (s, i) => (s % 3) + (i === 20_000 ? 50 : 0));
  const pixel = 3599.9 / 530;
  const picks = pixelPicks(hour, teeth, 0, pixel);
  expect(picks.length).toBeLessThanOrEqual(2 * 531);
  expect(picks.every((p, k) => k === 0 || p > picks[k - 1])).toBe(true);
  // The one spike, and every pixel's trough and crest, survive.
  expect(picks).toContain(20_000);
  const range = (indices: Iterable<number>) => {
    const byPixel = new Map<number, [number, number]>();
    for (const i of indices) {
      const [lo, hi] = byPixel.get(Math.floor(hour[i] / pixel)) ?? [Infinity, -Infinity];
      byPixel.set(Math.floor(hour[i] / pixel), [Math.min(lo, teeth[i]), Math.max(hi, teeth[i])]);
    }
    return byPixel;
  };
  expect(range(picks)).toEqual(range(hour.keys()));
});

test("the band is drawn through every bound where there is at most one a pixel, otherwise through each pixel's highest", () => {
  const t = Float64Array.from({ length: 875 }, (_, i) => i / 10);
  // A saw-tooth bound, as between packets: 5 m after each, 20 m before the next, 3 s apart.
  const bound = Float64Array.from(t, (s) => 5 + 5 * (s % 3));
  expect(pixelTops(t, bound, 0, 87.4 / 1000)).toEqual([...t.keys()]);
  const pixel = 87.4 / 40;
  const tops = pixelTops(t, bound, 0, pixel);
  expect(tops.length).toBe(41);
  expect(tops.every((p, k) => k === 0 || p > tops[k - 1])).toBe(true);
  const highest = new Map<number, number>();
  t.forEach((s, i) => highest.set(Math.floor(s / pixel), Math.max(highest.get(Math.floor(s / pixel)) ?? -Infinity, bound[i])));
  expect(tops.map((i) => bound[i])).toEqual([...highest.values()]);
  // A bound the station could not give (NaN) yields to a number in its pixel; an unbounded one shows.
  expect(pixelTops([0, 1, 2, 3], [Number.NaN, 4, 2, 1], 0, 2)).toEqual([1, 2]);
  expect(pixelTops([0, 1, 2, 3], [4, Number.POSITIVE_INFINITY, 2, 1], 0, 2)).toEqual([1, 2]);
});

test("the picked samples become one set of columns, station after station, labelled for the tip, and keep the series' largest error and bound", () => {
  const station = (model: 'dr' | '3d-ctra', shift: number) => ({
    model,
    t: Float64Array.from({ length: 600 }, (_, i) => i / 10),
    error3d: Float64Array.from({ length: 600 }, (_, i) => shift + (i % 37) / 3),
    bound95: Float64Array.from({ length: 600 }, (_, i) => 2 * shift + (i % 41)),
  });
  const models = [station('dr', 1), station('3d-ctra', 2)];
  const pixel = 59.9 / 100;
  const lines = pickedColumns(models, models.map((m) => pixelPicks(m.t, m.error3d, 0, pixel)));
  const band = pickedColumns(models, models.map((m) => pixelTops(m.t, m.bound95, 0, pixel)));
  expect(lines.rows.length).toBe(lines.t.length);
  expect(new Set(lines.model.value)).toEqual(new Set(['DR', '3D-CTRA']));
  expect(lines.model.label).toBe('model');
  const firstOf3d = lines.model.value.indexOf('3D-CTRA');
  expect(lines.model.value.slice(firstOf3d).every((m) => m === '3D-CTRA')).toBe(true);
  expect(lines.e[firstOf3d]).toBe(models[1].error3d[pixelPicks(models[1].t, models[1].error3d, 0, pixel)[0]]);
  expect(errorScale([lines.e], [band.b])).toEqual(errorScale(models.map((m) => m.error3d), models.map((m) => m.bound95)));
});

test('a thinned series says so under the chart, with how many samples it rests on; a whole one adds nothing', () => {
  const whole = { t: new Float64Array(800), samples: 800 };
  expect(thinnedNote([whole, whole])).toBe('');
  const hour = { t: new Float64Array(2998), samples: 36_000 };
  expect(thinnedNote([whole, hour])).toMatch(/36,000 samples a station are drawn as their envelope.*2,998 kept.*CSV/);
});

test("a station's changes of data rate are the arrivals whose rate differs from the one before", () => {
  const changes = rateChanges(Float64Array.from([1, 2, 3, 4, 5]), [6, 6, 5, null, 5], 'DR');
  expect(changes.map((c) => [c.t, c.label])).toEqual([
    [1, 'DR6'],
    [3, 'DR5'],
    [5, 'DR5'],
  ]);
  expect(rateChanges([1, 2], undefined, 'DR')).toEqual([]);
});
