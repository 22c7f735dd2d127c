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

const NUMERIC: (keyof Settings)[] = ['sf', 'bw', 'distance', 'threshold', 'flightNumber', 'cr', 'txPower', 'pathLossExponent', 'shadowing', 'sensorRate', 'step', 'eta', 'seed'];

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

/** Settings from a URL query; unknown or malformed values fall back to the defaults. */
export function fromQuery(search: string): Settings {
  const q = new URLSearchParams(search);
  const s: Settings = { ...DEFAULTS };
  for (const key of NUMERIC) {
    const raw = q.get(key);
    const v = raw === null ? NaN : Number(raw);
    if (Number.isFinite(v)) (s as unknown as Record<string, number>)[key] = v;
  }
  const model = q.get('model');
  if (model !== null && MODEL_CHOICES.includes(model)) s.model = model;
  const prediction = q.get('prediction');
  if (prediction === 'paper' || prediction === 'bounded') s.prediction = prediction;
  const sender = q.get('sender');
  if (sender === 'periodic' || sender === 'error') s.sender = sender;
  const mode = q.get('dutyCycleMode');
  if (mode === 'per-packet' || mode === 'budget') s.dutyCycleMode = mode;
  const adr = q.get('adr');
  if (adr === 'off' || adr === 'lorawan' || adr === 'tracking') s.adr = adr;
  const flight = q.get('flight');
  // An uploaded CSV cannot travel in a URL; such links open the default flight.
  if (flight === 'synthetic' || flight === 'all' || flight === 'canberra') s.flight = flight;
  if (q.get('lorawan') === 'false') s.lorawan = false;
  return s;
}
