//! Any JSON as the parameters of `simulate` (what the page and the JS API send): they are refused
//! with a message or run, never panic, and a run that counts errors reports finite statistics;
//! their command line (`commandLine`) is written without a panic either.
#![no_main]
use libfuzzer_sys::fuzz_target;
use loratrack::{CliCommand, Scenario, Simulator};

fuzz_target!(|data: &[u8]| {
    let Ok(params) = serde_json::from_slice::<Scenario>(data) else { return };
    if let Ok(line) = params.command_line(CliCommand::Swarm) {
        assert!(line.starts_with("loratrack swarm"), "{line}");
    }
    let Ok(cfg) = params.validate() else { return };
    let Ok(report) = Simulator::new().run(&cfg) else { return };
    for r in &report.results {
        if r.error3d.count > 0 {
            let e = &r.error3d;
            assert!([e.mean, e.p50, e.p75, e.p95, e.max].iter().all(|v| v.is_finite()), "{e:?}");
        }
    }
});
