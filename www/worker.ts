// Runs simulations off the main thread so the page never freezes. One message in, one out:
//   { id, params, sweep? }  →  [{ id, partial }] { id, progress }* then { id, report } | { id, error }
//                               then, with sweep points, { id, sweep: [{ point, report?, error? }] }
import { load, loadCsv, settingOf, simulate, stationsOf, swarm, valueThatFits, type SimReport, type SimulateParams, type SwarmParams, type SwarmReport } from './loratrack';
import { firstRefusal, merge } from './merge';
import { withoutUnreadFlightSettings } from './stations';

/** One point of a sweep beside the main run: the gateway at another distance, or another SF. */
export type SweepPoint = { distance: number } | { sf: number };

/** One sweep point's run: its report, and why the core refused it (e.g. an error-triggered
 * heartbeat shorter than SF12's interval) where it refused any station: the report then has the
 * stations that ran, if any. The main run stands either way. */
export interface SweepResult {
  point: SweepPoint;
  report?: SimReport;
  error?: string;
  /** The setting the error names (`settingOf`), for the page to give its label. */
  setting?: string;
  /** That setting's value with which the point would run (`valueThatFits`), where the core knows one. */
  valueThatFits?: number;
}

export interface SimulateRequest {
  id: number;
  params: SimulateParams;
  sweep?: SweepPoint[];
  /** An uploaded flight's file, read here into `params.trajectory`: a Blob goes to a worker by
   * reference, where its 31 MB of text (10⁶ rows) copied to each worker held the page's thread
   * ~50 ms. */
  trajectoryFile?: Blob;
  /** A blob URL the page revokes to stop this run (`SimulationPool.interrupt`): checked between
   * flights (`stillWanted`), so a run a newer one replaced ends within ~0.1 s and its worker,
   * caches kept, takes the next request. */
  stop?: string;
  /** A blob URL the page revokes to stop the reading of `trajectoryFile` (`SimulationPool`'s
   * `readStop`): kept while runs of the same file follow, whose stop URLs are revoked. */
  readStop?: string;
}

/** Swarms of each size in `sizes`, otherwise `params`. */
export interface SwarmRequest {
  id: number;
  swarm: { sizes: number[]; params: SwarmParams };
  /** A blob URL the page revokes to stop these swarms (`runSwarms`' `stop`), as `SimulateRequest`'s. */
  stop?: string;
}

/** A worker's first message: the page's compiled module, which it instantiates (`spawnWorker`). */
export interface ModuleMessage {
  module: WebAssembly.Module;
}

export type Request = SimulateRequest | SwarmRequest;

export type Response =
  | { id: number; progress: number }
  /** The whole synthetic set's first flight alone, sent before the set (its own report: 1 flight). */
  | { id: number; partial: SimReport }
  | { id: number; report: SimReport; millis: number }
  /** The core's message, the setting it refuses where one is at fault (`settingOf`) and, where
   * the core knows one, the value of that setting with which the run would go ahead
   * (`valueThatFits`: the seeds that fit, the heartbeat the slowest data rate needs). */
  | { id: number; error: string; setting?: string; valueThatFits?: number }
  | { id: number; sweep: SweepResult[] }
  | { id: number; swarms: SwarmReport[] };

/** CSV texts above this size are read first with their own progress. */
const LARGE_CSV_BYTES = 1 << 20;

let icuWarmed = false;
/**
 * Builds the page's first `Intl.NumberFormat`, once, here instead of on the main thread. Plot's
 * chunk builds one when it is evaluated (its default tick format), and the first in a page loads
 * ICU's number data: 20–33 ms of a cold load's main thread, most of that chunk's evaluating task.
 * ICU keeps that data for the whole renderer process, so built once in a worker it costs the main
 * thread 0.3 ms. Done just after the first report (or the whole set's first flight) is posted,
 * while the page handles it and before it asks for the charts' code (docs/performance.md).
 */
function warmNumberFormat(): void {
  if (icuWarmed) return;
  icuWarmed = true;
  new Intl.NumberFormat('en-US').format(1.5);
}

/** How often a run checks whether it is still wanted, ms: each check is a request to the browser
 * (about 1–3 ms on a busy 2-core machine), so a run spends at most a few per cent on them. */
const STOP_CHECK_MS = 100;

/** Whether this worker can read a blob URL synchronously: where it cannot, no run is ever
 * stopped (each then ends as it would have). */
const canCheck = ((): boolean => {
  try {
    const url = URL.createObjectURL(new Blob(['']));
    const ok = loads(url);
    URL.revokeObjectURL(url);
    return ok;
  } catch {
    return false;
  }
})();

/** Whether `url` loads now: a synchronous request, allowed in a worker. */
function loads(url: string): boolean {
  try {
    const request = new XMLHttpRequest();
    request.open('GET', url, false);
    request.send();
    return request.status === 200;
  } catch {
    return false;
  }
}

/**
 * Whether the run whose stop URL is `stop` is still wanted: checked at its first call (a request
 * that waited behind a stopped run may itself have been replaced since) and then at most every
 * STOP_CHECK_MS. A worker busy in the core reads no message until the run returns, and terminating
 * it would throw away its caches; a page that closes mid-run left its workers computing for seconds
 * in Chromium (docs/performance.md, twenty-second and twenty-third sessions). A URL the page revokes
 * is the one signal that reaches a running worker without SharedArrayBuffer (which static hosting
 * cannot enable), and a closing page's URLs are revoked with it.
 */
function stillWanted(stop: string | undefined): () => boolean {
  if (!stop || !canCheck) return () => true;
  let last = -Infinity;
  let wanted = true;
  return () => {
    const now = performance.now();
    if (wanted && now - last >= STOP_CHECK_MS) {
      last = now;
      wanted = loads(stop);
    }
    return wanted;
  };
}

let give: (module: WebAssembly.Module) => void;
const ready = load(new Promise((resolve) => (give = resolve)));

self.onmessage = async (event: MessageEvent<Request | ModuleMessage>) => {
  if ('module' in event.data) return give(event.data.module);
  await ready;
  const post = (r: Response) => (self as unknown as Worker).postMessage(r);
  if ('swarm' in event.data) return runSwarms(event.data, post);
  const { id, sweep: points, trajectoryFile } = event.data;
  const wanted = stillWanted(event.data.stop);
  const readWanted = stillWanted(event.data.readStop);
  try {
    const params = trajectoryFile ? { ...event.data.params, trajectory: await trajectoryFile.text() } : event.data.params;
    const t0 = performance.now();
    let last = 0;
    // A few dozen messages at most: one per 2 % of the work. A large CSV is read first, with its
    // own progress (the first half of the bar), then simulated from the module's cache.
    // Returns whether the work goes on (`simulate`'s and `loadCsv`'s progress: false stops it).
    const report_ = (from: number, share: number, goOn = wanted) => (done: number, total: number) => {
      const p = from + (share * done) / total;
      if (p - last >= 0.02 || done === total) {
        last = p;
        post({ id, progress: p });
      }
      return goOn();
    };
    const large = (params.trajectory?.length ?? 0) > LARGE_CSV_BYTES;
    // The whole set takes 30 flights' time; its first flight alone, about a thirtieth of it, gives
    // the page numbers to show (marked as one flight) while the rest runs.
    if (params.synthetic === 'all') {
      post({ id, partial: simulate({ ...params, synthetic: 1, series: true }) });
      warmNumberFormat();
    }
    // A file's reading goes on when only its run is stopped (a setting changed): its lines are the
    // module's cache for the next run of the file. It stops when the page reads another.
    if (large && params.trajectory) loadCsv({ trajectory: params.trajectory, trajectoryName: params.trajectoryName }, report_(0, 0.5, readWanted));
    const report = simulate({ ...params, series: true }, large ? report_(0.5, 0.5) : report_(0, 1));
    post({ id, report, millis: performance.now() - t0 });
    warmNumberFormat();
    if (points?.length) {
      // Only the link changes between these runs: the drone filters come from the cache. One
      // seed each (the charts show the spread across the sweep, not across seeds). A distance
      // moves the one default gateway, so listed gateways are left out; another SF is a fixed
      // data rate (ADR would move it).
      if (!wanted()) return;
      const sweep = points.map((point) => sweepPoint({ ...params, ...('distance' in point ? { gateways: [] } : { adr: 'off' }), ...point, seeds: 1, series: false }, point));
      post({ id, sweep });
    }
  } catch (e) {
    post(refusal(id, e));
  }
};

/** What the core said in refusing a run: its message, the setting it names and the value of that
 * setting that fits, where it knows one. */
const why = (e: unknown) => ({ error: e instanceof Error ? e.message : String(e), setting: settingOf(e), valueThatFits: valueThatFits(e) });

/** The answer to request `id` when the core refused it. */
const refusal = (id: number, e: unknown): Response => ({ id, ...why(e) });

/** A sweep point's run. Where the core refuses it, each station is tried alone: a data rate may
 * carry DR's and CTRA+'s frames but not the 12-byte one (US915's SF10), or an error-triggered
 * heartbeat fit the shorter frames' intervals; those that run are kept, with the refusal. */
function sweepPoint(params: SimulateParams, point: SweepPoint): SweepResult {
  const run = (p: SimulateParams): SweepResult => {
    try {
      return { point, report: simulate(p) };
    } catch (e) {
      return { point, ...why(e) };
    }
  };
  const all = run(params);
  const stations = stationsOf(params.model);
  if (all.report || stations.length < 2) return all;
  const alone = stations.map((m) => run(withoutUnreadFlightSettings({ ...params, model: m })));
  const ran = alone.flatMap((x) => (x.report ? [x.report] : []));
  return ran.length ? { point, report: merge(ran, stations, params.model ?? 'all'), ...firstRefusal([...alone, all]) } : all;
}

function runSwarms({ id, swarm: { sizes, params }, stop }: SwarmRequest, post: (r: Response) => void): void {
  const wanted = stillWanted(stop);
  try {
    const total = sizes.reduce((a, b) => a + b, 0);
    let before = 0;
    const swarms = sizes.map((drones) => {
      // The core asks every ~0.2–0.4 s (a group of drones computed ahead, or of stations scored).
      const r = swarm({ ...params, drones }, (done, all) => {
        post({ id, progress: (before + (done / all) * drones) / total });
        return wanted();
      });
      before += drones;
      return r;
    });
    post({ id, swarms });
  } catch (e) {
    post(refusal(id, e));
  }
}
