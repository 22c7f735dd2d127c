// The worker pool splits a run by station and merges the reports: the merged report must be what
// one worker (or the CLI) reports for all stations at once.
import { expect, test, vi } from 'vitest';
import { merge, mergeSweepPoint } from '../../www/merge';
import { runSwarms, shareOut, SimulationPool } from '../../www/pool';
import type { SimReport } from '../../www/loratrack';
import type { Response, SimulateRequest } from '../../www/worker';

// The pool's workers are stand-ins: each keeps what it was sent and answers when told to. The
// module never compiles here (the stand-ins need none), a model list names its stations, and the
// core's pooling of the network totals (its own tests: Delivery::pooled, tests/wasm.rs) and its
// pairing of every station with the lowest (versus_lowest) are stand-ins that remember what they
// were given.
const core = vi.hoisted(() => ({ pooled: [] as unknown[][], paired: [] as unknown[][] }));
const VERSUS = { lowest: 'ctra-plus', ratio: 1.5, interval: [1.2, 1.8], runs: 30 };
const TOTALS = { packetsSent: 7, packetsReceived: 5, deliveryRatio: 5 / 7, duplicates: 2, gateways: [] };
vi.mock('../../www/loratrack', () => ({
  compiledModule: () => new Promise(() => {}),
  stationsOf: (model: string) => model.split(','),
  // The core's split (its own tests: split_stations) stands in as the one it makes for the
  // paper's three on two workers, and round robin otherwise.
  splitStations: (model: string, workers: number) => {
    if (model === 'dr,ctra-plus,3d-ctra' && workers === 2) return [['dr', 'ctra-plus'], ['3d-ctra']];
    const stations = model.split(',');
    return Array.from({ length: Math.min(workers, stations.length) }, (_, w) => stations.filter((_, k) => k % workers === w));
  },
  poolDelivery: (results: unknown[]) => (core.pooled.push(results), TOTALS),
  versusLowest: (results: { model: string }[]) => (core.paired.push(results), results.map((r) => (r.model === 'ctra-plus' ? null : VERSUS))),
}));
class StandIn {
  static all: StandIn[] = [];
  sent: SimulateRequest[] = [];
  terminated = false;
  onmessage?: (e: { data: Response }) => void;
  constructor() {
    StandIn.all.push(this);
  }
  postMessage(m: SimulateRequest) {
    this.sent.push(m);
  }
  terminate() {
    this.terminated = true;
  }
  /** Answers the last request it was sent with a report of its stations. */
  answer() {
    const last = this.sent.at(-1)!;
    const stations = String(last.params.model).split(',');
    this.onmessage?.({ data: { id: last.id, report: report(stations.map((m) => result(m, 10, 10))), millis: 1 } });
  }
}
vi.stubGlobal('Worker', StandIn);

const gateway = (heard: number) => ({ east: 1000, north: 0, height: 15, heard, onlyHeard: heard, downlinksSent: 0, downlinksDropped: 0 });
const result = (model: string, sent: number, received: number) => ({ model, packetsSent: sent, packetsReceived: received, duplicates: 1, gateways: [gateway(received)] });
const report = (results: ReturnType<typeof result>[]) =>
  ({ config: { model: 'x', models: results.map((r) => r.model) }, packetsSent: 0, packetsReceived: 0, deliveryRatio: 0, duplicates: 0, gateways: [gateway(0)], results, series: { flight: 'f', models: results.map((r) => ({ model: r.model })) } }) as unknown as SimReport;

test('merged stations come in the request order, with the totals the core pools from every station', () => {
  const a = report([result('dr', 28, 28), result('3d-ctra', 26, 20)]);
  const b = report([result('ctra-plus', 26, 25)]);
  core.pooled = [];
  core.paired = [];
  const m = merge([a, b], ['dr', 'ctra-plus', '3d-ctra'], 'all');
  expect(m.results.map((r) => r.model)).toEqual(['dr', 'ctra-plus', '3d-ctra']);
  expect(m.series?.models.map((s) => s.model)).toEqual(['dr', 'ctra-plus', '3d-ctra']);
  // Every station's own run, once each, and not a worker's partial totals.
  expect(core.pooled).toEqual([m.results]);
  // Every station against the lowest of all, not of its worker's group: paired by the core once,
  // over every station.
  expect(core.paired.map((rs) => rs.map((r) => (r as { model: string }).model))).toEqual([['dr', 'ctra-plus', '3d-ctra']]);
  expect(m.results.map((r) => r.p75VsLowest)).toEqual([VERSUS, null, VERSUS]);
  expect(m).toMatchObject(TOTALS);
  expect(m.config.model).toBe('all');
  expect(m.config.models).toEqual(['dr', 'ctra-plus', '3d-ctra']);
});

test('the mission plan is kept whichever worker ran the mission station', () => {
  const a = report([result('3d-ctra', 26, 26)]);
  const b = report([result('mission', 26, 26)]);
  const plan = [[0, 0, 10], [100, 0, 10]] as [number, number, number][];
  (b.series as { plan?: typeof plan }).plan = plan;
  expect(merge([a, b], ['3d-ctra', 'mission'], '3d-ctra,mission').series?.plan).toEqual(plan);
  expect(merge([a], ['3d-ctra'], '3d-ctra').series?.plan).toBeUndefined();
  // And the vehicle it is followed as, which the group without it has none of.
  Object.assign(a.config, { planCornering: null, vehicle: 'auto' });
  Object.assign(b.config, { planCornering: 'fixed-wing', vehicle: 'fixed-wing' });
  const { planCornering, vehicle } = merge([a, b], ['3d-ctra', 'mission'], '3d-ctra,mission').config;
  expect([planCornering, vehicle]).toEqual(['fixed-wing', 'fixed-wing']);
});

test('a worker whose stations read no plan beside an uploaded flight is sent none, as the core refuses it there', () => {
  StandIn.all = [];
  const pool = new SimulationPool(2);
  const beside = { trajectoryName: 'log.csv', plan: '0,0,10\n100,0,10\n', planName: 'route.csv', vehicle: 'fixed-wing' as const };
  pool.run({ id: 5, params: { ...beside, model: '3d-ctra,mission' } }, () => {});
  const sent = (m: SimulateRequest) => [m.params.model, m.params.plan !== undefined, m.params.planName !== undefined, m.params.vehicle];
  expect(StandIn.all.map((w) => w.sent.map(sent))).toEqual([[['3d-ctra', false, false, undefined]], [['mission', true, true, 'fixed-wing']]]);
  // A bounded station reads the vehicle (left to the plan, the plan's): both are sent them.
  StandIn.all = [];
  new SimulationPool(2).run({ id: 6, params: { ...beside, vehicle: 'auto', model: '3d-ctra,mission', prediction: 'bounded' } }, () => {});
  expect(StandIn.all.map((w) => w.sent.map((m) => m.params.plan !== undefined))).toEqual([[true], [true]]);
});

const request = (id: number, distance: number): SimulateRequest => ({ id, params: { model: 'dr,ctra-plus', distance } });

test('each worker is sent the group of stations the core split for it, and the merged report keeps the request order', () => {
  StandIn.all = [];
  const pool = new SimulationPool(2);
  const answers: Response[] = [];
  pool.run({ id: 4, params: { model: 'dr,ctra-plus,3d-ctra', distance: 1000 } }, (r) => answers.push(r));
  expect(StandIn.all.map((w) => w.sent.map((m) => m.params.model))).toEqual([['dr,ctra-plus'], ['3d-ctra']]);
  // The lone 3D-CTRA answers first: the report waits for both.
  StandIn.all[1].answer();
  expect(answers).toEqual([]);
  StandIn.all[0].answer();
  expect(answers.map((r) => 'report' in r && r.report.results.map((m) => m.model))).toEqual([['dr', 'ctra-plus', '3d-ctra']]);
});

test('a run asked for with the settings of the run started early takes it over, answers so far included', () => {
  StandIn.all = [];
  const pool = new SimulationPool(2);
  pool.start(request(0, 1000));
  StandIn.all.forEach((w) => w.answer());
  const answers: Response[] = [];
  pool.run(request(7, 1000), (r) => answers.push(r));
  // Nothing is asked again, and the merged report comes under the new run's id.
  expect(StandIn.all.map((w) => w.sent.length)).toEqual([1, 1]);
  expect(StandIn.all.some((w) => w.terminated)).toBe(false);
  expect(answers.map((r) => r.id)).toEqual([7]);
  expect('report' in answers[0] && answers[0].report.results.map((r) => r.model)).toEqual(['dr', 'ctra-plus']);
});

test('answers of the early run that come after the takeover reach the new run', () => {
  StandIn.all = [];
  const pool = new SimulationPool(2);
  pool.start(request(0, 1000));
  StandIn.all[0].answer();
  const answers: Response[] = [];
  pool.run(request(3, 1000), (r) => answers.push(r));
  expect(answers).toEqual([]);
  StandIn.all[1].answer();
  expect(answers.map((r) => r.id)).toEqual([3]);
});

test('a run asked for with other settings stops the early run by its stop URL and runs on the same workers', () => {
  StandIn.all = [];
  const revoked = vi.spyOn(URL, 'revokeObjectURL');
  const pool = new SimulationPool(2);
  pool.start(request(0, 1000));
  const answers: Response[] = [];
  pool.run(request(1, 3000), (r) => answers.push(r));
  // The workers keep their caches: none is terminated or added, each is sent the new run after
  // the early one, under another stop URL, and the early one's is revoked.
  expect(StandIn.all.length).toBe(2);
  expect(StandIn.all.some((w) => w.terminated)).toBe(false);
  expect(StandIn.all.map((w) => w.sent.map((m) => m.params.distance))).toEqual([[1000, 3000], [1000, 3000]]);
  const [early, now] = StandIn.all[0].sent.map((m) => m.stop);
  expect(early && now && early !== now).toBe(true);
  expect(revoked).toHaveBeenCalledWith(early);
  expect(revoked).not.toHaveBeenCalledWith(now);
  // The stopped run's refusal, which comes first, is dropped; the new run's report arrives.
  for (const w of StandIn.all) w.onmessage?.({ data: { id: w.sent[0].id, error: 'the run was stopped by its progress callback' } });
  expect(answers).toEqual([]);
  StandIn.all.forEach((w) => w.answer());
  expect(answers.map((r) => r.id)).toEqual([1]);
  revoked.mockRestore();
});

test("an uploaded file's reading goes on through a change of settings and stops once another file or none is asked for", () => {
  StandIn.all = [];
  const revoked = vi.spyOn(URL, 'revokeObjectURL');
  const pool = new SimulationPool(2);
  const [first, second] = [new Blob(['t,x,y,z\n']), new Blob(['t,x,y,z\n'])];
  const upload = (id: number, file: Blob | undefined, distance: number) => {
    pool.interrupt();
    pool.run({ ...request(id, distance), trajectoryFile: file }, () => {});
    return StandIn.all.map((w) => w.sent.at(-1)!);
  };
  const sent = upload(1, first, 1000);
  const reading = sent[0].readStop;
  expect(reading && sent.every((m) => m.readStop === reading && m.stop !== reading)).toBe(true);
  // Another distance, the same file: the run is stopped, its reading (the workers' cache) is not.
  const moved = upload(2, first, 3000);
  expect(revoked).toHaveBeenCalledWith(sent[0].stop);
  expect(revoked).not.toHaveBeenCalledWith(reading);
  expect(moved.every((m) => m.readStop === reading)).toBe(true);
  // Another file: the first one's reading is stopped, the second read under a URL of its own.
  const other = upload(3, second, 3000);
  expect(revoked).toHaveBeenCalledWith(reading);
  const otherReading = other[0].readStop;
  expect(otherReading && otherReading !== reading).toBe(true);
  // No file (a synthetic flight): nothing is read, and the second file's reading is stopped.
  const none = upload(4, undefined, 3000);
  expect(revoked).toHaveBeenCalledWith(otherReading);
  expect(none.every((m) => m.readStop === undefined)).toBe(true);
  revoked.mockRestore();
});

test('a refusal reaches the page once, with the setting the core named', () => {
  StandIn.all = [];
  const pool = new SimulationPool(2);
  const answers: Response[] = [];
  pool.run(request(3, 1000), (r) => answers.push(r));
  for (const w of StandIn.all) {
    const id = w.sent.at(-1)!.id;
    w.onmessage?.({ data: { id, error: 'maxInterval must be at least …', setting: 'maxInterval' } });
  }
  expect(answers).toEqual([{ id: 3, error: 'maxInterval must be at least …', setting: 'maxInterval' }]);
});

test('swarms are shared out largest first, each to the worker with the fewest drones so far', () => {
  expect(shareOut([2, 25, 50, 100, 200], 2)).toEqual([[4], [3, 2, 1, 0]]);
  expect(shareOut([2, 3, 5, 10, 20], 3)).toEqual([[4], [3], [2, 1, 0]]);
  expect(shareOut([2, 6], 8)).toEqual([[1], [0]]);
  expect(shareOut([2, 6, 12], 1)).toEqual([[2, 1, 0]]);
});

test('swarms run on several workers come back in the order asked for, with progress over all their drones', async () => {
  StandIn.all = [];
  const progress: number[] = [];
  const run = runSwarms([2, 25, 50, 100, 200], { model: '3d-ctra' }, (p) => progress.push(p), 2);
  const [big, rest] = StandIn.all.slice(-2) as unknown as { sent: { swarm: { sizes: number[] } }[]; onmessage: (e: { data: unknown }) => void; terminated: boolean }[];
  expect(big.sent[0].swarm.sizes).toEqual([200]);
  expect(rest.sent[0].swarm.sizes).toEqual([100, 50, 25, 2]);
  big.onmessage({ data: { id: 1, progress: 0.5 } });
  rest.onmessage({ data: { id: 1, progress: 1 } });
  // 100 of the 200 drones and all 177 of the rest, of 377.
  expect(progress.at(-1)).toBeCloseTo(277 / 377);
  const swarm = (drones: number) => ({ config: { drones } });
  rest.onmessage({ data: { id: 1, swarms: [100, 50, 25, 2].map(swarm) } });
  big.onmessage({ data: { id: 1, swarms: [swarm(200)] } });
  const { swarms } = await run.done;
  expect(swarms.map((s) => s.config.drones)).toEqual([2, 25, 50, 100, 200]);
  expect(big.terminated && rest.terminated).toBe(true);
});

test('a swarm that fails stops every worker of the run and says why', async () => {
  StandIn.all = [];
  const run = runSwarms([2, 20], { model: '3d-ctra' }, () => {}, 2);
  const workers = StandIn.all.slice(-2) as unknown as { onmessage: (e: { data: unknown }) => void; terminated: boolean }[];
  workers[1].onmessage({ data: { id: 1, error: 'drones: at most 500' } });
  await expect(run.done).rejects.toThrow('drones: at most 500');
  expect(workers.every((w) => w.terminated)).toBe(true);
});

test('a swarm run stopped revokes the stop URL its workers were sent before terminating them; one that ends revokes it too', async () => {
  const revoked = vi.spyOn(URL, 'revokeObjectURL');
  type SwarmWorker = { sent: { stop?: string }[]; onmessage: ((e: { data: unknown }) => void) | null; terminated: boolean };
  StandIn.all = [];
  const stopped = runSwarms([2, 20], { model: '3d-ctra' }, () => {}, 2);
  const workers = StandIn.all.slice(-2) as unknown as SwarmWorker[];
  const url = workers[0].sent[0].stop;
  expect(url && workers.every((w) => w.sent[0].stop === url)).toBe(true);
  expect(revoked).not.toHaveBeenCalledWith(url);
  stopped.stop();
  // Revoked, so a worker busy in the core stops at its next check, and terminated; answers after
  // that are not listened to.
  expect(revoked).toHaveBeenCalledWith(url);
  expect(workers.every((w) => w.terminated && w.onmessage === null)).toBe(true);

  StandIn.all = [];
  const run = runSwarms([2], { model: '3d-ctra' }, () => {}, 1);
  const [only] = StandIn.all as unknown as SwarmWorker[];
  const own = only.sent[0].stop;
  expect(own && own !== url).toBe(true);
  only.onmessage?.({ data: { id: 1, swarms: [{ config: { drones: 2 } }] } });
  await run.done;
  expect(revoked).toHaveBeenCalledWith(own);
  revoked.mockRestore();
});

test('a sweep point some of whose stations the core refused keeps those that ran, in order, with the refusal', () => {
  const a = report([result('dr', 28, 28)]);
  const point = { sf: 10 };
  const m = mergeSweepPoint(point, [{ point, report: a, error: 'over the dwell time' }, { point, error: 'over the dwell time' }], ['dr', 'ctra-plus', '3d-ctra'], 'all');
  expect(m.report?.results.map((r) => r.model)).toEqual(['dr']);
  expect(m.report?.config.models).toEqual(['dr']);
  expect(m.error).toBe('over the dwell time');
  // None ran: the refusal alone; all ran: the report alone.
  expect(mergeSweepPoint(point, [{ point, error: 'no data rate' }], ['dr'], 'dr')).toEqual({ point, error: 'no data rate' });
  expect(mergeSweepPoint(point, [{ point, report: a }], ['dr'], 'dr').error).toBeUndefined();
  // The setting a refusal names comes with it, for the page to give its label.
  expect(mergeSweepPoint(point, [{ point, report: a }, { point, error: 'heartbeat too short', setting: 'maxInterval' }], ['dr', '3d-ctra'], 'all').setting).toBe('maxInterval');
  // And the value of it that fits, for the SF chart's button.
  const fits = mergeSweepPoint(point, [{ point, report: a }, { point, error: 'heartbeat too short', setting: 'maxInterval', valueThatFits: 74.2 }], ['dr', '3d-ctra'], 'all');
  expect([fits.setting, fits.valueThatFits]).toEqual(['maxInterval', 74.2]);
});
