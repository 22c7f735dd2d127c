import { presenting } from '../dom';
import type { ModelName } from '../loratrack';

/** Text a chart writes beside its marks ("no packet arrives", "DR: none"): the page's hint grey, 6.4:1
 * on white, where a station's colour would be small text at 3:1. */
export const NOTE_GREY = '#5a6068';

/** Whether each of `rows` (a chart's runs at one distance or SF) sent no packet at all: such a
 * place says "sent", not "arrives", since no gateway distance mends it (TTN's fair use at a slow
 * rate sends less often than a flight lasts). `sent` left out counts as sent. */
export const noneSent = (rows: { sent?: number }[]) => rows.length > 0 && rows.every((r) => r.sent === 0);

/** One colour per model everywhere on the page (colour-blind-safe Tableau hues). */
export const MODEL_COLORS: Record<ModelName, string> = { dr: '#e15759', 'ctra-plus': '#4e79a7', '3d-ctra': '#59a14f', imm: '#b07aa1', mission: '#f28e2b' };
export const TRUTH_COLOR = '#222222';
/** One colour per spreading factor, SF7 first, in every chart that tells SFs apart (link budget,
 * time on air, the swarm's drones): the same SF reads the same from chart to chart. */
export const SF_COLORS = ['#4e79a7', '#59a14f', '#9c755f', '#f28e2b', '#e15759', '#76b7b2'];
/** The column behind the chosen setting in a sweep's chart (the SF chart's SF, the distance
 * chart's distance): over white #eef0f3, light enough that the grey notes standing in it keep
 * 5.5:1, and translucent so that the grid's lines (drawn under it) show through. Its class tells
 * it from the boxes and marks that stand in front of it. */
export const CHOSEN_COLUMN = { fill: '#d5dae1', fillOpacity: 0.4, className: 'chosen-column' };
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
 * chart, not shrink its plot area: `height` is what the frame and Plot's default margins take,
 * and `panelPlots` what the plot heights of all the charts in its panel add up to (the chart's own
 * where it is alone), for presentation mode ([`presentedScale`]).
 */
export function chartFrame(height: number, panelPlots = height): { style: Partial<CSSStyleDeclaration>; height: number; marginTop: number; marginBottom: number } {
  const font = chartFont();
  const marginTop = font + 14;
  const marginBottom = 2 * font + 14;
  const plot = height * presentedScale(panelPlots);
  return { style: chartStyle(), height: Math.round(plot + marginTop - PLOT_MARGIN_TOP + marginBottom - PLOT_MARGIN_BOTTOM), marginTop, marginBottom };
}

/** The first of `labels` (longest first) that fits on one line of a chart `width` px wide at
 * [`chartFont`], at about 0.55 em a character (the page's sans-serif averages 0.49), or the last:
 * an axis label wider than its chart runs off both its ends ("spreading factor (250 kHz, gateway
 * at 1.0 km)" on a 360 px phone). Plot adds the axis's arrow, one character more. */
export function fitLabel(width: number, ...labels: string[]): string {
  return labels.find((l) => (l.length + 2) * 0.55 * chartFont() <= width - 8) ?? labels[labels.length - 1];
}

/** A margin that holds tick labels, px: `px` at the page's 13 px type, grown with the type (at
 * presentation mode's 18 px, "1,000" and "−140" ran past the chart's left edge in 50 px). */
export function labelRoom(px: number): number {
  return Math.round((px * chartFont()) / 13);
}

/**
 * How much taller a chart is drawn in presentation mode, where each panel has a screen to itself:
 * its panel's charts (`panelPlots`, their heights at the page's size, px) together take up to 55 %
 * of the window's height, at most three times their size. At 1024×768 the error chart was 212 px
 * of a 718 px panel, at 1920×1080 of a 1030 px one; the rest of the panel (title, legend, buttons,
 * notes) keeps its room. Drawn at the window's height when drawn: a window made taller afterwards
 * scales the chart with its width only.
 */
function presentedScale(panelPlots: number): number {
  if (!presenting()) return 1;
  return Math.min(3, Math.max(1, (0.55 * innerHeight) / panelPlots));
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
