// Reports of some of a run's stations made one: the pool's workers each run a group of stations,
// and a sweep point some stations of which the core refuses runs the others alone (worker.ts).
import { poolDelivery, versusLowest, type SimReport } from './loratrack';
import type { SweepPoint, SweepResult } from './worker';

/** The reports of disjoint groups of stations as one report, stations in `models` order (those
 * that ran: a sweep point may lack some), with the network totals the core pools from every
 * station's run (`poolDelivery`) and every station against the lowest of them all
 * (`versusLowest`: a worker compared its own stations only). */
export function merge(reports: SimReport[], models: string[], model: SimReport['config']['model']): SimReport {
  const ran = models.flatMap((m) => reports.flatMap((r) => r.results).filter((x) => x.model === m).slice(0, 1));
  const versus = versusLowest(ran);
  const results = ran.map((r, i) => ({ ...r, p75VsLowest: versus[i] }));
  const base = reports[0];
  // The mission's plan, the vehicle it is followed as and the vehicle set come with whichever
  // group read them (a group that does not is sent none: `withoutUnreadFlightSettings`).
  const plan = reports.map((r) => r.series?.plan).find((p) => p !== undefined);
  const planCornering = reports.map((r) => r.config.planCornering).find((c) => c != null) ?? base.config.planCornering;
  const vehicle = reports.map((r) => r.config.vehicle).find((v) => v !== 'auto') ?? base.config.vehicle;
  const series = base.series && { ...base.series, ...(plan ? { plan } : {}), models: models.flatMap((m) => reports.flatMap((r) => r.series?.models ?? []).filter((s) => s.model === m).slice(0, 1)) };
  return {
    ...base,
    config: { ...base.config, model, models: results.map((r) => r.model), planCornering, vehicle },
    ...poolDelivery(results),
    results,
    ...(series ? { series } : {}),
  };
}

/** One sweep point as the groups of stations ran it: the stations that ran, merged, and the
 * first refusal where the core refused any (`report` without `error`: all ran; `error` alone:
 * none did). */
export function mergeSweepPoint(point: SweepPoint, runs: SweepResult[], models: string[], model: SimReport['config']['model']): SweepResult {
  const reports = runs.flatMap((x) => (x.report ? [x.report] : []));
  return { point, ...(reports.length ? { report: merge(reports, models, model) } : {}), ...firstRefusal(runs) };
}

/** The first of `runs` the core refused, as its error, the setting it names and the value of that
 * setting that fits; `{}` where none was. */
export function firstRefusal(runs: SweepResult[]): Pick<SweepResult, 'error' | 'setting' | 'valueThatFits'> {
  const refused = runs.find((x) => x.error);
  return refused ? { error: refused.error, setting: refused.setting, valueThatFits: refused.valueThatFits } : {};
}
