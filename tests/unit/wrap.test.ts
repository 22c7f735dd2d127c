// A slide's caption and notes break into lines that fit, whatever measures the fit.
import { expect, test } from 'vitest';
import { unbreakable, wrap } from '../../www/export';

test('a caption breaks at spaces into the longest lines that fit, none lost', () => {
  const caption = 'SF7, 250 kHz, 3.0 km, bounded prediction; synthetic flight 1; seed 1; loratrack 0.1.0';
  const lines = wrap(caption, (t) => t.length <= 30);
  expect(lines.every((l) => l.length <= 30)).toBe(true);
  expect(lines.join(' ')).toBe(caption);
  // Longest: each line but the last would overflow with the next word (a number with its unit).
  lines.slice(0, -1).forEach((l, i) => expect(`${l} ${unbreakable(lines[i + 1])[0]}`.length).toBeGreaterThan(30));
});

test('a measured width wraps as a character count does, and a word too long stands alone', () => {
  const px = (t: string) => 7 * t.length;
  expect(wrap('a bb ccc dddd', (t) => px(t) <= 35)).toEqual(['a bb', 'ccc', 'dddd']);
  expect(wrap('short averyveryverylongword end', (t) => t.length <= 8)).toEqual(['short', 'averyveryverylongword', 'end']);
  expect(wrap('', () => true)).toEqual(['']);
});

test('a number stays on the line of its unit, as a slide\'s note needs ("95 %", "13 B", "250 kHz,")', () => {
  const note = "dashed band: the station's own 95 % bound on its error; 13 B LoRaWAN overhead at 250 kHz, 1.0 km";
  expect(unbreakable(note)).toContain('95 %');
  expect(unbreakable(note)).toContain('250 kHz,');
  expect(unbreakable(note)).toContain('1.0 km');
  // Each width at which a plain split would end a line on a number: the number moves down with its unit.
  for (let width = 10; width <= note.length; width++) {
    const lines = wrap(note, (t) => t.length <= width);
    expect(lines.join(' ')).toBe(note);
    for (const l of lines.slice(0, -1)) expect(l, `at ${width}: ${JSON.stringify(lines)}`).not.toMatch(/\d$/);
  }
  // A number before an ordinary word may still end a line.
  expect(wrap('seed 1 alone here', (t) => t.length <= 6)).toEqual(['seed 1', 'alone', 'here']);
});
