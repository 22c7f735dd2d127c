// Evaluated first (main.ts imports it before anything else): the simulation workers and the
// page's own copy of the WebAssembly module start loading while the rest of the page's modules
// (the chart libraries among them) are still being evaluated.
import { load } from './loratrack';
import { SimulationPool } from './pool';

/** The page's worker pool, one worker per core. */
export const pool = new SimulationPool();
void load();
