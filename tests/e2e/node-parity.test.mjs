// The WebAssembly build under Node gives the same numbers as the native CLI for the same seed
// (reference §9: loadable in Node with initSync). Needs `npm run build` (www/pkg) first.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { nativeJson, planePlan } from './harness.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');

/** `value` as JSON reads it back, typed arrays written as arrays (README, JS API). */
const asJson = (value) => (value === undefined ? undefined : JSON.parse(JSON.stringify(value, (_, v) => (ArrayBuffer.isView(v) ? Array.from(v) : v))));

test('simulate in WASM under Node equals the native CLI bit for bit', async () => {
  const pkg = await import(join(root, 'www', 'pkg', 'loratrack.js'));
  pkg.initSync({ module: readFileSync(join(root, 'www', 'pkg', 'loratrack_bg.wasm')) });
  const plane = join(mkdtempSync(join(tmpdir(), 'loratrack-parity-')), 'plane.plan');
  writeFileSync(plane, planePlan());
  for (const [args, params] of [
    [['--synthetic', '3', '--seed', '11', '--sf', '9', '--distance', '3500', '--series'], { synthetic: 3, seed: 11, sf: 9, distance: 3500, series: true }],
    [['--synthetic', '17', '--paper', '--bw', '125'], { synthetic: 17, overhead: 0, bw: 125 }],
    // Natively the flights run on every core; in WebAssembly one after another.
    [['--synthetic', 'all', '--model', '3d-ctra,imm', '--prediction', 'bounded'], { synthetic: 'all', model: '3d-ctra,imm', prediction: 'bounded' }],
    // The mission station follows each synthetic flight's own plan.
    [['--synthetic', 'all', '--model', '3d-ctra,mission', '--sf', '10', '--bw', '125'], { synthetic: 'all', model: '3d-ctra,mission', sf: 10, bw: 125 }],
    // Lean payloads: each packet's payload is chosen from the drone's estimate as it goes.
    [['--synthetic', 'all', '--model', 'all,imm', '--prediction', 'bounded', '--sf', '10', '--bw', '125', '--payload', 'lean'], { synthetic: 'all', model: 'all,imm', prediction: 'bounded', sf: 10, bw: 125, payload: 'lean' }],
    // A plane's plan flown without a log (its corners' arcs, its loiter, the trigonometry of
    // both), the mission station following its arcs.
    [['--plan', plane, '--model', 'dr,3d-ctra,mission', '--prediction', 'bounded', '--sf', '9', '--bw', '125', '--series'], { plan: planePlan(), planName: plane, model: 'dr,3d-ctra,mission', prediction: 'bounded', sf: 9, bw: 125, series: true }],
    // With ADR the flights run in order everywhere (the data rate carries over).
    [['--synthetic', 'all', '--model', '3d-ctra', '--adr', 'tracking', '--distance', '5000'], { synthetic: 'all', model: '3d-ctra', adr: 'tracking', distance: 5000 }],
  ]) {
    const wasm = pkg.simulate(params);
    const native = nativeJson(['simulate', ...args]);
    // Both sides print the shortest decimal that round-trips, so equal text means equal bits.
    assert.deepStrictEqual(wasm.results, native.results, args.join(' '));
    // The series' numbers come as Float64Arrays (reference §9), each the same bits as the CLI's.
    assert.deepStrictEqual(asJson(wasm.series), native.series, args.join(' '));
    if (wasm.series) {
      assert.ok(wasm.series.t instanceof Float64Array && wasm.series.models.every((m) => m.error3d instanceof Float64Array && Array.isArray(m.arrivalDr)));
    }
  }
});

test('a bad call throws an Error and the module keeps working', async () => {
  const pkg = await import(join(root, 'www', 'pkg', 'loratrack.js'));
  pkg.initSync({ module: readFileSync(join(root, 'www', 'pkg', 'loratrack_bg.wasm')) });
  assert.throws(() => pkg.timeOnAir({ sf: 6, bw: 125, payload: 10 }), /spreading factor/);
  assert.throws(() => pkg.simulate({ trajectory: '' }), /empty/);
  assert.ok(pkg.timeOnAir({ sf: 7, bw: 125, payload: 14, overhead: 0 }).timeOnAir > 0.046);
});

test('a swarm with gateways and ADR in WASM under Node equals the native CLI, and the production package has no benchmark hooks', async () => {
  const pkg = await import(join(root, 'www', 'pkg', 'loratrack.js'));
  pkg.initSync({ module: readFileSync(join(root, 'www', 'pkg', 'loratrack_bg.wasm')) });
  const args = ['--drones', '24', '--duration', '120', '--adr', 'lorawan', '--sf-plan', 'fixed', '--bw', '125', '--gateway', '0,0', '--gateway', '1500,-800,30'];
  const params = { drones: 24, duration: 120, adr: 'lorawan', sfPlan: 'fixed', bw: 125, gateways: [{ east: 0, north: 0 }, { east: 1500, north: -800, height: 30 }] };
  const wasm = pkg.swarm(params);
  const native = nativeJson(['swarm', ...args]);
  const { config: _w, ...w } = wasm;
  const { config: _n, ...n } = native;
  assert.deepStrictEqual(w, n);
  assert.equal(typeof pkg.benchUkf, 'undefined');
  assert.equal(typeof pkg.benchSimulateCold, 'undefined');
  assert.equal(typeof pkg.limits, 'function');
});
