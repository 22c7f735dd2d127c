// Downloads: error series (CSV), configuration and results (JSON), charts (SVG or PNG). Everything
// is made in the page from data it already has: no request leaves it.
import type { SimReport } from './loratrack';

function save(blob: Blob, name: string): void {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

/** The first flight's error series: one row per evaluation time, one column per model. */
export function downloadErrorCsv(report: SimReport): void {
  const models = report.series?.models ?? [];
  const header = ['t_s', ...models.map((m) => `${m.model}_error3d_m`)];
  // Each station starts at its own first packet: join the series on time, empty before it.
  const byTime = new Map<number, string[]>();
  models.forEach((m, k) =>
    m.t.forEach((t, i) => {
      const row = byTime.get(t) ?? models.map(() => '');
      row[k] = m.error3d[i].toFixed(4);
      byTime.set(t, row);
    }),
  );
  const rows = [...byTime.entries()].sort((a, b) => a[0] - b[0]).map(([t, cells]) => [t.toFixed(2), ...cells]);
  save(new Blob([[header, ...rows].map((r) => r.join(',')).join('\n') + '\n'], { type: 'text/csv' }), 'loratrack-error-series.csv');
}

/** Configuration and results, without the bulky series. */
export function downloadJson(report: SimReport, settings: unknown): void {
  const { series: _series, ...rest } = report;
  save(new Blob([JSON.stringify({ settings, ...rest }, null, 2)], { type: 'application/json' }), 'loratrack-results.json');
}

/** The chart itself: the largest SVG (a figure also holds the legend's small swatches). */
export function chartSvg(chart: Element): SVGSVGElement | null {
  if (chart instanceof SVGSVGElement) return chart;
  const area = (s: SVGSVGElement) => Number(s.getAttribute('width') ?? 0) * Number(s.getAttribute('height') ?? 0);
  return [...chart.querySelectorAll('svg')].reduce<SVGSVGElement | null>((best, s) => (!best || area(s) > area(best) ? s : best), null);
}

function svgText(svg: SVGSVGElement): string {
  const clone = svg.cloneNode(true) as SVGSVGElement;
  clone.setAttribute('xmlns', 'http://www.w3.org/2000/svg');
  clone.style.background = 'white';
  return new XMLSerializer().serializeToString(clone);
}

export function downloadSvg(chart: Element, name: string): void {
  const svg = chartSvg(chart);
  if (svg) save(new Blob([svgText(svg)], { type: 'image/svg+xml' }), `${name}.svg`);
}

export function downloadPng(chart: Element, name: string): void {
  const svg = chartSvg(chart);
  if (!svg) return;
  const { width, height } = svg.getBoundingClientRect();
  const img = new Image();
  img.onload = () => {
    const canvas = document.createElement('canvas');
    canvas.width = Math.ceil(width * 2);
    canvas.height = Math.ceil(height * 2);
    const ctx = canvas.getContext('2d')!;
    ctx.fillStyle = 'white';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
    canvas.toBlob((b) => b && save(b, `${name}.png`));
  };
  img.src = URL.createObjectURL(new Blob([svgText(svg)], { type: 'image/svg+xml' }));
}

export function downloadDataUrl(url: string, name: string): void {
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  a.click();
}
