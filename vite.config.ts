import { defineConfig, type Plugin } from 'vite';
import { readFileSync, readdirSync } from 'node:fs';
import { posix } from 'node:path';
import { Marked, type Tokens } from 'marked';
// Every export's caption names the version that made it.
import packageJson from './package.json' with { type: 'json' };

// The built page talks to no other host: a Content-Security-Policy makes that a rule the browser
// enforces. Only for the production build; the dev server needs its own websocket and inline client.
const csp: Plugin = {
  name: 'loratrack-csp',
  apply: 'build',
  transformIndexHtml(html) {
    const policy = [
      "default-src 'self'",
      "script-src 'self' 'wasm-unsafe-eval'",
      "style-src 'self' 'unsafe-inline'",
      "img-src 'self' data: blob:",
      "worker-src 'self' blob:",
      "connect-src 'self'",
      "object-src 'none'",
      "base-uri 'self'",
    ].join('; ');
    return html.replace('<head>', `<head>\n    <meta http-equiv="Content-Security-Policy" content="${policy}" />`);
  },
};

// The WebAssembly module is the page's largest download and every simulation needs it: fetch it from the first
// line of the page, not from when the entry script runs (www/loratrack.ts compiles the response).
const preloadWasm: Plugin = {
  name: 'loratrack-preload-wasm',
  apply: 'build',
  transformIndexHtml: {
    order: 'post',
    handler(html, { bundle }) {
      const wasm = Object.keys(bundle ?? {}).find((f) => f.endsWith('.wasm'));
      if (!wasm) throw new Error('no .wasm asset in the bundle');
      const charset = '<meta charset="utf-8" />';
      if (!html.includes(charset)) throw new Error('index.html has no charset declaration to follow');
      return html.replace(charset, `${charset}\n    <link rel="preload" href="./${wasm}" as="fetch" type="application/wasm" crossorigin>`);
    },
  },
};

/** A heading's anchor as GitHub makes it: lower case, punctuation dropped, spaces as hyphens. */
const slug = (text: string) => text.toLowerCase().replace(/<[^>]+>/g, '').replace(/[^\p{L}\p{N} _-]/gu, '').trim().replace(/ /g, '-');

/**
 * Markdown as the docs are written (GitHub's tables and heading anchors), for the Markdown file at
 * `source` (a path in the repository). Each link is resolved from that file's folder, then: a doc
 * or the README points at its rendered page, an image or SVG in `docs/` at its copy beside the
 * pages, an anchor or another host stays as written, and anything else (a source file) is left as
 * its text: the built page has no repository to open.
 */
function markdownFor(source: string): Marked {
  const page = (path: string): string | undefined => {
    if (path === 'README.md') return 'readme.html';
    const doc = /^docs\/([a-z-]+)\.md$/.exec(path);
    if (doc) return `${doc[1]}.html`;
    const figure = /^docs\/([\w.-]+\.(?:svg|png))$/.exec(path);
    return figure?.[1];
  };
  return new Marked({
    gfm: true,
    renderer: {
      link(this: { parser: { parseInline(tokens: Tokens.Generic[]): string } }, token: Tokens.Link) {
        const text = this.parser.parseInline(token.tokens);
        if (/^(https?:|#)/.test(token.href)) return `<a href="${token.href}">${text}</a>`;
        const [path, anchor = ''] = token.href.split(/(?=#)/);
        const target = page(posix.normalize(posix.join(posix.dirname(source), path)));
        return target ? `<a href="${target}${anchor}">${text}</a>` : text;
      },
      image(token: Tokens.Image) {
        const target = page(posix.normalize(posix.join(posix.dirname(source), token.href)));
        return target ? `<img src="${target}" alt="${token.text.replace(/"/g, '&quot;')}">` : token.text;
      },
      heading(this: { parser: { parseInline(tokens: Tokens.Generic[]): string } }, token: Tokens.Heading) {
        const text = this.parser.parseInline(token.tokens);
        return `<h${token.depth} id="${slug(text)}">${text}</h${token.depth}>\n`;
      },
    },
  });
}

/** The page's icon (index.html's), so that a doc page asks its server for no favicon. */
const ICON = /<link rel="icon" href="([^"]+)"/.exec(readFileSync('index.html', 'utf8'))?.[1] ?? 'data:,';

/** Each table in a box that scrolls sideways on a narrow screen, reachable by keyboard (a
 * focusable region, named by its number). */
function scrollingTables(html: string): string {
  let n = 0;
  return html.replace(/<table>/g, () => `<div class="scroll" tabindex="0" role="region" aria-label="Table ${++n}"><table>`).replace(/<\/table>/g, '</table></div>');
}

/** The Markdown file of page `name`: `docs/<name>.md`, or the README for `readme`. */
const sourceOf = (name: string) => (name === 'readme' ? 'README.md' : `docs/${name}.md`);

/** Page `name` (`docs/<name>.md`, or the README) as a page of its own: no script, nothing from
 * another host (its own CSP). */
function docPage(name: string): string {
  const source = readFileSync(sourceOf(name), 'utf8');
  const title = name === 'readme' ? 'README' : (/^# (.+)$/m.exec(source)?.[1] ?? name);
  return `<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8" />
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src 'self' data:; style-src 'unsafe-inline'" />
<link rel="icon" href="${ICON}" />
<meta name="viewport" content="width=device-width, initial-scale=1" />
<title>${title.replace(/[<>&]/g, '')} · loratrack</title>
<style>
h1 { font-size: 1.6rem; line-height: 1.25; }
body { font: 16px/1.5 system-ui, -apple-system, "Segoe UI", sans-serif; color: #1b1f24; margin: 0 auto; max-width: 60rem; padding: 1rem; }
.scroll { overflow-x: auto; }
table { border-collapse: collapse; font-size: 0.9rem; }
th, td { border: 1px solid #d8dde3; padding: 0.25rem 0.5rem; vertical-align: top; }
code { font-size: 0.9em; background: #f6f7f9; }
pre { overflow-x: auto; background: #f6f7f9; padding: 0.5rem; }
img { max-width: 100%; }
a { color: #1a55a0; }
</style>
</head>
<body>
<nav><a href="../">← the playground</a></nav>
<main>
${scrollingTables(markdownFor(sourceOf(name)).parse(source) as string)}
</main>
</body>
</html>
`;
}

const DOCS = [...readdirSync('docs').filter((f) => f.endsWith('.md')).map((f) => f.slice(0, -3)), 'readme'];

// The docs the page cites ("docs/senders.md", "README.md") as pages beside it, `docs/<name>.html`
// (the README's `docs/readme.html`): written into the build with the figures they show, and
// rendered on request by the dev server.
const docsPages: Plugin = {
  name: 'loratrack-docs',
  configureServer(server) {
    server.middlewares.use((req, res, next) => {
      const name = /^\/docs\/([a-z-]+)\.html$/.exec((req.url ?? '').split('?')[0])?.[1];
      if (!name || !DOCS.includes(name)) return next();
      res.setHeader('Content-Type', 'text/html; charset=utf-8');
      res.end(docPage(name));
    });
  },
  generateBundle() {
    for (const name of DOCS) this.emitFile({ type: 'asset', fileName: `docs/${name}.html`, source: docPage(name) });
    for (const figure of readdirSync('docs').filter((f) => /\.(svg|png)$/.test(f))) this.emitFile({ type: 'asset', fileName: `docs/${figure}`, source: readFileSync(`docs/${figure}`) });
  },
};

export default defineConfig({
  // Relative asset paths: dist/ works from any static server and under any sub-path.
  base: './',
  // Copied as they are: the one classic script, which must run before the first paint (present-mode.js).
  publicDir: 'www/public',
  plugins: [csp, preloadWasm, docsPages],
  define: { __LORATRACK_VERSION__: JSON.stringify(packageJson.version) },
  build: { target: 'es2022', outDir: 'dist', emptyOutDir: true, chunkSizeWarningLimit: 1024 },
  worker: { format: 'es' },
  server: { fs: { allow: ['.'] } },
});
