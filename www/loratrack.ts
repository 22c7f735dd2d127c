// The one module that imports the generated WebAssembly package (www/pkg, built by
// scripts/build-wasm.mjs). Everything else — the page and its worker — imports these typed
// functions. Shapes follow SPEC §8–9: each function takes the CLI's long options in camelCase and
// returns what `loratrack <command> --json` prints; bad input throws an Error.
import init, * as wasm from './pkg/loratrack.js';
import wasmUrl from './pkg/loratrack_bg.wasm?url';

let ready: Promise<void> | undefined;

/** Loads and instantiates the WebAssembly module once; later calls return the same promise. */
export function load(): Promise<void> {
  ready ??= init({ module_or_path: wasmUrl }).then(() => undefined);
  return ready;
}

export type Ldro = 'auto' | 'on' | 'off';
/** A motion model: what predict, encode and decode take. */
export type MotionModelName = 'dr' | 'ctra-plus' | '3d-ctra';
/** A station: one motion model, or the IMM mixture of the three. */
export type ModelName = MotionModelName | 'imm';
/** `all` (the paper's three), one station, or a comma list such as `dr,3d-ctra,imm`. */
export type ModelChoice = ModelName | 'all' | (string & {});
/** The station's prediction between packets: as published, or bounded by physical limits. */
export type Prediction = 'paper' | 'bounded';

export const MODEL_LABELS: Record<ModelName, string> = { dr: 'DR', 'ctra-plus': 'CTRA+', '3d-ctra': '3D-CTRA', imm: 'IMM' };

/** Input of timeOnAir (`loratrack airtime`). */
export interface AirtimeParams {
  sf: number;
  bw: number;
  payload: number;
  overhead?: number;
  cr?: number;
  preamble?: number;
  implicitHeader?: boolean;
  noCrc?: boolean;
  ldro?: Ldro;
  dutyCycle?: number;
}

/** Output of timeOnAir: seconds, symbols, bytes. */
export interface AirtimeReport {
  timeOnAir: number;
  symbolTime: number;
  payloadSymbols: number;
  phyPayloadBytes: number;
  lowDataRateOptimize: boolean;
  minInterval: number;
  /** Packets a day within TTN's 30 s/day fair use (information only). */
  ttnPacketsPerDay: number;
}

/** Input of predict (`loratrack predict`): state in SPEC §2 order. */
export interface PredictParams {
  model: MotionModelName;
  state: number[];
  dt: number;
  step?: number;
  eta?: number;
}

export interface StateReport {
  model: MotionModelName;
  state: number[];
}

export interface EncodeParams {
  model: MotionModelName;
  state: number[];
  origin?: [number, number, number];
}

export interface EncodeReport {
  hex: string;
  saturated: string[];
}

export interface DecodeParams {
  model: MotionModelName;
  hex: string;
  origin?: [number, number, number];
}

/** Input of simulate (`loratrack simulate`); exactly one of trajectory (CSV text), synthetic, sample. */
export interface SimulateParams {
  trajectory?: string;
  trajectoryName?: string;
  synthetic?: number | 'all';
  sample?: 'canberra';
  model?: ModelChoice | ModelName[];
  prediction?: Prediction;
  /** When the drone sends: as often as allowed, or when the station's belief drifts past `threshold` m. */
  sender?: 'periodic' | 'error';
  threshold?: number;
  maxInterval?: number;
  /** Off-time after every packet, or an airtime budget holding up to `burst` packets. */
  dutyCycleMode?: 'per-packet' | 'budget';
  burst?: number;
  /** Adaptive data rate, starting at `sf`/`bw` (an EU868 data rate): off, LoRaWAN's network ADR, or the tracking-aware one. */
  adr?: AdrMode;
  /** LoRaWAN ADR's device margin, dB (default 10). */
  adrMargin?: number;
  /** LoRaWAN ADR's history, uplinks (default 20). */
  adrHistory?: number;
  sf?: number;
  bw?: number;
  distance?: number;
  /** A whole number, or 'random' for a fresh one from Web Crypto (reported in config.seed). */
  seed?: number | 'random';
  overhead?: number;
  cr?: number;
  dutyCycle?: number;
  txPower?: number;
  pathLossExponent?: number;
  shadowing?: number;
  gatewayHeight?: number;
  sensorRate?: number;
  step?: number;
  eta?: number;
  q?: number;
  series?: boolean;
}

export type AdrMode = 'off' | 'lorawan' | 'tracking';

/** Packets sent at one data rate; `dr` is the EU868 index, null for an SF/bandwidth that is none. */
export interface DataRateUse {
  dr: number | null;
  sf: number;
  bw: number;
  packets: number;
  received: number;
  timeOnAir: number;
}

/** Error statistics in metres; null when count is 0. */
export interface Summary {
  mean: number | null;
  p50: number | null;
  p75: number | null;
  p95: number | null;
  max: number | null;
  count: number;
}

export interface Boxplot {
  whiskerLow: number | null;
  q1: number | null;
  median: number | null;
  q3: number | null;
  whiskerHigh: number | null;
  outliers: number;
  count: number;
}

export interface ModelResult {
  model: ModelName;
  payloadBytes: number;
  timeOnAir: number;
  interval: number;
  packetsSent: number;
  /** Seconds on air over all flights. */
  airtime: number;
  packetsReceived: number;
  error3d: Summary;
  errorX: Summary;
  errorY: Summary;
  errorZ: Summary;
  boxplot: { error3d: Boxplot; errorX: Boxplot; errorY: Boxplot; errorZ: Boxplot };
  filterRecoveries: number;
  /** Share of steps whose true position lay inside the station's 95 % ellipsoid; null if none. */
  coverage95: number | null;
  /** Packets per data rate, slowest first (one entry without ADR). */
  dataRateUse: DataRateUse[];
  /** IMM only: mean probability of each member over the run. */
  modelProbability?: Partial<Record<MotionModelName, number>>;
}

export interface ModelSeries {
  model: ModelName;
  t: number[];
  error3d: number[];
  /** The station's own 95 % bound on the error (longest semi-axis of its 95 % ellipsoid), m. */
  bound95: number[];
  x: number[];
  y: number[];
  z: number[];
  arrivals: number[];
  lost: number[];
  /** EU868 data rate of each arrival / lost packet (null when the SF and bandwidth form none). */
  arrivalDr: (number | null)[];
  lostDr: (number | null)[];
}

export interface SimReport {
  config: {
    trajectory: string;
    flights: number;
    flightTime: number;
    models: ModelName[];
    prediction: Prediction;
    sender: 'periodic' | 'error';
    threshold: number;
    maxInterval: number;
    dutyCycleMode: 'per-packet' | 'budget';
    burst: number;
    adr: AdrMode;
    adrMargin: number;
    adrHistory: number;
    sf: number;
    bandwidthKhz: number;
    distance: number;
    seed: number;
    overhead: number;
    etaPerSecond: number;
    sensitivityDbm: number;
    rangeM: number;
    [key: string]: unknown;
  };
  results: ModelResult[];
  series?: { flight: string; t: number[]; x: number[]; y: number[]; z: number[]; gateway: number[]; models: ModelSeries[] };
}

/** Time on air and 1 % duty-cycle interval of one packet. */
export function timeOnAir(params: AirtimeParams): AirtimeReport {
  return wasm.timeOnAir(params) as AirtimeReport;
}

/** Input of linkBudget: simulate's channel options and the horizontal distances (m). */
export interface LinkBudgetParams {
  bw?: number;
  txPower?: number;
  pathLossExponent?: number;
  shadowing?: number;
  gatewayHeight?: number;
  distances?: number[];
}

export interface LinkBudgetReport {
  distances: number[];
  /** Mean received power at each distance, dBm (before shadowing). */
  meanRxDbm: number[];
  shadowing: number;
  sfs: { sf: number; sensitivityDbm: number; rangeM: number; delivery: number[] }[];
}

/** Received power, sensitivity, range and delivery ratio per SF against distance. */
export function linkBudget(params: LinkBudgetParams): LinkBudgetReport {
  return wasm.linkBudget(params) as LinkBudgetReport;
}

/** Noise-free propagation of a state with one motion model. */
export function predict(params: PredictParams): StateReport {
  return wasm.predict(params) as StateReport;
}

/** Quantises a state into its 9/11/12-byte payload. */
export function encode(params: EncodeParams): EncodeReport {
  return wasm.encode(params) as EncodeReport;
}

/** Decodes a payload into a state. */
export function decode(params: DecodeParams): StateReport {
  return wasm.decode(params) as StateReport;
}

/**
 * Runs the tracking simulation (drone filter runs are cached between calls). `onProgress(done,
 * total)` is called as flights complete; it must not call back into this module.
 */
export function simulate(params: SimulateParams, onProgress?: (done: number, total: number) => void): SimReport {
  return wasm.simulate(params, onProgress) as SimReport;
}

/** Input of swarm (`loratrack swarm`): N drones around one gateway. */
export interface SwarmParams {
  drones?: number;
  duration?: number;
  distance?: number;
  channels?: 1 | 3;
  sfPlan?: 'spread' | 'fixed';
  sf?: number;
  bw?: number;
  model?: ModelName;
  prediction?: Prediction;
  sender?: 'periodic' | 'error';
  threshold?: number;
  maxInterval?: number;
  dutyCycleMode?: 'per-packet' | 'budget';
  burst?: number;
  capture?: boolean;
  interSf?: boolean;
  shadowing?: number;
  overhead?: number;
  seed?: number;
}

export interface SwarmDrone {
  id: number;
  sf: number;
  bearingDeg: number;
  channelUse: number[];
  packetsSent: number;
  packetsReceived: number;
  packetsCollided: number;
  error3d: Summary;
}

/** Output of swarm: collisions at the gateway beside the ALOHA formula, and every drone's error. */
export interface SwarmReport {
  config: Required<Omit<SwarmParams, 'bw'>> & { bandwidthKhz: number; dutyCycle: number };
  collisionRate: number;
  collisionRateTheory: number;
  deliveryRatio: number;
  packetsSent: number;
  packetsReceived: number;
  packetsCollided: number;
  packetsBelowSensitivity: number;
  packetsNoDemodulator: number;
  airtime: number;
  error3d: Summary;
  medianDroneP75: number | null;
  drones: SwarmDrone[];
}

/** Simulates a swarm sharing one gateway. `onProgress(done, total)` as drones complete. */
export function swarm(params: SwarmParams, onProgress?: (done: number, total: number) => void): SwarmReport {
  return wasm.swarm(params, onProgress) as SwarmReport;
}
