// The DOM helpers the page's modules share.

/** The element `selector` names; the page's markup (index.html) has every one they ask for. */
export const $ = <T extends HTMLElement>(selector: string) => document.querySelector<T>(selector)!;

/**
 * Whether the page is in presentation mode: the class `present` on `<html>`, which the stylesheet
 * keys on. A `?present=1` link sets it before the first paint (public/present-mode.js), the
 * button and key P toggle it (present.ts); everything else reads it here.
 */
export const presenting = (): boolean => document.documentElement.classList.contains('present');

/**
 * Makes every mention of a doc in `root`'s text ("docs/senders.md") a link to that doc's page
 * beside the playground (`docs/senders.html`, which the build renders: vite.config.ts), opened in
 * a new tab so that the settings on show stay. The texts keep naming the Markdown file, as the
 * README and the repository do; a slide's caption copies them as plain text.
 */
export function linkDocs(root: Element): void {
  const mention = /(docs\/[a-z-]+\.md|README\.md)/;
  const walker = document.createTreeWalker(root, NodeFilter.SHOW_TEXT);
  const found: Text[] = [];
  for (let n = walker.nextNode(); n; n = walker.nextNode()) if (mention.test(n.nodeValue ?? '') && !n.parentElement?.closest('a')) found.push(n as Text);
  for (const text of found) {
    const parts = (text.nodeValue ?? '').split(mention).map((part, i) => {
      if (i % 2 === 0) return part;
      const link = document.createElement('a');
      link.href = docHref(part);
      link.target = '_blank';
      link.rel = 'noopener';
      link.textContent = part;
      return link;
    });
    text.replaceWith(...parts);
  }
}

/** The rendered page of a doc the page names: `docs/<name>.md` → `docs/<name>.html`, the README →
 * `docs/readme.html` (vite.config.ts renders them). */
const docHref = (mention: string) => (mention === 'README.md' ? 'docs/readme.html' : mention.replace(/\.md$/, '.html'));

/**
 * Marks each of `wraps` (`.table-wrap` boxes) `.tight` where its table is too wide for it as it
 * is; the stylesheet then lets some of its cells break where they may (a p75's interval after its
 * dash, a time on air before its interval). Only then: were breaking always allowed, the table's
 * layout would narrow every column that can wrap where the headers alone make room. Returns
 * whether they all fit.
 */
export function tighten(wraps: Iterable<HTMLElement>): boolean {
  let fits = true;
  for (const wrap of wraps) {
    wrap.classList.remove('tight');
    if (wrap.scrollWidth <= wrap.clientWidth + 1) continue;
    wrap.classList.add('tight');
    fits &&= wrap.scrollWidth <= wrap.clientWidth + 1;
  }
  return fits;
}

/**
 * `fit` for `box`, to be called whenever `box`'s content changes: it also runs whenever the box
 * changes width (a phone turned, a window resized, presentation mode toggled), but not when only
 * the box's height changes, which fitting does, so the observer cannot feed itself; nor when the
 * observer first reports the box at the width it was just fitted at (the results table was laid
 * out twice on every load: 15–30 ms more at 390 px, 2–7 ms at 1280 px).
 */
export function fitOnWidth(box: HTMLElement, fit: () => void): () => void {
  let fitted = -1;
  const run = () => {
    fitted = box.clientWidth;
    fit();
  };
  new ResizeObserver(() => {
    if (box.clientWidth !== fitted) run();
  }).observe(box);
  return run;
}
