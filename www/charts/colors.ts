import type { ModelName } from '../loratrack';

/** One colour per model everywhere on the page (colour-blind-safe Tableau hues). */
export const MODEL_COLORS: Record<ModelName, string> = { dr: '#e15759', 'ctra-plus': '#4e79a7', '3d-ctra': '#59a14f', imm: '#b07aa1' };
export const TRUTH_COLOR = '#222222';

/** Chart text at 13 CSS px (Plot's default is 10): legible at 1280 px and on a phone, where the
 * charts are drawn at their box's width and never scaled down much. */
export const CHART_STYLE = { fontSize: '13px', overflow: 'visible' };
