// The README's JavaScript API example is run line by line through www/loratrack.ts, as a reader
// would paste it: each call must work with the names its import line imports, and where a line's
// comment begins with a value (a number, a quoted string, a list) the call must give that value.
// Needs the WebAssembly package (`npm run build`), as `npm test` builds it before this suite.
import { readFileSync } from 'node:fs';
import { beforeAll, expect, test } from 'vitest';
import { api, loadCore } from './core';

const readme = readFileSync(new URL('../../README.md', import.meta.url), 'utf8');
const section = readme.slice(readme.indexOf('## JavaScript API'));
const block = /```ts\n([\s\S]*?)```/.exec(section)?.[1] ?? '';
const lines = block.split('\n');
const imports = /^import \{([^}]*)\} from '\.\/www\/loratrack';$/.exec(lines[0])?.[1].split(',').map((name) => name.trim()) ?? [];

/** A minute's flight at 1 Hz, accelerating sideways. */
const flight = `t,x,y,z\n${Array.from({ length: 61 }, (_, i) => `${i},${5 * i},${0.05 * i * i},30`).join('\n')}\n`;
/** The names the example leaves to the reader: a CSV flight, two runs of stations apart, and a
 * quiet console for its progress. */
const reader = () => ({
  console: { log: () => {} },
  csvText: flight,
  text: flight,
  a: api.simulate({ synthetic: 1, model: 'dr,ctra-plus' }),
  b: api.simulate({ synthetic: 1, model: '3d-ctra' }),
});

/** `code` run with only the example's imports (and the reader's names) in scope. */
function run(code: string, scope: Record<string, unknown>): unknown {
  const names = Object.keys(scope);
  return new Function(...names, `return (${code});`)(...names.map((name) => scope[name]));
}

/** The index just past the bracket that closes the one at `text[0]`, quotes skipped. */
function closing(text: string): number {
  let depth = 0;
  let quote = '';
  for (let i = 0; i < text.length; i++) {
    const c = text[i];
    if (quote) {
      if (c === quote) quote = '';
    } else if (c === "'" || c === '"') {
      quote = c;
    } else if (c === '[' || c === '{') {
      depth++;
    } else if ((c === ']' || c === '}') && --depth === 0) {
      return i + 1;
    }
  }
  return -1;
}

type Claim = { value: unknown } | { prefix: string } | null;

/** The value a comment begins with, or null where it begins with words: `0.072192`, `1 (US915
 * DR1)`, `'loratrack …'`, `['dr', …], as …`; a quoted text ending in "…" is a beginning. */
function claimOf(comment: string): Claim {
  const number = /^-?\d+(\.\d+)?(?=\s|$)/.exec(comment);
  if (number) return { value: Number(number[0]) };
  const text = /^(['"])(.*?)\1/.exec(comment);
  if (text) return text[2].endsWith('…') ? { prefix: text[2].slice(0, -1).trimEnd() } : { value: text[2] };
  if (comment.startsWith('[')) {
    try {
      return { value: run(comment.slice(0, closing(comment)), {}) };
    } catch {
      return null; // a shape in words ("[lo, hi], m: …")
    }
  }
  return null;
}

beforeAll(loadCore);

test('the example imports what it calls', () => {
  expect(imports.length).toBeGreaterThan(5);
  const code = block.replace(/\/\/.*$/gm, '');
  const called = new Set([...code.matchAll(/(?<![.\w])([a-z]\w*)\(/g)].map((m) => m[1]));
  const own = new Set(['console', 'load']);
  expect([...called].filter((name) => !imports.includes(name) && !own.has(name) && !(name in globalThis))).toEqual([]);
  for (const name of imports) expect(api, name).toHaveProperty(name);
});

test("every call of the example runs, and gives the value its comment begins with", { timeout: 120_000 }, () => {
  const scope: Record<string, unknown> = { ...Object.fromEntries(imports.map((name) => [name, (api as Record<string, unknown>)[name]])), ...reader() };
  const checked: string[] = [];
  for (const line of lines.slice(1)) {
    const [, code, comment] = /^(\S[^;]*);\s*(?:\/\/\s*(.*))?$/.exec(line) ?? [];
    if (!code || code.startsWith('await ')) continue;
    const got = run(code, scope);
    const claim = claimOf(comment ?? '');
    if (claim === null) continue;
    if ('prefix' in claim) expect(String(got).startsWith(claim.prefix), `${code}: ${String(got)}`).toBe(true);
    else if (typeof claim.value === 'number') expect(got, code).toBeCloseTo(claim.value, String(claim.value).split('.')[1]?.length ?? 0);
    else expect(got, code).toEqual(claim.value);
    checked.push(code);
  }
  // The values the example states: time on air, two command lines, a data rate, a refusal, the stations.
  expect(checked.length).toBeGreaterThanOrEqual(7);
});
