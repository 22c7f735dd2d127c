//! Any text as a CSV flight: the parser returns a trajectory or an error naming what is wrong,
//! never panics, and every trajectory it returns is finite with strictly increasing time.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(t) = loratrack::parse_csv(&text, "fuzz") {
        assert!(t.t.windows(2).all(|w| w[1] > w[0]));
        assert!(t.pos.iter().chain(&t.vel).chain(&t.acc).flatten().all(|v| v.is_finite()));
    }
});
