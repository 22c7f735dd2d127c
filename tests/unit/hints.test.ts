// The page's static hints quote numbers that the core declares: a hint that drifted from the core
// would tell a reader a rule the simulation no longer follows.
import { readFileSync } from 'node:fs';
import { expect, test } from 'vitest';
import { LEAN_SIGNIFICANCE } from '../../www/generated/types';

const page = readFileSync(new URL('../../index.html', import.meta.url), 'utf8');

test("the Payload hint states the lean payload's significance as the core sets it", () => {
  const hint = /<p id="payload-help"[^>]*>([^<]*)<\/p>/.exec(page)?.[1] ?? '';
  expect(hint).toContain(`within ${LEAN_SIGNIFICANCE} standard deviations of zero`);
});
