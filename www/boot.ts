// The page's entry. It starts what the first results wait for before the rest of the page's code
// (./main) is evaluated: the module's compilation, the simulation workers, and the run of the
// link's settings, which main.ts takes over when it asks for the same (pool.ts `start`). As one
// script, the workers could not even start until all of it had been evaluated, since a worker
// starts only once the page's thread is free. The chart libraries come later still (main.ts
// `plots`, the 3D view on first draw).
import { load } from './loratrack';
import { SimulationPool } from './pool';
import { simulateRequest } from './state';
import { store } from './store';

/** The page's worker pool, one worker per core. */
export const pool = new SimulationPool();
// An uploaded flight is never in a link: such a page waits for the file.
void load().then(() => store.settings.flight !== 'csv' && pool.start(simulateRequest(0, store.settings)));
void import('./main');
