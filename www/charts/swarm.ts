// Swarms sharing one gateway: the measured collision rate as the swarm grows, beside the pure
// ALOHA formula; and each drone's tracking error (p75) in the largest swarm.
import { chartFrame, chartFont, fitLabel, SF_COLORS, labelRoom } from './colors';
import * as Plot from '@observablehq/plot';
import type { SwarmReport } from '../loratrack';
import { advancedChanged, beyondRange, counted, downlinkCounts, flightTime, planLimit, stationPhrase, trackedPercent } from '../format';
import { DEFAULTS, plan, sendingLimit } from '../state';
import { logAxis, plainNumber } from './logAxis';

/** " (errors over 88 % of the flight time: ...)": said when a swarm's stations spend enough of it
 * waiting for an episode's first packet (the core's `wholeFlight.partlyTracked`). */
function untracked(r: SwarmReport): string {
  return r.wholeFlight.partlyTracked ? ` (errors over ${trackedPercent(r.wholeFlight.tracked)} % of the flight time: before an episode's first packet a station has no estimate)` : '';
}

/** The swarm's SF plan as it dealt the SFs: "all on SF9" (`fixed`), or a `spread` plan's SFs
 * one after another, "SF7–SF12 in turn"; with ADR, where the drones started ("all starting on
 * SF9", "SF7–SF12 in turn at the start"). Where `spread` dealt fewer SFs than it had drones for,
 * it says why (the core's `sfLimit`, which the CLI's header says too): "SF7–SF9 in turn (at
 * 125 kHz US915 carries the frame at no other SF)", "all starting on SF7 (at 250 kHz ADR can
 * start at no other SF)", "SF7–SF11 in turn (at 125 kHz a slower SF’s frame outlasts the 1 s
 * interval set)". The note under the charts and the slide's caption. */
export function sfPlanWords(r: Pick<SwarmReport, 'drones' | 'config' | 'sfLimit'>): string {
  const adr = r.config.adr !== 'off';
  const sfs = r.config.sfPlan === 'spread' ? [...new Set(r.drones.map((d) => d.sf))].sort((a, b) => a - b) : [r.config.sf];
  if (sfs.length < 2) return `all ${adr ? 'starting ' : ''}on SF${sfs[0]}${why(r)}`;
  const run = sfs.every((sf, i) => sf === sfs[0] + i);
  return `${run ? `SF${sfs[0]}–SF${sfs[sfs.length - 1]}` : sfs.map((sf) => `SF${sf}`).join(', ')} in turn${adr ? ' at the start' : ''}${why(r)}`;
}

/** Why a `spread` plan dealt fewer SFs than it had drones for; else nothing. */
function why(r: Pick<SwarmReport, 'config' | 'sfLimit'>): string {
  const at = `at ${r.config.bw} kHz`;
  switch (r.sfLimit) {
    case null:
      return '';
    case 'adr':
      return ` (${at} ADR can start at no other SF)`;
    case 'region':
      return ` (${at} ${plan(r.config.region).label} carries the frame at no other SF)`;
    case 'interval':
      return ` (${at} a slower SF’s frame outlasts the ${r.config.interval ?? DEFAULTS.interval} s interval set)`;
  }
}

/** Where a swarm's packets went, by SF (the core's `packetsBySf`): "SF7 61 %, SF8 30 %, SF9 9 %,
 * SF10 <1 %" (SFs with none left out; halves round up, as the CLI's `share_words` rounds them). */
export function sfShares(r: Pick<SwarmReport, 'packetsBySf'>): string {
  const total = r.packetsBySf.reduce((a, b) => a + b, 0);
  return r.packetsBySf
    .map((n, k) => ({ n, sf: k + 7 }))
    .filter(({ n }) => n > 0)
    .map(({ n, sf }) => `SF${sf} ${(100 * n) / total < 0.5 ? '<1' : ((100 * n) / total).toFixed(0)} %`)
    .join(', ');
}

/** What the strip of p75s leaves out or draws hollow, of a swarm of `total` drones whose `drawn`
 * received a packet (the rest have no p75, so no dot) and `thin` of those too few to compare. */
export function stripCounts(total: number, drawn: number, thin: number): string {
  if (drawn === total) return thin ? `; ${thin} of ${total} drones (hollow) received too few packets for their own p75 to compare` : '';
  return `; ${total - drawn} of ${total} drones received no packet (no dot)${thin ? ` and ${thin} (hollow) too few for their own p75 to compare` : ''}`;
}

/** One drone's point on the strip of p75s. */
type Drone = { p75: number; sf: string; colour: string; received: number; few: boolean; saturated: number };

export function swarmCharts(swarms: SwarmReport[], width: number): HTMLElement {
  // A swarm that sent nothing has no collision share (null): no dot, and its title says why.
  // The charts' side margins, px, as drawn: their log axes run between them. The collision chart
  // keeps Plot's default right margin; the strip needs room for half its last tick label
  // ("10,000" ran past the right edge).
  const margin = { left: labelRoom(50), collisionsRight: 20, stripRight: labelRoom(24) };
  const rates = swarms.map((r) => ({ n: r.config.drones, measured: r.collisionRate === null ? Number.NaN : 100 * r.collisionRate, theory: 100 * r.collisionRateTheory }));
  const collisions = Plot.plot({
    ...chartFrame(220, 360),
    width,
    marginLeft: margin.left,
    marginRight: margin.collisionsRight,
    x: { label: 'drones sharing the gateway', type: 'log', ...logAxis(rates.map((r) => r.n), { px: width - margin.left - margin.collisionsRight, font: chartFont() }), tickFormat: plainNumber },
    y: { label: 'packets collided (%)', grid: true, zero: true },
    marks: [
      Plot.lineY(rates, { x: 'n', y: 'theory', stroke: '#888', strokeDasharray: '4,3' }),
      Plot.dot(rates, { x: 'n', y: 'measured', fill: '#4e79a7', r: 4, title: (d) => `${d.n} drones: ${Number.isNaN(d.measured) ? 'no packet sent' : `${d.measured.toFixed(1)} % collided`} (ALOHA ${d.theory.toFixed(1)} %)` }),
      Plot.text(rates.slice(-1), { x: 'n', y: 'theory', text: () => 'ALOHA', dx: -20, dy: -8, fill: '#666', fontSize: chartFont() }),
    ],
  });
  const largest = swarms[swarms.length - 1];
  // With ADR a drone's SF is where it started: the network moves it (`dataRateUse` says where to).
  const adr = largest.config.adr !== 'off';
  const sfName = (sf: number) => (adr ? `from SF${sf}` : `SF${sf}`);
  const drones = largest.drones.filter((d) => d.error3d.p75 !== null).map((d) => ({ p75: d.error3d.p75 as number, sf: sfName(d.sf), colour: SF_COLORS[d.sf - 7], received: d.packetsReceived, few: d.caveats.fewPackets, saturated: d.caveats.saturatedPackets }));
  // A drone whose p75 rests on too few packets (an SF12 drone's two minutes see one or two) is
  // drawn hollow, as the SF chart's points are, and the note counts them.
  const thin = drones.filter((d) => d.few).length;
  // The strip's axis counts the dots it draws: "of each of 4 of 50 drones" where 46 received nothing.
  const shown = drones.length < largest.drones.length ? `${drones.length} of ${largest.drones.length}` : `${largest.drones.length}`;
  // SF7 first (not SF10, as sorting the names put it), in the SFs' page-wide colours.
  const sfs = [...new Set(largest.drones.map((d) => d.sf))].sort((a, b) => a - b);
  // Each drone a dot piled up from the axis as far as the spread of their p75s needs (dodgeY):
  // the strip is drawn once, then again at the height of its pile. At a fixed height 200 drones
  // on a phone piled 41 px past its top, over the legend (and out of the SVG download), while 50
  // at 1280 px left an empty band as tall as their pile.
  const frame = chartFrame(140, 360);
  const r = (3 * chartFont()) / 13;
  // No axis or label above the dots: the legend is the strip's top edge.
  const marginTop = Math.round(2 * r);
  const strip = (height: number) =>
    Plot.plot({
      ...frame,
      marginTop,
      height,
      width,
      marginLeft: margin.left,
      marginRight: margin.stripRight,
      // Labelling only the powers of ten left a swarm whose p75s lie within one decade (all on SF7:
      // 2–7 m) without a single number on its axis.
      x: { label: fitLabel(width, `p75 error of each of ${shown} drones (m, log scale)`, `p75 of each of ${shown} drones (m, log)`, 'p75 per drone (m, log)'), type: 'log', ...logAxis(drones.map((d) => d.p75), { px: width - margin.left - margin.stripRight, font: chartFont() }), tickFormat: plainNumber },
      y: { axis: null },
      color: { legend: true, domain: sfs.map(sfName), range: sfs.map((sf) => SF_COLORS[sf - 7]) },
      marks: [Plot.dotX(drones, Plot.dodgeY({ x: 'p75', fill: { value: (d: Drone) => (d.few ? 'white' : d.colour), scale: null }, stroke: 'sf', strokeWidth: 1.2, r, title: (d: Drone) => `${d.sf}: p75 ${d.p75.toFixed(2)} m over ${counted(d.received, 'packet')}${d.few ? ', too few to compare' : ''}${d.saturated ? `, ${d.saturated} beyond the payload's range` : ''}` }))],
    });
  const first = strip(frame.height);
  const fitted = marginTop + pileHeight(first, frame.height - frame.marginBottom, 2 * r) + frame.marginBottom;
  const errors = Math.abs(fitted - frame.height) > 2 ? strip(Math.round(fitted)) : first;
  const note = document.createElement('p');
  note.className = 'note';
  // The plan's limit and the advanced settings where not the defaults: the note is all the panel
  // says of what its numbers rest on (the slide's caption names every setting).
  // A chosen flight is flown whole, whatever the duration (which chains synthetic flights).
  const flight = largest.config.sample ? `the real flight (${Math.round(largest.flightTime)} s)` : `${flightTime(largest.config.duration)} of the synthetic set`;
  const flown = `${largest.config.drones} drones flying ${flight} each to a ${stationPhrase(largest.config.station, largest.config)}, ${largest.config.channels ?? 1} channel${(largest.config.channels ?? 1) > 1 ? 's' : ''}, ${sfPlanWords(largest)}${[planLimit(largest.config), ...advancedChanged(largest.config)].filter(Boolean).map((a) => `, ${a}`).join('')}`;
  // Shares of no packet are none: a swarm whose drones all send less often than they fly (SF12,
  // 2 minutes) sent nothing, which "0.0 % of packets collided" and "0.0 % delivered" would hide.
  const { collisionRate, deliveryRatio, energy } = largest;
  note.textContent =
    collisionRate === null || deliveryRatio === null || energy.chargePerUplink === null
      ? `${flown}: no drone sent a packet within its flight, so no station had an estimate.`
      : `${flown}${adr ? `, ADR sent their packets at ${sfShares(largest)}` : ''}: ${(100 * collisionRate).toFixed(1)} % of packets collided (ALOHA predicts ${(100 * largest.collisionRateTheory).toFixed(1)} %)${largest.leanPackets > 0 ? `, ${largest.leanPackets} of ${counted(largest.packetsSent, 'packet')} with lean payloads` : ''}, median per-drone p75 ${largest.medianDroneP75?.toFixed(2) ?? '—'} m${drones.length < largest.drones.length ? ` (of the ${drones.length} that received a packet)` : ''}, p95 pooled over the drones ${largest.error3d.p95?.toFixed(2) ?? '—'} m${untracked(largest)}${stripCounts(largest.drones.length, drones.length, thin)}; ${(100 * deliveryRatio).toFixed(1)} % of packets delivered${largest.gateways.length > 1 ? ` by ${largest.gateways.length} gateways (${counted(largest.duplicates, 'duplicate copy', 'duplicate copies')} removed)` : ''}${adr ? `, ${downlinkCounts(largest.gateways)}${largest.packetsGatewayTransmitting > 0 ? `, ${counted(largest.packetsGatewayTransmitting, 'packet')} lost while the gateway sent them (it cannot listen meanwhile)` : ''}` : ''}; radio ${energy.chargePerUplink.toFixed(2)} mC per uplink (mean over the drones that sent).${largest.frameLength === null ? '' : ` Slotted: longest frame ${largest.frameLength.toFixed(1)} s.`}`;
  const l = largest.largestSwarm;
  note.textContent += ` Largest swarm one gateway serves at these settings${adr ? ' (at the starting SFs)' : ''}${largest.leanPackets > 0 ? ' (with full frames: the lean ones, shorter, leave room for more)' : ''}, every drone sending ${pace(largest.config)}: ${l.aloha1} drone${l.aloha1 === 1 ? '' : 's'} at ≤ 1 % collisions and ${l.aloha10} at ≤ 10 % with ALOHA (by its formula), ${l.slotted} slotted with none.`;
  note.textContent += saturatedWords(largest);
  const box = document.createElement('div');
  box.append(collisions, errors, note);
  return box;
}

/** The drones whose received packets carried a value beyond the payload's range (the core's
 * `saturation`, as the CLI's `saturated:` line says it): a swarm of the real flight saturates
 * the turn and tilt rate in its ACRO end. Nothing where none did. */
function saturatedWords(r: SwarmReport): string {
  const s = r.saturation;
  if (s.drones === 0) return '';
  return ` Saturated: ${s.packets} of the drones' ${counted(r.packetsReceived, 'received packet')}, from ${counted(s.drones, 'drone')}, ${beyondRange(s.fields, true)}`;
}

/** How far above `base` (the plot's bottom, px from the SVG's top) the highest dot of `chart`
 * reaches, its radius included, and at least `least` (a strip with no drone on it): dodgeY piles
 * dots up from the bottom, so their places do not depend on the plot's height. */
function pileHeight(chart: Element, base: number, least: number): number {
  const tops = [...chart.querySelectorAll('circle')].map((c) => Number(c.getAttribute('cy')) - Number(c.getAttribute('r')));
  return Math.max(least, ...tops.filter(Number.isFinite).map((top) => base - top));
}

/** How often each drone of the largest-swarm estimate sends (the core's `LargestSwarm`): as often
 * as its duty cycle (or listen before talk's share of the air) allows, or where the plan has no
 * duty cycle, at the interval set; never more than fair use leaves (as `intervalRule` says of the
 * results' interval). */
function pace(c: SwarmReport['config']): string {
  const p = plan(c.region);
  const rule = {
    interval: `every ${c.interval ?? DEFAULTS.interval} s (the interval set: ${p.label} has no duty cycle)`,
    lbt: "as often as listen before talk's airtime (100 s per hour) allows",
    dutyCycle: 'as often as its duty cycle allows',
  }[sendingLimit(c)];
  return c.fairUse === 'off' ? rule : `${rule}, or less often where ${c.fairUse.toUpperCase()} fair use leaves less airtime`;
}
