//! WebAssembly bindings: the only module that knows about JavaScript.
//!
//! Each export takes one plain JS object, deserializes it into the matching [`crate::api`]
//! parameter struct, runs the operation and serializes the report back. Every error becomes a
//! thrown JS `Error` with the core's message; nothing here panics, so a bad call never poisons
//! the module.

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

fn call<P: DeserializeOwned, R: Serialize>(
    params: JsValue,
    op: impl FnOnce(P) -> Result<R, ApiError>,
) -> Result<JsValue, JsError> {
    let value: serde_json::Value = serde_wasm_bindgen::from_value(params)
        .map_err(|e| JsError::new(&format!("invalid parameters: {e}")))?;
    let p: P = serde_json::from_value(value)
        .map_err(|e| JsError::new(&format!("invalid parameters: {e}")))?;
    let report = op(p).map_err(|e| JsError::new(&e.to_string()))?;
    report
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| JsError::new(&e.to_string()))
}

/// `timeOnAir({sf, bw, payload, overhead?, cr?, preamble?, implicitHeader?, noCrc?, ldro?, dutyCycle?})`
/// → `{timeOnAir, symbolTime, payloadSymbols, phyPayloadBytes, lowDataRateOptimize, minInterval}`.
#[wasm_bindgen(js_name = timeOnAir)]
pub fn time_on_air(params: JsValue) -> Result<JsValue, JsError> {
    call(params, |p: api::AirtimeParams| api::airtime(&p))
}

/// `predict({model, state, dt, step?, eta?})` → `{model, state}` (noise-free model propagation).
#[wasm_bindgen]
pub fn predict(params: JsValue) -> Result<JsValue, JsError> {
    call(params, |p: api::PredictParams| api::predict(&p))
}

/// `encode({model, state, origin?})` → `{hex, saturated}`.
#[wasm_bindgen]
pub fn encode(params: JsValue) -> Result<JsValue, JsError> {
    call(params, |p: api::EncodeParams| api::encode(&p))
}

/// `decode({model, hex, origin?})` → `{model, state}`.
#[wasm_bindgen]
pub fn decode(params: JsValue) -> Result<JsValue, JsError> {
    call(params, |p: api::DecodeParams| api::decode(&p))
}

/// `simulate({synthetic | sample | trajectory (CSV text), model?, sf?, bw?, distance?, seed?, …, series?})`
/// → `{config, results, series?}` (SPEC §8). Drone-side filter runs are cached between calls.
#[wasm_bindgen]
pub fn simulate(params: JsValue) -> Result<JsValue, JsError> {
    call(params, |p: crate::sim::SimParams| {
        SIMULATOR.with(|s| api::simulate(&mut s.borrow_mut(), &p))
    })
}
