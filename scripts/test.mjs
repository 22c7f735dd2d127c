// `npm test`: set-up, then every suite, then each suite's time and a pass/fail summary. Exit 1 if
// any failed.
//
// Why it is shaped this way (a 2-core machine; every dependency build is minutes):
// - Clippy lints while the tests compile: every crate of ours is compiled by clippy-driver
//   (scripts/clippy-rustc.sh, warnings are errors), so the test builds are also the clippy passes and
//   no dependency is checked a second time only to be linted.
// - The WebAssembly tests run in the release profile, on the dependencies the production build
//   has just compiled.
// - Fuzzing (its own nightly build in fuzz/target) runs beside the WebAssembly and browser suites,
//   which mostly wait on one core, Node or Chromium; its output goes to test-results/fuzz.log and is
//   summarised at the end. Like the Rust suites it is skipped when nothing it reads changed since
//   it last passed here, so a change to the page alone does not share the cores with a fuzz build.
// - The type check and the TypeScript unit tests run beside the WebAssembly tests, whose build
//   ends in one long single-threaded link (LTO): they need the package the production build has
//   just generated, and nothing else from the suites around them.
import { spawn, spawnSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { closeSync, existsSync, mkdirSync, openSync, readFileSync, readdirSync, statSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
// Not incremental: the test profile optimises, so an incremental cache saves little on a rebuild
// and costs its writing on every build (a clean build of the crate's test targets: 109 -> 97 s).
// Built in a target directory of its own: Cargo compiles this crate again whenever its wrapper
// changes, so builds with and without clippy-driver sharing `target/` undid each other (`npm start`
// after `npm test`, then `npm test` again: the WebAssembly module compiled twice, 35-41 s each; a
// plain `cargo test` in between: every test binary). Each directory now keeps its own.
const env = {
  ...process.env,
  RUSTC_WORKSPACE_WRAPPER: join(root, 'scripts', 'clippy-rustc.sh'),
  CARGO_INCREMENTAL: '0',
  CARGO_TARGET_DIR: join(root, 'target', 'clippy'),
};
const WASM = ['--target', 'wasm32-unknown-unknown'];

/**
 * Everything the Rust suites read: the crate, its tests and benches, the bundled flight, the
 * checked-in TypeScript types (a test compares them with the Rust source), the documents whose
 * numbers a test recomputes (README.md, docs/, and package.json's scripts that generate them),
 * the lint wrapper and the toolchain. When none of it changed since a suite last passed on this
 * machine, that suite is not run again (`npm test -- --all` runs it anyway); a fresh clone, as in
 * CI, has no record.
 */
const RUST_INPUTS = ['Cargo.toml', 'Cargo.lock', 'build.rs', '.cargo', 'src', 'tests', 'benches', 'data', 'www/generated', 'README.md', 'docs', 'package.json', 'scripts/clippy-rustc.sh'];
const NOT_RUST = ['tests/e2e', 'tests/unit', 'fuzz/target', 'fuzz/corpus', 'fuzz/artifacts'];
/** What the fuzz suite reads: the crate and its fuzz targets and seeds (not its working corpus). */
const FUZZ_INPUTS = [...RUST_INPUTS, 'fuzz'];
/** The TypeScript tests that recompute, through the WebAssembly package, the numbers index.html's
 * explanations and the README's JavaScript example cite: half a minute of simulations on each core,
 * which a change to another page file need not repeat beside the browser suite. */
const CITED = ['tests/unit/explanations.test.ts', 'tests/unit/readme.test.ts'];
/** What they read: the core and the README (the Rust suites' inputs), the page's text, the module
 * that wraps the package, and vitest's configuration and version. */
const CITED_INPUTS = [...RUST_INPUTS, ...CITED, 'tests/unit/core.ts', 'index.html', 'www/loratrack.ts', 'vite.config.ts', 'tsconfig.json', 'package-lock.json'];

/** Each suite is one or more commands run in order; the first failure fails the suite. */
const suites = [
  ['set-up', [['node', ['scripts/setup.mjs', '--browser']]]],
  ['format', [['cargo', ['fmt', '--all', '--check']]]],
  [
    'clippy + cargo test + API docs (native)',
    [
      ['cargo', ['test', '--all-targets', '--no-run']],
      ['cargo', ['test']],
      // The API docs, their links checked: a link that no longer resolves is an error.
      ['cargo', ['doc', '--no-deps', '--lib'], { RUSTDOCFLAGS: '-D warnings' }],
    ],
    RUST_INPUTS,
  ],
  ['build (wasm + page)', [['npm', ['run', 'build']]]],
  ['clippy + wasm-bindgen-test (Node)', [['cargo', ['test', '--release', ...WASM, '--test', 'wasm']]], RUST_INPUTS],
  ['end-to-end (headless Chromium)', [['npm', ['run', 'test:e2e']]]],
];
/**
 * Suites started in the background just before the suite they are keyed by, their output written
 * to test-results/<log>, and waited for at the end: [name, command, arguments, log, inputs].
 * Fuzzing starts once the native build has had both cores: what follows links with LTO on one
 * core and waits on Node and Chromium.
 */
const BESIDE = {
  'build (wasm + page)': [['fuzz (nightly, 20 s per target)', 'node', ['scripts/fuzz.mjs', '20'], 'fuzz.log', FUZZ_INPUTS]],
  'clippy + wasm-bindgen-test (Node)': [
    ['type check', 'npm', ['run', 'typecheck'], 'typecheck.log'],
    ['TypeScript unit tests (vitest)', 'npx', ['vitest', 'run', '--dir', 'tests/unit', ...CITED.flatMap((file) => ['--exclude', `**/${file.split('/').at(-1)}`])], 'vitest.log'],
    ['numbers the page and README cite (vitest)', 'npx', ['vitest', 'run', ...CITED], 'vitest-cited.log', CITED_INPUTS],
  ],
};

/** A digest of the files under `paths` (and of the toolchain), or null when `paths` is not given. */
function digest(paths) {
  if (!paths) return null;
  const hash = createHash('sha256');
  hash.update(spawnSync('rustc', ['-vV'], { encoding: 'utf8' }).stdout ?? '');
  const walk = (rel) => {
    if (NOT_RUST.includes(rel) || !existsSync(join(root, rel))) return;
    if (statSync(join(root, rel)).isDirectory()) {
      for (const name of readdirSync(join(root, rel)).sort()) walk(`${rel}/${name}`);
    } else {
      hash.update(`${rel}\0`).update(readFileSync(join(root, rel)));
    }
  };
  paths.forEach(walk);
  return hash.digest('hex');
}

const stampOf = (name) => join(root, 'target', 'npm-test', `${name.replace(/[^a-z0-9]+/gi, '-')}.sha256`);
const runAll = process.argv.includes('--all');
const UNCHANGED = { ok: true, seconds: 0, note: 'unchanged, not run' };

/** Whether suite `name` last passed here on inputs that digest to `before` (it then says so). */
function passedOn(name, before) {
  const stamp = stampOf(name);
  if (!before || runAll || !existsSync(stamp) || readFileSync(stamp, 'utf8') !== before) return false;
  console.log(`\n=== ${name}: nothing it reads changed since it passed here (npm test -- --all runs it)`);
  return true;
}

/** Records that suite `name` passed on `before`: only what was read before the run and is still
 * there after it counts as tested. */
function recordPass(name, inputs, before) {
  if (!before || digest(inputs) !== before) return;
  mkdirSync(dirname(stampOf(name)), { recursive: true });
  writeFileSync(stampOf(name), before);
}

function runSuite(commands) {
  for (const [cmd, args, extra = {}] of commands) {
    console.log(`\n=== ${Object.entries(extra).map(([k, v]) => `${k}='${v}' `).join('')}${cmd} ${args.join(' ')}`);
    if (spawnSync(cmd, args, { cwd: root, stdio: 'inherit', env: { ...env, ...extra } }).status !== 0) return false;
  }
  return true;
}

/**
 * Runs a suite in the background with its output written straight to test-results/`log`;
 * resolves to its result. The suites in front run with spawnSync, which blocks this process:
 * output piped through it would fill the pipe and stall the suite until they end.
 */
function inBackground([name, cmd, args, logName, inputs]) {
  const before = digest(inputs);
  if (passedOn(name, before)) return Promise.resolve({ name, ...UNCHANGED });
  mkdirSync(join(root, 'test-results'), { recursive: true });
  const log = join(root, 'test-results', logName);
  const out = openSync(log, 'w');
  console.log(`\n=== ${name}: ${cmd} ${args.join(' ')} (in the background, output in ${log})`);
  const started = Date.now();
  // Without the suites' environment (clippy-driver): cargo-fuzz builds with a minimal nightly
  // toolchain, which has no clippy, and the TypeScript suites build nothing with Cargo.
  // Its exit is only seen once the suites in front are done, so its log's last write says when it
  // ended: a line of its own, since a suite that passes may print nothing at its end (tsc).
  const child = spawn('sh', ['-c', '"$@"; status=$?; echo "(exit status $status)"; exit $status', 'sh', cmd, ...args], { cwd: root, stdio: ['ignore', out, out] });
  closeSync(out);
  return new Promise((resolve) => {
    child.on('close', (code) => {
      const ok = code === 0;
      if (ok) recordPass(name, inputs, before);
      resolve({ name, ok, seconds: (statSync(log).mtimeMs - started) / 1000, log });
    });
  });
}

const results = [];
const began = Date.now();
const background = [];
for (const [name, commands, inputs] of suites) {
  for (const suite of BESIDE[name] ?? []) background.push(inBackground(suite));
  const started = Date.now();
  const before = digest(inputs);
  if (passedOn(name, before)) {
    results.push({ name, ...UNCHANGED });
    continue;
  }
  const ok = runSuite(commands);
  if (ok) recordPass(name, inputs, before);
  results.push({ name, ok, seconds: (Date.now() - started) / 1000 });
  // Without the set-up nothing else can run.
  if (!ok && name === 'set-up') break;
}
for (const r of await Promise.all(background)) {
  if (r.log) {
    const lines = readFileSync(r.log, 'utf8').trimEnd().split('\n');
    // A failure shows the suite's report; a pass only its last words.
    console.log(`\n=== ${r.name}: the last lines of ${r.log}\n${lines.slice(r.ok ? -4 : -150).join('\n')}`);
  }
  results.push(r);
}

const expected = suites.length + Object.values(BESIDE).flat().length;
console.log('\n=== summary');
for (const r of results) console.log(`${r.ok ? 'PASS' : 'FAIL'}  ${r.name} (${r.note ?? `${r.seconds.toFixed(1)} s`})`);
const failed = results.filter((r) => !r.ok).length;
const skipped = expected - results.length;
console.log(`suites: ${results.length - failed} passed, ${failed + skipped} failed, in ${((Date.now() - began) / 60000).toFixed(1)} min`);
process.exit(failed + skipped === 0 ? 0 : 1);
