// A small pool of simulation workers, one per core (at most 8), each with its own module
// instance: no SharedArrayBuffer, so the page still works statically hosted and in an iframe.
//
// A request is split by station: each worker simulates some of the models and the pool merges
// their reports in the request's model order. Every station's numbers depend only on the
// flight, the seed and its own settings (the link's random streams are derived per flight), so
// the merged report equals what one worker (or the CLI) computes for all models at once.
import { compiledModule, splitStations, stationsOf, type SimReport, type SwarmParams, type SwarmReport } from './loratrack';
import { merge, mergeSweepPoint } from './merge';
import { withoutUnreadFlightSettings } from './stations';
import type { ModuleMessage, Request, Response, SimulateRequest, SweepResult } from './worker';

/** A simulation worker (www/worker.ts), given the page's compiled module once it is ready;
 * messages sent before then wait in the worker until it has instantiated the module. */
export function spawnWorker(): Worker {
  const worker = new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' });
  void compiledModule().then((module) => worker.postMessage({ module } satisfies ModuleMessage));
  return worker;
}

/** One worker per core, at most 8. */
const defaultPoolSize = () => Math.max(1, Math.min(8, navigator.hardwareConcurrency || 2));

/** The drones of the swarms `share` (indices into `sizes`) together. */
const dronesIn = (share: number[], sizes: number[]) => share.reduce((sum, i) => sum + sizes[i], 0);

/** Which swarms (indices into `sizes`, their drone counts) each of at most `workers` workers
 * runs: largest first, each to the worker with the fewest drones so far. */
export function shareOut(sizes: number[], workers: number): number[][] {
  const shares: number[][] = Array.from({ length: Math.max(1, Math.min(workers, sizes.length)) }, () => []);
  for (const i of sizes.map((_, i) => i).sort((a, b) => sizes[b] - sizes[a])) {
    shares.reduce((least, share) => (dronesIn(share, sizes) < dronesIn(least, sizes) ? share : least)).push(i);
  }
  return shares;
}

/** A fresh stop URL: a run's workers go on while it loads (www/worker.ts `stillWanted`). */
const newStop = () => URL.createObjectURL(new Blob(['']));

/** A swarm run under way on its workers (`runSwarms`). */
export interface SwarmRun {
  /** The swarms in the order asked for, and the wall-clock time they took, ms. */
  done: Promise<{ swarms: SwarmReport[]; millis: number }>;
  /** Stops every worker of the run, the swarm under way within ~0.4 s; `done` then never settles. */
  stop(): void;
}

/**
 * Swarms of each size in `sizes` (otherwise `params`) on up to `workers` workers at once, each
 * swarm going, largest first, to the worker with the fewest drones so far (a swarm's work grows
 * with its drones). Every swarm is independent and its numbers depend only on its settings and
 * seed, so where it runs changes nothing but the wait: on two cores, swarms of 2 … 200 drones take
 * about as long as the 200 alone instead of all of them in turn. `progress` gets the share of
 * drones done, 0…1.
 */
export function runSwarms(sizes: number[], params: SwarmParams, progress: (done: number) => void, workers = defaultPoolSize()): SwarmRun {
  const started = performance.now();
  const shares = shareOut(sizes, workers);
  const total = sizes.reduce((a, b) => a + b, 0);
  const running = shares.map(() => spawnWorker());
  const done = new Array<number>(shares.length).fill(0);
  const swarms = new Array<SwarmReport>(sizes.length);
  // A page that closes mid-swarm left its workers computing for seconds in Chromium (where another
  // page of the site kept the renderer, as the browser suite's pages do: 4.1-4.2 CPU-s in the 3 s
  // after the close); the run's URL, revoked by stop() and by a closing page alike, stops its
  // swarm at the core's next question (www/worker.ts `stillWanted`).
  const stopUrl = newStop();
  const stop = () => {
    URL.revokeObjectURL(stopUrl);
    running.forEach((w) => {
      w.onmessage = null;
      w.terminate();
    });
  };
  const finished = Promise.all(
    shares.map(
      (share, k) =>
        new Promise<void>((resolve, reject) => {
          running[k].onmessage = (e: MessageEvent<Response>) => {
            const r = e.data;
            if ('progress' in r) {
              done[k] = r.progress * dronesIn(share, sizes);
              progress(done.reduce((a, b) => a + b, 0) / total);
            } else if ('swarms' in r) {
              share.forEach((i, j) => (swarms[i] = r.swarms[j]));
              running[k].terminate();
              resolve();
            } else if ('error' in r) {
              stop();
              // With the setting the core names and the value of it that fits, as a thrown
              // error carries them (`settingOf`, `valueThatFits`).
              reject(Object.assign(new Error(r.error), { setting: r.setting, valueThatFits: r.valueThatFits }));
            }
          };
          running[k].postMessage({ id: 1, swarm: { sizes: share.map((i) => sizes[i]), params }, stop: stopUrl } satisfies Request);
        }),
    ),
  );
  return {
    done: finished.then(() => {
      URL.revokeObjectURL(stopUrl);
      return { swarms, millis: performance.now() - started };
    }),
    stop,
  };
}

type Part = { progress: number; partial?: SimReport; report?: SimReport; millis?: number; sweep?: SweepResult[] };

export class SimulationPool {
  private workers: Worker[];
  private handlers = new Map<number, (r: Response) => void>();
  /** The URL the runs sent from now on carry; revoked to stop them (`interrupt`). */
  private stop = newStop();
  /** The uploaded file the runs sent from now on read, and the URL revoked to stop its reading
   * once a run asks for another file or none (`readStop`). */
  private reading?: { file: Blob; stop: string };
  /** A run started before anyone asked for it (`start`), with the answers it has had so far. */
  private early?: { key: string; answers: Response[]; on?: (r: Response) => void };

  constructor(readonly size = defaultPoolSize()) {
    this.workers = Array.from({ length: size }, () => {
      const w = spawnWorker();
      w.onmessage = (e: MessageEvent<Response>) => this.handlers.get(e.data.id)?.(e.data);
      return w;
    });
  }

  /** Stops the runs under way: each worker ends its run before its next flight (within ~0.1 s
   * and that flight) and takes the next request with its caches, so a change of settings during
   * a whole set waits neither for the set nor for fresh workers to compute the drones again.
   * Their answers are dropped. (Terminated and replaced, the workers started without caches: 1.8 s
   * to a new whole set's results instead of 0.9 s, docs/performance.md.) */
  interrupt(): void {
    URL.revokeObjectURL(this.stop);
    this.stop = newStop();
    this.handlers.clear();
  }

  /** The stop URL for reading `file`: a file's reading goes on through a change of settings, which
   * stops only its run (the lines read are the workers' cache for the next run of the same file),
   * and ends once a run asks for another file or none, so that a second upload does not wait for
   * the first (10⁶ rows: about 2 s). */
  private readStop(file: Blob | undefined): string | undefined {
    if (this.reading?.file === file) return this.reading?.stop;
    if (this.reading) URL.revokeObjectURL(this.reading.stop);
    this.reading = file && { file, stop: newStop() };
    return this.reading?.stop;
  }

  /** Starts `request` before anyone asks for it (boot.ts: the link's settings, while the rest of
   * the page loads); the next `run` takes it over, answers so far included, if it asks for the
   * same, and stops it otherwise. */
  start(request: SimulateRequest): void {
    const early: NonNullable<typeof this.early> = { key: sameRun(request), answers: [] };
    this.run(request, (r) => (early.on ? early.on(r) : early.answers.push(r)));
    this.early = early;
  }

  /** Runs `request`, calling `on` with the merged first flight of a whole set, progress, then the
   * merged report, then the merged sweep (or one error), as a single worker would. */
  run(request: SimulateRequest, on: (r: Response) => void): void {
    const early = this.early;
    this.early = undefined;
    // Only when a run was started early: the key writes the whole request out (an early run is
    // never an upload's: a link cannot carry the file).
    if (early && early.key === sameRun(request)) {
      early.on = (r) => on({ ...r, id: request.id });
      for (const r of early.answers) early.on(r);
      return;
    }
    // Its answers would come before this run's: stop it.
    if (early) this.interrupt();
    // The core reads the model setting (the page has loaded the module before any run).
    const models: string[] = stationsOf(request.params.model);
    // Group g goes to worker g. The core splits the stations by their work (DR with CTRA+ and
    // 3D-CTRA alone, not DR with 3D-CTRA: the whole set's runs wait less for the busier worker),
    // and the same list always alike, so each worker's caches keep serving its stations.
    const groups = splitStations(request.params.model, this.workers.length);
    const readStop = this.readStop(request.trajectoryFile);
    const parts: Part[] = groups.map(() => ({ progress: 0 }));
    let failed = false;
    const forget = () => groups.forEach((_, k) => this.handlers.delete(request.id * 16 + k));
    groups.forEach((group, g) => {
      const id = request.id * 16 + g;
      this.handlers.set(id, (r) => {
        if (failed) return;
        const part = parts[g];
        if ('error' in r) {
          failed = true;
          forget();
          on({ id: request.id, error: r.error, setting: r.setting, valueThatFits: r.valueThatFits });
          return;
        }
        if ('partial' in r) {
          part.partial = r.partial;
          if (parts.every((p) => p.partial)) on({ id: request.id, partial: merge(parts.map((p) => p.partial!), models, request.params.model ?? 'all') });
        }
        if ('progress' in r) part.progress = r.progress;
        if ('report' in r) [part.report, part.millis] = [r.report, r.millis];
        if ('sweep' in r) part.sweep = r.sweep;
        if ('progress' in r) on({ id: request.id, progress: parts.reduce((a, p) => a + p.progress, 0) / parts.length });
        if ('report' in r && parts.every((p) => p.report)) {
          on({ id: request.id, report: merge(parts.map((p) => p.report!), models, request.params.model ?? 'all'), millis: Math.max(...parts.map((p) => p.millis ?? 0)) });
        }
        if ('sweep' in r && parts.every((p) => p.sweep)) {
          const sweep = parts[0].sweep!.map(({ point }, i) => mergeSweepPoint(point, parts.map((p) => p.sweep![i]), models, request.params.model ?? 'all'));
          forget();
          on({ id: request.id, sweep });
        }
      });
      // Groups are non-empty for workers 0..min(size, stations) − 1, in order: group g is worker g's.
      this.workers[g].postMessage({
        ...request,
        id,
        params: withoutUnreadFlightSettings({ ...request.params, model: group.join(',') }),
        stop: this.stop,
        readStop,
      } satisfies SimulateRequest);
    });
  }
}

/** Two requests with the same key ask for the same run (whatever their ids). */
function sameRun(request: SimulateRequest): string {
  return JSON.stringify({ ...request, id: 0 });
}

