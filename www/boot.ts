// The page's entry. It starts what the first results wait for before the rest of the page's code
// (./main) is evaluated: the module's compilation, the simulation workers, and the run of the
// link's settings, which main.ts takes over when it asks for the same (pool.ts `start`). As one
// script, the workers could not even start until all of it had been evaluated, since a worker
// starts only once the page's thread is free. The chart libraries come later still (main.ts
// `plots`, the 3D view on first draw).
import { load } from './loratrack';
import { SimulationPool } from './pool';
import { simulateRequest, uploaded } from './state';
import { store } from './store';

/** The settings a person changed in the form before main.ts took over, by control name, with
 * the value (or, for a checkbox, the state) each was left at: the form works as soon as the HTML
 * is parsed, and main.ts would otherwise write the link's settings over such a choice without a
 * word. */
export const changedEarly = new Map<string, string | boolean>();
const noteEarly = (e: Event) => {
  // As form.ts `field` finds a setting's control: by its name, or its id where it has none.
  const el = e.target as HTMLInputElement | HTMLSelectElement | null;
  // A chosen file cannot be written back to its control; one chosen this early is not read.
  if (el instanceof HTMLInputElement && el.type === 'file') return;
  const name = el?.name || el?.id;
  if (el && name) changedEarly.set(name, el instanceof HTMLInputElement && el.type === 'checkbox' ? el.checked : el.value);
};
for (const type of ['input', 'change']) document.getElementById('controls')?.addEventListener(type, noteEarly);

/** The page's worker pool, one worker per core. */
export const pool = new SimulationPool();
// An uploaded flight is never in a link: such a page waits for the file.
void load().then(() => !uploaded(store.settings.flight) && pool.start(simulateRequest(0, store.settings)));
void import('./main');
