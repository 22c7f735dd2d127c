// With ADR a swarm's drones do not stay on the SF they start at: the note says where the packets
// went, from the core's count of them by SF (`packetsBySf`).
import { expect, test } from 'vitest';
import { sfShares } from '../../www/charts/swarm';

const shares = (packetsBySf: number[]) => sfShares({ packetsBySf });

test('the packets are given as shares of all sent, SFs without any left out', () => {
  expect(shares([6, 3, 1, 0, 0, 0])).toBe('SF7 60 %, SF8 30 %, SF9 10 %');
});

test('a share that rounds to nothing still shows that packets went there', () => {
  expect(shares([999, 0, 0, 1, 0, 0])).toBe('SF7 100 %, SF10 <1 %');
});

test('a swarm that stayed on one SF says so', () => {
  expect(shares([0, 0, 0, 0, 0, 6])).toBe('SF12 100 %');
});

test('a half per cent rounds up, as the CLI rounds it (`share_words`): 1 packet of 8 is 13 %', () => {
  expect(shares([1, 7, 0, 0, 0, 0])).toBe('SF7 13 %, SF8 88 %');
});
