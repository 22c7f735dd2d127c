// Runs every fuzz target (fuzz/fuzz_targets) for a short time with cargo-fuzz on a nightly
// toolchain, installing both when missing. A crash fails the run (its input is saved under
// fuzz/artifacts/). Where no nightly toolchain can be installed the run says so and passes: the
// property tests cover the same ground on stable.
//   node scripts/fuzz.mjs [seconds per target, default 20]
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const seconds = Number(process.argv[2] ?? 20);
const say = (msg) => console.log(`[fuzz] ${msg}`);
const run = (cmd, args, opts = {}) => spawnSync(cmd, args, { cwd: root, stdio: 'inherit', ...opts }).status === 0;
const quiet = (cmd, args) => spawnSync(cmd, args, { cwd: root, stdio: 'ignore' }).status === 0;

if (!quiet('cargo', ['+nightly', '--version'])) {
  say('installing a minimal nightly toolchain (cargo-fuzz needs it)');
  if (!run('rustup', ['toolchain', 'install', 'nightly', '--profile', 'minimal'])) {
    say('skipped: no nightly toolchain can be installed here');
    process.exit(0);
  }
}
if (!quiet('cargo', ['fuzz', '--version'])) {
  say('installing cargo-fuzz');
  // The tool's own lock file may pin versions a registry mirror lacks; fall back to resolving anew.
  if (!run('cargo', ['install', 'cargo-fuzz', '--locked']) && !run('cargo', ['install', 'cargo-fuzz'])) {
    console.error('[fuzz] error: could not install cargo-fuzz');
    process.exit(1);
  }
}
// No sanitizer: the native crate forbids unsafe code (src/lib.rs), so AddressSanitizer has
// nothing of ours to check; what the fuzzer looks for here is a panic, an endless loop or the
// RSS limit, which libFuzzer catches by itself. Without it the build takes 112 s instead of
// 150 s (idle, 2 cores) and each second of fuzzing runs more inputs.
// The dev profile (fuzz/Cargo.toml: optimised at level 1, no debug info) instead of cargo-fuzz's
// release build with one codegen unit per crate: overflow checks and debug assertions are on, so
// an arithmetic overflow the release build would wrap is a finding, and it builds in 77 s and
// 134 s of CPU instead of 96 s and 165 s (idle, 2 cores), at 70-90 % of the release build's
// executions per second (2026-11-30).
const BUILD = ['--dev', '--sanitizer', 'none'];
// Every target is built in one cargo call, its binaries in parallel, before the first runs.
if (!run('cargo', ['+nightly', 'fuzz', 'build', ...BUILD])) {
  console.error('[fuzz] error: the fuzz targets do not build');
  process.exit(1);
}
const targets = readdirSync(join(root, 'fuzz', 'fuzz_targets'))
  .filter((f) => f.endsWith('.rs'))
  .map((f) => f.slice(0, -3))
  .sort();
for (const target of targets) {
  say(`${target}: ${seconds} s`);
  // The working corpus (git-ignored) first, then the committed seeds (fuzz/seeds/<target>: e.g.
  // CSVs with and without velocity columns, so the derivative path is reached from the start).
  const corpus = join('fuzz', 'corpus', target);
  mkdirSync(join(root, corpus), { recursive: true });
  const seeds = join('fuzz', 'seeds', target);
  const dirs = existsSync(join(root, seeds)) ? [corpus, seeds] : [corpus];
  if (!run('cargo', ['+nightly', 'fuzz', 'run', ...BUILD, target, ...dirs, '--', `-max_total_time=${seconds}`, '-rss_limit_mb=4096'])) {
    console.error(`[fuzz] error: ${target} found a failing input (see fuzz/artifacts/${target}/)`);
    process.exit(1);
  }
}
say(`${targets.length} targets ran ${seconds} s each without a failure`);
