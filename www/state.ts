// The page's settings: defaults (the paper's), conversion to simulate() parameters, and the URL
// round trip that makes every view shareable. Every numeric default and limit comes from the
// core's one table (src/options.rs), and every named choice's default from `Scenario::default`,
// both generated into www/generated/types.ts, so the form, the URL checks, the CLI help and the
// core's validation cannot disagree.
import { decaysTilt, runsMission, withoutUnreadFlightSettings } from './stations';
import type { SimulateRequest, SweepPoint } from './worker';
import { CHOICE_DEFAULTS, OPTIONS, PLANS, stationsOf, type AdrMode, type ChannelAccess, type ChannelSense, type FairUse, type GatewaySite, type HeadingNoise, type ModelChoice, type NumberOption, type PayloadChoice, type Plan, type Prediction, type Region, type ShadowingModel, type SimulateParams, type VehicleChoice } from './loratrack';

export type FlightChoice = 'synthetic' | 'all' | 'canberra' | 'csv' | 'plan';

export interface Settings {
  sf: number;
  bw: number;
  distance: number;
  model: ModelChoice;
  prediction: Prediction;
  /** The bounded station's noise on heading and pitch (the paper's station has only `fixed`). */
  headingNoise: HeadingNoise;
  sender: 'periodic' | 'error';
  threshold: number;
  /** Error-triggered sending's heartbeat: the longest silence, s. */
  maxInterval: number;
  /** Error-triggered sending: whether the drone listens to its channel and sends less where it is crowded. */
  channelSense: ChannelSense;
  dutyCycleMode: 'per-packet' | 'budget';
  /** The model's own payload, or the smallest that carries every manoeuvre field worth its bytes. */
  payload: PayloadChoice;
  adr: AdrMode;
  /** The LoRaWAN regional plan. */
  region: Region;
  /** Where the plan has no duty cycle: seconds between uplinks. */
  interval: number;
  /** Duty cycle or listen-before-talk (plans with a duty cycle). */
  access: ChannelAccess;
  /** The duty cycle as a fraction where the plan has one and the drone keeps it (not listening
   * before talk): 0.01, one EU868 sub-band; 0.02, two alternated (reference §6.1). */
  dutyCycle: number;
  fairUse: FairUse;
  flight: FlightChoice;
  flightNumber: number;
  /** The vehicle an uploaded flight or plan is (a QGroundControl .plan's by default); the
   * bundled flights are multicopters. */
  vehicle: VehicleChoice;
  lorawan: boolean;
  cr: number;
  txPower: number;
  pathLossExponent: number;
  shadowing: number;
  /** Shadowing along the drone's path (the default) or fixed in space. */
  shadowingModel: ShadowingModel;
  sensorRate: number;
  step: number;
  eta: number;
  seed: number;
  /** Seeds the run repeats with (seed, seed + 1, …): each statistic then gets a 95 % interval. */
  seeds: number;
  /** The gateways; empty for the one default gateway `distance` m east of the flight's start. */
  gateways: GatewaySite[];
}

const option = (key: string): NumberOption => {
  const o = OPTIONS.find((x) => x.key === key);
  if (!o) throw new Error(`no option ${key} in the core's table`);
  return o;
};
const def = (key: string) => option(key).default;

/** The paper's setting (SF7, 250 kHz, 1 km, all models) on one synthetic flight, with LoRaWAN's 13-byte overhead. */
export const DEFAULTS: Settings = {
  sf: def('sf'),
  bw: def('bw'),
  distance: def('distance'),
  model: CHOICE_DEFAULTS.model,
  prediction: CHOICE_DEFAULTS.prediction,
  headingNoise: CHOICE_DEFAULTS.headingNoise,
  sender: CHOICE_DEFAULTS.sender,
  threshold: def('threshold'),
  maxInterval: def('maxInterval'),
  channelSense: CHOICE_DEFAULTS.channelSense,
  dutyCycleMode: CHOICE_DEFAULTS.dutyCycleMode,
  payload: CHOICE_DEFAULTS.payload,
  adr: CHOICE_DEFAULTS.adr,
  region: CHOICE_DEFAULTS.region,
  interval: def('interval'),
  access: CHOICE_DEFAULTS.access,
  dutyCycle: def('dutyCycle'),
  fairUse: CHOICE_DEFAULTS.fairUse,
  flight: 'synthetic',
  flightNumber: 1,
  vehicle: CHOICE_DEFAULTS.vehicle,
  lorawan: def('overhead') > 0,
  cr: def('cr'),
  txPower: def('txPower'),
  pathLossExponent: def('pathLossExponent'),
  shadowing: def('shadowing'),
  shadowingModel: CHOICE_DEFAULTS.shadowingModel,
  sensorRate: def('sensorRate'),
  step: def('step'),
  eta: def('eta'),
  seed: def('seed'),
  seeds: def('seeds'),
  gateways: [],
};

/** The model choices the page offers (the options of its Model control). */
export const MODEL_CHOICES: string[] = ['all', 'dr', 'ctra-plus', '3d-ctra', 'imm', 'dr,ctra-plus,3d-ctra,imm', 'mission', '3d-ctra,mission', 'dr,ctra-plus,3d-ctra,imm,mission'];

/** The stations in the order the page lists them, and what `all` stands for (the paper's three). */
const STATION_ORDER = ['dr', 'ctra-plus', '3d-ctra', 'imm', 'mission'];
const PAPER_THREE = 'dr,ctra-plus,3d-ctra';

/** The page's choice that runs the same stations as a link's `model` written as the CLI accepts
 * it (any order or case, `all` beside others: `all,imm`, `IMM,DR,ctra-plus,3d-ctra`), or null
 * when the page offers no such set. The link is read before the core has loaded, so this follows
 * the core's spelling (`ModelChoice::parse`, which `stationsOf` calls) rather than calling it. */
export function modelChoiceOf(raw: string): string | null {
  const named = raw.toLowerCase().split(',').map((m) => m.trim()).filter((m) => m !== '');
  const expanded = new Set(named.flatMap((m) => (m === 'all' ? PAPER_THREE.split(',') : [m])));
  if (named.length === 0 || [...expanded].some((m) => !STATION_ORDER.includes(m))) return null;
  const joined = STATION_ORDER.filter((m) => expanded.has(m)).join(',');
  const choice = joined === PAPER_THREE ? 'all' : joined;
  return MODEL_CHOICES.includes(choice) ? choice : null;
}

/** Whether the flight comes from a file the user uploaded (a CSV flight, or a plan flown): it
 * never leaves this computer, so no link carries it and a page opened from a link never has it. */
export function uploaded(flight: FlightChoice): boolean {
  return flight === 'csv' || flight === 'plan';
}

/** Whether the flight's plan is known to the page: the synthetic flights carry theirs, an
 * uploaded flight has one when its plan was uploaded too, as a flown plan has once it is chosen;
 * the real flight has none here (the CLI's `--plan` and the JS API's `plan` give one). */
export function planKnown(flight: FlightChoice, uploadedPlan = false): boolean {
  return flight === 'synthetic' || flight === 'all' || (uploaded(flight) && uploadedPlan);
}

/** Why the mission station is not offered for this flight (shown beside the Model control). */
export const MISSION_REASON = 'The mission station follows the drone’s flight plan: the synthetic flights carry theirs; for an uploaded flight upload its plan too; for the real flight give one with the CLI’s --plan or the JS API’s plan.';

/** What each numeric setting accepts, as the form and the URL enforce it: the core's own limits. */
export interface Limit {
  /** The name users see (the control's label). */
  label: string;
  min: number;
  max: number;
  /** `min` itself is refused. */
  aboveMin?: boolean;
  /** Whole numbers only. */
  integer?: boolean;
  /** The only values allowed, when a list. */
  values?: number[];
  unit?: string;
  /** One sentence from the core's table. */
  help?: string;
  /** The core's default. */
  default?: number;
}

function limit(key: string, label?: string): Limit {
  const o = option(key);
  return { label: label ?? o.label, min: o.min, max: o.max, aboveMin: o.aboveMin, integer: o.integer, values: o.values.length ? o.values : undefined, unit: o.unit || undefined, help: o.help, default: o.default };
}

export const LIMITS: Record<NumericKey, Limit> = {
  sf: limit('sf'),
  bw: limit('bw'),
  distance: limit('distance'),
  threshold: limit('threshold'),
  maxInterval: limit('maxInterval'),
  interval: limit('interval'),
  dutyCycle: limit('dutyCycle'),
  flightNumber: { label: 'Synthetic flight number', min: 1, max: 30, integer: true },
  cr: limit('cr'),
  txPower: limit('txPower'),
  pathLossExponent: limit('pathLossExponent'),
  shadowing: limit('shadowing'),
  sensorRate: limit('sensorRate'),
  step: limit('step'),
  eta: limit('eta'),
  seed: limit('seed'),
  seeds: limit('seeds'),
};

/** What a gateway's coordinates and height accept (the core's limits). */
export const GATEWAY_LIMITS = { coordinate: limit('gateway', 'Gateway coordinate'), height: limit('gatewayHeight', 'Gateway height'), count: limit('gateways', 'Gateways') };

export type NumericKey = 'sf' | 'bw' | 'distance' | 'threshold' | 'maxInterval' | 'interval' | 'dutyCycle' | 'flightNumber' | 'cr' | 'txPower' | 'pathLossExponent' | 'shadowing' | 'sensorRate' | 'step' | 'eta' | 'seed' | 'seeds';
const NUMERIC = Object.keys(LIMITS) as NumericKey[];

/** Why `value` is not acceptable for `key`, in the words of the form; null when it is. */
export function invalid(key: NumericKey, value: number): string | null {
  const l = LIMITS[key];
  const unit = l.unit ? ` ${l.unit}` : '';
  if (!Number.isFinite(value)) return `${l.label}: enter a number.`;
  if (l.values && !l.values.includes(value)) return `${l.label} must be one of ${l.values.join(', ')}${unit}.`;
  if (value < l.min || value > l.max || (l.aboveMin && value === l.min)) return `${l.label} must be ${l.aboveMin ? 'above' : 'between'} ${l.min}${l.aboveMin ? ' and at most' : ' and'} ${l.max}${unit}.`;
  if (l.integer && !Number.isInteger(value)) return `${l.label} must be a whole number.`;
  return null;
}

/** The regional plan `region` (data rates and limits from the core's table, src/lora/region.rs). */
export function plan(region: Region): Plan {
  return PLANS.find((p) => p.region === region) ?? PLANS[0];
}

/** What sets how often a drone may send: the interval set (a plan without a duty cycle), listen
 * before talk's airtime, or the plan's duty cycle. One decision for every sentence that names it
 * (the results' interval header, the swarm's note, a setting's phrase). */
export function sendingLimit(s: { region: Region; access: string }): 'interval' | 'lbt' | 'dutyCycle' {
  if (plan(s.region).dutyCycle === null) return 'interval';
  return s.access === 'lbt' ? 'lbt' : 'dutyCycle';
}

/** The plan's data rate at `sf` / `bw` kHz, if it has one it allows. */
export function planRate(region: Region, sf: number, bw: number): number | null {
  const r = plan(region).rates.find((x) => x.sf === sf && x.bw === bw && x.maxPayload !== null);
  return r ? r.dr : null;
}

/** Whether the plan lets a drone send at `sf` / `bw` kHz: at one of its data rates, or as raw
 * LoRa where it allows that (EU868). The core also checks the payload and the dwell time. */
export function planAllows(region: Region, sf: number, bw: number): boolean {
  return plan(region).rawLora || planRate(region, sf, bw) !== null;
}

/** Why the plan does not offer `sf` / `bw`, in the form's words. */
export function planReason(region: Region): string {
  const p = plan(region);
  const rates = p.rates.filter((r) => r.maxPayload !== null).map((r) => `DR${r.dr} SF${r.sf}/${r.bw}`);
  return `${p.label} offers only ${rates.join(', ')}.`;
}

/** Whether ADR can start at `sf` / `bw` kHz: only at an EU868 data rate (the core's table), as
 * the core checks. */
export function adrCanStart(sf: number, bw: number): boolean {
  return planRate('eu868', sf, bw) !== null;
}

/** Why ADR cannot start here, in the form's words (shown beside the disabled choices). */
export const ADR_START_REASON = 'ADR starts at an EU868 data rate: SF7–SF12 at 125 kHz or SF7 at 250 kHz.';

export function isNumericKey(key: string): key is NumericKey {
  return key in LIMITS;
}

/** The overhead the LoRaWAN box stands for: the core's default (LoRaWAN's 13 bytes), or none. */
export function overheadBytes(s: Pick<Settings, 'lorawan'>): number {
  return s.lorawan ? def('overhead') : 0;
}

/** What a packet's time on air and the plan's verdict on it depend on besides its SF, bandwidth
 * and payload: the overhead, coding rate and plan settings (the interval where the plan has no
 * duty cycle, the duty cycle where the drone keeps one), as `timeOnAir` takes them. */
export function packetPlan(s: Pick<Settings, 'lorawan' | 'cr' | 'region' | 'access' | 'fairUse' | 'interval' | 'dutyCycle'>) {
  return { overhead: overheadBytes(s), cr: s.cr, region: s.region, access: accessSetting(s), fairUse: s.fairUse, ...sendingSetting(s) };
}

/** The channel access a run takes: the form's where the plan has a duty cycle, which listening
 * before talk replaces, and the default where it has none (the form then hides the choice, which
 * keeps a listen before talk chosen under another plan, and the core refuses it there). */
function accessSetting(s: Pick<Settings, 'region' | 'access'>): ChannelAccess {
  return sendingLimit(s) === 'interval' ? CHOICE_DEFAULTS.access : s.access;
}

/** The setting that paces the drone where it applies, as the core takes it: the interval where
 * the plan has no duty cycle, the duty cycle where the drone keeps one, none with listen before
 * talk (the core refuses either setting where it does not apply). */
function sendingSetting(s: Pick<Settings, 'region' | 'access' | 'interval' | 'dutyCycle'>): { interval?: number; dutyCycle?: number } {
  const limit = sendingLimit(s);
  return limit === 'interval' ? { interval: s.interval } : limit === 'dutyCycle' ? { dutyCycle: s.dutyCycle } : {};
}

/** The settings a swarm of the swarm panel rests on, as its captions give them: one seed (its
 * drones give its spread), and the flights its drones chain: the real flight where it is chosen,
 * the synthetic set otherwise (an uploaded flight stays with the single drone). */
export function swarmSettings(s: Settings): Settings {
  return { ...s, seeds: 1, flight: s.flight === 'canberra' ? 'canberra' : 'all' };
}

/** The swarm panel's choices (its selects, index.html's `.swarm-controls`): the largest swarm's
 * drones, its channels (one, or all the plan's), how SFs are dealt, the schedule, and the seconds
 * of synthetic flight each drone chains. */
export interface SwarmChoices {
  drones: number;
  channels: '1' | 'plan';
  sfPlan: 'fixed' | 'spread';
  schedule: 'aloha' | 'slotted';
  duration: number;
}

/** The swarms the panel runs for settings `s` and the panel's `choices`: growing sizes up to its
 * drones, each with the single drone's settings, as a swarm rests on them (`swarmSettings`: its
 * flights, one seed), and the panel's choices. Its drones chain those flights around the centre
 * and run one station: a list of models runs 3D-CTRA, as `all` does, and so does the mission
 * station, which would need each drone's own plan. */
export function swarmRequest(s: Settings, choices: SwarmChoices): { sizes: number[]; params: SimulateParams } {
  const n = choices.drones;
  const sizes = [...new Set([2, Math.round(n / 8), Math.round(n / 4), Math.round(n / 2), n])].filter((k) => k >= 1);
  const made = swarmSettings(s);
  const { synthetic: _s, sf, ...shared } = toParams(made);
  const params: SimulateParams = {
    ...shared,
    // Spread deals SF7..SF12 in turn: the form's SF is read only where every drone is on it.
    ...(choices.sfPlan === 'fixed' ? { sf } : {}),
    // Whether an error-triggered drone listens for the others' frames, which a drone alone
    // (the results) never hears.
    ...(made.sender === 'error' ? { channelSense: made.channelSense } : {}),
    // The drones' distance from the centre, which the swarm reads where gateways are listed too.
    distance: made.distance,
    model: stationsOf(s.model).length === 1 && !runsMission(s.model) ? s.model : 'all',
    // The real flight is flown whole (the panel hides the choice); the duration chains synthetic flights.
    ...(made.flight === 'canberra' ? {} : { duration: choices.duration }),
    // One channel, or all the plan's (its default).
    ...(choices.channels === '1' ? { channels: 1 } : {}),
    sfPlan: choices.sfPlan,
    schedule: choices.schedule,
  };
  return { sizes, params };
}

/** Beside every run, the gateway distances (m) and spreading factors the distance and SF charts
 * show: only the link changes between them, so they reuse the run's drone filters. */
const SWEEP: SweepPoint[] = [...[500, 1000, 2000, 3000, 4000, 5000].map((distance) => ({ distance })), ...[7, 8, 9, 10, 11, 12].map((sf) => ({ sf }))];

/** What the page asks its workers for these settings: the run and the charts' sweep, and an
 * uploaded flight's file, whose text the workers read (`trajectory`). */
export function simulateRequest(id: number, s: Settings, csv?: { file: Blob; name: string }, missionPlan?: { text: string; name?: string }): SimulateRequest {
  const file = s.flight === 'csv' && csv ? { trajectoryFile: csv.file } : {};
  return { id, params: toParams(s, csv, missionPlan), sweep: SWEEP, ...file };
}

/** A mission plan's parameters: its text and, where it has one, its file's name. */
function planParams(missionPlan?: { text: string; name?: string }): SimulateParams {
  return missionPlan ? { plan: missionPlan.text, ...(missionPlan.name ? { planName: missionPlan.name } : {}) } : {};
}

/** simulate() parameters for these settings; `csv` names the uploaded flight, whose text the
 * worker adds as `trajectory` from the request's file, and `missionPlan` is its mission plan (with
 * `flight: 'plan'` the flight itself: the core flies it). */
export function toParams(s: Settings, csv?: { name: string }, missionPlan?: { text: string; name?: string }): SimulateParams {
  const flight: SimulateParams =
    s.flight === 'all'
      ? { synthetic: 'all' }
      : s.flight === 'canberra'
        ? { sample: 'canberra' }
        : s.flight === 'csv' && csv
          ? { trajectoryName: csv.name, ...planParams(missionPlan), vehicle: s.vehicle }
          : s.flight === 'plan' && missionPlan
            ? { ...planParams(missionPlan), vehicle: s.vehicle }
            : { synthetic: s.flightNumber };
  // A plan uploaded beside the CSV flight, and the vehicle, stay in the form while no station
  // reads them.
  return withoutUnreadFlightSettings({
    ...flight,
    model: s.model,
    prediction: s.prediction,
    // Kept in the form while the paper's station is chosen, which has no hedge to choose.
    headingNoise: s.prediction === 'bounded' ? s.headingNoise : 'fixed',
    sender: s.sender,
    // Kept in the form while sending periodically, which has no threshold or heartbeat (the core
    // refuses them there). Whether the drone listens to its channel is a swarm's setting: a drone
    // alone never hears another's frame (the swarm's request adds it).
    ...(s.sender === 'error' ? { threshold: s.threshold, maxInterval: s.maxInterval } : {}),
    dutyCycleMode: s.dutyCycleMode,
    payload: s.payload,
    adr: s.adr,
    region: s.region,
    ...sendingSetting(s),
    access: accessSetting(s),
    fairUse: s.fairUse,
    sf: s.sf,
    bw: s.bw,
    // Kept in the form where gateways are listed, which replace the one gateway it places (the
    // core refuses it there; the swarm, which spreads its drones that far, adds it back).
    ...(s.gateways.length ? {} : { distance: s.distance }),
    seed: s.seed,
    seeds: s.seeds,
    overhead: overheadBytes(s),
    cr: s.cr,
    txPower: s.txPower,
    pathLossExponent: s.pathLossExponent,
    shadowing: s.shadowing,
    // Kept in the form where there is no shadowing, whose fades it places (the core refuses it there).
    ...(s.shadowing > 0 ? { shadowingModel: s.shadowingModel } : {}),
    sensorRate: s.sensorRate,
    step: s.step,
    // Kept in the form where no station decays the tilt rate (the core refuses it there).
    ...(decaysTilt(s.model) ? { eta: s.eta } : {}),
    gateways: s.gateways,
  });
}

/** `gateways=E,N[,H];E,N[,H]` in the URL. */
export function gatewaysToText(g: GatewaySite[]): string {
  return g.map((x) => [x.east, x.north, ...(x.height === undefined ? [] : [x.height])].join(',')).join(';');
}

/** Why a gateway list is not acceptable, in the words of the form; null when it is. */
export function invalidGateways(g: GatewaySite[]): string | null {
  const { coordinate: c, height: h, count } = GATEWAY_LIMITS;
  if (g.length > count.max) return `At most ${count.max} gateways.`;
  for (const [i, x] of g.entries()) {
    for (const v of [x.east, x.north]) {
      if (!Number.isFinite(v) || v < c.min || v > c.max) return `Gateway ${i + 1}: each coordinate must be between ${c.min} and ${c.max} m.`;
    }
    if (x.height !== undefined && (!Number.isFinite(x.height) || x.height < h.min || x.height > h.max)) return `Gateway ${i + 1}: the height must be between ${h.min} and ${h.max} m.`;
  }
  return null;
}

export function gatewaysFromText(text: string): GatewaySite[] | null {
  if (text.trim() === '') return [];
  const out: GatewaySite[] = [];
  for (const part of text.split(';')) {
    const n = part.split(',').map((v) => (v.trim() === '' ? NaN : Number(v)));
    if (n.length < 2 || n.length > 3 || n.some((v) => !Number.isFinite(v))) return null;
    out.push(n.length === 3 ? { east: n[0], north: n[1], height: n[2] } : { east: n[0], north: n[1] });
  }
  return out;
}

/** Only the settings that differ from the defaults go into the URL. */
export function toQuery(s: Settings, extra: Record<string, string> = {}): string {
  const q = new URLSearchParams();
  for (const key of Object.keys(DEFAULTS) as (keyof Settings)[]) {
    if (key === 'gateways') {
      if (s.gateways.length) q.set('gateways', gatewaysToText(s.gateways));
    } else if (s[key] !== DEFAULTS[key]) q.set(key, String(s[key]));
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
  const model = q.get('model');
  if (model !== null) {
    const chosen = modelChoiceOf(model);
    if (chosen !== null) s.model = chosen;
    else problems.push(`The link's model=${model.slice(0, 20)} was replaced by ${DEFAULTS.model}: expected one of ${MODEL_CHOICES.join(', ')}.`);
  }
  choice('prediction', ['paper', 'bounded']);
  choice('headingNoise', ['fixed', 'adaptive']);
  choice('sender', ['periodic', 'error']);
  choice('channelSense', ['off', 'cad']);
  choice('dutyCycleMode', ['per-packet', 'budget']);
  choice('payload', ['full', 'lean']);
  choice('adr', ['off', 'lorawan', 'tracking']);
  choice('region', PLANS.map((p) => p.region));
  choice('access', ['duty-cycle', 'lbt']);
  choice('fairUse', ['off', 'ttn']);
  choice('shadowingModel', ['path', 'field']);
  choice('vehicle', ['auto', 'multicopter', 'fixed-wing']);
  // An uploaded CSV or plan cannot travel in a URL; such links open the default flight.
  choice('flight', ['synthetic', 'all', 'canberra']);
  if (q.get('lorawan') === 'false') s.lorawan = false;
  if (!planAllows(s.region, s.sf, s.bw)) {
    problems.push(`The link's region=${s.region} was replaced by eu868: SF${s.sf} / ${s.bw} kHz is not in it. ${planReason(s.region)}`);
    s.region = 'eu868';
  }
  if (s.access === 'lbt' && plan(s.region).dutyCycle === null) {
    problems.push(`The link's access=lbt was replaced by duty-cycle: listen-before-talk replaces a duty cycle, and ${plan(s.region).label} has none.`);
    s.access = 'duty-cycle';
  }
  if (runsMission(s.model) && !planKnown(s.flight)) {
    problems.push(`The link's model=${s.model} was replaced by 3d-ctra: ${MISSION_REASON}`);
    s.model = '3d-ctra';
  }
  if (s.adr !== 'off' && s.region !== 'eu868') {
    problems.push(`The link's adr=${s.adr} was replaced by off: ADR runs EU868's data rates.`);
    s.adr = 'off';
  }
  if (s.adr !== 'off' && !adrCanStart(s.sf, s.bw)) {
    problems.push(`The link's adr=${s.adr} was replaced by off: ${ADR_START_REASON}`);
    s.adr = 'off';
  }
  const g = q.get('gateways');
  if (g !== null) {
    const parsed = gatewaysFromText(g);
    const why = parsed ? invalidGateways(parsed) : 'expected E,N or E,N,H in metres, separated by ;.';
    if (parsed && !why) s.gateways = parsed;
    else problems.push(`The link's gateways=${g.slice(0, 40)} were replaced by the one default gateway: ${why}`);
  }
  return { settings: s, problems };
}
