// How the page words numbers and settings: captions on every download and embed rest on these.
import { expect, test } from 'vitest';
import { adrFrom, advancedChanged, bandNote, caption, counted, describe, planLimit, downlinkCounts, stationPhrase, fewPacketsNote, fixedRateNote, flightTime, noLineNote, offChartNote, oneGatewayNote, oneSeedNote, refusedNote, seriesNote, fmt, names, sendsAsPublished, trackedPercent } from '../../www/format';
import { DEFAULTS, LIMITS } from '../../www/state';
import { OPTIONS, type ModelResult } from '../../www/loratrack';

test('a statistic with no data is a dash, never NaN or "null"', () => {
  expect(fmt(null)).toBe('—');
  expect(fmt(2.345)).toBe('2.35');
  expect(fmt(16.14, 1)).toBe('16.1');
});

// Whether it is said at all is the core's `wholeFlight.partlyTracked` (src/metrics/whole_flight.rs).
test('the tracked share is said in whole percent', () => {
  expect(trackedPercent(0.169)).toBe(17);
  expect(trackedPercent(0.946)).toBe(95);
  expect(trackedPercent(null)).toBe(0);
});

test('a count of one names one thing; ADR answers are counted as the CLI counts them', () => {
  expect(counted(1, 'packet')).toBe('1 packet');
  expect(counted(0, 'packet')).toBe('0 packets');
  expect(counted(3, 'copy', 'copies')).toBe('3 copies');
  const g = (downlinksSent: number, downlinksDropped: number, downlinksHeldBack: number) => ({ east: 0, north: 0, height: 15, heard: 9, onlyHeard: 9, downlinksSent, downlinksDropped, downlinksHeldBack, missedWhileTransmitting: 0 });
  expect(downlinkCounts([g(1, 2, 0)])).toBe("1 ADR downlink sent, 2 dropped by the gateway's duty cycle");
  expect(downlinkCounts([g(4, 0, 5), g(2, 1, 1)])).toBe("6 ADR downlinks sent, 1 dropped by the gateway's duty cycle, 6 held back for a later uplink to keep a crowded gateway listening");
});

test('station lists read as a sentence', () => {
  const m = (model: string) => ({ model }) as ModelResult;
  expect(names([m('dr')])).toBe('DR');
  expect(names([m('dr'), m('ctra-plus')])).toBe('DR and CTRA+');
  expect(names([m('dr'), m('ctra-plus'), m('3d-ctra')])).toBe('DR, CTRA+ and 3D-CTRA');
});

test("the error chart's band says how often it held wherever one station's band failed as a 95 % bound", () => {
  const r = (model: string, underBound95: number | null) => ({ model, underBound95 }) as Pick<ModelResult, 'model' | 'underBound95'>;
  const paper = bandNote('paper', [r('dr', 0.855), r('ctra-plus', 0.9996), r('3d-ctra', 0.87)]);
  expect(paper).toBe("The paper's station does not calibrate its band: the error stayed under it 86 % (DR), 100 % (CTRA+) and 87 % (3D-CTRA) of the time in the results' runs.");
  // Every band held, in whole per cent, however cautious: nothing to say under the chart.
  expect(bandNote('paper', [r('dr', 0.956), r('ctra-plus', 0.9996), r('3d-ctra', 1)])).toBe('');
  expect(bandNote('bounded', [r('dr', 0.895), r('3d-ctra', 0.957), r('imm', 0.993)])).toBe('');
  // One station's band fails: every share is given.
  expect(bandNote('bounded', [r('dr', 0.894), r('imm', 0.993)])).toBe("The error stayed under it 89 % (DR) and 99 % (IMM) of the time in the results' runs.");
  // Nothing scored (no packet arrived): no claim.
  expect(bandNote('paper', [r('dr', null)])).toBe('');
});

test('the error chart names the stations with no line on its flight, only where others have one', () => {
  const series = (model: string, samples: number, lost = 3) => ({ model, t: new Float64Array(samples), lost: new Float64Array(lost) }) as Parameters<typeof noLineNote>[0][number];
  expect(noLineNote([series('dr', 10), series('ctra-plus', 5)], 'canberra')).toBe('');
  expect(noLineNote([series('dr', 0), series('ctra-plus', 0)], 'canberra')).toBe('');
  expect(noLineNote([series('dr', 0), series('ctra-plus', 5), series('3d-ctra', 5)], 'canberra')).toBe('DR received no packet on canberra: no line, only the ✕ of its lost packets.');
  expect(noLineNote([series('dr', 0), series('ctra-plus', 0), series('3d-ctra', 5)], 'canberra')).toMatch(/^DR and CTRA\+ received no packet on canberra: .* their lost packets\.$/);
  expect(noLineNote([series('dr', 0), series('ctra-plus', 5)], 'canberra', 'view')).toBe('DR received no packet on canberra: no track.');
  // A drone that sent nothing on the flight (fair use at a slow rate) has no lost packet to mark.
  expect(noLineNote([series('dr', 5), series('ctra-plus', 0, 0), series('3d-ctra', 0)], 'synthetic 1')).toBe('3D-CTRA received no packet on synthetic 1: no line, only the ✕ of its lost packets. CTRA+ sent no packet on synthetic 1: no line.');
  expect(noLineNote([series('dr', 5), series('ctra-plus', 0, 0)], 'synthetic 1', 'view')).toBe('CTRA+ sent no packet on synthetic 1: no track.');
});

test('a swarm names the one station its drones report to, its prediction and any sending not the paper\'s', () => {
  expect(stationPhrase('3d-ctra', DEFAULTS)).toBe('3D-CTRA station (paper prediction)');
  expect(stationPhrase('dr', { ...DEFAULTS, prediction: 'bounded', sender: 'error' })).toBe('DR station (bounded prediction, error-triggered sending (2 m, heartbeat 10 s, listening to its channel))');
});

test('the distance chart says it places one gateway where the table rests on listed ones', () => {
  expect(oneGatewayNote(0)).toBe('');
  expect(oneGatewayNote(1)).toBe('This chart places one gateway at each distance; the results table rests on the 1 gateway listed under Settings.');
  expect(oneGatewayNote(3)).toMatch(/rests on the 3 gateways listed/);
});

test('the distance chart says where the table\'s gateway lies outside its distances, and nothing where it lies within', () => {
  const swept = [500, 1000, 2000, 3000, 4000, 5000];
  const beyond = offChartNote(7000, swept, 0);
  expect(beyond).toMatch(/7\.0 km/);
  expect(beyond).toMatch(/beyond this chart's furthest distance, 5 km/);
  expect(offChartNote(200, swept, 0)).toMatch(/0\.2 km lies nearer than this chart's nearest distance, 0\.5 km/);
  // On a box, or between two, the chart holds the table's distance.
  for (const d of [500, 2500, 5000]) expect(offChartNote(d, swept, 0)).toBe('');
  // Listed gateways have no one distance: the one-gateway note speaks for them.
  expect(offChartNote(7000, swept, 2)).toBe('');
  expect(offChartNote(7000, [], 0)).toBe('');
});

test('the SF chart says its points keep their SF where the table\'s ADR moves the rate', () => {
  expect(fixedRateNote('off')).toBe('');
  expect(fixedRateNote('tracking')).toBe('Each point keeps its SF fixed; the results table\'s tracking ADR moves the rate from the chosen SF.');
  expect(fixedRateNote('lorawan')).toMatch(/LoRaWAN ADR/);
});

test('a results caption names the rate ADR moves the drone from, and nothing without ADR', () => {
  expect(adrFrom(DEFAULTS)).toBe('');
  expect(adrFrom({ ...DEFAULTS, adr: 'tracking', sf: 12, bw: 125 })).toBe('; tracking ADR from SF12, 125 kHz');
  expect(adrFrom({ ...DEFAULTS, adr: 'lorawan' })).toBe('; LoRaWAN ADR from SF7, 250 kHz');
});

test('a caption names the settings, the flight, every seed and the version', () => {
  expect(describe(DEFAULTS)).toBe('SF7, 250 kHz, 1.0 km, paper prediction, periodic sending');
  expect(describe({ ...DEFAULTS, adr: 'tracking', sf: 12, bw: 125 })).toBe('SF12, 125 kHz, 1.0 km, paper prediction, periodic sending, tracking ADR');
  // LoRaWAN's as the page names it everywhere else, not as its key is spelt.
  expect(describe({ ...DEFAULTS, adr: 'lorawan', sf: 12, bw: 125 })).toBe('SF12, 125 kHz, 1.0 km, paper prediction, periodic sending, LoRaWAN ADR');
  expect(describe({ ...DEFAULTS, payload: 'lean', dutyCycleMode: 'budget' })).toBe('SF7, 250 kHz, 1.0 km, paper prediction, periodic sending, duty-cycle budget, lean payloads');
  expect(sendsAsPublished(DEFAULTS)).toBe(true);
  expect(sendsAsPublished({ ...DEFAULTS, payload: 'lean' })).toBe(false);
  // The plan is named whenever its limit is not the paper's 1 % duty cycle.
  expect(describe({ ...DEFAULTS, region: 'us915', sf: 9, bw: 125 })).toBe('SF9, 125 kHz, US915, every 1 s, 1.0 km, paper prediction, periodic sending');
  expect(describe({ ...DEFAULTS, access: 'lbt', fairUse: 'ttn' })).toBe('SF7, 250 kHz, EU868, listen before talk, TTN fair use, 1.0 km, paper prediction, periodic sending');
  // Two sub-bands alternated: the duty cycle the intervals rest on; none where it does not apply.
  expect(describe({ ...DEFAULTS, dutyCycle: 0.02 })).toBe('SF7, 250 kHz, EU868, 2 % duty cycle, 1.0 km, paper prediction, periodic sending');
  expect(describe({ ...DEFAULTS, dutyCycle: 0.02, access: 'lbt' })).toBe(describe({ ...DEFAULTS, access: 'lbt' }));
  // The plan's limit alone, as the results' caption gives it (from a run's echoed config, which may lack the interval).
  expect(planLimit(DEFAULTS)).toBe('');
  expect(planLimit({ ...DEFAULTS, dutyCycle: 0.02 })).toBe('EU868, 2 % duty cycle');
  expect(planLimit({ region: 'us915', access: 'duty-cycle', fairUse: 'ttn', dutyCycle: 0.01 })).toBe('US915, every 1 s, TTN fair use');
  expect(describe({ ...DEFAULTS, txPower: 10, sensorRate: 5 })).toBe('SF7, 250 kHz, 1.0 km, paper prediction, periodic sending, Tx power 10 dBm, sensor rate 5 Hz');
  expect(describe({ ...DEFAULTS, region: 'as923', sf: 7, bw: 125 })).toMatch(/^SF7, 125 kHz, AS923, 1\.0 km/);
  // Fades fixed in space are other fades: a caption says so.
  expect(describe({ ...DEFAULTS, shadowingModel: 'field' })).toBe('SF7, 250 kHz, 1.0 km, paper prediction, periodic sending, shadowing fixed in space');
  // Two error-triggered runs with different thresholds, or different link settings, must not read alike;
  // nor two swarms of which one listens to its channel (the default) and one does not. A drone
  // alone never hears another's frame: its runs do not read that, nor say it.
  const crowd = { ...DEFAULTS, sender: 'error', threshold: 20, maxInterval: 60, dutyCycleMode: 'budget' } as const;
  const alone = 'SF7, 250 kHz, 1.0 km, paper prediction, error-triggered sending (20 m, heartbeat 60 s), duty-cycle budget';
  expect(describe(crowd)).toBe(alone);
  expect(describe({ ...crowd, channelSense: 'off' })).toBe(alone);
  expect(describe(crowd, { fixedSf: true })).toBe(alone.replace('heartbeat 60 s', 'heartbeat 60 s, listening to its channel'));
  expect(describe({ ...crowd, channelSense: 'off' }, { fixedSf: true })).toBe(alone);
  // Gateways placed by hand replace the default gateway's distance.
  expect(describe({ ...DEFAULTS, gateways: [{ east: 500, north: -200 }, { east: 0, north: 3000 }] })).toBe(
    'SF7, 250 kHz, gateways at (500, -200) m, (0, 3000) m, paper prediction, periodic sending',
  );
  expect(describe({ ...DEFAULTS, shadowing: 8, cr: 4, sensorRate: 5 })).toBe('SF7, 250 kHz, 1.0 km, paper prediction, periodic sending, coding rate 4/8, shadowing sigma 8 dB, sensor rate 5 Hz');
  // A run's echoed config, which has the core's settings but not the form's own (flight number,
  // seeds…), names what it changed as the form's settings do: the results' caption reads it.
  expect(advancedChanged({ shadowingModel: 'path', cr: 1, txPower: 10, shadowing: DEFAULTS.shadowing, step: 0.5 })).toEqual(['Tx power 10 dBm', 'prediction step T 0.5 s']);
  expect(advancedChanged({ shadowingModel: 'field', cr: 2 })).toEqual(['coding rate 4/6', 'shadowing fixed in space']);
  expect(advancedChanged(DEFAULTS)).toEqual([]);
  expect(caption(DEFAULTS)).toMatch(/^SF7, 250 kHz, 1\.0 km, paper prediction, periodic sending, 13 B LoRaWAN overhead; synthetic flight 1; seed 1; loratrack \d+\.\d+\.\d+$/);
  expect(caption({ ...DEFAULTS, flight: 'all', seed: 5, seeds: 10, lorawan: false })).toMatch(/no LoRaWAN overhead; whole synthetic set; seed 5 to 14;/);
  // A vehicle set over an uploaded flight or plan is named where a station reads it (a bounded or
  // mission station over a CSV flight); the bundled flights fly as they are.
  expect(caption({ ...DEFAULTS, flight: 'plan', vehicle: 'fixed-wing' })).toMatch(/; plan \(flown\) as a plane; seed 1;/);
  expect(caption({ ...DEFAULTS, flight: 'csv', vehicle: 'multicopter', prediction: 'bounded' })).toMatch(/; uploaded CSV as a multicopter; seed 1;/);
  expect(caption({ ...DEFAULTS, flight: 'csv', vehicle: 'multicopter' })).toMatch(/; uploaded CSV; seed 1;/);
  expect(caption({ ...DEFAULTS, flight: 'csv' })).toMatch(/; uploaded CSV; seed 1;/);
  // A spread swarm's caption leaves out the form's SF, which its drones are not all on.
  expect(caption({ ...DEFAULTS, sf: 9 }, '', { fixedSf: false })).toMatch(/^250 kHz, 1\.0 km, paper prediction/);
  expect(caption({ ...DEFAULTS, sf: 9 }, '', { fixedSf: true })).toMatch(/^SF9, 250 kHz, 1\.0 km, paper prediction/);
  expect(caption({ ...DEFAULTS, vehicle: 'fixed-wing' })).toMatch(/; synthetic flight 1; seed 1;/);
});

// A caption lists the settings the core's table marks (`listedWhenChanged`, which the CLI's
// `settings:` line reads too) and words the rest itself: every numeric setting of the form,
// changed, must move it, or two different runs are captioned alike.
test('every numeric setting of the form, changed from its default, changes the caption', () => {
  // Worded only where they apply: with error-triggered sending, and on a plan without a duty cycle.
  const elsewhere: Partial<Record<keyof typeof LIMITS, Partial<typeof DEFAULTS>>> = {
    threshold: { sender: 'error' },
    maxInterval: { sender: 'error' },
    interval: { region: 'us915', sf: 9, bw: 125 },
  };
  const keys = (Object.keys(LIMITS) as (keyof typeof LIMITS)[]).filter((k) => OPTIONS.some((o) => o.key === k));
  expect(keys.length).toBeGreaterThan(10);
  for (const key of keys) {
    const o = OPTIONS.find((x) => x.key === key)!;
    // The distance moves by the slider's step (100 m), as the page can set it.
    const step = key === 'distance' ? 100 : 1;
    const other = o.values.find((v) => v !== o.default) ?? (o.default + step <= o.max ? o.default + step : (o.min + o.default) / 2);
    const base = { ...DEFAULTS, ...elsewhere[key] };
    expect(caption({ ...base, [key]: other }), `${key} ${other}`).not.toBe(caption(base));
  }
});

test('a flight time reads in whole minutes where it is one, else in seconds', () => {
  expect(flightTime(120)).toBe('2 minutes');
  expect(flightTime(1200)).toBe('20 minutes');
  expect(flightTime(60)).toBe('1 minute');
  expect(flightTime(90)).toBe('90 s');
});

// Whether a point is thin is the core's `caveats.fewPackets` (src/sim/caveats.rs).
test('a sweep chart says which of its points rest on too few packets, with their packets', () => {
  const p = (at: string, received: number) => ({ at, received, few: received < 10 });
  expect(fewPacketsNote([p('SF7', 28), p('SF7', 26)], 'Hollow points', 'synthetic')).toBe('');
  expect(fewPacketsNote([p('SF8', 15), p('SF9', 8), p('SF9', 7), p('SF9', 12), p('SF12', 1)], 'Hollow points', 'synthetic')).toBe(
    'Hollow points rest on too few received packets to tell the stations apart: SF9 (7–8), SF12 (1) packets. More flight time gives them more: the whole synthetic set (Trajectory) flies 44 minutes.',
  );
  expect(fewPacketsNote([p('4 km', 1)], 'Dashed boxes', 'synthetic')).toMatch(/^Dashed boxes rest on .*: 4 km \(1\) packet\./);
  // What gives more follows the flight: the real flight's length is fixed, the whole set has what it has.
  expect(fewPacketsNote([p('SF12', 1)], 'Hollow points', 'canberra')).toMatch(/packet\. More flight time gives them more: the whole synthetic set/);
  expect(fewPacketsNote([p('SF12', 1)], 'Hollow points', 'csv')).toMatch(/packet\. A longer flight gives them more\.$/);
  expect(fewPacketsNote([p('SF12', 3)], 'Hollow points', 'all')).toMatch(/SF12 \(3\) packets\.$/);
});

test('a sweep chart of one seed says so where the table pools more', () => {
  expect(oneSeedNote(1, 1)).toBe('');
  expect(oneSeedNote(10, 3)).toBe('This chart runs seed 3 alone; the results table pools 10 seeds.');
});

test('the error chart says which flight and seed it draws where the table pools more', () => {
  expect(seriesNote({ flights: 1, seeds: 1, seed: 4 }, 'synthetic 3')).toBe('');
  expect(seriesNote({ flights: 30, seeds: 1, seed: 1 }, 'synthetic 1')).toBe('This chart is synthetic 1 with seed 1 alone; the results table pools 30 flights × 1 seed.');
  expect(seriesNote({ flights: 1, seeds: 10, seed: 2 }, 'canberra')).toBe('This chart is canberra with seed 2 alone; the results table pools 1 flight × 10 seeds.');
  expect(seriesNote({ flights: 30, seeds: 2, seed: 1 }, 'synthetic 1', 'view')).toMatch(/^This view is synthetic 1 with seed 1 alone/);
});

test('the refused note names whole points and the stations of a point that did not run, one reason at a time', () => {
  const asked = ['dr', 'ctra-plus', '3d-ctra'] as const;
  const note = refusedNote([
    { at: 'SF9', asked: [...asked], ran: [...asked] },
    { at: 'SF10', asked: [...asked], ran: ['dr', 'ctra-plus'], error: 'over the dwell time' },
    { at: 'SF11', asked: [...asked], ran: [], error: 'no such data rate.' },
    { at: 'SF12', asked: [...asked], ran: [], error: 'no such data rate.' },
  ]);
  expect(note).toBe('3D-CTRA not simulated at SF10: over the dwell time. Not simulated at SF11, SF12: no such data rate.');
  expect(refusedNote([{ at: 'SF7', asked: [...asked], ran: [...asked] }])).toBe('');
  // Stations refused for one frame length: the core's reason, given for the first, speaks for each.
  const frame = '3D-CTRA sends 12 bytes (+13 overhead): the frame takes 411.6 ms on air';
  const both = refusedNote([{ at: 'SF10', asked: ['dr', '3d-ctra', 'imm'], ran: ['dr'], error: frame }]);
  expect(both).toBe('3D-CTRA and IMM not simulated at SF10: each sends 12 bytes (+13 overhead): the frame takes 411.6 ms on air.');
  // Not where their payloads differ (CTRA+'s 11 bytes beside 3D-CTRA's 12): the first's reason stays its own.
  const apart = refusedNote([{ at: 'SF10', asked: ['dr', 'ctra-plus', '3d-ctra'], ran: ['dr'], error: frame }]);
  expect(apart).toBe(`CTRA+ and 3D-CTRA not simulated at SF10: ${frame}.`);
  // Nor where no station ran: the sentence names none for "each" to speak of.
  const none = refusedNote([{ at: 'SF10', asked: ['3d-ctra', 'mission'], ran: [], error: frame }]);
  expect(none).toBe(`Not simulated at SF10: ${frame}.`);
});

test('points refused alike but for their numbers share one sentence, the numbers side by side', () => {
  const asked = ['dr'] as const;
  const why = (sf: number, s: number) => `maxInterval must be at least the interval (SF${sf} at 250 kHz: ${s} s), got 10`;
  const note = refusedNote([9, 10, 11].map((sf, i) => ({ at: `SF${sf}`, asked: [...asked], ran: [], error: why(sf, [10.3, 18.5, 33][i]) })));
  expect(note).toBe('Not simulated at SF9, SF10, SF11: maxInterval must be at least the interval (SF9/10/11 at 250 kHz: 10.3/18.5/33 s), got 10.');
});
