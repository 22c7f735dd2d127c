// What a model choice's stations read, known without the core (the form consults it before the
// core has loaded, and the pool and workers for each part of a run they split): the tilt decay,
// the mission plan, the vehicle. Each rule mirrors the core's refusal of a setting nothing reads.
import type { ModelChoice, SimulateParams } from './loratrack';

/** Whether a model choice runs a station that decays the tilt rate by `eta`: 3D-CTRA, and the
 * IMM and mission stations, which run it (the core's `StationModel::sent_model`; it refuses
 * `eta` changed for the others). */
export function decaysTilt(model: ModelChoice): boolean {
  return named(model).some((m) => ['all', '3d-ctra', 'imm', 'mission'].includes(m));
}

/** Whether a run reads the vehicle set (the core refuses one it does not: `check_read`,
 * src/sim/scenario/mod.rs): a plan `flown` is flown as it, a mission station follows its plan as
 * it, and a bounded station holds the drone to its top speed. */
export function readsVehicle(flown: boolean, model: ModelChoice, prediction: SimulateParams['prediction']): boolean {
  return flown || runsMission(model) || prediction === 'bounded';
}

/** `params` without the flight settings the run would not read, as the core decides, which
 * refuses them there: a plan beside a logged flight (a CSV or the real flight), which the mission
 * station follows and, over a CSV log, a bounded station with the vehicle left to the plan reads
 * the vehicle of (`check_plan_read`, src/sim/scenario/mod.rs; a plan alone is the flight), and
 * the vehicle ([`readsVehicle`]). For the form's request and for each part of it a worker runs
 * alone (a group of its stations, one station of a sweep's point). */
export function withoutUnreadFlightSettings(params: SimulateParams): SimulateParams {
  const csv = params.trajectory !== undefined || params.trajectoryName !== undefined;
  const logged = csv || params.sample !== undefined || params.synthetic !== undefined;
  const model = params.model ?? 'all';
  const vehicle = params.vehicle ?? 'auto';
  const planRead = !logged || runsMission(model) || (csv && params.prediction === 'bounded' && vehicle === 'auto');
  const { plan, planName, ...rest } = params;
  const read: SimulateParams = plan === undefined || planRead ? params : rest;
  if (vehicle === 'auto' || readsVehicle(!logged && plan !== undefined, model, params.prediction)) return read;
  const { vehicle: _unread, ...withoutVehicle } = read;
  return withoutVehicle;
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
