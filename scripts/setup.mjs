// Installs whatever the build and the tests need and is missing; quick when all is present.
//   node scripts/setup.mjs            Rust wasm target, wasm-bindgen-cli (Cargo.lock's version), npm packages
//   node scripts/setup.mjs --browser  the same plus Debian's chromium for the end-to-end tests
// Uses only Node's standard library: it runs before node_modules exists.
import { execFileSync, spawnSync } from 'node:child_process';
import { existsSync, readFileSync, statSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const withBrowser = process.argv.includes('--browser');
export const CHROMIUM = '/usr/bin/chromium';

function say(msg) {
  console.log(`[setup] ${msg}`);
}

function fail(msg) {
  console.error(`[setup] error: ${msg}`);
  process.exit(1);
}

function run(cmd, args, what) {
  say(`${what}: ${cmd} ${args.join(' ')}`);
  const r = spawnSync(cmd, args, { cwd: root, stdio: 'inherit' });
  return r.status === 0;
}

function output(cmd, args) {
  try {
    return execFileSync(cmd, args, { cwd: root, encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'] });
  } catch {
    return null;
  }
}

function wasmTarget() {
  if (output('rustup', ['--version']) === null) {
    fail('rustup not found: install Rust with rustup (https://rustup.rs) and run this again');
  }
  const installed = output('rustup', ['target', 'list', '--installed']) ?? '';
  if (installed.split('\n').includes('wasm32-unknown-unknown')) {
    say('wasm32-unknown-unknown target: present');
    return;
  }
  if (!run('rustup', ['target', 'add', 'wasm32-unknown-unknown'], 'adding the WebAssembly target')) {
    fail('could not add the wasm32-unknown-unknown target with rustup');
  }
}

/** The wasm-bindgen version Cargo.lock resolves: the CLI must match it exactly. */
export function lockedWasmBindgenVersion() {
  const lock = readFileSync(join(root, 'Cargo.lock'), 'utf8');
  const m = lock.match(/\[\[package\]\]\nname = "wasm-bindgen"\nversion = "([^"]+)"/);
  if (!m) fail('Cargo.lock has no wasm-bindgen package');
  return m[1];
}

function wasmBindgenCli() {
  const want = lockedWasmBindgenVersion();
  const have = (output('wasm-bindgen', ['--version']) ?? '').trim().split(' ')[1];
  const runner = output('wasm-bindgen-test-runner', ['--version']);
  if (have === want && runner !== null) {
    say(`wasm-bindgen-cli ${want}: present`);
    return;
  }
  say(`wasm-bindgen-cli ${want} needed (found ${have ?? 'none'}); compiling it takes about 4 minutes`);
  // --locked reproduces the CLI's own lock file; a registry that lacks one of its exact
  // dependency versions makes that fail, and the newest compatible versions are used instead.
  if (run('cargo', ['install', 'wasm-bindgen-cli', '--version', want, '--locked', '--force'], 'installing')) return;
  say('--locked install failed; retrying with the newest compatible dependencies');
  if (!run('cargo', ['install', 'wasm-bindgen-cli', '--version', want, '--force'], 'installing')) {
    fail(`could not install wasm-bindgen-cli ${want} with cargo`);
  }
}

function npmPackages() {
  const marker = join(root, 'node_modules', '.package-lock.json');
  const lock = join(root, 'package-lock.json');
  if (existsSync(marker) && statSync(marker).mtimeMs >= statSync(lock).mtimeMs) {
    say('npm packages: present');
    return;
  }
  if (!run('npm', ['ci', '--no-audit', '--no-fund'], 'installing npm packages')) {
    fail('npm ci failed');
  }
}

function chromium() {
  if (existsSync(CHROMIUM)) {
    say(`chromium: present (${CHROMIUM})`);
    return;
  }
  const sudo = process.getuid && process.getuid() !== 0 ? ['sudo'] : [];
  const apt = (args) => (sudo.length ? run('sudo', ['apt-get', ...args], 'installing chromium') : run('apt-get', args, 'installing chromium'));
  if (!apt(['update']) || !apt(['install', '-y', 'chromium'])) {
    fail("could not install Debian's chromium with apt-get (needed for the end-to-end tests)");
  }
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  wasmTarget();
  wasmBindgenCli();
  npmPackages();
  if (withBrowser) chromium();
  say('ready');
}
