// What a model choice's stations read, known without the core (the form consults it before the
// core has loaded, and the pool and workers for each part of a run they split): the tilt decay,
// the mission plan. Each rule mirrors the core's refusal of a setting no station reads.
import type { ModelChoice, SimulateParams } from './loratrack';

/** Whether a model choice runs a station that decays the tilt rate by `eta`: 3D-CTRA, and the
 * IMM and mission stations, which run it (the core's `StationModel::sent_model`; it refuses
 * `eta` changed for the others). */
export function decaysTilt(model: ModelChoice): boolean {
  return named(model).some((m) => ['all', '3d-ctra', 'imm', 'mission'].includes(m));
}

/** `params` without their mission plan where the run would not read it, as the core decides
 * (`check_plan_read`, src/sim/scenario/mod.rs), which refuses it there: beside a logged flight (a
 * CSV or the real flight) the mission station follows it, and over a CSV log a bounded station
 * with the vehicle left to the plan reads its vehicle (a plane's top speed). A plan alone is the
 * flight. For the form's request and for each part of it a worker runs alone (a group of its
 * stations, one station of a sweep's point). */
export function withoutUnreadPlan(params: SimulateParams): SimulateParams {
  const csv = params.trajectory !== undefined || params.trajectoryName !== undefined;
  const logged = csv || params.sample !== undefined;
  const reads = !logged || runsMission(params.model ?? 'all') || (csv && params.prediction === 'bounded' && (params.vehicle ?? 'auto') === 'auto');
  if (params.plan === undefined || reads) return params;
  const { plan: _plan, planName: _name, ...read } = params;
  return read;
}

/** Whether a model choice runs the mission station. */
export function runsMission(model: ModelChoice): boolean {
  return named(model).includes('mission');
}

/** The names a model choice lists, as given (`all` unexpanded): read without the core, which the
 * form consults before it has loaded. */
function named(model: ModelChoice): string[] {
  return Array.isArray(model) ? model : model.split(',');
}
