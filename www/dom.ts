// The one DOM helper the page's modules share.

/** The element `selector` names; the page's markup (index.html) has every one they ask for. */
export const $ = <T extends HTMLElement>(selector: string) => document.querySelector<T>(selector)!;
