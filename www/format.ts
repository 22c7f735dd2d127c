// How the page words its numbers and settings: one place for every caption, label and dash.
import { MODEL_LABELS, OPTIONS, PAYLOAD_BYTES, PAYLOAD_FIELDS, type GatewayReport, type ModelName, type ModelResult, type ModelSeries } from './loratrack';
import { DEFAULTS, isNumericKey, LIMITS, overheadBytes, plan, sendingLimit, uploaded, type NumericKey, type Settings } from './state';
import { decaysTilt, readsVehicle } from './stations';
import { store } from './store';

/** A statistic with `digits` decimals, or a dash where there is none (an empty sample). */
export const fmt = (v: number | null, digits = 2) => (v === null || v === undefined ? '—' : v.toFixed(digits));

/** The share of the flight time a station's errors cover (`wholeFlight.tracked`, 0-1; before a
 * flight's first packet there is no estimate), in whole percent. */
export const trackedPercent = (tracked: number | null) => Math.round(100 * (tracked ?? 0));

/** `n` and the noun `one` names one of, in the plural unless `n` is 1: "1 packet", "3 packets". */
export const counted = (n: number, one: string, many = `${one}s`): string => `${n} ${n === 1 ? one : many}`;

/** The ADR answers the network server wanted to send through gateway `g`: sent, dropped or held back. */
export const downlinksWanted = (g: GatewayReport): number => g.downlinksSent + g.downlinksDropped + g.downlinksHeldBack;

/** What became of the ADR answers the network server wanted to send through `gateways`, summed:
 * sent, refused by the gateway's duty cycle, and (where any) held back for a later uplink to keep
 * a crowded gateway listening; the counts the CLI's gateway lines print. */
export function downlinkCounts(gateways: GatewayReport[]): string {
  const sum = (count: (g: GatewayReport) => number) => gateways.reduce((total, g) => total + count(g), 0);
  const held = sum((g) => g.downlinksHeldBack);
  return `${counted(sum((g) => g.downlinksSent), 'ADR downlink')} sent, ${sum((g) => g.downlinksDropped)} dropped by the gateway's duty cycle${held ? `, ${held} held back for a later uplink to keep a crowded gateway listening` : ''}`;
}

/** Words as a list in a sentence: "a", "a and b", "a, b and c". */
export const listed = (words: string[]): string => (words.length < 2 ? words.join('') : `${words.slice(0, -1).join(', ')} and ${words[words.length - 1]}`);

/** The payload fields `names` (the core's `saturated`) with their ranges, in state order as the
 * CLI names them (PAYLOAD_FIELDS is generated in that order): "turn rate ω, ±2 rad/s; tilt rate
 * ψ, ±2 rad/s". */
const payloadFieldWords = (names: readonly string[]): string =>
  Object.entries(PAYLOAD_FIELDS)
    .filter(([name]) => names.includes(name))
    .map(([, words]) => words)
    .join('; ');

/** What received packets that saturated `names` (the core's `saturated`) did to a station
 * (`swarm`: to their drones' stations): the words the results' and the swarm's saturated notes
 * end with, as the CLI's `saturated:` lines do. */
export function beyondRange(names: readonly string[], swarm: boolean): string {
  const [whose, its] = swarm ? ['Their stations', 'their'] : ['The station', 'its'];
  return `carried a value beyond the payload's range (${payloadFieldWords(names)}), sent as the range's edge. ${whose} started from a state other than the drone's estimate, so part of ${its} error is the payload's, not the model's (the payload is sized for a quadcopter; docs/reference.md §5).`;
}

/** Station names as a list: "DR", "DR and CTRA+", "DR, CTRA+ and 3D-CTRA". */
export const names = (list: Pick<ModelResult, 'model'>[]) => listed(list.map((m) => MODEL_LABELS[m.model]));

/** The sending policy with what it rests on, the duty-cycle rule when it is not the paper's
 * off-time per packet and the payload when it is not the model's own: two error-triggered runs
 * with different thresholds must not read alike. Takes the page's settings or a report's own
 * config. Whether the drone listens to its channel is said of a `swarm`'s drones alone: a drone
 * alone never hears another's frame, and its runs do not read it. */
export function sending(s: Pick<Settings, 'sender' | 'threshold' | 'maxInterval' | 'dutyCycleMode'> & Partial<Pick<Settings, 'channelSense' | 'payload'>>, swarm = false): string {
  const listens = swarm && s.channelSense !== 'off' ? ', listening to its channel' : '';
  const sender = s.sender === 'error' ? `error-triggered sending (${s.threshold} m, heartbeat ${s.maxInterval} s${listens})` : 'periodic sending';
  const lean = s.payload === 'lean' ? ', lean payloads' : '';
  return `${sender}${s.dutyCycleMode === 'budget' ? ', duty-cycle budget' : ''}${lean}`;
}

/** Whether the drone sends as the paper's does: every packet the duty cycle allows, each with the
 * model's own payload. */
export const sendsAsPublished = (s: Pick<Settings, 'sender' | 'dutyCycleMode'> & Partial<Pick<Settings, 'payload'>>) =>
  s.sender === 'periodic' && s.dutyCycleMode === 'per-packet' && s.payload !== 'lean';

/** The settings a caption lists with their values where they differ from their defaults: those the
 * core's table marks (`listedWhenChanged`, src/options.rs; the CLI's `settings:` line lists the same)
 * that the form sets (link and filter). */
const ADVANCED = OPTIONS.filter((o) => o.listedWhenChanged)
  .map((o) => o.key)
  .filter(isNumericKey);

/** The form's advanced settings changed from their defaults, in the core table's words:
 * `['shadowing sigma 8 dB']`. Reads the page's settings or a run's echoed config alike, so that a
 * table names what its numbers rest on, not what the form says now. */
export function advancedChanged(s: Partial<Record<NumericKey, number>> & Pick<Settings, 'shadowingModel'>): string[] {
  const named = ADVANCED.filter((k) => s[k] !== undefined && s[k] !== DEFAULTS[k]).map((k) => {
    if (k === 'cr') return `coding rate 4/${4 + (s.cr ?? DEFAULTS.cr)}`;
    const { label, unit } = LIMITS[k];
    // Lower case within the sentence, but an abbreviation keeps its capital ("Tx power").
    const named = label.startsWith('Tx ') ? label : `${label.charAt(0).toLowerCase()}${label.slice(1)}`;
    return `${named} ${s[k]}${unit ? ` ${unit}` : ''}`;
  });
  // Without shadowing (0 dB) there are no fades to fix in space: not sent (`toParams`), nor said.
  const fixed = s.shadowingModel === 'field' && (s.shadowing ?? DEFAULTS.shadowing) > 0;
  return fixed ? [...named, 'shadowing fixed in space'] : named;
}

/** Where the gateways stand: the default gateway's distance, or the sites given (the distance
 * then places nothing). */
function link(s: Settings): string {
  if (s.gateways.length === 0) return `${(s.distance / 1000).toFixed(1)} km`;
  const sites = s.gateways.map((g) => `(${g.east}, ${g.north}) m`).join(', ');
  return `${s.gateways.length === 1 ? 'gateway' : 'gateways'} at ${sites}`;
}

/** The station's prediction in words: `bounded prediction, adaptive heading noise`. */
export function prediction(s: Pick<Settings, 'prediction'> & Partial<Pick<Settings, 'headingNoise'>>): string {
  return `${s.prediction} prediction${s.prediction === 'bounded' && s.headingNoise === 'adaptive' ? ', adaptive heading noise' : ''}`;
}

/** The one station a swarm's drones report to, with its prediction and (where not the paper's)
 * the sending: `3D-CTRA station (bounded prediction, error-triggered sending (2 m, …))`. */
export function stationPhrase(station: ModelName, s: Parameters<typeof prediction>[0] & Parameters<typeof sending>[0] & Parameters<typeof sendsAsPublished>[0]): string {
  return `${MODEL_LABELS[station]} station (${prediction(s)}${sendsAsPublished(s) ? '' : `, ${sending(s, true)}`})`;
}

/** An ADR as the page names it: "LoRaWAN ADR", "tracking ADR" ("no ADR": a fixed rate). */
export const adrName = (adr: 'off' | 'lorawan' | 'tracking'): string => ({ off: 'no ADR', lorawan: 'LoRaWAN ADR', tracking: 'tracking ADR' })[adr];

/** The data rate's adaptation in words, for a caption that names the station and the sending:
 * `; tracking ADR from SF12, 125 kHz` (the rate the network moves the drone from), or nothing
 * without ADR. */
export function adrFrom(s: Pick<Settings, 'adr' | 'sf' | 'bw'>): string {
  return s.adr === 'off' ? '' : `; ${adrName(s.adr)} from SF${s.sf}, ${s.bw} kHz`;
}

/** A fraction as a percentage, to three significant digits: 0.02 → "2 %". */
export const percent = (fraction: number): string => `${+(fraction * 100).toPrecision(3)} %`;

/** The plan and what limits sending, where it is not the paper's EU868 1 % duty cycle, and fair
 * use: "EU868, 2 % duty cycle", "US915, every 1 s", "EU868, listen before talk, TTN fair use";
 * '' for the paper's. Settings and a run's echoed config both have these. */
export function planLimit(s: Pick<Settings, 'region' | 'access' | 'fairUse' | 'dutyCycle'> & { interval?: number }): string {
  const dutyCycle = s.dutyCycle === DEFAULTS.dutyCycle ? '' : `, ${percent(s.dutyCycle)} duty cycle`;
  const limit = { interval: `, every ${s.interval ?? DEFAULTS.interval} s`, lbt: ', listen before talk', dutyCycle }[sendingLimit(s)];
  const region = s.region === 'eu868' && !limit ? [] : [`${plan(s.region).label}${limit}`];
  const fair = s.fairUse === 'off' ? [] : [`${s.fairUse.toUpperCase()} fair use`];
  return [...region, ...fair].join(', ');
}

/** The settings behind a number, in one short phrase: the plan's limit whenever it is not the
 * paper's EU868 1 % duty cycle, the sender's threshold and heartbeat, and any advanced setting
 * changed from its default. Of a `swarm` it says whether the drones listen to their channel, and
 * names the SF only where the swarm's plan puts every drone on it (spread deals SF7..SF12 in
 * turn, which its caption names). */
export function describe(s: Settings, swarm?: SwarmOf): string {
  const namesSf = swarm?.fixedSf ?? true;
  const limit = planLimit(s);
  // A tilt decay kept in the form where no station reads it is not sent (`toParams`), nor said.
  const advanced = advancedChanged(decaysTilt(s.model) ? s : { ...s, eta: DEFAULTS.eta });
  return `${namesSf ? `SF${s.sf}, ` : ''}${s.bw} kHz${limit ? `, ${limit}` : ''}, ${link(s)}, ${prediction(s)}, ${sending(s, swarm !== undefined)}${s.adr === 'off' ? '' : `, ${adrName(s.adr)}`}${advanced.map((a) => `, ${a}`).join('')}`;
}

/** What a swarm's caption says otherwise than the single drone's ([`describe`]). */
export interface SwarmOf {
  /** Whether every drone is on the form's SF (`sfPlan` fixed). */
  fixedSf: boolean;
}

/** One line for a download's caption: the settings, flight, seed and version behind a chart (of
 * a `swarm`: [`describe`]). */
export function caption(s: Settings, extra = '', swarm?: SwarmOf): string {
  const flight = s.flight === 'all' ? 'whole synthetic set' : s.flight === 'canberra' ? 'real flight (Canberra)' : s.flight === 'csv' ? (store.csv?.name ?? 'uploaded CSV') : s.flight === 'plan' ? `${store.plan?.name ?? 'plan'} (flown)` : `synthetic flight ${s.flightNumber}`;
  // A vehicle set over an uploaded file's changes how it is flown, followed and bounded, where
  // a station reads it.
  const set = uploaded(s.flight) && s.vehicle !== 'auto' && readsVehicle(s.flight === 'plan', s.model, s.prediction);
  const vehicle = set ? (s.vehicle === 'fixed-wing' ? ' as a plane' : ' as a multicopter') : '';
  const seeds = s.seeds > 1 ? ` to ${s.seed + s.seeds - 1}` : '';
  return `${describe(s, swarm)}, ${s.lorawan ? `${overheadBytes(s)} B` : 'no'} LoRaWAN overhead; ${flight}${vehicle}; seed ${s.seed}${seeds}${extra}; loratrack ${__LORATRACK_VERSION__}`;
}

/** A flight time as a sentence says it: "2 minutes", "1 minute", "90 s". */
export function flightTime(seconds: number): string {
  return seconds % 60 === 0 ? `${seconds / 60} minute${seconds === 60 ? '' : 's'}` : `${seconds} s`;
}

/** Under a sweep's chart, what its `marks` for thin numbers stand for: the points at which a
 * station received too few packets to compare (the core's `caveats.fewPackets`, the results
 * table's "Too few packets to compare"), by where they stand, with their packets, and what
 * would give them more for the `flight` flown (the whole set has what it has); '' for none.
 * One flight at SF12 sees a packet or two, and a p75 over them is mostly where they fell. */
export function fewPacketsNote(points: { at: string; received: number; few: boolean }[], marks: string, flight: Settings['flight']): string {
  const at = [...new Set(points.filter((p) => p.few).map((p) => p.at))];
  if (!at.length) return '';
  const counts = at.map((a) => {
    const received = points.filter((p) => p.at === a && p.few).map((p) => p.received);
    const [lo, hi] = [Math.min(...received), Math.max(...received)];
    return `${a} (${lo === hi ? lo : `${lo}–${hi}`})`;
  });
  const unit = at.length === 1 && counts[0].endsWith('(1)') ? 'packet' : 'packets';
  const more = flight === 'all' ? '' : flight === 'csv' ? ' A longer flight gives them more.' : flight === 'plan' ? ' A longer plan gives them more.' : ' More flight time gives them more: the whole synthetic set (Trajectory) flies 44 minutes.';
  return `${marks} rest on too few received packets to tell the stations apart: ${counts.join(', ')} ${unit}.${more}`;
}

/** Under a sweep's chart, what the core refused and why, one reason at a time: a whole point
 * ("Not simulated at SF11: US915 has no uplink data rate at SF11/125 kHz.") or the stations of it
 * that did not run ("3D-CTRA not simulated at SF10: …"). Points refused alike are named together,
 * with the numbers in which their reasons differ side by side ("(SF9/10 at 250 kHz: 10.3/18.5
 * s)"); '' where nothing was refused. `asked` are the stations the run names, `ran` those of each
 * point's report. */
export function refusedNote(points: { at: string; asked: ModelName[]; ran: ModelName[]; error?: string }[]): string {
  const groups = new Map<string, { who: string; at: string[]; errors: string[] }>();
  for (const p of points) {
    if (!p.error) continue;
    const missing = p.asked.filter((m) => !p.ran.includes(m));
    const who = p.ran.length ? `${names(missing.map((model) => ({ model })))} not simulated` : 'Not simulated';
    const error = p.ran.length ? forEach(missing, p.error.replace(/\.$/, '')) : p.error.replace(/\.$/, '');
    const key = `${who}\n${error.replace(NUMBER, '#')}`;
    const g = groups.get(key) ?? { who, at: [], errors: [] };
    groups.set(key, { who, at: [...g.at, p.at], errors: [...g.errors, error] });
  }
  return [...groups.values()].map((g) => `${g.who} at ${g.at.join(', ')}: ${sideBySide(g.errors)}.`).join(' ');
}

/** A refusal the core gave for one of `missing` ("3D-CTRA sends 12 bytes …", the first station
 * that was tried) as the reason of them all where they send the same payload ("each sends 12
 * bytes …", under "3D-CTRA and IMM not simulated"). */
function forEach(missing: ModelName[], error: string): string {
  if (missing.length < 2 || new Set(missing.map((m) => PAYLOAD_BYTES[m])).size > 1) return error;
  const first = missing.find((m) => error.startsWith(`${MODEL_LABELS[m]} sends `));
  return first ? `each sends ${error.slice(`${MODEL_LABELS[first]} sends `.length)}` : error;
}

const NUMBER = /\d+(?:\.\d+)?/g;

/** Messages alike but for their numbers as one, each number that differs given as all of them in
 * turn: "SF9 at 250 kHz: 10.3 s" and "SF10 at 250 kHz: 18.5 s" make "SF9/10 at 250 kHz: 10.3/18.5 s". */
function sideBySide(messages: string[]): string {
  const numbers = messages.map((m) => m.match(NUMBER) ?? []);
  let k = 0;
  return messages[0].replace(NUMBER, () => {
    const all = [...new Set(numbers.map((n) => n[k]))];
    k++;
    return all.join('/');
  });
}

/** Under a sweep's chart, which runs one seed whatever the table pools (the page's sweep charts
 * each run 6 settings more): says so where the table on show pools `tableSeeds` seeds, whose
 * numbers the chart's point at the same setting would otherwise seem to contradict; '' for one. */
export function oneSeedNote(tableSeeds: number, seed: number): string {
  return tableSeeds > 1 ? `This chart runs seed ${seed} alone; the results table pools ${tableSeeds} seeds.` : '';
}

/** Under the error-versus-distance chart where gateways are listed: its runs place one gateway at
 * each distance instead (a distance to several sites has no one meaning), which the reader of a
 * table resting on the listed sites must be told; '' without listed gateways. */
export function oneGatewayNote(listed: number): string {
  return listed > 0 ? `This chart places one gateway at each distance; the results table rests on the ${listed} gateway${listed === 1 ? '' : 's'} listed under Settings.` : '';
}

/** Under the error-versus-distance chart where the results table's one gateway (at `distance` m,
 * none listed) lies outside the chart's distances (`swept`, m): a lecturer at 7 km sees the
 * table's errors and a chart that stops at 5 km, which must not seem to contain them; '' where it
 * lies within (between two boxes it is read between them) or gateways are `listed`. */
export function offChartNote(distance: number, swept: number[], listed: number): string {
  if (listed > 0 || !swept.length) return '';
  const [near, far] = [Math.min(...swept), Math.max(...swept)];
  const at = `The results table's gateway at ${(distance / 1000).toFixed(1)} km lies`;
  if (distance > far) return `${at} beyond this chart's furthest distance, ${far / 1000} km.`;
  if (distance < near) return `${at} nearer than this chart's nearest distance, ${near / 1000} km.`;
  return '';
}

/** Under the error-versus-SF chart with ADR on: its runs keep each SF fixed (a point per data
 * rate is the chart's point), while the results table's network moves the rate; '' without ADR. */
export function fixedRateNote(adr: Settings['adr']): string {
  return adr === 'off' ? '' : `Each point keeps its SF fixed; the results table's ${adrName(adr)} moves the rate from the chosen SF.`;
}

/** Under the error-over-time chart (`what`: the 3D view), which draw one flight: the stations
 * none of whose packets arrived on it (where another's did), which have no line there (in the
 * chart, only the ✕ of their lost packets), and apart from them those whose drone sent none on
 * it (a slow rate under fair use: each station's payload sets its own interval), which have no ✕
 * either; '' where every station or none has a line (the chart then says so itself). */
export function noLineNote(models: Pick<ModelSeries, 'model' | 't' | 'lost'>[], flight: string, what: 'chart' | 'view' = 'chart'): string {
  const silent = models.filter((m) => m.t.length === 0);
  if (silent.length === 0 || silent.length === models.length) return '';
  const lost = silent.filter((m) => m.lost.length > 0);
  const unsent = silent.filter((m) => m.lost.length === 0);
  const drawn = (of: unknown[]) => (what === 'chart' ? `no line, only the ✕ of ${of.length === 1 ? 'its' : 'their'} lost packets` : 'no track');
  return [
    ...(lost.length ? [`${names(lost)} received no packet on ${flight}: ${drawn(lost)}.`] : []),
    ...(unsent.length ? [`${names(unsent)} sent no packet on ${flight}: no ${what === 'chart' ? 'line' : 'track'}.`] : []),
  ].join(' ');
}

/** Under the error-over-time chart and the 3D view (`what`), which draw one flight with one seed
 * (the series of a run is its first flight's): says which, where the table on show pools more, whose p75 a reader would
 * otherwise look for in it; '' where the run is that one flight. */
export function seriesNote(c: { flights: number; seeds: number; seed: number }, flight: string, what = 'chart'): string {
  if (c.flights <= 1 && c.seeds <= 1) return '';
  const pooled = `${c.flights} flight${c.flights === 1 ? '' : 's'} × ${c.seeds} seed${c.seeds === 1 ? '' : 's'}`;
  return `This ${what} is ${flight} with seed ${c.seed} alone; the results table pools ${pooled}.`;
}

/** The share of the time under the error chart's band, in whole per cent, below which the band
 * has failed as a 95 % bound and the note under it says so. Bounded stations hold 94–99 % over the
 * synthetic set at SF7–SF12, 1 and 3 km, the paper's 51–97 % below SF7/250 kHz (docs/reference.md
 * §12). */
const BAND_FAILS_BELOW = 90;

/**
 * Under the error-over-time chart, and on its slide: how often each station's error stayed under
 * its band over the results' runs (`underBound95`, in whole per cent), wherever one station's
 * share falls below 90 %: that band claims more than it holds. A band held more often than 95 % is
 * a cautious bound, not a broken one (the paper's station at SF7/250 kHz: 95–100 %), and a note
 * there would push the chart off a laptop's first screen. The paper's station does not calibrate
 * its covariance, which the note then says. '' where every band held or nothing was scored.
 */
export function bandNote(prediction: Settings['prediction'], results: Pick<ModelResult, 'model' | 'underBound95'>[]): string {
  const shares = results.flatMap((m) => (m.underBound95 === null ? [] : [{ model: m.model, percent: Math.round(100 * m.underBound95) }]));
  if (!shares.some((m) => m.percent < BAND_FAILS_BELOW)) return '';
  const held = listed(shares.map((m) => `${m.percent} % (${MODEL_LABELS[m.model]})`));
  const uncalibrated = prediction === 'paper' ? "The paper's station does not calibrate its band: the error stayed" : 'The error stayed';
  return `${uncalibrated} under it ${held} of the time in the results' runs.`;
}
