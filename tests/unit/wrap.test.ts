// A slide's caption and notes break into lines that fit, whatever measures the fit.
import { expect, test } from 'vitest';
import { wrap } from '../../www/export';

test('a caption breaks at spaces into the longest lines that fit, none lost', () => {
  const caption = 'SF7, 250 kHz, 3.0 km, bounded prediction; synthetic flight 1; seed 1; loratrack 0.1.0';
  const lines = wrap(caption, (t) => t.length <= 30);
  expect(lines.every((l) => l.length <= 30)).toBe(true);
  expect(lines.join(' ')).toBe(caption);
  // Longest: each line but the last would overflow with the next word.
  lines.slice(0, -1).forEach((l, i) => expect(`${l} ${lines[i + 1].split(' ')[0]}`.length).toBeGreaterThan(30));
});

test('a measured width wraps as a character count does, and a word too long stands alone', () => {
  const px = (t: string) => 7 * t.length;
  expect(wrap('a bb ccc dddd', (t) => px(t) <= 35)).toEqual(['a bb', 'ccc', 'dddd']);
  expect(wrap('short averyveryverylongword end', (t) => t.length <= 8)).toEqual(['short', 'averyveryverylongword', 'end']);
  expect(wrap('', () => true)).toEqual(['']);
});
