// The worker pool splits a run by station and merges the reports: the merged report must be what
// one worker (or the CLI) reports for all stations at once.
import { expect, test } from 'vitest';
import { merge } from '../../www/pool';
import type { SimReport } from '../../www/loratrack';

const gateway = (heard: number) => ({ east: 1000, north: 0, height: 15, heard, onlyHeard: heard, downlinksSent: 0, downlinksDropped: 0 });
const result = (model: string, sent: number, received: number) => ({ model, packetsSent: sent, packetsReceived: received, duplicates: 1, gateways: [gateway(received)] });
const report = (results: ReturnType<typeof result>[]) =>
  ({ config: { model: 'x', models: results.map((r) => r.model) }, packetsSent: 0, packetsReceived: 0, deliveryRatio: 0, duplicates: 0, gateways: [gateway(0)], results, series: { flight: 'f', models: results.map((r) => ({ model: r.model })) } }) as unknown as SimReport;

test('merged stations come in the request order and the network totals add up every station', () => {
  const a = report([result('dr', 28, 28), result('3d-ctra', 26, 20)]);
  const b = report([result('ctra-plus', 26, 25)]);
  const m = merge([a, b], ['dr', 'ctra-plus', '3d-ctra'], 'all');
  expect(m.results.map((r) => r.model)).toEqual(['dr', 'ctra-plus', '3d-ctra']);
  expect(m.series?.models.map((s) => s.model)).toEqual(['dr', 'ctra-plus', '3d-ctra']);
  expect(m.packetsSent).toBe(80);
  expect(m.packetsReceived).toBe(73);
  expect(m.deliveryRatio).toBeCloseTo(73 / 80, 12);
  expect(m.duplicates).toBe(3);
  expect(m.gateways[0].heard).toBe(73);
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
});
