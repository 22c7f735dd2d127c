import type { ModelName } from '../loratrack';

/** One colour per model everywhere on the page (colour-blind-safe Tableau hues). */
export const MODEL_COLORS: Record<ModelName, string> = { dr: '#e15759', 'ctra-plus': '#4e79a7', '3d-ctra': '#59a14f', imm: '#b07aa1', mission: '#f28e2b' };
export const TRUTH_COLOR = '#222222';
/** The mission's flight plan in the 3D view (dashed). */
export const PLAN_COLOR = '#9c755f';

/** Chart text, CSS px: 13 (Plot's default is 10), legible at 1280 px and on a phone, where the
 * charts are drawn at their box's width and never scaled down much; 18 in presentation mode
 * (`<body class="present">`), for the back of a lecture room. */
export function chartFont(): number {
  return document.body.classList.contains('present') ? 18 : 13;
}

/** Plot's style for every chart, at [`chartFont`]. */
export function chartStyle(): Partial<CSSStyleDeclaration> {
  return { fontSize: `${chartFont()}px`, overflow: 'visible' };
}
