// `npm run bench`: times the WebAssembly build in Node and prints a table. Loads the generated
// package directly with initSync (this is tooling, not UI: the page goes through www/loratrack.ts).
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { performance } from 'node:perf_hooks';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const pkg = await import(join(root, 'www', 'pkg', 'loratrack.js'));
pkg.initSync({ module: readFileSync(join(root, 'www', 'pkg', 'loratrack_bg.wasm')) });

/** Median time per call (µs) over `rounds` rounds of `inner` calls, after a warm-up. */
function time(fn, { inner = 1, rounds = 15 } = {}) {
  for (let i = 0; i < Math.min(3, rounds); i++) fn();
  const samples = [];
  for (let r = 0; r < rounds; r++) {
    const t0 = performance.now();
    for (let i = 0; i < inner; i++) fn();
    samples.push(((performance.now() - t0) * 1e3) / inner);
  }
  samples.sort((a, b) => a - b);
  return samples[Math.floor(samples.length / 2)];
}

const rows = [];
const add = (name, us, note = '') => rows.push({ name, us, note });

add('timeOnAir', time(() => pkg.timeOnAir({ sf: 9, bw: 125, payload: 12 }), { inner: 10000 }));
for (const [model, n] of [['dr', 6], ['ctra-plus', 8], ['3d-ctra', 9]]) {
  const timing = pkg.benchUkf({ model, steps: 20000 });
  add(`ukf_predict/${model}`, timing.predictMicros, `${n} states`);
  add(`ukf_update/${model}`, timing.updateMicros, `${n} states`);
}
add('simulate one flight (~90 s), 3 models, cold', time(() => pkg.benchSimulateCold({ synthetic: 1 }), { rounds: 9 }), 'target ≤ 30 ms');
pkg.simulate({ synthetic: 1 });
add('simulate one flight, link change (cached drone)', time(() => pkg.simulate({ synthetic: 1, distance: 2000 + Math.random() })), 'what a slider drag costs');
// As the page asks: with the plotted series, which cross to JS as Float64Arrays (src/wasm.rs).
add('simulate one flight, link change, with its series', time(() => pkg.simulate({ synthetic: 1, series: true, distance: 2000 + Math.random() })), 'what the page pays per run');
add('simulate whole set (44 min), 3 models, cold', time(() => pkg.benchSimulateCold({ synthetic: 'all' }), { rounds: 3 }), 'target ≤ 2× native');
pkg.simulate({ synthetic: 'all' });
add('simulate whole set, link change (cached drone)', time(() => pkg.simulate({ synthetic: 'all', distance: 2000 + Math.random() }), { rounds: 5 }), 'target ≤ 100 ms');
// The paper's sweep: SF 7/8 × 1/2/3 km over the whole set, no overhead, drone runs cached.
const paperSweep = (eta = 0.9) => {
  for (const sf of [7, 8]) for (const distance of [1000, 2000, 3000]) pkg.simulate({ synthetic: 'all', overhead: 0, sf, distance, eta });
};
paperSweep();
add('paper sweep (6 runs × 3 models, drone runs cached)', time(paperSweep, { rounds: 5 }), 'target ≤ 600 ms');
// A new eta keeps the drone runs but no station prediction: every chain is computed afresh.
add('paper sweep, station predictions not yet cached', time(() => paperSweep(0.9 - 1e-6 * Math.random()), { rounds: 3 }), 'each SF computed once');

const fmt = (us) => (us >= 1000 ? `${(us / 1000).toFixed(2)} ms` : `${us.toFixed(3)} µs`);
const w = Math.max(...rows.map((r) => r.name.length));
console.log(`${('benchmark (WASM in Node ' + process.version + ')').padEnd(w)}      median`);
for (const r of rows) console.log(`${r.name.padEnd(w)}  ${fmt(r.us).padStart(10)}  ${r.note}`);
