// Presentation mode (`?present=1`, the button, key P): large type, high contrast, one panel per
// screen, the arrow keys step between panels; the charts are drawn again at the larger size.
import { $, presenting } from './dom';
import { pageQuery } from './store';

/** Wires the button and the keys; `redraw` draws every chart again at the current size. */
export function setUpPresent(redraw: () => void): void {
  function setPresent(on: boolean): void {
    document.documentElement.classList.toggle('present', on);
    $('#present-toggle').setAttribute('aria-pressed', String(on));
    history.replaceState(null, '', `?${pageQuery()}`);
    // Charts are drawn at their box's width with text in px: draw them again at the new size.
    redraw();
  }

  $('#present-toggle').addEventListener('click', () => setPresent(!presenting()));
  document.addEventListener('keydown', (e) => {
    const target = e.target as HTMLElement;
    if (e.ctrlKey || e.metaKey || e.altKey || target.closest('input, select, textarea, canvas, dialog, [contenteditable]')) return;
    if (e.key === 'p' || e.key === 'P') {
      e.preventDefault();
      setPresent(!presenting());
      return;
    }
    const step = { ArrowDown: 1, ArrowRight: 1, PageDown: 1, ArrowUp: -1, ArrowLeft: -1, PageUp: -1 }[e.key];
    if (!step || !presenting()) return;
    e.preventDefault();
    stepScreen(step);
  });
  // The link's `?present=1` is read once, before the first paint (public/present-mode.js, which
  // marks <html>); the button follows it.
  if (presenting()) $('#present-toggle').setAttribute('aria-pressed', 'true');
}

/** How far (px) a panel's edge may lie from the window's top and still count as at it. */
const AT_TOP = 5;
/** What one step within a tall panel keeps of the screen before it, px: a line or two, so that
 * the reader sees where the new screen goes on from. */
const OVERLAP = 60;

/**
 * One step of the arrow keys: to the next (`step` 1) or the previous (−1) panel's top, but first,
 * where the panel in view is taller than the window, a screen at a time through it. A panel
 * longer than its screen (at 1024×768 the time-on-air table filled the screen and hid the chart
 * under it; the link budget's buttons lay 118 px below the fold) was otherwise never shown whole:
 * the next step went to the next panel's top, and from the last panel nowhere.
 */
function stepScreen(step: number): void {
  const shown = [...document.querySelectorAll<HTMLElement>('.panel')]
    .filter((p) => p.offsetParent !== null)
    .map((p) => ({ p, box: p.getBoundingClientRect() }))
    .sort((a, b) => a.box.top - b.box.top);
  // The panel in view: the last whose top is at or above the window's.
  const current = shown.filter((s) => s.box.top <= AT_TOP).at(-1)?.box;
  if (step > 0) {
    const below = current ? current.bottom - innerHeight : 0;
    if (below > AT_TOP) {
      scrollBy({ top: Math.min(below + AT_TOP, innerHeight - OVERLAP) });
      return;
    }
    shown.find((s) => s.box.top > AT_TOP)?.p.scrollIntoView({ block: 'start' });
    return;
  }
  if (current && current.top < -AT_TOP && current.bottom > 0) {
    scrollBy({ top: -Math.min(-current.top, innerHeight - OVERLAP) });
    return;
  }
  const previous = [...shown].reverse().find((s) => s.box.top < -AT_TOP);
  // Before the first panel: the page's top, with its title (and a lesson's steps).
  if (previous) previous.p.scrollIntoView({ block: 'start' });
  else scrollTo({ top: 0 });
}
