//! # loratrack
//!
//! Remote UAV tracking over LoRa, after Mason et al., "Combining LoRaWAN and a New 3D Motion
//! Model for Remote UAV Tracking". A drone runs an Unscented Kalman Filter on its sensors and, as
//! often as LoRa's duty cycle allows, sends its state in a 9/11/12-byte payload to a ground
//! station, which predicts the drone's position between packets with one of three motion models
//! (DR, CTRA+, 3D-CTRA).
//!
//! The core (every module but `wasm`) is pure Rust with no JavaScript dependency; the WebAssembly
//! bindings (`src/wasm.rs`) and the CLI (`src/bin/loratrack`) are thin skins over [`api`].
//! Conventions (reference §2): local ENU metres, seconds, radians.

// No unsafe code: the native build (the CLI, the tests and the fuzz targets, which run without
// AddressSanitizer for that reason: scripts/fuzz.mjs) forbids it. The WebAssembly build cannot,
// since wasm-bindgen's macros in src/wasm.rs expand to unsafe blocks.
#![cfg_attr(not(target_arch = "wasm32"), forbid(unsafe_code))]
// Every public item says what it is (house style: units and sources); clippy runs with warnings as
// errors, so an undocumented one fails `npm test`.
#![warn(missing_docs)]

pub mod api;
pub mod codec;
pub mod filter;
pub mod lora;
pub mod math;
pub mod metrics;
pub mod models;
pub mod options;
mod parallel;
pub mod rng;
pub mod sim;
pub mod trajectory;

#[cfg(all(test, not(target_arch = "wasm32")))]
mod typescript;

#[cfg(target_arch = "wasm32")]
pub mod wasm;

pub use codec::*;
pub use filter::*;
pub use lora::*;
pub use math::wrap_angle;
pub use metrics::*;
pub use models::*;
pub use rng::Rng;
pub use sim::*;
pub use trajectory::*;
