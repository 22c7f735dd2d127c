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

export default defineConfig({
  // Relative asset paths: dist/ works from any static server and under any sub-path.
  base: './',
  plugins: [csp],
  define: { __LORATRACK_VERSION__: JSON.stringify(packageJson.version) },
  build: { target: 'es2022', outDir: 'dist', emptyOutDir: true, chunkSizeWarningLimit: 1024 },
  worker: { format: 'es' },
  server: { fs: { allow: ['.'] } },
});
