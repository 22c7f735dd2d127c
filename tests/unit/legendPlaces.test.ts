// A slide's legend entries go in rows within its width, in order, whatever measures them.
import { expect, test } from 'vitest';
import { legendPlaces } from '../../www/export';

test('entries fill a row left to right and start the next where they would pass the right edge', () => {
  const widths = [100, 150, 60, 80, 90, 120, 70];
  const places = legendPlaces(widths, 16, 400, 13);
  places.forEach(({ x, row }, i) => {
    expect(x + widths[i]).toBeLessThanOrEqual(400);
    if (i > 0 && row === places[i - 1].row) expect(x).toBe(places[i - 1].x + widths[i - 1] + 13);
    // A new row starts at the left edge only because the entry would not fit after the last.
    if (i > 0 && row !== places[i - 1].row) {
      expect(row).toBe(places[i - 1].row + 1);
      expect(x).toBe(16);
      expect(places[i - 1].x + widths[i - 1] + 13 + widths[i]).toBeGreaterThan(400);
    }
  });
  expect(places[places.length - 1].row).toBeGreaterThan(0);
});

test('an entry wider than any row stands alone in its own row rather than being lost', () => {
  const places = legendPlaces([50, 500, 50], 0, 300, 10);
  expect(places).toEqual([
    { x: 0, row: 0 },
    { x: 0, row: 1 },
    { x: 0, row: 2 },
  ]);
  expect(legendPlaces([], 0, 300, 10)).toEqual([]);
});
