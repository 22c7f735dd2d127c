// The time-on-air table's numbers (the paper's Table II at the settings' overhead, coding rate and
// plan): every SF × bandwidth pair with its data rate in the plan, and for each of the paper's
// payloads its time on air and interval, or why the plan refuses it. The core decides each cell
// (`timeOnAir`); the panel's table and its CSV both read them from here.
import { PAYLOAD_BYTES, PLANS, timeOnAir, type AirtimeParams, type ModelName, type Region } from './loratrack';

export const SFS = [7, 8, 9, 10, 11, 12];
export const BWS = [125, 250, 500];
/** The paper's three stations, whose payloads (9, 11, 12 bytes) are the table's columns. */
export const PAPER_STATIONS = ['dr', 'ctra-plus', '3d-ctra'] as const satisfies readonly ModelName[];

/** The plan's settings the table speaks: region, interval where it has no duty cycle, duty cycle
 * where the drone keeps one, access, fair use. */
export type PlanOpts = Pick<AirtimeParams, 'region' | 'interval' | 'access' | 'fairUse'> & Partial<Pick<AirtimeParams, 'dutyCycle'>>;

/** One payload at one SF and bandwidth. */
export interface AirtimeCell {
  station: (typeof PAPER_STATIONS)[number];
  /** Application payload, bytes (before the overhead). */
  payload: number;
  /** Time on air, s. */
  timeOnAir: number;
  /** The shortest interval between packets under the plan's rule, s; null where it is refused. */
  interval: number | null;
  /** Why the plan refuses the packet; null where it carries it. */
  refused: string | null;
}

/** One SF and bandwidth: its data rate in the plan's words ("DR5", "raw LoRa", "not in US915"). */
export interface AirtimeRow {
  sf: number;
  bw: number;
  dataRate: string;
  cells: AirtimeCell[];
}

const inPlan = (region: Region, sf: number, bw: number) => PLANS.some((p) => p.region === region && p.rates.some((r) => r.sf === sf && r.bw === bw));
const rawLora = (region: Region) => PLANS.some((p) => p.region === region && p.rawLora);

/** Every row of the table at `opts` (overhead, coding rate and plan), SF by SF, bandwidth by bandwidth. */
export function airtimeRows(opts: { overhead: number; cr: number } & PlanOpts): AirtimeRow[] {
  const plan = { region: opts.region, interval: opts.interval, dutyCycle: opts.dutyCycle, access: opts.access, fairUse: opts.fairUse };
  return SFS.flatMap((sf) =>
    BWS.map((bw) => {
      const cells = PAPER_STATIONS.map((station) => {
        const payload = PAYLOAD_BYTES[station];
        const r = timeOnAir({ sf, bw, payload, overhead: opts.overhead, cr: opts.cr, ...plan });
        return { station, payload, timeOnAir: r.timeOnAir, interval: r.refused ? null : r.minInterval, refused: r.refused, dataRate: r.dataRate };
      });
      const dr = cells[0].dataRate;
      const dataRate = dr !== null ? `DR${dr}` : inPlan(opts.region, sf, bw) || rawLora(opts.region) ? 'raw LoRa' : `not in ${opts.region.toUpperCase()}`;
      return { sf, bw, dataRate, cells: cells.map(({ dataRate: _, ...cell }) => cell) };
    }),
  );
}
