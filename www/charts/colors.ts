import { presenting } from '../dom';
import type { ModelName } from '../loratrack';

/** One colour per model everywhere on the page (colour-blind-safe Tableau hues). */
export const MODEL_COLORS: Record<ModelName, string> = { dr: '#e15759', 'ctra-plus': '#4e79a7', '3d-ctra': '#59a14f', imm: '#b07aa1', mission: '#f28e2b' };
export const TRUTH_COLOR = '#222222';
/** One colour per spreading factor, SF7 first, in every chart that tells SFs apart (link budget,
 * time on air, the swarm's drones): the same SF reads the same from chart to chart. */
export const SF_COLORS = ['#4e79a7', '#59a14f', '#9c755f', '#f28e2b', '#e15759', '#76b7b2'];
/** The mission's flight plan in the 3D view (dashed). */
export const PLAN_COLOR = '#9c755f';

/** Chart text, CSS px: 13 (Plot's default is 10), legible at 1280 px and on a phone, where the
 * charts are drawn at their box's width and never scaled down much; 18 in presentation mode
 * (`<html class="present">`), for the back of a lecture room. */
export function chartFont(): number {
  return presenting() ? 18 : 13;
}

/** Plot's style for every chart, at [`chartFont`] ([`chartFrame`] gives it with the margins). */
function chartStyle(): Partial<CSSStyleDeclaration> {
  return { fontSize: `${chartFont()}px`, overflow: 'visible' };
}

/** Plot's default margins above and below the frame, px: sized for its own 10 px text. */
const PLOT_MARGIN_TOP = 20;
const PLOT_MARGIN_BOTTOM = 30;

/**
 * Every chart's style, height and vertical margins at [`chartFont`]: below the frame a row of
 * tick labels and, under it, the x axis's label; above it the y axis's label clear of the top
 * tick label. Plot's default margins, made for 10 px, put both axis labels on tick labels at 13
 * and 18 px (`tests/e2e` checks that no axis label overlaps other text). The margins grow the
 * chart, not shrink its plot area: `height` is what the frame and Plot's default margins take.
 */
export function chartFrame(height: number): { style: Partial<CSSStyleDeclaration>; height: number; marginTop: number; marginBottom: number } {
  const font = chartFont();
  const marginTop = font + 14;
  const marginBottom = 2 * font + 14;
  return { style: chartStyle(), height: height + marginTop - PLOT_MARGIN_TOP + marginBottom - PLOT_MARGIN_BOTTOM, marginTop, marginBottom };
}

/**
 * `chart` with its key: one line saying what its marks mean that its legend (colours) does not,
 * such as the error chart's dots and crosses. A slide of the chart (`export.ts`) draws it under
 * the chart; the page says the same in the panel's "What this shows", since a visible line under
 * each chart would push the second chart below a laptop's screen.
 */
export function withKey<T extends SVGSVGElement | HTMLElement>(chart: T, key: string): T {
  chart.dataset.key = key;
  return chart;
}
