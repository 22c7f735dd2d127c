// The one module that imports the generated WebAssembly package (www/pkg, built by
// scripts/build-wasm.mjs). Everything else — the page and its worker — imports these typed
// functions. Each takes the CLI's long options in camelCase and returns what
// `loratrack <command> --json` prints; bad input throws an Error (`settingOf` names the setting
// at fault). The types come from the Rust
// ones (www/generated/types.ts, generated and checked by `cargo test`); see docs/reference.md.
import init, * as wasm from './pkg/loratrack.js';
import wasmUrl from './pkg/loratrack_bg.wasm?url';
import type {
  AirtimeParams,
  AirtimeReport,
  DecodeParams,
  DecodeReport,
  Delivery,
  DeliverySpread,
  EncodeParams,
  EncodeReport,
  LinkBudgetParams,
  LinkBudgetReport,
  ModelName,
  ModelResult,
  ModelSeries,
  NumberOption,
  PredictParams,
  PredictReport,
  Scenario,
  SimReport,
  SwarmReport,
  VersusLowest,
} from './generated/types';

export type * from './generated/types';
export { CHOICE_DEFAULTS, OPTIONS, PAYLOAD_BYTES, PAYLOAD_FIELDS, PLANS, TOP_SPEEDS } from './generated/types';

let compiled: Promise<WebAssembly.Module> | undefined;
let ready: Promise<void> | undefined;

/** The WebAssembly module, compiled once while it downloads (or from its bytes where the server
 * does not say `application/wasm`). The page's instance and every worker's are made from this one
 * compilation: each thread compiling its own copy would triple the work the first results wait
 * for, and the code each thread compiles on first use would not serve the others. */
export function compiledModule(): Promise<WebAssembly.Module> {
  compiled ??= WebAssembly.compileStreaming(fetch(wasmUrl)).catch(async () => WebAssembly.compile(await (await fetch(wasmUrl)).arrayBuffer()));
  return compiled;
}

/** Instantiates the module once (from `module`, a worker's copy of the page's compilation, or
 * else `compiledModule()`); later calls return the same promise. */
export function load(module?: Promise<WebAssembly.Module>): Promise<void> {
  ready ??= (module ?? compiledModule())
    .then((m) => init({ module_or_path: m }))
    .then(() => {
      loaded = true;
    });
  return ready;
}

let loaded = false;
/** Whether `load` has finished: the functions below may be called. */
export const isLoaded = (): boolean => loaded;

export const MODEL_LABELS: Record<ModelName, string> = { dr: 'DR', 'ctra-plus': 'CTRA+', '3d-ctra': '3D-CTRA', imm: 'IMM', mission: 'Mission' };

/** Whether a station's series was thinned to its envelope (`ModelSeries.samples`: a flight of more
 * than 3000 evaluation times), which the error chart and its CSV then say. */
export const isThinned = (m: Pick<ModelSeries, 't' | 'samples'>): boolean => m.samples > m.t.length;

/** Input of simulate and swarm: any of the Scenario's settings (the rest take their defaults);
 * `seed: 'random'` draws one from Web Crypto (reported in `config.seed`). */
export type SimulateParams = Partial<Omit<Scenario, 'seed'>> & {
  seed?: number | 'random';
  /** CSV text of a flight (input only: reports give its name). */
  trajectory?: string;
  /** A name for the CSV flight, shown in reports. */
  trajectoryName?: string;
  /** The drone's mission plan for a CSV or sample flight, or alone (input only): CSV text of
   * `x,y,z[,speed[,hold]]`, a QGroundControl `.plan` or a `QGC WPL` waypoint list (Mission Planner's
   * `.waypoints`); the synthetic flights carry their own. Given without a flight, the drone flies it:
   * as a multicopter's autopilot does, at the leg's speed (5 m/s where none is given; slower where
   * that would climb faster than 2.5 m/s or descend faster than 1.5 m/s), speeding up and braking
   * at 2 m/s², through each waypoint it does not hold at on an arc within 2 m of it, holding as
   * planned, without wind: the mission station's best case. */
  plan?: string;
  /** The plan's file name, for `commandLine`. */
  planName?: string;
};
/** Input of swarm: the same settings, with `drones`, `duration`, `sfPlan` and `schedule`. */
export type SwarmParams = SimulateParams;
/** Output of predict. */
export type StateReport = PredictReport;

/** Time on air of one packet and the shortest interval between packets under the plan (its duty cycle, 1 % unless `dutyCycle` says otherwise; listen before talk; or the interval set where it has none). */
export function timeOnAir(params: Partial<AirtimeParams> & Pick<AirtimeParams, 'sf' | 'bw' | 'payload'>): AirtimeReport {
  return wasm.timeOnAir(params) as AirtimeReport;
}

/** Received power, sensitivity, range and delivery ratio per SF against distance. */
export function linkBudget(params: Partial<LinkBudgetParams>): LinkBudgetReport {
  return wasm.linkBudget(params) as LinkBudgetReport;
}

/** Noise-free propagation of a state with one motion model. */
export function predict(params: Partial<PredictParams> & Pick<PredictParams, 'model' | 'state' | 'dt'>): PredictReport {
  return wasm.predict(params) as PredictReport;
}

/** Quantises a state into its 9/11/12-byte payload. */
export function encode(params: Partial<EncodeParams> & Pick<EncodeParams, 'model' | 'state'>): EncodeReport {
  return wasm.encode(params) as EncodeReport;
}

/** Decodes a payload into a state. */
export function decode(params: Partial<DecodeParams> & Pick<DecodeParams, 'model' | 'hex'>): DecodeReport {
  return wasm.decode(params) as DecodeReport;
}

/**
 * Runs the tracking simulation (drone filter runs are cached between calls). `onProgress(done,
 * total)` is called as flights complete; it must not call back into this module. Where it returns
 * `false` the run stops before its next flight and this throws "the run was stopped by its
 * progress callback" (any other return value goes on).
 */
export function simulate(params: SimulateParams, onProgress?: (done: number, total: number) => boolean | void): SimReport {
  return wasm.simulate(params, onProgress) as SimReport;
}

/** The `loratrack simulate` command line (`'swarm'`: `loratrack swarm`) that gives the numbers
 * `simulate(params)` gives: each setting away from its default as its CLI option, a CSV flight
 * or plan by `trajectoryName` and `planName`. */
export function commandLine(params: SimulateParams, command?: 'simulate' | 'swarm'): string {
  return wasm.commandLine(params, command) as string;
}

/** Simulates drones sharing the gateways through the same event loop as simulate.
 * `onProgress(done, total)` as episodes and drones complete (every ~0.2–0.4 s of work); where it
 * returns `false` the swarm stops there and this throws "the run was stopped by its progress
 * callback" (any other return value goes on). */
export function swarm(params: SwarmParams, onProgress?: (done: number, total: number) => boolean | void): SwarmReport {
  return wasm.swarm(params, onProgress) as SwarmReport;
}

/** Reads a CSV flight into the module's cache, calling `onProgress(lines read, lines)` as it
 * goes; a following simulate of the same text starts at once. Where `onProgress` returns `false`
 * the reading stops there, caching nothing, and this throws as a stopped `simulate` does. */
export function loadCsv(params: { trajectory: string; trajectoryName?: string }, onProgress?: (done: number, total: number) => boolean | void): { rows: number } {
  return wasm.loadCsv(params, onProgress) as { rows: number };
}

/** The setting a thrown error refuses: its key as these functions take it (`maxInterval`,
 * `sf`, `plan`, a number given as text, …), which the core names where one setting is at fault;
 * `undefined` otherwise (a setting that conflicts with another, a run too long for several
 * together, an unknown key). */
export function settingOf(error: unknown): string | undefined {
  const setting = (error as { setting?: unknown } | null)?.setting;
  return typeof setting === 'string' ? setting : undefined;
}

/** For a run the core refused, the value of the setting it names (`settingOf`) with which the
 * run would go ahead, where the core knows one: how many seeds fit a run too long only for its
 * seeds (the whole synthetic set at the default rates: 18), how many drones fit a swarm too long
 * only for its drones, or the heartbeat (`maxInterval`) the slowest drone's data rate needs;
 * `undefined` for any other error. */
export function valueThatFits(error: unknown): number | undefined {
  const fit = (error as { valueThatFits?: unknown } | null)?.valueThatFits;
  return typeof fit === 'number' ? fit : undefined;
}

/** Every numeric setting's default and accepted range, as the core validates them. */
export function limits(): NumberOption[] {
  return wasm.limits() as NumberOption[];
}

/** The network's totals over `simulate` results run apart (each result carries its own run's
 * counts), as one run of all their stations reports them: packets, copies and every gateway's
 * counts added up (the core's `Delivery::pooled`). */
export function poolDelivery(results: Delivery[]): Delivery {
  return wasm.poolDelivery({ results }) as Delivery;
}

/** The stations of `results` whose packets the link delivered at rates more than 5 points apart
 * (the core's `DeliverySpread`), or null. */
export function deliverySpread(results: ModelResult[]): DeliverySpread | null {
  return wasm.deliverySpread({ results }) as DeliverySpread | null;
}

/** Each of `results`' p75 against the lowest station's, paired over the same runs (`p75VsLowest`
 * of each, from their `draws`; null for the lowest itself), as one run of all their stations
 * reports them (the core's `versus_lowest`): the stations a worker ran alone were compared only
 * with each other. */
export function versusLowest(results: ModelResult[]): (VersusLowest | null)[] {
  return wasm.versusLowest({ results }) as (VersusLowest | null)[];
}

/** The stations a `model` setting names, in order (`all` is the paper's three). */
export function stationsOf(model: SimulateParams['model']): ModelName[] {
  return wasm.stationsOf({ model }) as ModelName[];
}

/** The stations `model` names split into at most `workers` groups, each in `stationsOf`'s order,
 * so that the group with the most work finishes soonest (the core's `split_stations`: stations
 * that receive the same payload share its drone run). The same list always splits alike. */
export function splitStations(model: SimulateParams['model'], workers: number): ModelName[][] {
  return wasm.splitStations({ model, workers }) as ModelName[][];
}
