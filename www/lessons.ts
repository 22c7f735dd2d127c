// Guided scenarios for teaching: each is a URL state (the settings, sometimes a pinned baseline
// or a swarm to run), a few sentences, and what to notice. The end-to-end suite checks that each
// lesson's claim shows in the numbers it loads, so a lesson cannot start teaching the opposite.
import { toQuery, DEFAULTS, type Settings } from './state';

export interface Lesson {
  id: string;
  title: string;
  /** The settings the lesson opens with (the rest at their defaults). */
  settings: Partial<Settings>;
  /** Settings to pin as the baseline, when the lesson is a comparison. */
  baseline?: Partial<Settings>;
  /** A swarm to run in the swarm panel: largest size, channels, SF plan. */
  swarm?: { drones: number; channels: number; plan: 'fixed' | 'spread' };
  /** Two or three sentences: the idea. */
  text: string;
  /** What to look at, and what it should show. */
  notice: string[];
}

export const LESSONS: Lesson[] = [
  {
    id: 'why-not-sf12',
    title: 'Why not always SF12?',
    settings: { sf: 12, bw: 125, flight: 'all' },
    text: 'SF12 reaches furthest, so why not always use it? Each SF step about doubles the time on air, and the 1 % duty cycle makes the drone wait 100 times that between packets: at SF12 a 12-byte state goes out every two and a half minutes.',
    notice: [
      'The interval column: about 148 s at SF12 and 125 kHz, against 3 s at the paper’s SF7 and 250 kHz.',
      'The error-versus-SF chart: at 1 km every model’s p75 rises with the SF; SF12’s is many times SF7’s.',
      'The note under the table: the errors cover only part of each flight, because a flight is untracked until its first packet, which at SF12 comes late in the flight or not at all (packets 148 s apart, flights of 88 s on average): SF12 is worse than its p75 says.',
    ],
  },
  {
    id: 'duty-cycle-wall',
    title: 'The duty-cycle wall',
    settings: { sf: 10, bw: 125 },
    text: 'In the EU868 band a device may be on air 1 % of the time. Whatever the link could carry, the next packet waits until the last one’s time on air has been paid for 99 times over. The 1 % holds per sub-band: a drone that alternates two, as The Things Network’s eight channels allow, waits half as long.',
    notice: [
      'The interval is exactly 100 times the time on air, for every model.',
      'The time-on-air table: the second number in each cell is that interval.',
      'Set Duty cycle to 0.02 (two sub-bands alternated): every interval halves, to 50 times the time on air, and twice the packets arrive.',
    ],
  },
  {
    id: 'eu868-vs-us915',
    title: 'The same drone in Europe and in the US',
    settings: { region: 'us915', sf: 9, bw: 125, flight: 'all' },
    baseline: { sf: 9, bw: 125, flight: 'all' },
    text: 'Europe’s 868 MHz band limits each device to 1 % of the time on air; the US 915 MHz band has no duty cycle, only a 400 ms limit on each packet (and hopping over 8 channels). At SF9 (US915’s DR1) the drone that waits 21 s between packets in Europe may send every second, Remote ID’s rate.',
    notice: [
      'The interval column: 1 s here, against about 21 s in the pinned EU868 baseline.',
      'Every model’s p75 falls far below the baseline’s (▼): the station rarely has to predict for long.',
      'The time-on-air table speaks US915: SF11 and SF12 are not in it, and SF10’s 12-byte frame is refused (over 400 ms on air), so the form offers SF10 to DR and CTRA+ alone.',
    ],
  },
  {
    id: 'which-model',
    title: 'Which motion model when',
    settings: { flight: 'all' },
    text: 'Between packets the station predicts. Dead reckoning (DR) flies straight on; CTRA+ also turns and accelerates; 3D-CTRA also tilts. Over the whole synthetic set, with packets every 3 s, the richer models pay off.',
    notice: [
      'DR’s p75 interval lies wholly above CTRA+’s and 3D-CTRA’s: a clear difference.',
      'CTRA+’s and 3D-CTRA’s intervals overlap, yet the verdict names CTRA+ clearly lowest: on the same runs resampled together 3D-CTRA’s p75 is about 1.06× CTRA+’s, and every resample agrees within a few per cent. Each model’s own interval carries the spread all models share (a hard flight is hard for every model); the verdict compares them run by run. Our synthetic climbs are short, so the tilt rate rarely pays off.',
    ],
  },
  {
    id: 'imm-lets-the-packets-choose',
    title: 'Let the packets choose the model',
    settings: { sf: 8, flight: 'all', model: 'dr,ctra-plus,3d-ctra,imm', prediction: 'bounded' },
    text: 'No motion model is best all the time: dead reckoning while the drone flies straight, CTRA+ and 3D-CTRA while it turns or speeds up. The IMM station runs all three between packets and weighs them at every packet, by how well each forecast that packet and by the acceleration and turn rate the packet itself reports.',
    notice: [
      'The results table: at SF8, with a packet about every 5 s, IMM’s p75 and p95 are the lowest of the four stations (it receives 3D-CTRA’s 12-byte packets).',
      'The tooltip of IMM’s “in 95 % region” cell: its mean probabilities, about a third each: straight legs and turns share each flight.',
      'IMM’s p75 interval overlaps CTRA+’s and 3D-CTRA’s, yet the verdict names IMM clearly lowest: on the same runs resampled together their p75 is about 1.07× IMM’s, an interval wholly above 1.',
    ],
  },
  {
    id: 'range-paper-vs-bounded',
    title: 'Losing packets at range: the paper’s station against a bounded one',
    settings: { flight: 'all', distance: 3000, model: '3d-ctra', prediction: 'bounded' },
    baseline: { flight: 'all', distance: 3000, model: '3d-ctra', prediction: 'paper' },
    text: 'At 3 km and SF7 a fifth of the packets are lost. The paper’s station keeps accelerating and turning through every gap; the bounded one holds the speed in 0–20 m/s, lets an acceleration fade within seconds (as a multicopter’s does) and a turn once a packet is overdue.',
    notice: [
      'The pinned baseline is the paper’s station: the bounded one’s mean and p95 errors are far lower (▼).',
      'The delivery column: the same packets arrive for both.',
      'Error over time: the band is the station’s own 95 % bound. Each lost packet widens it, far past the error itself; where it runs off the chart, its peak is written at the top.',
    ],
  },
  {
    id: 'swarms-share-the-air',
    title: 'Swarms share the air',
    settings: {},
    swarm: { drones: 50, channels: 1, plan: 'fixed' },
    text: 'Every drone sends on its own schedule. Two packets on the same channel and SF that overlap in time collide, unless one is much stronger: the more drones, the more collisions.',
    notice: ['The swarm panel: the collision rate climbs as the swarm grows from 2 to 50 drones on one channel.', 'The dashed line is the pure-ALOHA formula.'],
  },
  {
    id: 'crowd-sends-less',
    title: 'In a crowd, send less',
    settings: { bw: 125, prediction: 'bounded', sender: 'error', threshold: 20, maxInterval: 60, dutyCycleMode: 'budget', channelSense: 'off' },
    swarm: { drones: 72, channels: 1, plan: 'fixed' },
    text: 'With 72 drones on one SF7 channel most packets collide. An error-triggered drone with the default 2 m threshold that does not listen to its channel finds its station that far off at nearly every chance to send, so it sends like a periodic one. With a threshold on the scale of the errors such a crowd allows (20 m, a heartbeat of 60 s and a duty-cycle budget) each drone sends when its station has drifted, the channel clears, and more of what is sent arrives. The lesson’s drones do not listen (Channel sensing off), so the threshold is the one set: listening, the default, raises a small threshold by itself where the channel is busy, and one already on the crowd’s scale too far.',
    notice: [
      'The note under the swarm charts: with 72 drones about half the packets are delivered, and the median drone’s p75 is under 40 m.',
      'Set Sending to Periodic and the duty-cycle rule to Off-time per packet (the paper’s drone) and run the swarm again: every drone sends as often as the duty cycle allows, about a third of the packets are delivered, and the median drone’s p75 is just over 40 m.',
      'Over 8 seeds of 300 s each (docs/swarm.md): 0.78× periodic sending’s p75 on 0.62 of its airtime.',
      'Raise the threshold to 40 m: the drones use about a third of periodic sending’s airtime, their p75 stays below it (0.86×), and against periodic sending slowed to the same airtime the p95 is 0.85× (docs/swarm.md, 8 seeds): no better than at 20 m, where the p95 is 0.78×.',
    ],
  },
  {
    id: 'adr-chases-the-link',
    title: 'ADR chases the link',
    settings: { sf: 12, bw: 125, adr: 'tracking', flight: 'all' },
    baseline: { sf: 12, bw: 125, adr: 'off', flight: 'all' },
    text: 'Starting at SF12, adaptive data rate lets the network move the drone to a faster data rate when the link allows. At 1 km it does: packets go out far more often and the error falls.',
    notice: ['Packets per data rate (below the table): after the first few, they go out at DR5 or DR6.', 'Against the pinned fixed-SF12 baseline every model’s p75 falls (▼) and far more packets arrive (▲).'],
  },
  {
    id: 'lean-payloads',
    title: 'Three bytes at SF10: send only the manoeuvres that matter',
    settings: { sf: 10, bw: 125, flight: 'all', model: 'dr,ctra-plus,3d-ctra,imm', prediction: 'bounded', payload: 'lean' },
    baseline: { sf: 10, bw: 125, flight: 'all', model: 'dr,ctra-plus,3d-ctra,imm', prediction: 'bounded', payload: 'full' },
    text: 'A LoRa frame grows in blocks of symbols, and at SF10 one block is seconds of duty-cycle silence. With LoRaWAN’s 13 bytes of overhead, 3D-CTRA’s 12-byte state needs one block more than CTRA+’s 11 bytes or DR’s 9, so its packets come less often. A lean payload leaves out the acceleration, turn rate or climb rate while each is near zero, and the next packet comes sooner.',
    notice: [
      'Against the pinned baseline, which sends full payloads: 3D-CTRA and IMM send more packets (▲) and their p75 falls (▼); DR and CTRA+, whose frames are already as short as a lean one, are unchanged.',
      'The payload column counts the packets that went lean; its tooltip says what the interval and time-on-air cells rest on.',
      'On the whole synthetic set over 16 seeds this brings the IMM within 2 % of the best single model at SF10 and SF11; on the real flight it helps at some rates and costs at others (docs/beyond-the-paper.md).',
    ],
  },
  {
    id: 'payload-ranges',
    title: 'What 12 bytes cannot say',
    settings: { flight: 'canberra', seeds: 8 },
    text: 'The paper packs a drone’s state into 9 to 12 bytes by giving each field a quadcopter’s range: speed 0–25.5 m/s, acceleration ±6.35 m/s², turn and tilt rates ±2 rad/s, positions within 6.5 km of the start. A value beyond its range is sent as the range’s edge. The real Canberra flight ends in ACRO flips that turn faster than 2 rad/s.',
    notice: [
      'The note under the table: some of CTRA+’s and 3D-CTRA’s received packets carried a turn or tilt rate beyond ±2 rad/s, sent as 2 rad/s; DR’s payload has no turn rate, and none of its packets saturate.',
      'They are a few in a hundred, and not what separates the models here: a bounded station that read them as zero moved the worst richer station’s p95 against DR’s by under 0.01 at every data rate (64 seeds; docs/beyond-the-paper.md).',
      'A flight of your own faster than 25.5 m/s, or further than 6.5 km from its start, shows the same note for every packet it sends out there: upload one under Trajectory.',
    ],
  },
  {
    id: 'flight-plan',
    title: 'A flight plan beats any motion model when packets are scarce',
    settings: { sf: 11, bw: 125, flight: 'all', model: 'dr,ctra-plus,3d-ctra,imm,mission', prediction: 'bounded' },
    text: 'At SF11 a 12-byte state goes out every 82 s. Between packets a motion model can only extrapolate the last manoeuvre, and 82 s are many manoeuvres. A drone flying a mission has a plan; a station that knows it flies the plan from each packet on.',
    notice: [
      'The results table: Mission’s p75 is a fraction of every other station’s, and its 95 % interval lies below theirs.',
      'The error-over-time chart: the motion models’ error grows through every gap between packets; Mission’s stays near the flight.',
      'A caveat the page cannot show: each synthetic flight keeps to its own plan within 2 m and on time. A real drone in wind strays further; docs/mission.md says what this rests on.',
    ],
  },
];

/** The settings `lesson` opens with: its own over the defaults. */
export function lessonSettings(lesson: Lesson): Settings {
  return { ...DEFAULTS, ...lesson.settings };
}

/** The settings of the baseline `lesson` pins, its own over the defaults; undefined without one. */
function lessonBaseline(lesson: Lesson): Settings | undefined {
  return lesson.baseline && { ...DEFAULTS, ...lesson.baseline };
}

/** The URL query that opens `lesson`. */
export function lessonQuery(lesson: Lesson): string {
  const extra: Record<string, string> = { lesson: lesson.id };
  const baseline = lessonBaseline(lesson);
  if (baseline) extra.baseline = toQuery(baseline);
  return toQuery(lessonSettings(lesson), extra);
}

/** The keys of `to` whose values are not `from`'s, in the settings' order. */
const changed = (from: Settings, to: Settings) => (Object.keys(DEFAULTS) as (keyof Settings)[]).filter((k) => JSON.stringify(to[k]) !== JSON.stringify(from[k]));

/** The settings in `now` that are not the lesson's, in the settings' order: what the page must name
 * while the lesson's text, which speaks of its own settings, stays on show beside other numbers
 * (a link typed by hand, or a step the lesson asks for). */
export function changedFromLesson(lesson: Lesson, now: Settings): (keyof Settings)[] {
  return changed(lessonSettings(lesson), now);
}

/** Whether the pinned baseline is the lesson's: true for a lesson without one. `pinned` is the
 * baseline's settings, undefined when none is pinned. */
export function baselineIsLessons(lesson: Lesson, pinned: Settings | undefined): boolean {
  const own = lessonBaseline(lesson);
  if (!own) return true;
  return pinned !== undefined && changed(own, pinned).length === 0;
}
