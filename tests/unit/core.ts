// The core for unit tests that run it: www/loratrack.ts's functions, on the WebAssembly package
// `npm run build` makes (www/pkg), compiled from its bytes (Node's fetch reads no file URL).
import { readFileSync } from 'node:fs';
import * as api from '../../www/loratrack';

/** Instantiates the package once; every function of www/loratrack.ts may be called after it. */
export function loadCore(): Promise<void> {
  return api.load(WebAssembly.compile(readFileSync(new URL('../../www/pkg/loratrack_bg.wasm', import.meta.url))));
}

export { api };
