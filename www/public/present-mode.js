// Presentation mode as the link asks (`?present=1`), before the page's first paint. A classic
// script in the head: the page's own code (www/present.ts) comes after the first paint, so the page
// was laid out and painted as usual, then again as a presentation, the whole of it moving (a layout
// shift of 0.4-0.8 at a projector's sizes). The stylesheet keys on this class of <html>.
if (new URLSearchParams(location.search).get('present') === '1') document.documentElement.classList.add('present');
