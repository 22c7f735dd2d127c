// Compiles the crate to WebAssembly (release) and generates the JS bindings into www/pkg
// (`--target web`, git-ignored). `node scripts/build-wasm.mjs [--features bench]`. The page and the Node tests import it only through www/loratrack.ts.
import { spawnSync } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');

function run(cmd, args) {
  console.log(`[build-wasm] ${cmd} ${args.join(' ')}`);
  const r = spawnSync(cmd, args, { cwd: root, stdio: 'inherit' });
  if (r.status !== 0) {
    console.error(`[build-wasm] error: ${cmd} failed`);
    process.exit(1);
  }
}

// `--features bench` (npm run bench only) adds the benchmark hooks benchUkf and
// benchSimulateCold; the production package leaves them out.
const features = process.argv.includes('--features') ? ['--features', process.argv[process.argv.indexOf('--features') + 1]] : [];
run('cargo', ['build', '--lib', '--release', '--target', 'wasm32-unknown-unknown', ...features]);
run('wasm-bindgen', [
  '--target', 'web',
  '--out-dir', 'www/pkg',
  '--out-name', 'loratrack',
  // Function names are for debuggers; without them the module is 15 KB smaller gzipped.
  '--remove-name-section',
  '--remove-producers-section',
  // `npm test` builds in a target directory of its own (scripts/test.mjs).
  join(process.env.CARGO_TARGET_DIR ?? 'target', 'wasm32-unknown-unknown', 'release', 'loratrack.wasm'),
]);
