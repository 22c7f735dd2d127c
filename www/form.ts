// The settings form: written from the settings, read back with each field checked against the
// core's limits (the problem shown beside the field), the gateway rows, and the choices offered
// (settings the core would refuse are disabled, with the reason).
import { isLoaded, linkBudget, MODEL_LABELS, PAYLOAD_BYTES, stationsOf, timeOnAir, type GatewaySite, type Region } from './loratrack';
import { $ } from './dom';
import { listed } from './format';
import { ADR_START_REASON, adrCanStart, DEFAULTS, GATEWAY_LIMITS, invalid, invalidGateways, isNumericKey, LIMITS, MISSION_REASON, overheadBytes, packetPlan, plan, planAllows, planKnown, planReason, type FlightChoice, type Settings } from './state';
import { decaysTilt, runsMission } from './stations';
import { store } from './store';

export const form = $<HTMLFormElement>('#controls');

/** What runs when the form changes through its own buttons (adding or removing a gateway). */
let changed: () => void = () => undefined;
export function onFormChange(run: () => void): void {
  changed = run;
}

export function field(name: string): HTMLInputElement | HTMLSelectElement {
  return form.elements.namedItem(name) as HTMLInputElement | HTMLSelectElement;
}

function writeGateways(list: GatewaySite[]): void {
  const heading = document.createElement('div');
  heading.className = 'gateway-heading';
  heading.setAttribute('aria-hidden', 'true');
  heading.innerHTML = '<span></span><span>east (m)</span><span>north (m)</span><span>height (m)</span>';
  gatewayRows.replaceChildren(
    ...(list.length ? [heading] : []),
    ...list.map((g, i) => {
      const row = document.createElement('div');
      row.className = 'gateway-row';
      const input = (name: string, label: string, value: number | undefined, min: number, max: number) => {
        const el = document.createElement('input');
        el.type = 'number';
        el.name = `gateway-${name}`;
        el.dataset.gateway = name;
        el.min = String(min);
        el.max = String(max);
        el.step = '10';
        el.value = value === undefined ? '' : String(value);
        el.setAttribute('aria-label', `Gateway ${i + 1} ${label}`);
        // A blank height is the default antenna height (the core's table).
        if (name === 'height') el.placeholder = String(GATEWAY_LIMITS.height.default ?? '');
        return el;
      };
      const c = GATEWAY_LIMITS.coordinate;
      const h = GATEWAY_LIMITS.height;
      const remove = document.createElement('button');
      remove.type = 'button';
      remove.textContent = 'Remove';
      remove.setAttribute('aria-label', `Remove gateway ${i + 1}`);
      remove.addEventListener('click', () => {
        store.settings.gateways = store.settings.gateways.filter((_, k) => k !== i);
        writeGateways(store.settings.gateways);
        changed();
      });
      const label = document.createElement('span');
      label.textContent = `${i + 1}`;
      label.className = 'gateway-number';
      row.append(label, input('east', 'east (m)', g.east, c.min, c.max), input('north', 'north (m)', g.north, c.min, c.max), input('height', 'height (m)', g.height, h.min, h.max), remove);
      return row;
    }),
  );
  $<HTMLButtonElement>('#add-gateway').disabled = list.length >= GATEWAY_LIMITS.count.max;
}

/** The gateways in the form, and why they cannot be simulated (null when they can). */
function readGateways(): { list: GatewaySite[]; why: string | null } {
  const list = [...gatewayRows.querySelectorAll<HTMLElement>('.gateway-row')].map((row) => {
    const v = (name: string) => row.querySelector<HTMLInputElement>(`[data-gateway="${name}"]`)!.value.trim();
    const g: GatewaySite = { east: v('east') === '' ? NaN : Number(v('east')), north: v('north') === '' ? NaN : Number(v('north')) };
    if (v('height') !== '') g.height = Number(v('height'));
    return g;
  });
  return { list, why: invalidGateways(list) };
}

export function writeControls(s: Settings): void {
  writeGateways(s.gateways);
  for (const [key, value] of Object.entries(s)) {
    if (key === 'gateways') continue;
    const el = field(key);
    if (!el) continue;
    if (el instanceof HTMLInputElement && el.type === 'checkbox') el.checked = Boolean(value);
    else el.value = String(value);
  }
  showConditional();
}

/** A setting as the form words it, its label and what its control shows for `s`: ("Spreading
 * factor", "SF12"), ("Sending", "Error-triggered"), ("Distance", "3000 m"). */
export function settingWords(key: keyof Settings, s: Settings): { label: string; value: string } {
  if (key === 'gateways') return { label: 'Gateways', value: s.gateways.length ? s.gateways.map((g) => `(${g.east}, ${g.north}) m`).join(', ') : 'none listed' };
  if (key === 'lorawan') return { label: 'LoRaWAN overhead', value: s.lorawan ? 'on' : 'off' };
  const el = field(key);
  // The label's own text, without an <output> showing the value inside it (the distance's).
  const label = [...(form.querySelector(`label[for="${key}"]`)?.childNodes ?? [])].filter((n) => n.nodeType === Node.TEXT_NODE).map((n) => n.textContent).join('').trim() || key;
  const value = String(s[key]);
  const shown = el instanceof HTMLSelectElement ? ([...el.options].find((o) => o.value === value)?.textContent ?? value) : key === 'distance' ? `${value} m` : value;
  return { label, value: shown };
}

/** The form's settings, and the fields whose values are not acceptable (marked next to them). */
export function readControls(): { next: Settings; errors: string[] } {
  const s: Settings = { ...store.settings };
  const errors: string[] = [];
  const gateways = readGateways();
  if (gateways.why) errors.push(gateways.why);
  else s.gateways = gateways.list;
  for (const key of Object.keys(DEFAULTS) as (keyof Settings)[]) {
    if (key === 'gateways') continue;
    const el = field(key);
    if (!el) continue;
    if (el instanceof HTMLInputElement && el.type === 'checkbox') (s as unknown as Record<string, unknown>)[key] = el.checked;
    else if (isNumericKey(key)) {
      const v = el.value.trim() === '' ? NaN : Number(el.value);
      const why = invalid(key, v);
      markField(el, why);
      if (why) errors.push(why);
      else (s as unknown as Record<string, unknown>)[key] = v;
    } else (s as unknown as Record<string, unknown>)[key] = el.value;
  }
  // A flight without a known plan cannot run the mission station: 3D-CTRA, its fallback, instead.
  if (runsMission(s.model) && !planKnown(s.flight, Boolean(store.plan))) {
    s.model = '3d-ctra';
    field('model').value = s.model;
  }
  return { next: s, errors };
}

/** Shows (or clears) a field's problem beside it, for eyes and for screen readers. */
export function markField(el: HTMLInputElement | HTMLSelectElement, why: string | null): void {
  const id = `${el.id}-error`;
  let message = document.getElementById(id);
  if (!why) {
    el.removeAttribute('aria-invalid');
    message?.remove();
    el.setAttribute('aria-describedby', (el.getAttribute('aria-describedby') ?? '').replace(id, '').trim());
    if (!el.getAttribute('aria-describedby')) el.removeAttribute('aria-describedby');
    return;
  }
  el.setAttribute('aria-invalid', 'true');
  // A field under a closed section (Advanced: the core refused a link's seeds) is brought into
  // view: its mark is the answer to "what do I change?".
  const section = el.closest('details');
  if (section && !section.open) section.open = true;
  if (!message) {
    message = document.createElement('p');
    message.id = id;
    message.className = 'error field-error';
    el.insertAdjacentElement('afterend', message);
    el.setAttribute('aria-describedby', `${el.getAttribute('aria-describedby') ?? ''} ${id}`.trim());
  }
  message.textContent = why;
}

export function showConditional(): void {
  for (const el of document.querySelectorAll<HTMLElement>('[data-when]')) el.hidden = !el.dataset.when!.split(' ').includes(field('flight').value);
  for (const el of document.querySelectorAll<HTMLElement>('[data-when-sender]')) el.hidden = el.dataset.whenSender !== field('sender').value;
  for (const el of document.querySelectorAll<HTMLElement>('[data-when-prediction]')) el.hidden = el.dataset.whenPrediction !== field('prediction').value;
  // Only 3D-CTRA (and the stations that run it) decays the tilt rate.
  for (const el of document.querySelectorAll<HTMLElement>('[data-when-model]')) el.hidden = !decaysTilt(field('model').value);
  const km = `${(Number(field('distance').value) / 1000).toFixed(1)} km`;
  $('#distance-value').textContent = km;
  // Listed gateways replace the one gateway the distance places: the results then do not read it
  // (the core refuses it), only the swarm, which spreads its drones that far around its centre.
  const listed = gatewayRows.querySelector('.gateway-row') !== null;
  $('#distance-help').textContent = listed ? DISTANCE_HELP_LISTED : DISTANCE_HELP;
  // Screen readers hear the distance with its unit, not a bare number of metres.
  field('distance').setAttribute('aria-valuetext', listed ? `${km}, the swarm's spread` : `${km} to the gateway`);
  const noDutyCycle = plan(field('region').value as Region).dutyCycle === null;
  for (const el of document.querySelectorAll<HTMLElement>('[data-when-plan]')) el.hidden = (el.dataset.whenPlan === 'interval') !== noDutyCycle;
  // The duty cycle is not the drone's to keep where it listens before talk instead.
  for (const el of document.querySelectorAll<HTMLElement>('[data-when-access]')) el.hidden ||= el.dataset.whenAccess !== field('access').value;
  showPlanChoices();
  showSfReach();
}

/** How much further each SF step reaches, in the SF hint and the link budget's explanation, from
 * the core's link budget at the form's path-loss exponent: each SF step's gain in sensitivity
 * over that exponent (17 % at the default 3.76, 24 % at 2.7). */
function showSfReach(): void {
  const n = Number(field('pathLossExponent').value);
  if (!isLoaded() || invalid('pathLossExponent', n)) return;
  const [sf7, sf8] = linkBudget({ pathLossExponent: n, distances: [] }).sfs;
  const further = Math.round(100 * (sf8.rangeM / sf7.rangeM - 1));
  const at = n === DEFAULTS.pathLossExponent ? '' : ` at path-loss exponent ${n}`;
  $('#sf-help').textContent = `Each step up about doubles the time on air (and the wait between packets) and reaches about ${further} % further${at}.`;
  $('#link-sf-reach').textContent = `about ${further} % more range${at}`;
}

/** Settings the core would refuse are not offered: a plan's missing SF/bandwidth pairs; a data
 * rate that cannot carry a station's frame (over the plan's dwell time or payload limit); ADR
 * outside EU868 or away from an EU868 data rate; listen-before-talk where the plan has no duty
 * cycle. Each disabled choice says why. */
function showPlanChoices(): void {
  const sf = Number(field('sf').value);
  const bw = Number(field('bw').value);
  const region = field('region').value as Region;
  const model = field('model').value;
  const adrOn = field('adr').value !== 'off';
  const rateWhy = (s: number, b: number) =>
    !planAllows(region, s, b) ? planReason(region) : adrOn && !adrCanStart(s, b) ? ADR_START_REASON : frameRefusal(model, s, b, region);
  // Disables the choices `whyNot` gives a reason for, and returns the distinct reasons.
  const offer = (name: string, whyNot: (o: HTMLOptionElement) => string | null) => {
    const reasons = new Set<string>();
    for (const o of (field(name) as HTMLSelectElement).options) {
      const why = whyNot(o);
      o.disabled = why !== null;
      o.title = why ?? '';
      if (why) reasons.add(why);
    }
    return [...reasons];
  };
  const adrWhy = region === 'eu868' ? ADR_START_REASON : `ADR runs EU868's data rates; ${plan(region).label} has its own.`;
  const adrBlocked = offer('adr', (o) => (o.value === 'off' || (region === 'eu868' && adrCanStart(sf, bw)) ? null : adrWhy));
  // Every list is updated (no short-circuit).
  const rateReasons = new Set([...offer('sf', (o) => rateWhy(Number(o.value), bw)), ...offer('bw', (o) => rateWhy(sf, Number(o.value)))]);
  offer('region', (o) =>
    !planAllows(o.value as Region, sf, bw) || (adrOn && o.value !== 'eu868') ? `Not at SF${sf} / ${bw} kHz${adrOn ? ' with ADR on' : ''}.` : frameRefusal(model, sf, bw, o.value as Region),
  );
  offer('access', (o) => (o.value === 'duty-cycle' || plan(region).dutyCycle !== null ? null : `Listen-before-talk replaces a duty cycle; ${plan(region).label} has none.`));
  const known = planKnown(field('flight').value as FlightChoice, Boolean(store.plan));
  offer('model', (o) => (!known && runsMission(o.value) ? MISSION_REASON : frameRefusal(o.value, sf, bw, region)));
  // Every station the list offers, with the plan's reasons for those it cannot carry.
  const everyStation = [...(field('model') as HTMLSelectElement).options].map((o) => o.value).join(',');
  const stationsRefused = frameRefusal(everyStation, sf, bw, region);
  const modelNote = [known ? '' : MISSION_REASON, stationsRefused ? `Not offered at SF${sf} / ${bw} kHz: ${stationsRefused}` : ''].filter(Boolean).join(' ');
  show($('#model-note'), modelNote || null);
  show($('#adr-note'), adrBlocked.length && region === 'eu868' ? `ADR is not offered at SF${sf} / ${bw} kHz. ${ADR_START_REASON}` : null);
  const rateNote = adrOn ? `With ADR on, only EU868 data rates can be chosen. ${ADR_START_REASON}` : `Some SF and bandwidth pairs are not offered: ${[...rateReasons].join(' ')}`;
  show($('#region-note'), rateReasons.size ? rateNote : null);
}

/** A form note: shown with `text`, hidden and emptied without. */
function show(note: HTMLElement, text: string | null): void {
  note.hidden = text === null;
  note.textContent = text ?? '';
}

/** Why the plan cannot carry the frames of the stations `model` runs at `sf` / `bw` kHz in
 * `region` (over its dwell time or payload limit, or longer on air than the interval where it has
 * no duty cycle), as the core decides it for the time-on-air table and for a run: the stations
 * refused for one reason named together, e.g. "3D-CTRA and IMM (25-byte frame): the frame takes
 * 411.6 ms on air at US915 DR0 (SF10/125 kHz): over the 400 ms dwell time."; `null` where every
 * frame fits, and until the WebAssembly module is loaded (main.ts then asks again). */
function frameRefusal(model: string, sf: number, bw: number, region: Region): string | null {
  if (!isLoaded() || !planAllows(region, sf, bw)) return null;
  // A field's value where it is acceptable, else the settings' (its mark says why).
  const typed = (key: 'interval' | 'dutyCycle') => {
    const v = Number(field(key).value);
    return invalid(key, v) ? store.settings[key] : v;
  };
  const link = packetPlan({
    region,
    lorawan: (field('lorawan') as HTMLInputElement).checked,
    cr: Number(field('cr').value),
    access: field('access').value as Settings['access'],
    fairUse: field('fairUse').value as Settings['fairUse'],
    interval: typed('interval'),
    dutyCycle: typed('dutyCycle'),
  });
  // Each reason with the stations refused for it by their frames' length in bytes.
  const refused = new Map<string, Map<number, string[]>>();
  try {
    for (const station of stationsOf(model)) {
      const why = timeOnAir({ sf, bw, payload: PAYLOAD_BYTES[station], ...link }).refused;
      if (!why) continue;
      const bytes = PAYLOAD_BYTES[station] + link.overhead;
      const byBytes = refused.get(why) ?? new Map<number, string[]>();
      refused.set(why, byBytes.set(bytes, [...(byBytes.get(bytes) ?? []), MODEL_LABELS[station]]));
    }
  } catch {
    // A setting the form marks beside its field; the core says the rest when the run is asked for.
    return null;
  }
  const stations = (byBytes: Map<number, string[]>) => [...byBytes].map(([bytes, labels]) => `${listed(labels)} (${bytes}-byte frame)`);
  return refused.size ? [...refused].map(([why, byBytes]) => `${listed(stations(byBytes))}: ${why}.`).join(' ') : null;
}

/** The form's min and max come from the core's table, as the URL's checks do; the distance
 * slider keeps its teaching range (0.1–10 km), and a link beyond it is said to be moved. */
for (const [key, l] of Object.entries(LIMITS)) {
  const el = field(key);
  if (el instanceof HTMLInputElement && el.type !== 'checkbox' && el.type !== 'range' && !l.values) {
    el.min = String(l.min);
    el.max = String(l.max);
  }
  if (el && l.help) el.title = `${l.help} Accepted: ${l.min}–${l.max}${l.unit ? ` ${l.unit}` : ''}.`;
}

// The overhead the LoRaWAN box adds, as the core's table declares it.
$('#overhead-bytes').textContent = String(overheadBytes({ lorawan: true }));

const gatewayRows = $('#gateway-rows');

/** The distance's hint: as the page words it for the one default gateway, and where gateways are
 * listed. */
const DISTANCE_HELP = $('#distance-help').textContent ?? '';
const DISTANCE_HELP_LISTED =
  "The gateways listed below (Gateways) replace the one gateway this distance places east of the flight's start, so the results do not read it; the swarm spreads its drones this far around its centre.";

$('#add-gateway').addEventListener('click', () => {
  // The first added gateway keeps the default one where it was, so adding never moves it.
  const list = store.settings.gateways.length ? [...store.settings.gateways] : [{ east: store.settings.distance, north: 0 }];
  list.push({ east: 0, north: 0 });
  store.settings.gateways = list;
  writeGateways(list);
  changed();
});

