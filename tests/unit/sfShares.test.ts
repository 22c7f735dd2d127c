// With ADR a swarm's drones do not stay on the SF they start at: the note says where the packets went.
import { expect, test } from 'vitest';
import { sfShares } from '../../www/charts/swarm';

/** A drone that sent `sent[k]` packets at SF 7 + k (at 125 kHz; SF7 also at 250 kHz when given twice). */
const drone = (sent: number[]) =>
  ({ dataRateUse: sent.flatMap((packets, k) => (packets > 0 ? [{ dr: 5 - k, sf: 7 + k, bw: 125, packets, received: packets, timeOnAir: 0.1 }] : [])) }) as unknown as Parameters<typeof sfShares>[0]['drones'][number];

test('the packets are counted by the SF they went at, over every drone, SFs without any left out', () => {
  const shares = sfShares({ drones: [drone([6, 3, 0, 0, 0, 0]), drone([0, 0, 1, 0, 0, 0])] });
  expect(shares).toBe('SF7 60 %, SF8 30 %, SF9 10 %');
});

test('a share that rounds to nothing still shows that packets went there', () => {
  expect(sfShares({ drones: [drone([999, 0, 0, 1, 0, 0])] })).toBe('SF7 100 %, SF10 <1 %');
});

test('SF7 at both bandwidths counts as one SF: their frames meet', () => {
  const both = { dataRateUse: [{ dr: 5, sf: 7, bw: 125, packets: 3, received: 3, timeOnAir: 0.06 }, { dr: 6, sf: 7, bw: 250, packets: 1, received: 1, timeOnAir: 0.03 }] } as unknown as Parameters<typeof sfShares>[0]['drones'][number];
  expect(sfShares({ drones: [both, drone([0, 4])] })).toBe('SF7 50 %, SF8 50 %');
});

test('a swarm that stayed on one SF says so', () => {
  expect(sfShares({ drones: [drone([0, 0, 0, 0, 0, 4]), drone([0, 0, 0, 0, 0, 2])] })).toBe('SF12 100 %');
});

test('a half per cent rounds up, as the CLI rounds it (`share_words`): 1 packet of 8 is 13 %', () => {
  expect(sfShares({ drones: [drone([1, 7, 0, 0, 0, 0])] })).toBe('SF7 13 %, SF8 88 %');
});
