//! The 9/11/12-byte state payload (reference §5; paper Fig. "payload", §III-C).
//!
//! | bytes | field | encoding | range | step (max error = step/2) |
//! | --- | --- | --- | --- | --- |
//! | 0–1 | x − origin_x | i16 big-endian | ±6553.4 m | 0.2 m |
//! | 2–3 | y − origin_y | i16 big-endian | ±6553.4 m | 0.2 m |
//! | 4–5 | z − origin_z | i16 big-endian | ±6553.4 m | 0.2 m |
//! | 6 | theta | u8, wraps | full circle | 2π/256 rad (1.406°) |
//! | 7 | phi | i8 | ±π/2 rad | (π/2)/127 rad (0.709°) |
//! | 8 | v | u8 | 0 … 25.5 m/s | 0.1 m/s |
//! | 9 | a (CTRA+, 3D-CTRA) | i8 | ±6.35 m/s² | 0.05 m/s² |
//! | 10 | omega (CTRA+, 3D-CTRA) | i8 | ±2 rad/s | 2/127 rad/s |
//! | 11 | psi (3D-CTRA) | i8 | ±2 rad/s | 2/127 rad/s |
//!
//! Ranges are a quadcopter's physical limits (speeds up to ~20 m/s, about 0.6 g of tangential
//! acceleration, turn and tilt rates up to 2 rad/s) with margin. Values outside a range saturate
//! and the encoder names the fields that did. A pitch beyond ±π/2 (a loop) is first rewritten as
//! the identical motion (theta + π, π − phi, −psi), which the ODE of reference §3 cannot tell apart.

mod error;
mod fields;
mod payload;
mod saturated;

pub use error::CodecError;
pub use fields::{Encoding, FieldSpec, FIELDS};
pub use payload::{decode, encode, quantization_variance, Encoded};
pub use saturated::SaturatedFields;
