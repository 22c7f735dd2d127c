// Shared harness for the end-to-end suite: serves dist/ under a sub-path on 127.0.0.1, drives
// Debian's chromium through playwright-core, and records console errors and any request that
// leaves the local origin.
import { execFileSync } from 'node:child_process';
import { createServer } from 'node:http';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, statSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, extname, isAbsolute, join, normalize, relative, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const dist = join(root, 'dist');
export const SCREENSHOTS = join(root, 'test-results', 'screenshots');
export const SUB_PATH = '/docs/loratrack/';

/** The CLI binary as `cargo test` builds it for the integration tests (Cargo's optimised `test`
 * profile), found once per test file. `cargo run --profile test` would build another copy: without
 * the dev-dependencies its dependencies resolve to other feature sets, and a fresh clone spent
 * about 80 s compiling them again in the middle of this suite. */
let cli;
function cliPath() {
  if (cli) return cli;
  const out = execFileSync('cargo', ['test', '--no-run', '--quiet', '--test', 'integration', '--message-format=json'], { cwd: root, encoding: 'utf8', maxBuffer: 64 << 20 });
  for (const line of out.split('\n')) {
    if (!line.startsWith('{')) continue;
    const m = JSON.parse(line);
    if (m.reason === 'compiler-artifact' && m.target.kind.includes('bin') && m.target.name === 'loratrack' && m.executable) cli = m.executable;
  }
  if (!cli) throw new Error('cargo test --no-run built no loratrack binary');
  return cli;
}

/** The native CLI's JSON for `args` (`--json` is added). It is already compiled when `npm test`'s
 * native suite has run; otherwise it is compiled once here. */
export function nativeJson(args) {
  return JSON.parse(execFileSync(cliPath(), [...args, '--json'], { cwd: root, encoding: 'utf8', maxBuffer: 256 << 20 }));
}

/** The native CLI's text output for `args`, as a person reads it in a terminal. Its stderr is
 * kept with the error thrown when it fails (`e.stderr`: a refusal a test expects), not printed. */
export function nativeText(args) {
  return execFileSync(cliPath(), args, { cwd: root, encoding: 'utf8', maxBuffer: 256 << 20, stdio: ['ignore', 'pipe', 'pipe'] });
}

/** The JSON of a `loratrack …` command line (the page's "Copy command") as a POSIX shell runs it,
 * in `cwd` (where the files it names are), the native CLI standing for `loratrack`. */
export function commandJson(line, cwd = root) {
  if (!line.startsWith('loratrack ')) throw new Error(`not a loratrack command: ${line}`);
  return JSON.parse(execFileSync('sh', ['-c', `"$0" ${line.slice('loratrack '.length)} --json`, cliPath()], { cwd, encoding: 'utf8', maxBuffer: 256 << 20 }));
}

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript',
  '.css': 'text/css',
  '.wasm': 'application/wasm',
  '.svg': 'image/svg+xml',
  '.json': 'application/json',
  '.csv': 'text/csv',
};

const scratch = [];
process.on('exit', () => scratch.forEach((dir) => rmSync(dir, { recursive: true, force: true })));

/** A fixed-wing QGroundControl mission: take-off to 80 m, two lines 600 m long 150 m apart at
 * 18 m/s, a 60 s loiter, a landing; flown as ArduPlane flies it (its arcs, its climb-out). */
export function planePlan() {
  const home = [-35.3632, 149.1652, 584];
  const k = (Math.PI / 180) * 6371000;
  const at = ([x, y]) => [home[0] + y / k, home[1] + x / (k * Math.cos((home[0] * Math.PI) / 180))];
  const item = (command, params) => ({ type: 'SimpleItem', command, frame: 3, params });
  const items = [
    item(22, [15, 0, 0, null, 0, 0, 80]),
    ...[[100, 100], [700, 100], [700, 250], [100, 250]].map((c) => item(16, [0, 0, 0, null, ...at(c), 80])),
    item(19, [60, 0, 0, 0, ...at([400, 400]), 80]),
    item(21, [0, 0, 0, null, ...at([0, 0]), 0]),
  ];
  return JSON.stringify({ fileType: 'Plan', version: 1, groundStation: 'QGroundControl', mission: { version: 2, vehicleType: 1, firmwareType: 3, cruiseSpeed: 18, hoverSpeed: 5, plannedHomePosition: home, items } });
}

/** A fresh directory for a test's files (uploads, downloads), removed when the test file's process exits. */
export function scratchDir() {
  const dir = mkdtempSync(join(tmpdir(), 'loratrack-'));
  scratch.push(dir);
  return dir;
}

/** A static file server for dist/ (or another build's directory, `dir`) mounted at SUB_PATH,
 * like a documentation site would host it. With `stall`, the page's HTML arrives as a slow network
 * or a busy device would parse it: up to `stall.after`, then the rest `stall.ms` later. */
export async function serveDist(dir = dist, stall) {
  const server = createServer((req, res) => {
    const url = new URL(req.url, 'http://x');
    if (!url.pathname.startsWith(SUB_PATH)) {
      res.writeHead(404).end();
      return;
    }
    let rel = normalize(decodeURIComponent(url.pathname.slice(SUB_PATH.length)));
    if (rel === '.' || rel === '' || rel.endsWith('/')) rel = join(rel, 'index.html');
    const file = join(dir, rel);
    // Inside `dir` itself: a bare prefix test would also pass a sibling such as `dist-old/`.
    const inside = relative(dir, file);
    if (inside === '..' || inside.startsWith(`..${sep}`) || isAbsolute(inside)) {
      res.writeHead(403).end();
      return;
    }
    try {
      if (!statSync(file).isFile()) throw new Error('not a file');
      // As a documentation host serves it (GitHub Pages: ten minutes): a page loaded again takes
      // its scripts and its WebAssembly module's compiled code from the browser's caches.
      res.writeHead(200, {
        'content-type': TYPES[extname(file)] ?? 'application/octet-stream',
        'cache-control': 'max-age=600',
        'last-modified': statSync(file).mtime.toUTCString(),
      });
      const body = readFileSync(file);
      const at = stall && rel === 'index.html' ? body.indexOf(stall.after) : -1;
      if (at >= 0) {
        const cut = at + stall.after.length;
        res.write(body.subarray(0, cut));
        setTimeout(() => res.end(body.subarray(cut)), stall.ms);
      } else {
        res.end(body);
      }
    } catch {
      res.writeHead(404).end();
    }
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address();
  return { origin: `http://127.0.0.1:${port}`, url: `http://127.0.0.1:${port}${SUB_PATH}`, close: () => server.close() };
}

/** Launches headless chromium with the flags this closed network needs. With `oneRenderer`, the
 * pages of one site share one renderer process, as a user's tabs of one site come to once their
 * browser runs short of processes (`usePlayground`). */
export async function launch({ oneRenderer = false } = {}) {
  return chromium.launch({
    executablePath: '/usr/bin/chromium',
    args: [
      '--headless',
      '--no-sandbox',
      '--disable-gpu',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
      // Chromium 156 loads its WebUI omnibox popup (chrome://omnibox-popup.top-chrome, ~70 scripts
      // in a renderer of its own) with every new window: ~0.5-0.7 s of CPU in each fresh context,
      // beside the page being measured, for a popup no headless page shows. A user's browser
      // loads it once when it starts, not with the page.
      '--disable-features=WebUIOmniboxPopup,WebUIOmniboxAimPopup,WebUIOmniboxFullPopup',
      ...(oneRenderer ? ['--process-per-site'] : []),
    ],
  });
}

/** A new page that records problems: console errors, uncaught exceptions, foreign requests.
 * `opener` is a browser (the page gets a context of its own) or a context (`usePlayground`'s: the
 * page shares it). */
export async function openPage(opener, origin, viewport = { width: 1280, height: 900 }) {
  const shared = !('newContext' in opener);
  const page = shared ? await opener.newPage() : await opener.newPage({ viewport, acceptDownloads: true });
  if (shared) await page.setViewportSize(viewport);
  const problems = [];
  page.on('console', (msg) => {
    if (msg.type() === 'error') problems.push(`console error: ${msg.text()}`);
  });
  page.on('response', (res) => {
    if (res.status() >= 400) problems.push(`HTTP ${res.status()}: ${res.url()}`);
  });
  page.on('pageerror', (err) => problems.push(`page error: ${err.message}`));
  page.on('request', (req) => {
    const u = req.url();
    if (!u.startsWith(origin) && !u.startsWith('data:') && !u.startsWith('blob:')) problems.push(`external request: ${u}`);
  });
  return { page, problems };
}

export async function screenshot(page, name) {
  mkdirSync(SCREENSHOTS, { recursive: true });
  const path = join(SCREENSHOTS, `${name}.png`);
  await page.screenshot({ path, fullPage: true });
  return path;
}
