// The error series CSV: whole series joined on time; a thinned one as its envelope on shared stretches.
import { expect, test } from 'vitest';
import { errorCsv } from '../../www/export';
import type { ModelName } from '../../www/loratrack';

/** A station's series kept as the Rust side thins it: each run's lowest and highest error, at
 * their own times; `start` its first evaluation time (s), `samples` the whole series' length. */
function thinned(model: ModelName, start: number, runs: number, samples: number) {
  const t: number[] = [];
  const error3d: number[] = [];
  for (let r = 0; r < runs; r++) {
    // Two picks a run of 0.4 s, a peak of 50 m in run 7.
    t.push(start + r * 0.4 + 0.1, start + r * 0.4 + 0.3);
    error3d.push(1 + (r % 5), r === 7 ? 50 : 3 + (r % 3));
  }
  return { model, t, error3d, samples };
}

/** A series as the package gives it: `Float64Array`s. */
function typed(m: { model: ModelName; t: number[]; error3d: number[]; samples: number }) {
  return { ...m, t: Float64Array.from(m.t), error3d: Float64Array.from(m.error3d) };
}

test('a whole series is one row per evaluation time, a station empty before its first packet', () => {
  const a = { model: 'dr' as const, t: [0, 0.1, 0.2], error3d: [1, 2, 3], samples: 3 };
  const b = { model: 'imm' as const, t: [0.1, 0.2], error3d: [4, 5], samples: 2 };
  const { rows, name } = errorCsv([typed(a), typed(b)]);
  expect(name).toBe('loratrack-error-series.csv');
  expect(rows).toEqual([
    ['t_s', 'dr_error3d_m', 'imm_error3d_m'],
    ['0.00', '1.0000', ''],
    ['0.10', '2.0000', '4.0000'],
    ['0.20', '3.0000', '5.0000'],
  ]);
});

/** Whether time `t` (s), as the CSV prints times, lies within row `r`'s first and last kept time. */
const within = (t: number, r: string[]) => Number(r[0]) <= Number(t.toFixed(2)) && Number(t.toFixed(2)) <= Number(r[1]);

test("a thinned series gives every station's lowest and highest error in shared stretches of time", () => {
  const dr = thinned('dr', 0, 100, 400);
  const late = thinned('3d-ctra', 10.05, 75, 300);
  const { rows, name } = errorCsv([typed(dr), typed(late)]);
  expect(name).toBe('loratrack-error-envelope.csv');
  const [header, ...body] = rows;
  expect(header).toEqual(['t_from_s', 't_to_s', 'dr_min_error3d_m', 'dr_max_error3d_m', '3d-ctra_min_error3d_m', '3d-ctra_max_error3d_m']);
  // As many stretches as runs: every row holds the first station; the second from its start on.
  expect(body.length).toBe(100);
  expect(body.every((r) => r[2] !== '' && r[3] !== '')).toBe(true);
  expect(body.filter((r) => Number(r[0]) > 10.1).every((r) => r[4] !== '')).toBe(true);
  // Each kept sample lies within its stretch's range, and each range's ends are kept samples.
  for (const [k, m] of [dr, late].entries()) {
    const [lo, hi] = [2 + 2 * k, 3 + 2 * k];
    // (A sample on the printed edge of two stretches lies in one of them.)
    m.t.forEach((t, i) => {
      const e = m.error3d[i];
      const holds = (r: string[]) => within(t, r) && Number(r[lo]) <= e && e <= Number(r[hi]);
      expect(body.some(holds), `${m.model} at ${t} s`).toBe(true);
    });
    for (const r of body.filter((r) => r[lo] !== '')) {
      const inside = m.error3d.filter((_, i) => within(m.t[i], r));
      expect(inside.map((e) => e.toFixed(4))).toContain(r[lo]);
      expect(inside.map((e) => e.toFixed(4))).toContain(r[hi]);
    }
  }
  // The peak survives.
  expect(Math.max(...body.map((r) => Number(r[3])))).toBe(50);
});
