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
    const shown = [...document.querySelectorAll<HTMLElement>('.panel')].filter((p) => p.offsetParent !== null).sort((a, b) => a.getBoundingClientRect().top - b.getBoundingClientRect().top);
    const next = step > 0 ? shown.find((p) => p.getBoundingClientRect().top > 5) : [...shown].reverse().find((p) => p.getBoundingClientRect().top < -5);
    next?.scrollIntoView({ block: 'start' });
  });
  // The link's `?present=1` is read once, before the first paint (public/present-mode.js, which
  // marks <html>); the button follows it.
  if (presenting()) $('#present-toggle').setAttribute('aria-pressed', 'true');
}
