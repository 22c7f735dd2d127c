// The WebAssembly build under Node gives the same numbers as the native CLI for the same seed
// (SPEC §9: loadable in Node with initSync). Needs `npm run build` (www/pkg) first.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');

test('simulate in WASM under Node equals the native CLI to 1e-9 relative', async () => {
  const pkg = await import(join(root, 'www', 'pkg', 'loratrack.js'));
  pkg.initSync({ module: readFileSync(join(root, 'www', 'pkg', 'loratrack_bg.wasm')) });
  for (const [args, params] of [
    [['--synthetic', '3', '--seed', '11', '--sf', '9', '--distance', '3500'], { synthetic: 3, seed: 11, sf: 9, distance: 3500 }],
    [['--synthetic', '17', '--paper', '--bw', '125'], { synthetic: 17, overhead: 0, bw: 125 }],
  ]) {
    const wasm = pkg.simulate(params);
    const native = JSON.parse(execFileSync('cargo', ['run', '--quiet', '--', 'simulate', ...args, '--json'], { cwd: root, encoding: 'utf8' }));
    assert.equal(wasm.results.length, 3);
    wasm.results.forEach((w, i) => {
      const n = native.results[i];
      assert.equal(w.packetsSent, n.packetsSent);
      assert.equal(w.packetsReceived, n.packetsReceived);
      for (const key of ['error3d', 'errorX', 'errorY', 'errorZ']) {
        for (const stat of ['mean', 'p50', 'p75', 'p95', 'max']) {
          const rel = Math.abs(w[key][stat] - n[key][stat]) / Math.max(1e-12, Math.abs(n[key][stat]));
          assert.ok(rel <= 1e-9, `${args.join(' ')} ${w.model} ${key}.${stat}: ${w[key][stat]} vs ${n[key][stat]}`);
        }
      }
    });
  }
});

test('a bad call throws an Error and the module keeps working', async () => {
  const pkg = await import(join(root, 'www', 'pkg', 'loratrack.js'));
  pkg.initSync({ module: readFileSync(join(root, 'www', 'pkg', 'loratrack_bg.wasm')) });
  assert.throws(() => pkg.timeOnAir({ sf: 6, bw: 125, payload: 10 }), /spreading factor/);
  assert.throws(() => pkg.simulate({ trajectory: '' }), /empty/);
  assert.ok(pkg.timeOnAir({ sf: 7, bw: 125, payload: 14, overhead: 0 }).timeOnAir > 0.046);
});
