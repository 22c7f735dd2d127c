// `npm test`: set-up, then every suite in order, then a pass/fail summary. Exit 1 if any failed.
import { spawnSync } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');

const suites = [
  ['set-up', 'node', ['scripts/setup.mjs', '--browser']],
  ['format', 'cargo', ['fmt', '--all', '--check']],
  ['clippy', 'cargo', ['clippy', '--all-targets', '--', '-D', 'warnings']],
  ['clippy (wasm32)', 'cargo', ['clippy', '--lib', '--tests', '--target', 'wasm32-unknown-unknown', '--', '-D', 'warnings']],
  ['cargo test (native)', 'cargo', ['test']],
  ['fuzz (nightly, 20 s per target)', 'node', ['scripts/fuzz.mjs', '20']],
  ['wasm-bindgen-test (Node)', 'cargo', ['test', '--target', 'wasm32-unknown-unknown', '--test', 'wasm']],
  ['build (wasm + page)', 'npm', ['run', 'build']],
  ['type check', 'npm', ['run', 'typecheck']],
  ['TypeScript unit tests (vitest)', 'npm', ['run', 'test:unit']],
  ['end-to-end (headless Chromium)', 'npm', ['run', 'test:e2e']],
];

const results = [];
for (const [name, cmd, args] of suites) {
  console.log(`\n=== ${name}: ${cmd} ${args.join(' ')}`);
  const started = Date.now();
  const r = spawnSync(cmd, args, { cwd: root, stdio: 'inherit' });
  const ok = r.status === 0;
  results.push({ name, ok, seconds: (Date.now() - started) / 1000 });
  // Without the set-up nothing else can run.
  if (!ok && name === 'set-up') break;
}

console.log('\n=== summary');
for (const r of results) console.log(`${r.ok ? 'PASS' : 'FAIL'}  ${r.name} (${r.seconds.toFixed(1)} s)`);
const failed = results.filter((r) => !r.ok).length;
const skipped = suites.length - results.length;
console.log(`suites: ${results.length - failed} passed, ${failed + skipped} failed`);
process.exit(failed + skipped === 0 ? 0 : 1);
