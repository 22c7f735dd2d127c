// A log axis that says its numbers: Plot's default labels a log axis at a few "nice" values and
// leaves most ticks blank, so a chart whose lowest line sits between 1 and 10 m showed no number
// below 10 (the p75-by-SF chart at short range).

/** The multiples of each power of ten that are labelled: 1-2-5 over up to three decades, the
 * powers of ten alone beyond (more labels would crowd a chart of ~200 px). */
function multiples(decades: number): number[] {
  return decades <= 3 ? [1, 2, 5] : [1];
}

/** A log scale's domain, rounded out to labelled values, and its labelled ticks, for positive
 * `values` (others ignored). `null` when there is no positive value. With `across` (a horizontal
 * axis's drawn length and its labels' font size, px), 1-2-5 labels that would run into each other
 * (1 and 2 lie 0.3 of a decade apart: on a phone "1,000" and "2,000" overlapped) give way to the
 * powers of ten alone. */
export function logAxis(values: number[], across?: { px: number; font: number }): { domain: [number, number]; ticks: number[] } | null {
  const positive = values.filter((v) => Number.isFinite(v) && v > 0);
  if (!positive.length) return null;
  const lo = Math.min(...positive);
  const hi = Math.max(...positive);
  const axis = labelled(lo, hi, multiples(Math.log10(hi / lo)));
  if (!across || axis.ticks.length < 2) return axis;
  // A label is about 0.6 em a character; two neighbours need half of each apart, and a gap.
  const widest = Math.max(...axis.ticks.map((t) => plainNumber(t).length)) * 0.6 * across.font;
  const closest = (Math.log10(2) * across.px) / Math.log10(axis.domain[1] / axis.domain[0]);
  return closest >= widest + 0.3 * across.font ? axis : labelled(lo, hi, [1]);
}

/** The domain from `lo` to `hi` rounded out to the `steps` of each power of ten, and those ticks. */
function labelled(lo: number, hi: number, steps: number[]): { domain: [number, number]; ticks: number[] } {
  const candidates: number[] = [];
  for (let e = Math.floor(Math.log10(lo)) - 1; e <= Math.ceil(Math.log10(hi)) + 1; e++) {
    // Rounded so that 0.1 × 2 reads 0.2, not 0.20000000000000004.
    for (const m of steps) candidates.push(Number((m * 10 ** e).toPrecision(12)));
  }
  const bottom = Math.max(...candidates.filter((c) => c <= lo));
  const top = Math.min(...candidates.filter((c) => c >= hi));
  return { domain: [bottom, top], ticks: candidates.filter((c) => c >= bottom && c <= top) };
}

/** A tick label as a plain number: "0.5", "20", "1,000" (not SI's "500m", which reads as metres). */
export const plainNumber = (d: number): string => d.toLocaleString('en', { maximumFractionDigits: 6 });
