//! WebAssembly bindings: the only module that knows about JavaScript.
//!
//! Each export takes one plain JS object, deserializes it into the matching [`crate::api`]
//! parameter struct, runs the operation and serializes the report back. Every error becomes a
//! thrown JS `Error` with the core's message (and, where one setting is at fault, its key as
//! `setting`); nothing here panics, so a bad call never poisons the module.

use crate::api::{self, ApiError};
use crate::sim::Simulator;
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::cell::RefCell;
use wasm_bindgen::prelude::*;

thread_local! {
    /// One simulator per module instance, so repeated calls reuse parsed flights and drone runs.
    static SIMULATOR: RefCell<Simulator> = RefCell::new(Simulator::new());
}

/// Parameters and reports cross the boundary as JSON text, as they do in the CLI:
///
/// * in, `JSON.stringify` then `serde_json`, whose parser refuses nesting deeper than 128 levels
///   with an error: walking a JS object recursively from Rust would instead overflow the
///   WebAssembly stack on a deeply nested argument and leave the module trapping on every later
///   call;
/// * out, `serde_json` then `JSON.parse`, so a statistic of an empty sample is `null` exactly as
///   in `--json` (a direct conversion would give `NaN`). The one exception is simulate's time
///   series, whose lists of numbers become `Float64Array`s ([`report_value`]).
fn call<P: DeserializeOwned, R: Serialize>(
    params: JsValue,
    op: impl FnOnce(P) -> Result<R, ApiError>,
) -> Result<JsValue, JsValue> {
    call_with(params, op, |r| json_value(&r))
}

/// [`call`] with the report turned into a JS value by `to_js`.
fn call_with<P: DeserializeOwned, R>(
    params: JsValue,
    op: impl FnOnce(P) -> Result<R, ApiError>,
    to_js: impl FnOnce(R) -> Result<JsValue, JsValue>,
) -> Result<JsValue, JsValue> {
    let invalid = |e: &dyn core::fmt::Display, setting: Option<&str>| {
        error_naming(
            &api::clean_message(&format!("invalid parameters: {e}")),
            setting,
        )
    };
    let text = js_sys::JSON::stringify(&params)
        .ok()
        .and_then(|s| s.as_string())
        .ok_or_else(|| {
            invalid(&"not a plain object of numbers, strings, booleans and arrays (too deep, circular, or holding a BigInt?)", None)
        })?;
    // serde's message cannot name the key of a flattened setting given the wrong kind of value
    // (or a NaN, which JSON.stringify turns into null): name it.
    let p: P = serde_json::from_str(&text).map_err(|e| match api::misread_setting(&text) {
        Some((message, setting)) if !e.to_string().starts_with("unknown field") => {
            invalid(&message, setting)
        }
        _ => invalid(&api::explain_serde_error(&text, &e.to_string()), None),
    })?;
    let report = op(p).map_err(|e| api_error(&e))?;
    to_js(report)
}

/// A JS `Error` with `message`.
fn js_error(message: &str) -> JsValue {
    error_naming(message, None)
}

/// The JS `Error` for an operation the core refused: its message, the setting at fault where one
/// is ([`ApiError::setting`], e.g. `maxInterval`) and, where the core knows one, the value of
/// that setting with which the run would go ahead, `valueThatFits` ([`ApiError::value_that_fits`]:
/// the seeds or the swarm's drones that fit, the heartbeat the slowest data rate needs).
fn api_error(e: &ApiError) -> JsValue {
    let message = crate::options::naming_settings(&e.to_string(), |_| None);
    let error = error_naming(&api::clean_message(&message), e.setting());
    if let Some(fit) = e.value_that_fits() {
        // Defining a property on a fresh Error cannot fail.
        let _ = set(&error, "valueThatFits", JsValue::from(fit));
    }
    error
}

/// A JS `Error` with `message` and, as `setting`, the key of the setting at fault, so that a
/// caller such as the page can point at that control without reading the message.
fn error_naming(message: &str, setting: Option<&str>) -> JsValue {
    let error = js_sys::Error::new(message);
    if let Some(key) = setting {
        // Defining a property on a fresh Error cannot fail.
        let _ = set(&error, "setting", JsValue::from_str(key));
    }
    error.into()
}

/// `value` as JSON text, parsed by JS (see the module's note on why).
fn json_value<R: Serialize>(value: &R) -> Result<JsValue, JsValue> {
    let json = serde_json::to_string(value).map_err(|e| js_error(&e.to_string()))?;
    js_sys::JSON::parse(&json).map_err(|_| js_error("could not build the result"))
}

/// simulate's report: JSON text like every report, but its time series, most of its numbers
/// (25 000 for one synthetic flight, 450 KB of text), go straight into `Float64Array`s
/// ([`series_value`]).
fn report_value(mut report: crate::sim::SimReport) -> Result<JsValue, JsValue> {
    let series = report.series.take();
    let value = json_value(&report)?;
    if let Some(series) = series {
        set(&value, "series", series_value(&series)?)?;
    }
    Ok(value)
}

/// A series with each list of numbers copied into a `Float64Array`, the rest as JSON would give
/// it (`serde-wasm-bindgen` in its JSON-compatible mode: `None` as `null`).
///
/// Why typed arrays: one copy of the numbers out of the module's memory, where a JS array is
/// built number by number (a warm run of one synthetic flight with the paper's three stations:
/// 8–10 ms with arrays, 5–6.5 ms with typed arrays, 1.5–2 ms without any series; Node; 2–3 ms
/// since the station's bound stopped taking libm's software square roots); and a typed
/// array crosses from the page's worker to the page as one block, where an array's numbers
/// become one heap object each on the page's thread (a cold load's first report: a task of
/// 48–56 ms with 9–20 ms of garbage collection before the results could be shown, 18–22 ms as
/// typed arrays; docs/performance.md).
/// A number that is not finite stays what it is (JSON writes it `null`, as does
/// `JSON.stringify` once the arrays are turned into plain ones).
fn series_value(series: &crate::sim::Series) -> Result<JsValue, JsValue> {
    // Destructured in full, so that a field added to either struct is placed here too.
    let crate::sim::Series {
        flight,
        t,
        x,
        y,
        z,
        gateway,
        gateways,
        plan,
        models,
    } = series;
    let out = JsValue::from(js_sys::Object::new());
    set(&out, "flight", JsValue::from_str(flight))?;
    set_numbers(&out, [("t", t), ("x", x), ("y", y), ("z", z)])?;
    set(&out, "gateway", plain_value(gateway)?)?;
    set(&out, "gateways", plain_value(gateways)?)?;
    if let Some(plan) = plan {
        set(&out, "plan", plain_value(plan)?)?;
    }
    let list = js_sys::Array::new();
    for m in models {
        let crate::sim::ModelSeries {
            model,
            t,
            samples,
            error3d,
            bound95,
            x,
            y,
            z,
            arrivals,
            lost,
            arrival_dr,
            lost_dr,
        } = m;
        let one = JsValue::from(js_sys::Object::new());
        set(&one, "model", JsValue::from_str(model.name()))?;
        set(&one, "samples", plain_value(samples)?)?;
        set_numbers(
            &one,
            [
                ("t", t),
                ("error3d", error3d),
                ("bound95", bound95),
                ("x", x),
                ("y", y),
                ("z", z),
                ("arrivals", arrivals),
                ("lost", lost),
            ],
        )?;
        set(&one, "arrivalDr", plain_value(arrival_dr)?)?;
        set(&one, "lostDr", plain_value(lost_dr)?)?;
        list.push(&one);
    }
    set(&out, "models", list.into())?;
    Ok(out)
}

/// Sets each `object[key]` to its list of numbers as a `Float64Array` (a copy: the module's
/// memory may move as it grows).
fn set_numbers<const N: usize>(
    object: &JsValue,
    lists: [(&str, &Vec<f64>); N],
) -> Result<(), JsValue> {
    for (key, numbers) in lists {
        set(object, key, js_sys::Float64Array::from(&numbers[..]).into())?;
    }
    Ok(())
}

/// A small value as JSON would give it.
fn plain_value<T: Serialize + ?Sized>(value: &T) -> Result<JsValue, JsValue> {
    value
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| js_error(&e.to_string()))
}

/// Sets `object[key] = value`.
fn set(object: &JsValue, key: &str, value: JsValue) -> Result<(), JsValue> {
    js_sys::Reflect::set(object, &JsValue::from_str(key), &value)
        .map(|_| ())
        .map_err(|_| js_error("could not build the result"))
}

/// `linkBudget({bw?, txPower?, pathLossExponent?, shadowing?, gatewayHeight?, distances?})`
/// → `{distances, meanRxDbm, shadowing, sfs: [{sf, sensitivityDbm, rangeM, delivery}]}`.
#[wasm_bindgen(js_name = linkBudget)]
pub fn link_budget(params: JsValue) -> Result<JsValue, JsValue> {
    call(params, |p: api::LinkBudgetParams| api::link_budget(&p))
}

/// `timeOnAir({sf, bw, payload, overhead?, cr?, preamble?, implicitHeader?, noCrc?, ldro?, dutyCycle?})`
/// → `{timeOnAir, symbolTime, payloadSymbols, phyPayloadBytes, lowDataRateOptimize, minInterval}`.
#[wasm_bindgen(js_name = timeOnAir)]
pub fn time_on_air(params: JsValue) -> Result<JsValue, JsValue> {
    call(params, |p: api::AirtimeParams| api::airtime(&p))
}

/// `predict({model, state, dt, step?, eta?})` → `{model, state}` (noise-free model propagation).
#[wasm_bindgen]
pub fn predict(params: JsValue) -> Result<JsValue, JsValue> {
    call(params, |p: api::PredictParams| api::predict(&p))
}

/// `encode({model, state, origin?})` → `{hex, saturated}`.
#[wasm_bindgen]
pub fn encode(params: JsValue) -> Result<JsValue, JsValue> {
    call(params, |p: api::EncodeParams| api::encode(&p))
}

/// `decode({model, hex, origin?})` → `{model, state}`.
#[wasm_bindgen]
pub fn decode(params: JsValue) -> Result<JsValue, JsValue> {
    call(params, |p: api::DecodeParams| api::decode(&p))
}

/// `simulate({synthetic | sample | trajectory (CSV text), model?, sf?, bw?, distance?, seed?, …, series?}, progress?)`
/// → `{config, results, series?}` (reference §9). Drone-side filter runs are cached between calls.
/// `progress(done, total)`, if given, is called as flights complete (it must not call back into
/// this module); where it returns `false` the run stops before its next flight and `simulate`
/// throws "the run was stopped by its progress callback" (the page's worker stops a run a newer
/// one replaced, docs/reference.md §9). Any other return value, or a throw, goes on.
#[wasm_bindgen]
pub fn simulate(params: JsValue, progress: JsValue) -> Result<JsValue, JsValue> {
    let progress = progress_function(progress)?;
    call_with(
        params,
        |p: crate::sim::Scenario| {
            SIMULATOR.with(|s| {
                let mut report = reporter(&progress);
                // A progress callback that calls simulate again would find the simulator busy: refuse
                // that call with an error rather than trap.
                let mut sim = s.try_borrow_mut().map_err(|_| {
                    ApiError::Invalid("simulate was called from its own progress callback".into())
                })?;
                api::simulate_stoppable(&mut sim, &p, &mut report)
            })
        },
        report_value,
    )
}

/// `commandLine(params, command?)` → the `loratrack simulate` command line (`command:
/// 'swarm'`: `loratrack swarm`) that runs the same settings as `simulate(params)` does, each
/// setting away from its default as its CLI option; a CSV flight or plan by `trajectoryName`
/// and `planName` ([`Scenario::command_line`](crate::Scenario::command_line)).
#[wasm_bindgen(js_name = commandLine)]
pub fn command_line(params: JsValue, command: JsValue) -> Result<JsValue, JsValue> {
    let command = match command.as_string().as_deref() {
        _ if command.is_undefined() || command.is_null() => crate::CliCommand::Simulate,
        Some("simulate") => crate::CliCommand::Simulate,
        Some("swarm") => crate::CliCommand::Swarm,
        _ => {
            return Err(js_error(
                "command must be 'simulate' or 'swarm', or left out",
            ))
        }
    };
    // A seed drawn here would not be the one a run drew: the command must name the run's.
    let seed = js_sys::Reflect::get(&params, &JsValue::from_str("seed")).ok();
    if seed.and_then(|s| s.as_string()).as_deref() == Some("random") {
        return Err(error_naming(
            "seed: give the seed the run drew (its report's config.seed), not 'random'",
            Some("seed"),
        ));
    }
    call(params, |p: crate::sim::Scenario| {
        Ok(p.command_line(command)?)
    })
}

/// `swarm({drones?, duration?, sfPlan?, schedule?, jitter?, clockDrift?, …every simulate
/// setting}, progress?)` → `{config, collisionRate, collisionRateTheory, frameLength,
/// largestSwarm, packetsSent, packetsReceived, deliveryRatio, duplicates, gateways, …, drones}`
/// (the CLI's `swarm --json`). `progress(done, total)` is called
/// as episodes and drones complete; where it returns `false` the swarm stops where it is and
/// `swarm` throws "the run was stopped by its progress callback" (the page's Stop button, a
/// re-run or a closing page stop its swarms so, docs/reference.md §9). Any other return value,
/// or a throw, goes on.
#[wasm_bindgen]
pub fn swarm(params: JsValue, progress: JsValue) -> Result<JsValue, JsValue> {
    let progress = progress_function(progress)?;
    call(params, |p: crate::sim::Scenario| {
        api::swarm_stoppable(&p, &mut reporter(&progress))
    })
}

/// `limits()` → `[{key, label, unit, default, min, max, aboveMin, integer, values, help}]`: every
/// numeric setting's default and accepted range, as the core validates them
/// ([`crate::options`]).
#[wasm_bindgen]
pub fn limits() -> Result<JsValue, JsValue> {
    call(JsValue::NULL, |_: serde_json::Value| {
        Ok(crate::options::OPTIONS.to_vec())
    })
}

/// `stationsOf({model})` → the stations `model` names, in order (`all`: the paper's three), as
/// `simulate` reads it.
#[wasm_bindgen(js_name = stationsOf)]
pub fn stations_of(params: JsValue) -> Result<JsValue, JsValue> {
    #[derive(serde::Deserialize)]
    struct Params {
        #[serde(default)]
        model: crate::sim::ModelChoice,
    }
    call(params, |p: Params| {
        Ok(p.model
            .models()
            .iter()
            .map(|m| m.name())
            .collect::<Vec<_>>())
    })
}

/// `splitStations({model, workers})` → the stations `model` names, split into at most
/// `workers` groups (names, each group in `stationsOf`'s order) whose slowest finishes soonest
/// ([`split_stations`](crate::split_stations)): the page's worker pool gives group g to worker g.
#[wasm_bindgen(js_name = splitStations)]
pub fn split_stations(params: JsValue) -> Result<JsValue, JsValue> {
    #[derive(serde::Deserialize)]
    struct Params {
        #[serde(default)]
        model: crate::sim::ModelChoice,
        workers: usize,
    }
    call(params, |p: Params| {
        Ok(crate::split_stations(p.model.models(), p.workers)
            .into_iter()
            .map(|g| g.into_iter().map(|m| m.name()).collect::<Vec<_>>())
            .collect::<Vec<_>>())
    })
}

/// `poolDelivery({results})` → the network's totals (`packetsSent`, `packetsReceived`,
/// `deliveryRatio`, `duplicates`, `gateways`) over `simulate` results run apart, as one run of
/// all their stations reports them ([`Delivery::pooled`](crate::Delivery::pooled)): the page's
/// worker pool runs stations on several workers and pools their results with it.
#[wasm_bindgen(js_name = poolDelivery)]
pub fn pool_delivery(params: JsValue) -> Result<JsValue, JsValue> {
    #[derive(serde::Deserialize)]
    struct Params {
        results: Vec<crate::sim::Delivery>,
    }
    call(params, |p: Params| {
        Ok(crate::sim::Delivery::pooled(&p.results))
    })
}

/// `{results}` as the page's pool sends them: `simulate` results of stations run apart, each
/// read as its `model` and the fields `T` takes from it.
#[derive(serde::Deserialize)]
struct Stations<T> {
    results: Vec<Named<T>>,
}

#[derive(serde::Deserialize)]
struct Named<T> {
    model: String,
    #[serde(flatten)]
    rest: T,
}

impl<T> Stations<T> {
    /// Each station's model, parsed, with its fields; an unknown model is refused.
    fn parsed(self) -> Result<Vec<(crate::StationModel, T)>, ApiError> {
        self.results
            .into_iter()
            .map(|s| Ok((s.model.parse::<crate::StationModel>()?, s.rest)))
            .collect::<Result<Vec<_>, crate::models::ModelError>>()
            .map_err(|e| ApiError::Invalid(e.to_string()))
    }
}

/// `versusLowest({results})` → for each of `simulate`'s results (each a `model` with its
/// `error3d` and `draws`), its p75 against the lowest station's on the same runs resampled
/// together (`{lowest, ratio, interval, runs}`) or `null` ([`versus_lowest`](crate::versus_lowest)):
/// the page pairs the stations its workers ran apart as one run pairs them.
#[wasm_bindgen(js_name = versusLowest)]
pub fn versus_lowest(params: JsValue) -> Result<JsValue, JsValue> {
    #[derive(serde::Deserialize)]
    struct Error3d {
        p75: Option<f64>,
        count: usize,
    }
    #[derive(serde::Deserialize)]
    struct Paired {
        error3d: Error3d,
        draws: Option<crate::metrics::Draws>,
    }
    call(params, |p: Stations<Paired>| {
        let stations: Vec<crate::Contender> = p
            .parsed()?
            .into_iter()
            .map(|(model, s)| crate::Contender {
                model,
                p75: s.error3d.p75.unwrap_or(f64::NAN),
                count: s.error3d.count,
                draws: s.draws,
            })
            .collect();
        Ok(crate::versus_lowest(&stations))
    })
}

/// `deliverySpread({results})` → `{lowest, lowestRatio, highest, highestRatio}` or `null`: the
/// stations of `simulate` results (each a `model` with its `packetsSent`, `packetsReceived`,
/// `deliveryRatio`) whose delivery ratios lie more than 5 points apart
/// ([`DeliverySpread`](crate::DeliverySpread)), so that the page, which pools stations run apart,
/// says what the CLI says.
#[wasm_bindgen(js_name = deliverySpread)]
pub fn delivery_spread(params: JsValue) -> Result<JsValue, JsValue> {
    call(params, |p: Stations<crate::sim::Delivery>| {
        let stations = p.parsed()?;
        Ok(crate::DeliverySpread::of(
            stations.iter().map(|(m, d)| (*m, d)),
        ))
    })
}

/// `loadCsv({trajectory, trajectoryName?}, progress?)` → `{rows}`: reads a CSV flight into the
/// module's cache, calling `progress(lines read, lines)` about a hundred times, so that the page
/// can show how far a large file is; a following `simulate` of the same text starts at once.
/// A progress callback that returns `false` stops the reading there, which then throws as a
/// stopped `simulate` does (the page stops the reading of a file its user has replaced).
#[wasm_bindgen(js_name = loadCsv)]
pub fn load_csv(params: JsValue, progress: JsValue) -> Result<JsValue, JsValue> {
    #[derive(serde::Deserialize)]
    #[serde(rename_all = "camelCase", deny_unknown_fields)]
    struct Params {
        trajectory: std::sync::Arc<str>,
        #[serde(default)]
        trajectory_name: Option<String>,
    }
    #[derive(serde::Serialize)]
    struct Rows {
        rows: usize,
    }
    let progress = progress_function(progress)?;
    call(params, |p: Params| {
        SIMULATOR.with(|s| {
            let mut report = reporter(&progress);
            let mut sim = s.try_borrow_mut().map_err(|_| {
                ApiError::Invalid("loadCsv was called from a progress callback".into())
            })?;
            let name = p
                .trajectory_name
                .unwrap_or_else(|| crate::sim::scenario::DEFAULT_CSV_NAME.into());
            let rows = sim.load_csv(p.trajectory, name, &mut report)?;
            Ok(Rows { rows })
        })
    })
}

/// A progress argument: a function, or undefined/null for none; anything else is refused.
fn progress_function(progress: JsValue) -> Result<Option<js_sys::Function>, JsValue> {
    use wasm_bindgen::JsCast;
    if progress.is_undefined() || progress.is_null() {
        return Ok(None);
    }
    progress
        .dyn_into()
        .map(Some)
        .map_err(|_| js_error("progress must be a function (done, total) => void, or left out"))
}

/// Calls `progress(done, total)` and tells whether the run may go on: unless the callback
/// returned `false` itself. A throwing callback must not abort the run, so its error is dropped.
fn reporter(progress: &Option<js_sys::Function>) -> impl FnMut(usize, usize) -> bool + '_ {
    move |done, total| {
        let Some(f) = progress else {
            return true;
        };
        let said = f.call2(
            &JsValue::NULL,
            &JsValue::from(done as u32),
            &JsValue::from(total as u32),
        );
        said.map_or(true, |v| v != JsValue::FALSE)
    }
}

/// Benchmark support for `npm run bench` (feature `bench`; not in the production package): times `steps` UKF
/// predictions and updates inside WebAssembly, so the boundary crossing is not measured.
/// `{model, steps}` → `{predictMicros, updateMicros}` per step.
#[cfg(feature = "bench")]
#[wasm_bindgen(js_name = benchUkf)]
pub fn bench_ukf(params: JsValue) -> Result<JsValue, JsValue> {
    use crate::filter::{
        measurement_noise, process_noise, SigmaParams, Ukf, PAPER_Q, PAPER_R_DIAGONAL,
    };
    use crate::models::{with_model, ModelKind, MotionModel, ANGLES};
    use nalgebra::SVector;

    #[derive(serde::Deserialize)]
    struct Params {
        model: ModelKind,
        steps: u32,
    }
    #[derive(serde::Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Timing {
        predict_micros: f64,
        update_micros: f64,
    }
    fn time<const N: usize, M: MotionModel<N>>(model: M, steps: u32) -> Result<Timing, ApiError> {
        let state = [10.0, -5.0, 40.0, 0.4, 0.1, 8.0, 0.3, 0.2, 0.05];
        let x = SVector::<f64, N>::from_fn(|i, _| state[i]);
        let r = measurement_noise::<N>(&PAPER_R_DIAGONAL);
        let fresh = Ukf::new(x, r, process_noise(PAPER_Q), SigmaParams::default(), ANGLES)
            .ok_or_else(|| ApiError::Invalid("sigma parameters".into()))?;
        let mut ukf = fresh.clone();
        let z = x.map(|v| v + 0.05);
        // The same workloads as the criterion benchmarks (benches/core.rs).
        let t0 = js_sys::Date::now();
        for _ in 0..steps {
            ukf.predict(&model, 0.1);
            if ukf.p[(0, 0)] > 100.0 {
                ukf = fresh.clone();
            }
        }
        let t1 = js_sys::Date::now();
        for _ in 0..steps {
            ukf.update(&z, &r);
            ukf.p = r;
        }
        let t2 = js_sys::Date::now();
        let per = 1000.0 / f64::from(steps.max(1));
        Ok(Timing {
            predict_micros: (t1 - t0) * per,
            update_micros: (t2 - t1) * per,
        })
    }
    call(params, |p: Params| with_model!(p.model, time(p.steps)))
}

/// Benchmark support (feature `bench`): `simulate` with a fresh simulator (no cached drone runs).
#[cfg(feature = "bench")]
#[wasm_bindgen(js_name = benchSimulateCold)]
pub fn bench_simulate_cold(params: JsValue) -> Result<JsValue, JsValue> {
    call(params, |p: crate::sim::Scenario| {
        api::simulate(&mut Simulator::new(), &p)
    })
}
