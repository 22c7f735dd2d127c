import { defineConfig, type Plugin } from 'vite';
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

export default defineConfig({
  // Relative asset paths: dist/ works from any static server and under any sub-path.
  base: './',
  plugins: [csp, preloadWasm],
  define: { __LORATRACK_VERSION__: JSON.stringify(packageJson.version) },
  build: { target: 'es2022', outDir: 'dist', emptyOutDir: true, chunkSizeWarningLimit: 1024 },
  worker: { format: 'es' },
  server: { fs: { allow: ['.'] } },
});
