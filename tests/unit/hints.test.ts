// The page's static hints quote numbers that the core declares: a hint that drifted from the core
// would tell a reader a rule the simulation no longer follows.
import { readFileSync } from 'node:fs';
import { expect, test } from 'vitest';
import { LEAN_SIGNIFICANCE, PLANS, TOP_SPEEDS } from '../../www/generated/types';

const page = readFileSync(new URL('../../index.html', import.meta.url), 'utf8');

test("the Payload hint states the lean payload's significance as the core sets it", () => {
  const hint = /<p id="payload-help"[^>]*>([^<]*)<\/p>/.exec(page)?.[1] ?? '';
  expect(hint).toContain(`within ${LEAN_SIGNIFICANCE} standard deviations of zero`);
});

test("each regional plan's choice names the duty cycle and dwell time of the core's plan table", () => {
  const select = /<select id="region"[^>]*>([\s\S]*?)<\/select>/.exec(page)?.[1] ?? '';
  const options = [...select.matchAll(/<option value="([^"]+)"[^>]*>([^<]*)<\/option>/g)].map((m) => [m[1], m[2]]);
  expect(options.map(([value]) => value)).toEqual(PLANS.map((p) => p.region));
  for (const [value, text] of options) {
    const p = PLANS.find((x) => x.region === value)!;
    const limits = [p.dutyCycle === null ? 'no duty cycle' : `${+(p.dutyCycle * 100).toPrecision(3)} % duty cycle`, ...(p.dwellTime === null ? [] : [`${Math.round(p.dwellTime * 1000)} ms dwell`])];
    // Where the plan applies may come first ("Europe, 1 % duty cycle").
    expect(text.replace(/\([A-Z][a-z]+, /, '(')).toBe(`${p.label} (${limits.join(', ')})`);
  }
});

test("the Vehicle and Station prediction hints state each vehicle's top speed as the core bounds it", () => {
  // The paragraph's text, its inline markup (a <code> file line) left out.
  const hint = (id: string) => (new RegExp(`<p id="${id}"[^>]*>([\\s\\S]*?)</p>`).exec(page)?.[1] ?? '').replace(/<[^>]+>/g, '');
  const [copter, plane] = [TOP_SPEEDS.multicopter, TOP_SPEEDS['fixed-wing']];
  expect(hint('vehicle-help')).toContain(`let it reach ${plane} m/s (a multicopter ${copter} m/s)`);
  expect(hint('prediction-help')).toContain(`holds speed in 0–${copter} m/s (a plane: ${plane} m/s)`);
});
