// The page's settings: defaults (the paper's), conversion to simulate() parameters, and the URL
// round trip that makes every view shareable.
import type { AdrMode, ModelChoice, Prediction, SimulateParams } from './loratrack';

export type FlightChoice = 'synthetic' | 'all' | 'canberra' | 'csv';

export interface Settings {
  sf: number;
  bw: number;
  distance: number;
  model: ModelChoice;
  prediction: Prediction;
  sender: 'periodic' | 'error';
  threshold: number;
  dutyCycleMode: 'per-packet' | 'budget';
  adr: AdrMode;
  flight: FlightChoice;
  flightNumber: number;
  lorawan: boolean;
  cr: number;
  txPower: number;
  pathLossExponent: number;
  shadowing: number;
  sensorRate: number;
  step: number;
  eta: number;
  seed: number;
}

/** The paper's setting (SF7, 250 kHz, 1 km, all models) on one synthetic flight, with LoRaWAN's 13-byte overhead. */
export const DEFAULTS: Settings = {
  sf: 7,
  bw: 250,
  distance: 1000,
  model: 'all',
  prediction: 'paper',
  sender: 'periodic',
  threshold: 2,
  dutyCycleMode: 'per-packet',
  adr: 'off',
  flight: 'synthetic',
  flightNumber: 1,
  lorawan: true,
  cr: 1,
  txPower: 14,
  pathLossExponent: 3.76,
  shadowing: 4,
  sensorRate: 10,
  step: 0.1,
  eta: 0.9,
  seed: 1,
};

/** The model choices the page offers (the options of its Model control). */
export const MODEL_CHOICES: string[] = ['all', 'dr', 'ctra-plus', '3d-ctra', 'imm', 'dr,ctra-plus,3d-ctra,imm'];

/** What each numeric setting accepts, as the form and the URL enforce it (within the core's own limits). */
export interface Limit {
  /** The name users see (the control's label). */
  label: string;
  min: number;
  max: number;
  /** Whole numbers only. */
  integer?: boolean;
  /** The only values allowed, when a list. */
  values?: number[];
  unit?: string;
}

export const LIMITS: Record<NumericKey, Limit> = {
  sf: { label: 'Spreading factor', min: 7, max: 12, integer: true },
  bw: { label: 'Bandwidth', min: 125, max: 500, values: [125, 250, 500], unit: 'kHz' },
  distance: { label: 'Distance', min: 100, max: 10000, unit: 'm' },
  threshold: { label: 'Threshold', min: 0, max: 100, unit: 'm' },
  flightNumber: { label: 'Synthetic flight number', min: 1, max: 30, integer: true },
  cr: { label: 'Coding rate', min: 1, max: 4, integer: true },
  txPower: { label: 'Tx power', min: -30, max: 30, unit: 'dBm' },
  pathLossExponent: { label: 'Path-loss exponent', min: 1.5, max: 6 },
  shadowing: { label: 'Shadowing sigma', min: 0, max: 20, unit: 'dB' },
  sensorRate: { label: 'Sensor rate', min: 1, max: 100, unit: 'Hz' },
  step: { label: 'Prediction step T', min: 0.01, max: 2, unit: 's' },
  eta: { label: 'Tilt decay eta', min: 0, max: 1 },
  seed: { label: 'Seed', min: 0, max: 2 ** 53 - 1, integer: true },
};

type NumericKey = 'sf' | 'bw' | 'distance' | 'threshold' | 'flightNumber' | 'cr' | 'txPower' | 'pathLossExponent' | 'shadowing' | 'sensorRate' | 'step' | 'eta' | 'seed';
const NUMERIC = Object.keys(LIMITS) as NumericKey[];

/** Why `value` is not acceptable for `key`, in the words of the form; null when it is. */
export function invalid(key: NumericKey, value: number): string | null {
  const l = LIMITS[key];
  const unit = l.unit ? ` ${l.unit}` : '';
  if (!Number.isFinite(value)) return `${l.label}: enter a number.`;
  if (l.values && !l.values.includes(value)) return `${l.label} must be one of ${l.values.join(', ')}${unit}.`;
  if (value < l.min || value > l.max) return `${l.label} must be between ${l.min} and ${l.max}${unit}.`;
  if (l.integer && !Number.isInteger(value)) return `${l.label} must be a whole number.`;
  return null;
}

export function isNumericKey(key: string): key is NumericKey {
  return key in LIMITS;
}

export function overheadBytes(s: Settings): number {
  return s.lorawan ? 13 : 0;
}

/** simulate() parameters for these settings; `csv` supplies the uploaded text. */
export function toParams(s: Settings, csv?: { text: string; name: string }): SimulateParams {
  const flight: SimulateParams =
    s.flight === 'all'
      ? { synthetic: 'all' }
      : s.flight === 'canberra'
        ? { sample: 'canberra' }
        : s.flight === 'csv' && csv
          ? { trajectory: csv.text, trajectoryName: csv.name }
          : { synthetic: s.flightNumber };
  return {
    ...flight,
    model: s.model,
    prediction: s.prediction,
    sender: s.sender,
    threshold: s.threshold,
    dutyCycleMode: s.dutyCycleMode,
    adr: s.adr,
    sf: s.sf,
    bw: s.bw,
    distance: s.distance,
    seed: s.seed,
    overhead: overheadBytes(s),
    cr: s.cr,
    txPower: s.txPower,
    pathLossExponent: s.pathLossExponent,
    shadowing: s.shadowing,
    sensorRate: s.sensorRate,
    step: s.step,
    eta: s.eta,
  };
}

/** Only the settings that differ from the defaults go into the URL. */
export function toQuery(s: Settings, extra: Record<string, string> = {}): string {
  const q = new URLSearchParams();
  for (const key of Object.keys(DEFAULTS) as (keyof Settings)[]) {
    if (s[key] !== DEFAULTS[key]) q.set(key, String(s[key]));
  }
  for (const [k, v] of Object.entries(extra)) q.set(k, v);
  return q.toString();
}

/** Settings from a URL query, and what was wrong with it: every unknown or out-of-range value
 * falls back to its default, with a sentence saying so. */
export function fromQuery(search: string): { settings: Settings; problems: string[] } {
  const q = new URLSearchParams(search);
  const s: Settings = { ...DEFAULTS };
  const problems: string[] = [];
  for (const key of NUMERIC) {
    const raw = q.get(key);
    if (raw === null) continue;
    const v = raw.trim() === '' ? NaN : Number(raw);
    const why = invalid(key, v);
    if (why) problems.push(`The link's ${key}=${raw.slice(0, 20)} was replaced by ${DEFAULTS[key]}: ${why}`);
    else (s as unknown as Record<string, number>)[key] = v;
  }
  const choice = <K extends keyof Settings>(key: K, allowed: readonly string[]) => {
    const raw = q.get(key);
    if (raw === null) return;
    if (allowed.includes(raw)) (s as unknown as Record<string, string>)[key] = raw;
    else problems.push(`The link's ${key}=${raw.slice(0, 20)} was replaced by ${DEFAULTS[key]}: expected one of ${allowed.join(', ')}.`);
  };
  choice('model', MODEL_CHOICES);
  choice('prediction', ['paper', 'bounded']);
  choice('sender', ['periodic', 'error']);
  choice('dutyCycleMode', ['per-packet', 'budget']);
  choice('adr', ['off', 'lorawan', 'tracking']);
  // An uploaded CSV cannot travel in a URL; such links open the default flight.
  choice('flight', ['synthetic', 'all', 'canberra']);
  if (q.get('lorawan') === 'false') s.lorawan = false;
  return { settings: s, problems };
}
