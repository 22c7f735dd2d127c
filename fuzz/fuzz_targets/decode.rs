//! Any bytes, any model, any hex text: the decoder returns a state or an error, never panics,
//! and every state it returns is finite and re-encodes without saturating.
#![no_main]
use libfuzzer_sys::fuzz_target;
use loratrack::api::{decode, DecodeParams};
use loratrack::ModelKind;

fuzz_target!(|data: &[u8]| {
    let Some((&selector, payload)) = data.split_first() else { return };
    let model = ModelKind::ALL[usize::from(selector) % 3];
    if let Ok(state) = loratrack::decode(model, payload, [0.0; 3]) {
        assert!(state.iter().all(|v| v.is_finite()));
        let again = loratrack::encode(model, &state, [0.0; 3]).expect("decoded state encodes");
        assert!(again.saturated.is_empty());
    }
    let hex = String::from_utf8_lossy(payload).into_owned();
    let _ = decode(&DecodeParams { model, hex, origin: None });
});
