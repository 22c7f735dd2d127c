//! The robustness contract in one place (issue "Hardening"): every case that once printed NaN,
//! a silently wrong number, `null` for infinity, panicked, hung or ate memory now gives a finite
//! answer or a one-line refusal with exit status 2 (the WebAssembly cases are in `tests/wasm.rs`:
//! a deeply nested argument, a progress that is not a function, null statistics).

use crate::cli;
use std::io::Write;
use std::process::{Command, Stdio};

/// Exit status 2 and exactly one stderr line `error: ...` containing `expected`.
fn refused(args: &[&str], expected: &str) {
    let out = cli(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: one line, got {err:?}");
    assert!(err.starts_with("error: "), "{args:?}: {err}");
    assert!(
        err.contains(expected),
        "{args:?}: {err:?} should contain {expected:?}"
    );
    assert!(
        err.len() < 400,
        "{args:?}: a short message, got {} bytes",
        err.len()
    );
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = cli(args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON output")
}

/// A file in the temporary directory, removed when dropped: also when its test fails.
pub(crate) struct TempFile(std::path::PathBuf);

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

impl std::ops::Deref for TempFile {
    type Target = std::path::Path;
    fn deref(&self) -> &std::path::Path {
        &self.0
    }
}

pub(crate) fn temp_file(name: &str, content: &[u8]) -> TempFile {
    let path = std::env::temp_dir().join(format!(
        "loratrack-robustness-{}-{name}",
        std::process::id()
    ));
    std::fs::File::create(&path)
        .unwrap()
        .write_all(content)
        .unwrap();
    TempFile(path)
}

// 1. NaN from valid settings: psi decayed by eta to subnormal values divided 0 by 0.
#[test]
fn valid_settings_never_give_nan() {
    for args in [
        &[
            "simulate",
            "--synthetic",
            "1",
            "--model",
            "3d-ctra",
            "--sf",
            "8",
            "--step",
            "0.001",
            "--json",
        ][..],
        &[
            "simulate",
            "--synthetic",
            "2",
            "--model",
            "all",
            "--eta",
            "0.01",
            "--step",
            "0.01",
            "--json",
        ][..],
    ] {
        let r = json(args);
        for m in r["results"].as_array().unwrap() {
            for stat in ["mean", "p50", "p75", "p95", "max"] {
                assert!(
                    m["error3d"][stat].as_f64().is_some_and(f64::is_finite),
                    "{args:?} {stat}: {}",
                    m["error3d"]
                );
            }
        }
    }
}

// 2. Exact maths at tiny rates: a straight flight at 10 m/s covers 10 m in 1 s.
#[test]
fn subnormal_rates_give_the_straight_line() {
    for (model, state) in [
        ("3d-ctra", "0,0,0,0,0,10,0,0,1.5e-323"),
        ("3d-ctra", "0,0,0,0,0,10,0,0,5e-324"),
        ("ctra-plus", "0,0,0,0,0,10,0,1.5e-323"),
    ] {
        let r = json(&[
            "predict", "--model", model, "--state", state, "--dt", "1", "--json",
        ]);
        assert_eq!(
            r["state"][0].as_f64(),
            Some(10.0),
            "{model} {state}: {}",
            r["state"]
        );
    }
}

// 4. Unbounded input: only regular files of at most 64 MiB are read.
#[test]
fn devices_fifos_and_huge_files_are_refused_at_once() {
    refused(
        &["simulate", "--trajectory", "/dev/zero"],
        "not a regular file",
    );
    refused(
        &["simulate", "--trajectory", "/dev/urandom"],
        "not a regular file",
    );
    let fifo =
        TempFile(std::env::temp_dir().join(format!("loratrack-fifo-{}", std::process::id())));
    if Command::new("mkfifo")
        .arg(&*fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        refused(
            &["simulate", "--trajectory", fifo.to_str().unwrap()],
            "not a regular file",
        );
    }
    let big = temp_file("big.csv", b"t,x,y,z\n");
    std::fs::OpenOptions::new()
        .write(true)
        .open(&*big)
        .unwrap()
        .set_len(65 << 20)
        .unwrap();
    refused(
        &["simulate", "--trajectory", big.to_str().unwrap()],
        "at most 64 MiB",
    );
}

// 5. Infinities: every output is finite or the input is refused naming the field and its range.
#[test]
fn inputs_that_would_give_infinities_are_refused_with_their_range() {
    refused(
        &[
            "airtime",
            "--sf",
            "7",
            "--bw",
            "125",
            "--payload",
            "9",
            "--duty-cycle",
            "5e-324",
        ],
        "--duty-cycle must be 0.0001..1, got 5e-324",
    );
    refused(
        &[
            "simulate",
            "--synthetic",
            "1",
            "--path-loss-exponent",
            "0.01",
        ],
        "--path-loss-exponent must be 1.5..6",
    );
    refused(
        &[
            "predict",
            "--model",
            "dr",
            "--state",
            "0,0,0,0,0,1e308",
            "--dt",
            "1e308",
        ],
        "state component 5 (v) must be -1000..1000 m/s",
    );
    refused(
        &[
            "predict",
            "--model",
            "dr",
            "--state",
            "0,0,0,0,0,1",
            "--dt",
            "1e308",
        ],
        "dt must be 0..86400 s",
    );
    let r = json(&[
        "predict",
        "--model",
        "3d-ctra",
        "--state",
        "1e7,0,0,0,0,1000,1000,100,100",
        "--dt",
        "86400",
        "--json",
    ]);
    assert!(r["state"]
        .as_array()
        .unwrap()
        .iter()
        .all(|v| v.as_f64().is_some_and(f64::is_finite)));
}

// 6. The smaller ones.
#[test]
fn hex_payloads_take_hex_digits_only_counted_in_characters() {
    refused(
        &["decode", "--model", "dr", "--hex", "+03ef00000000000000"],
        "'+' at position 0",
    );
    refused(
        &["decode", "--model", "dr", "--hex", "00ééé"],
        "'é' at position 2",
    );
}

#[test]
fn csv_kinematics_are_bounded_and_every_refusal_names_a_line() {
    let rows: String = (0..20)
        .map(|i| {
            format!(
                "{},{},0,10,1,0,0,1e300,0,0\n",
                i as f64 * 0.1,
                i as f64 * 0.1
            )
        })
        .collect();
    let acc = temp_file(
        "acc.csv",
        format!("t,x,y,z,vx,vy,vz,ax,ay,az\n{rows}").as_bytes(),
    );
    refused(
        &["simulate", "--trajectory", acc.to_str().unwrap()],
        "line 2: an acceleration over 300",
    );
    let rows: String = (0..20)
        .map(|i| format!("{:e},{i},0,10\n", i as f64 * 1e-310))
        .collect();
    let tiny = temp_file("tiny.csv", format!("t,x,y,z\n{rows}").as_bytes());
    refused(
        &["simulate", "--trajectory", tiny.to_str().unwrap()],
        "line 3: time step",
    );
    // A CR-only file with a bad header is quoted in a short excerpt, not echoed whole...
    let bad = temp_file(
        "cr-bad.csv",
        format!("{}\r", "time;east;north;up".repeat(500))
            .repeat(50)
            .as_bytes(),
    );
    refused(
        &["simulate", "--trajectory", bad.to_str().unwrap()],
        "line 1: no 't' column in the header 'time;east",
    );
    // ...and a good one is read line by line.
    let rows: String = (0..20)
        .map(|i| format!("{},{i},0,10\r", i as f64 * 0.1))
        .collect();
    let cr = temp_file("cr.csv", format!("t,x,y,z\r{rows}").as_bytes());
    let r = json(&[
        "simulate",
        "--trajectory",
        cr.to_str().unwrap(),
        "--model",
        "dr",
        "--json",
    ]);
    // 19 × 0.1 s: 1.9000000000000001 s, as written and read back exactly.
    assert!((r["config"]["flightTime"].as_f64().unwrap() - 1.9).abs() < 1e-12);
}

#[test]
fn a_closed_stdout_and_a_full_disk_are_write_errors() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_loratrack"))
        .args(["sweep", "--paper"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // the reader goes away, as `| head -c 0` would
    let out = child.wait_with_output().unwrap();
    // The output was not delivered: say so and exit non-zero, as for any failed write.
    assert_eq!(
        out.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).starts_with("error: cannot write the output"));
    if let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") {
        let out = Command::new(env!("CARGO_BIN_EXE_loratrack"))
            .args(["airtime", "--sf", "7", "--bw", "125", "--payload", "9"])
            .stdout(full)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&out.stderr).starts_with("error: cannot write the output"));
    }
}

#[test]
fn argument_errors_are_one_line() {
    refused(
        &[],
        "a command is needed: airtime, predict, encode, decode, simulate, sweep, swarm",
    );
    refused(&["simulate", "--foo"], "unexpected argument '--foo'");
    refused(&["simulate", "--sf"], "--sf");
    refused(
        &["simulate", "--synthetic", "nan"],
        "synthetic must be 'all' or a flight number 1..30",
    );
    refused(
        &["simulate", "--synthetic", "1", "--seed", "9007199254740992"],
        "seed must be 0..9007199254740991",
    );
    // Repeats run seed, seed + 1, …: every one of them must be a seed.
    refused(
        &[
            "simulate",
            "--synthetic",
            "1",
            "--seed",
            "9007199254740990",
            "--seeds",
            "3",
        ],
        "seeds 9007199254740990..9007199254740992 run past the largest seed",
    );
    refused(
        &[
            "sweep",
            "--distances",
            "1000",
            "--seeds",
            "4",
            "--seed",
            "9007199254740986",
            "--held-out",
            "--markdown",
        ],
        "--held-out runs the next 4 seeds, 9007199254740990..9007199254740993",
    );
}

#[test]
fn empty_statistics_are_null() {
    let r = json(&[
        "simulate",
        "--synthetic",
        "3",
        "--model",
        "dr",
        "--distance",
        "100000",
        "--json",
    ]);
    let e = &r["results"][0]["error3d"];
    assert_eq!(e["count"], 0);
    assert!(e["mean"].is_null() && e["p75"].is_null());
}

// 7. Run length: the work (flight time × filter rates) is bounded with a clear refusal.
#[test]
fn runs_beyond_the_work_limit_are_refused_quickly() {
    let rows: String = (0..10)
        .map(|i| format!("{},{},0,10\n", i as f64 * 9600.0, i))
        .collect();
    let long = temp_file("long.csv", format!("t,x,y,z\n{rows}").as_bytes());
    let started = std::time::Instant::now();
    refused(
        &["simulate", "--trajectory", long.to_str().unwrap()],
        "the run is too long",
    );
    refused(
        &[
            "simulate",
            "--trajectory",
            long.to_str().unwrap(),
            "--sensor-rate",
            "1000",
            "--step",
            "0.001",
        ],
        "the limit is 1\u{a0}000\u{a0}000",
    );
    // Several seeds of a flight: the refusal says how many fit, and that many run.
    refused(
        &["simulate", "--synthetic", "all", "--seeds", "20"],
        "(at most 18 seeds, or shorten the flight",
    );
    // A swarm is refused at its own limit, with a swarm's remedies: as many drones as fit first.
    refused(
        &[
            "swarm",
            "--drones",
            "500",
            "--duration",
            "3600",
            "--sensor-rate",
            "20",
        ],
        "the swarm is too long: its drones fly 1\u{a0}800\u{a0}000 s in all, 54\u{a0}000\u{a0}000 filter steps at these rates; the limit is 36\u{a0}000\u{a0}000 (at most 333 drones, or shorter flights",
    );
    assert!(
        started.elapsed().as_secs_f64() < 5.0,
        "refused in {:?}",
        started.elapsed()
    );
    drop(long);
    // The page's most demanding setting stays allowed.
    let r = json(&[
        "simulate",
        "--synthetic",
        "all",
        "--model",
        "dr",
        "--sensor-rate",
        "100",
        "--step",
        "0.01",
        "--sf",
        "12",
        "--json",
    ]);
    assert!(r["results"][0]["error3d"]["count"].as_u64().unwrap() > 0);
    let r = json(&[
        "simulate",
        "--synthetic",
        "all",
        "--seeds",
        "18",
        "--model",
        "dr",
        "--json",
    ]);
    assert_eq!(r["config"]["seeds"].as_u64(), Some(18));
}

#[test]
fn help_to_a_full_disk_is_an_error() {
    let out = Command::new(env!("CARGO_BIN_EXE_loratrack"))
        .args(["simulate", "--help"])
        .stdout(std::fs::File::create("/dev/full").expect("/dev/full exists on Linux"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).starts_with("error: cannot write the output"));
}

/// The CLI names a refused setting by the flag its user typed, whether the flag's parser or the
/// core refused it; the JS API names the same refusal by its key (`tests/wasm.rs`). A setting the
/// CLI has no flag for keeps its name.
#[test]
fn the_cli_names_a_refused_setting_by_its_flag_not_its_js_key() {
    let e = |extra: &[&str]| {
        let mut args = vec!["simulate", "--synthetic", "1"];
        args.extend_from_slice(extra);
        let out = cli(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    for (extra, flag, key) in [
        (
            &["--sender", "error", "--max-interval", "0"][..],
            "--max-interval",
            "maxInterval",
        ),
        (&["--max-interval", "x"], "--max-interval", "maxInterval"),
        (
            &["--sender", "error", "--sf", "12", "--bw", "125"],
            "--max-interval",
            "maxInterval",
        ),
        (&["--sensor-rate", "0"], "--sensor-rate", "sensorRate"),
        (&["--duty-cycle", "2"], "--duty-cycle", "dutyCycle"),
        (&["--adr-history", "0.5"], "--adr-history", "adrHistory"),
        (&["--sf", "13"], "--sf", "sf"),
    ] {
        let err = e(extra);
        assert!(
            err.starts_with(&format!("error: {flag} must be ")),
            "{extra:?}: {err}"
        );
        assert!(!err.contains(&format!(" {key} must")), "{extra:?}: {err}");
    }
    let err = String::from_utf8_lossy(&cli(&["simulate", "--synthetic", "40"]).stderr).into_owned();
    assert!(
        err.starts_with("error: --synthetic must be 'all' or a flight number 1..30, got 40"),
        "{err}"
    );
    // Settings named within a sentence too.
    for (args, expected) in [
        (
            &["--region", "us915", "--sf", "9", "--bw", "125", "--duty-cycle", "0.02"][..],
            "error: US915 has no duty cycle: set --interval instead of --duty-cycle\n",
        ),
        (
            &["--heading-noise", "adaptive"],
            "error: --heading-noise adaptive is a bounded station's: set --prediction to bounded\n",
        ),
        (
            &["--access", "lbt", "--duty-cycle", "0.02"],
            "error: --duty-cycle does not apply with --access lbt (ETSI's 100 s of airtime per hour)\n",
        ),
    ] {
        assert_eq!(e(args), expected);
    }
    let err = String::from_utf8_lossy(&cli(&["simulate"]).stderr).into_owned();
    assert!(
        err.starts_with("error: choose a flight: --trajectory (CSV), --synthetic"),
        "{err}"
    );
    // A value none of a flag's choices names them (clap puts them on a line the one line left out).
    assert_eq!(
        e(&["--fair-use", "x"]),
        "error: invalid value 'x' for --fair-use: expected off or ttn (see --help)\n"
    );
    assert_eq!(
        e(&["--region", "mars"]),
        "error: invalid value 'mars' for --region: expected eu868, us915, au915, as923 or in865 (see --help)\n"
    );
    // 17 gateways are 17 `--gateway` flags: the count has no flag of its own.
    let mut args = vec!["swarm", "--drones", "2"];
    args.extend(std::iter::repeat_n(["--gateway", "0,0"], 17).flatten());
    let err = String::from_utf8_lossy(&cli(&args).stderr).into_owned();
    assert!(err.starts_with("error: gateways must be 1..16"), "{err}");
}

/// A setting changed from its default where nothing reads it is refused, naming what makes it
/// apply (as `--duty-cycle` without a duty cycle is), where it was once ignored: the run would
/// have gone ahead on other settings than those typed. With that setting given it runs.
#[test]
fn a_setting_that_would_change_nothing_is_refused_with_what_makes_it_apply() {
    let run = |args: &[&str]| cli(&[&["simulate", "--synthetic", "1"][..], args].concat());
    for (given, enabling) in [
        (&["--threshold", "3"][..], &["--sender", "error"][..]),
        (&["--max-interval", "20"], &["--sender", "error"]),
        (&["--burst", "4"], &["--duty-cycle-mode", "budget"]),
        (&["--adr-margin", "15"], &["--adr", "lorawan"]),
        (&["--adr-history", "10"], &["--adr", "lorawan"]),
        (&["--plan-tolerance", "30"], &["--model", "mission"]),
        (&["--plan-pace", "packet"], &["--model", "mission"]),
    ] {
        let refused = run(given);
        assert_eq!(refused.status.code(), Some(2), "{given:?}");
        let err = String::from_utf8_lossy(&refused.stderr).into_owned();
        assert!(
            err.starts_with(&format!("error: {} is ", given[0])),
            "{err}"
        );
        let remedy = match enabling[0] {
            "--model" => format!("add mission to {}", enabling[0]),
            flag => format!("set {flag} to {}", enabling[1]),
        };
        assert!(err.ends_with(&format!(": {remedy}\n")), "{err}");
        let ran = run(&[given, enabling].concat());
        assert_eq!(ran.status.code(), Some(0), "{given:?} {enabling:?}");
    }
    // The tilt decay is 3D-CTRA's, which the default stations include, and the IMM's.
    let dr = run(&["--model", "dr", "--eta", "0.5"]);
    assert_eq!(dr.status.code(), Some(2));
    let err = String::from_utf8_lossy(&dr.stderr).into_owned();
    assert!(err.ends_with(": add 3d-ctra to --model\n"), "{err}");
    assert_eq!(
        run(&["--model", "imm", "--eta", "0.5"]).status.code(),
        Some(0)
    );
    // The swarm refuses them alike; the ADR's with tracking ADR too, which has no margin.
    let out = cli(&[
        "swarm",
        "--drones",
        "2",
        "--adr",
        "tracking",
        "--adr-margin",
        "15",
    ]);
    assert_eq!(out.status.code(), Some(2));
}

/// Listed gateways replace the one `--distance` places, and a listed gateway's own height leaves
/// `--gateway-height` to no one: both refused there. The one default gateway, a gateway listed
/// without a height and a swarm's drones (spread at the distance around the centre) read them.
#[test]
fn listed_gateways_leave_the_distance_and_a_default_height_unread_and_both_are_refused() {
    let simulate = ["simulate", "--synthetic", "1"];
    let listed = [&simulate[..], &["--gateway", "500,0,20"]].concat();
    refused(
        &[&listed[..], &["--distance", "3000"]].concat(),
        "--distance is where the one default gateway stands, and the listed gateways replace it: leave --distance out",
    );
    refused(
        &[&listed[..], &["--gateway-height", "40"]].concat(),
        "--gateway-height is the antenna height of every gateway not given its own: every listed gateway gives its own height; leave --gateway-height out",
    );
    for read in [
        &["--distance", "3000", "--gateway-height", "40"][..],
        &[
            "--gateway",
            "500,0,20",
            "--gateway",
            "0,500",
            "--gateway-height",
            "40",
        ],
    ] {
        let out = cli(&[&simulate[..], read].concat());
        assert_eq!(out.status.code(), Some(0), "{read:?}");
    }
    let swarm = ["swarm", "--drones", "2", "--duration", "60"];
    let out = cli(&[&swarm[..], &["--gateway", "500,0", "--distance", "3000"]].concat());
    assert_eq!(out.status.code(), Some(0));
}

/// How a swarm's drones share the air is the swarm's (one drone's frames never meet another's,
/// and listening for them it always finds the channel free), and the first flight's series are
/// simulate's (a swarm has no first flight to draw).
#[test]
fn simulate_and_swarm_refuse_each_others_settings() {
    let help = String::from_utf8(cli(&["simulate", "--help"]).stdout).unwrap();
    // Each the setting refused and what it is given with (listening is error-triggered
    // sending's; in a swarm its heartbeat must reach the slowest SF's interval).
    for (flag, given) in [
        ("--channels", &["--channels", "1"][..]),
        ("--capture", &["--capture", "off"]),
        ("--inter-sf", &["--inter-sf", "off"]),
        ("--schedule", &["--schedule", "slotted"]),
        (
            "--channel-sense",
            &[
                "--sender",
                "error",
                "--max-interval",
                "80",
                "--channel-sense",
                "off",
            ],
        ),
    ] {
        refused(
            &[&["simulate", "--synthetic", "1"][..], given].concat(),
            &format!("{flag} is a swarm setting: simulate flies one drone over its flight, with the air to itself"),
        );
        // Its help says so before the refusal does.
        let entry = help
            .split(&format!("      {flag} <"))
            .nth(1)
            .and_then(|rest| rest.split("\n\n").next())
            .unwrap_or_else(|| panic!("{flag} is not in simulate's help"));
        assert!(entry.contains("swarm only"), "{flag}: {entry}");
        let swarm = cli(&[&["swarm", "--drones", "2", "--duration", "60"][..], given].concat());
        assert_eq!(swarm.status.code(), Some(0), "{given:?}");
    }
    refused(
        &["swarm", "--drones", "2", "--series"],
        "--series is simulate's (the first flight's error and tracks over time): a swarm reports each drone's statistics; leave --series out",
    );
}

/// A sweep's flag given to another sweep, which would drop it, is refused, naming the sweeps
/// that read it (`sweep --paper --sf 9` ran the paper's fixed grid).
#[test]
fn a_sweep_refuses_a_flag_its_kind_would_drop_naming_the_sweeps_that_read_it() {
    for (kind, flag, readers) in [
        (
            &["--distances", "1000"][..],
            &["--burst", "4"][..],
            "--senders",
        ),
        (&["--paper"], &["--sf", "9"], "--senders, --distances"),
        (
            &["--swarm"],
            &["--seeds", "4"],
            "--senders, --distances, --mission, --payloads",
        ),
        (
            &["--mission"],
            &["--distance", "3000"],
            "--senders, --swarm",
        ),
        (
            &["--swarm"],
            &["--model", "dr"],
            "--paper, --senders, --distances",
        ),
        (&["--paper", "--markdown"], &["--held-out"], "--distances"),
        (&["--mission"], &["--svg"], "--senders"),
    ] {
        refused(
            &[&["sweep"][..], kind, flag].concat(),
            &format!(
                "{} is read only by sweep {readers}: sweep {} would drop it",
                flag[0], kind[0]
            ),
        );
    }
}

#[test]
fn negative_numbers_are_numbers_and_refused_by_their_own_field() {
    refused(
        &["simulate", "--synthetic", "1", "--overhead", "-1"],
        "--overhead must be 0..255 bytes, a whole number, got -1",
    );
    refused(
        &["simulate", "--synthetic", "1", "--drones", "-1"],
        "unexpected argument '--drones'",
    );
    refused(
        &["swarm", "--drones", "-1"],
        "--drones must be 1..500, a whole number, got -1",
    );
    refused(
        &["simulate", "--synthetic", "1", "--q", "-1"],
        "q must be in (0, 1000]",
    );
    // Whole-number settings given a fraction or text answer in the range's words, as the JS API
    // does, not with the integer type's "invalid digit found in string".
    refused(
        &["simulate", "--synthetic", "1", "--sf", "7.5"],
        "sf must be 7..12, a whole number, got 7.5",
    );
    refused(
        &["airtime", "--sf", "7", "--bw", "125", "--payload", "nine"],
        "payload must be a number, got 'nine'",
    );
    // A number given with its unit is named with the setting's range, not as a float literal.
    refused(
        &["simulate", "--synthetic", "1", "--distance", "1km"],
        "distance must be a number (0..100000 m), got '1km'",
    );
    // The seed too: not "unexpected argument '-1'".
    refused(
        &["simulate", "--synthetic", "1", "--seed", "-1"],
        "seed must be a whole number 0..2^53-1 or 'random', got '-1'",
    );
}

#[test]
fn swept_distances_are_checked_and_bounded_before_any_run() {
    refused(
        &["sweep", "--distances", "1000,-5"],
        "distances: distance must be 0..100000 m, got -5",
    );
    let many: Vec<String> = (1..=101).map(|k| (k * 10).to_string()).collect();
    refused(
        &["sweep", "--distances", &many.join(",")],
        "give 1..100 distances, got 101",
    );
    // An empty value (a doubled comma) or text is named as a distance, not as a float.
    refused(
        &["sweep", "--distances", "1000,,3000"],
        "distance must be a number (0..100000 m), got ''",
    );
}

#[test]
fn a_predicted_step_far_longer_than_dt_moves_the_state() {
    let moved = json(&[
        "predict",
        "--model",
        "ctra-plus",
        "--state",
        "0,0,0,0,0,1,1,1",
        "--dt",
        "0.5",
        "--step",
        "1e9",
        "--json",
    ]);
    let x = moved["state"][0].as_f64().unwrap();
    assert!((x - 0.5967208697966773).abs() < 1e-12, "x = {x}");
}

#[test]
fn messages_escape_control_characters_and_quote_at_most_80_characters() {
    let crafted = format!("\u{1b}]0;owned\u{7}{}", "y".repeat(500));
    let out = cli(&["simulate", "--sample", &crafted]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(!err.trim_end().chars().any(char::is_control), "{err:?}");
    assert!(err.contains("\\u{1b}"), "{err}");
    assert!(err.len() < 200, "{} bytes: {err}", err.len());
}

#[test]
fn a_csv_that_is_not_utf8_is_refused_at_its_line_and_byte() {
    let path = temp_file("latin1.csv", b"t,x,y,z\n0,0,0,0\n0.1,1,0,\xe9\n");
    refused(
        &["simulate", "--trajectory", path.to_str().unwrap()],
        "line 3, byte offset 24: not UTF-8 text",
    );
}

#[test]
fn every_sweep_takes_a_random_seed_and_reports_it() {
    let r = json(&["sweep", "--distances", "2000", "--seed", "random", "--json"]);
    let seed = r["seed"].as_u64().expect("the drawn seed is reported");
    assert!(seed <= 9_007_199_254_740_991);
    let again = json(&[
        "sweep",
        "--distances",
        "2000",
        "--seed",
        &seed.to_string(),
        "--json",
    ]);
    assert_eq!(again, r, "the reported seed repeats the sweep");
}

#[test]
fn the_adr_document_pools_the_seeds_it_names_and_judges_every_adr_row() {
    let out = cli(&["sweep", "--distances", "2000", "--seeds", "2", "--markdown"]);
    assert_eq!(out.status.code(), Some(0));
    let md = String::from_utf8_lossy(&out.stdout);
    assert!(md.contains("seeds 1–2 pooled"), "{md}");
    let findings = md
        .split("## What the table shows")
        .nth(1)
        .expect("a findings section");
    for row in [
        "lorawan from DR6",
        "tracking from DR6",
        "lorawan from DR0",
        "tracking from DR0",
    ] {
        let lines: Vec<&str> = findings
            .lines()
            .filter(|l| l.starts_with(&format!("- `{row}`: p75 / best fixed: ")))
            .collect();
        assert_eq!(lines.len(), 1, "{row}: {findings}");
        // Judged at the one distance, on the whole flight time.
        assert!(lines[0].contains("at 2000 m"), "{}", lines[0]);
    }
    // Two seeds give each ratio an interval from drawing them again: "1.00× (0.97–1.02) at".
    let ratio = first_ratio_interval(findings).expect("a ratio with its interval");
    assert!(ratio.0 <= ratio.1 && !ratio.1.is_nan(), "{findings}");
    // Two seeds fly the set twice: about twice the packets of one (the random start of each
    // run's duty-cycle phase moves a packet or two).
    let packets = |seeds: &str| {
        let r = json(&["sweep", "--distances", "2000", "--seeds", seeds, "--json"]);
        r["runs"][6]["result"]["packetsSent"]
            .as_u64()
            .expect("DR6's packets")
    };
    let (one, two) = (packets("1"), packets("2"));
    assert!(two.abs_diff(2 * one) <= 4, "{one} then {two}");
}

/// The first "1.00× (0.97–1.02)" in `text`: the interval's ends (∞ read as infinity).
fn first_ratio_interval(text: &str) -> Option<(f64, f64)> {
    let (_, rest) = text.split_once("× (")?;
    let (inside, _) = rest.split_once(')')?;
    let (lo, hi) = inside.split_once('–')?;
    let end = |s: &str| match s {
        "∞" => Some(f64::INFINITY),
        s => s.parse().ok(),
    };
    Some((end(lo)?, end(hi)?))
}

#[test]
fn the_distance_sweep_judges_every_row_against_the_best_fixed_rate_in_its_json() {
    let r = json(&["sweep", "--distances", "2000", "--seeds", "2", "--json"]);
    let runs = r["runs"].as_array().expect("runs");
    let p75 = |run: &serde_json::Value| run["result"]["wholeFlight"]["p75"].as_f64();
    let best = runs
        .iter()
        .filter(|run| run["dr"].is_u64())
        .filter_map(|run| Some((run, p75(run)?)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("a fixed rate with a p75 at 2 km");
    for run in runs {
        let v = &run["p75VsBestFixed"];
        assert_eq!(v["dr"], best.0["dr"], "{v}");
        match p75(run) {
            // Its ratio, and an interval holding it, from the same two seeds drawn alike.
            Some(p) => {
                let ratio = v["ratio"].as_f64().expect("a ratio");
                assert!((ratio - p / best.1).abs() < 1e-12, "{v}");
                let (lo, hi) = (
                    v["interval"][0].as_f64().unwrap(),
                    v["interval"][1].as_f64(),
                );
                assert!(lo <= ratio && hi.is_none_or(|hi| ratio <= hi), "{v}");
            }
            // No p75 of its own: an infinite ratio, written null, and no interval.
            None => assert!(v["ratio"].is_null() && v["interval"].is_null(), "{v}"),
        }
    }
    // The best fixed rate against itself: 1, with an interval of [1, 1].
    assert_eq!(best.0["p75VsBestFixed"]["ratio"].as_f64(), Some(1.0));
    assert_eq!(
        best.0["p75VsBestFixed"]["interval"],
        serde_json::json!([1.0, 1.0])
    );
}

#[test]
fn held_out_judges_the_adr_rows_again_on_the_next_block_of_seeds() {
    let verdicts = |md: &str, after: &str| -> Vec<String> {
        md.split(after)
            .nth(1)
            .unwrap_or_default()
            .lines()
            .take_while(|l| !l.starts_with("LoRaWAN's ADR") && !l.starts_with("## "))
            .filter(|l| l.starts_with("- `"))
            .map(str::to_string)
            .collect()
    };
    let markdown = |args: &[&str]| {
        let out = cli(args);
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let md = markdown(&[
        "sweep",
        "--distances",
        "2000",
        "--seeds",
        "2",
        "--held-out",
        "--markdown",
    ]);
    assert!(md.contains("--seeds 2 --held-out --markdown"), "{md}");
    let held = verdicts(&md, "## The same runs on seeds 3–4");
    assert_eq!(held.len(), 4, "{md}");
    // The held-out section is what the next block alone reports.
    let next = markdown(&[
        "sweep",
        "--distances",
        "2000",
        "--seed",
        "3",
        "--seeds",
        "2",
        "--markdown",
    ]);
    assert_eq!(held, verdicts(&next, "## What the table shows"));
    assert_ne!(
        held,
        verdicts(&md, "## What the table shows"),
        "a different block"
    );
    // It is a document's section: without --markdown it is refused.
    let out = cli(&["sweep", "--distances", "2000", "--held-out"]);
    assert_eq!(out.status.code(), Some(2));
    // Naming what it lacks: the one-line error once cut clap's list off and named nothing.
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("required arguments were not provided: --markdown"),
        "{err}"
    );
}

#[test]
fn a_drone_that_sends_nothing_shows_its_interval_and_no_delivery_or_charge() {
    // TTN's fair use at SF12: one packet every ~71 minutes, none in an 81 s flight. The table
    // printed "NaNs" (the mean over no packets) where the page shows the rate's interval, and
    // "0.0 %" delivered and 0.00 mC per uplink, as if every packet were lost and free.
    let args = [
        "simulate",
        "--synthetic",
        "1",
        "--fair-use",
        "ttn",
        "--sf",
        "12",
        "--bw",
        "125",
        "--model",
        "dr",
    ];
    let r = json(&[&args[..], &["--json"]].concat());
    assert_eq!(r["results"][0]["packetsSent"], 0);
    // The JSON (and so the page's CSV) has no share and no charge either, not zeros; the radio
    // slept through the flight.
    for shares in [&r, &r["results"][0]] {
        assert!(shares["deliveryRatio"].is_null(), "{shares}");
    }
    let energy = &r["results"][0]["energy"];
    assert!(energy["chargePerUplink"].is_null(), "{energy}");
    assert!(energy["chargePerHour"].as_f64() > Some(0.0), "{energy}");
    let interval = r["results"][0]["interval"].as_f64().unwrap();
    let text = String::from_utf8_lossy(&cli(&args).stdout).into_owned();
    let row = text
        .lines()
        .find(|l| l.starts_with("DR "))
        .unwrap_or_default();
    assert!(row.contains(&format!("{interval:.2}s")), "{row}");
    assert!(row.ends_with(" -"), "no charge per uplink: {row}");
    assert!(!text.contains("NaN"), "{text}");
    assert!(
        text.contains("0 of 0 packets delivered (none sent)"),
        "{text}"
    );
    assert!(text.contains("energy DR        no uplink sent"), "{text}");
}

/// One packet on a flight (SF12 for 81 s) is "1 of 1 packet", as a LoRaWAN ADR that reads one
/// uplink reads "1 uplink".
#[test]
fn counts_of_one_are_named_in_the_singular() {
    let one = cli(&[
        "simulate",
        "--synthetic",
        "1",
        "--model",
        "dr",
        "--sf",
        "12",
        "--bw",
        "125",
        "--adr",
        "lorawan",
        "--adr-history",
        "1",
    ]);
    let text = String::from_utf8_lossy(&one.stdout);
    assert!(text.contains("network: 1 of 1 packet delivered"), "{text}");
    assert!(text.contains("(margin 10 dB, 1 uplink)"), "{text}");
}

#[test]
fn a_swarm_that_sent_nothing_gives_no_shares_and_no_charge() {
    // Drones at SF12 (an interval of 148 s) flying 10 s: most send nothing.
    let sf12 = |drones: &str, seed: &str| -> Vec<String> {
        let args = "swarm --duration 10 --sf-plan fixed --sf 12 --bw 125 --drones";
        let mut a: Vec<String> = args.split(' ').map(String::from).collect();
        a.extend([drones.into(), "--seed".into(), seed.into()]);
        a
    };
    // Three drones, on this seed none sends.
    let args = sf12("3", "5");
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let r = json(&[&args[..], &["--json"]].concat());
    assert_eq!(r["packetsSent"], 0, "a seed on which no drone sends");
    for key in ["collisionRate", "deliveryRatio"] {
        assert!(r[key].is_null(), "{key}: {}", r[key]);
    }
    assert!(r["energy"]["chargePerUplink"].is_null());
    assert!(r["drones"][0]["energy"]["chargePerUplink"].is_null());
    let text = String::from_utf8_lossy(&cli(&args).stdout).into_owned();
    for line in [
        "collision rate      -  (",
        "delivery ratio      -  (",
        "energy              no uplink sent",
    ] {
        assert!(text.contains(line), "{line}: {text}");
    }
    // Where some drones sent and others did not, the charge per uplink is the senders' mean.
    let twelve = sf12("12", "1");
    let twelve: Vec<&str> = twelve.iter().map(String::as_str).collect();
    let mixed = json(&[&twelve[..], &["--json"]].concat());
    let drones = mixed["drones"].as_array().unwrap();
    let charges: Vec<f64> = drones
        .iter()
        .filter(|d| d["packetsSent"].as_u64() > Some(0))
        .map(|d| d["energy"]["chargePerUplink"].as_f64().unwrap())
        .collect();
    assert!(
        !charges.is_empty() && charges.len() < drones.len(),
        "some silent"
    );
    let mean = charges.iter().sum::<f64>() / charges.len() as f64;
    let reported = mixed["energy"]["chargePerUplink"].as_f64().unwrap();
    assert!((reported - mean).abs() < 1e-9, "{reported} vs {mean}");
}

#[test]
fn a_simulate_header_names_the_seeds_its_numbers_pool() {
    // It said "seed 1" above numbers pooled over three seeds.
    let text = |args: &[&str]| String::from_utf8_lossy(&cli(args).stdout).into_owned();
    let pooled = text(&[
        "simulate",
        "--synthetic",
        "1",
        "--seed",
        "4",
        "--seeds",
        "3",
    ]);
    let first = pooled.lines().next().unwrap_or_default();
    assert!(first.ends_with(", seeds 4–6 pooled"), "{first}");
    let one = text(&["simulate", "--synthetic", "1", "--seed", "4"]);
    let first = one.lines().next().unwrap_or_default();
    assert!(first.ends_with(", seed 4"), "{first}");
}

#[test]
fn a_sweep_table_says_what_it_rests_on() {
    // Their headers named neither the station's prediction, the overhead nor the seeds pooled.
    let first_line = |args: &[&str]| {
        let out = cli(args);
        assert!(out.status.success(), "{args:?}");
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        text.lines().next().unwrap_or_default().to_string()
    };
    let senders = first_line(&[
        "sweep",
        "--senders",
        "--seeds",
        "2",
        "--prediction",
        "bounded",
        "--overhead",
        "13",
    ]);
    assert!(
        senders.ends_with(
            ": the whole synthetic set, 3D-CTRA station, bounded prediction, SF7 / 250 kHz, gateway \
             at 1000 m, 13 bytes of MAC overhead per packet, seeds 1–2 pooled"
        ),
        "{senders}"
    );
    let distances = first_line(&[
        "sweep",
        "--distances",
        "3000",
        "--seed",
        "5",
        "--seeds",
        "2",
    ]);
    assert!(
        distances.ends_with(
            ": the whole synthetic set, 3D-CTRA station, paper prediction, no LoRaWAN overhead, \
             seeds 5–6 pooled"
        ),
        "{distances}"
    );
}

#[test]
fn a_swarm_header_says_what_each_drone_flies_on_which_sfs_and_why_spread_dealt_fewer() {
    // It said "1 drones x 600 s" for drones flying an 81-s chosen flight.
    let out = cli(&[
        "swarm",
        "--drones",
        "1",
        "--synthetic",
        "1",
        "--sf-plan",
        "fixed",
        "--channels",
        "1",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    let length = loratrack::synthetic_flight(1).unwrap().duration();
    let said = format!(
        "1 drone each flying synthetic 1 ({length:.0} s), at 1000 m, EU868 (1 % duty cycle), 1 channel, all on SF7,"
    );
    assert!(text.starts_with(&said), "{text}");
    let chained = cli(&["swarm", "--drones", "2", "--duration", "60"]);
    let text = String::from_utf8_lossy(&chained.stdout);
    assert!(
        text.starts_with(
            "2 drones x 60 s, at 1000 m, EU868 (1 % duty cycle), 3 channels, SF7-SF8 in turn,"
        ),
        "{text}"
    );
    // The SFs named are those dealt, and where `spread` dealt fewer than it had drones for, why:
    // in US915 at 125 kHz SF10's frame is over the dwell time; without a duty cycle a drone sends
    // at the interval set, which SF12's frame outlasts; ADR starts at a data rate, and at 250 kHz
    // EU868 has one at SF7 alone.
    let cases: [(&[&str], &str); 3] = [
        (
            &["--region", "us915", "--bw", "125"],
            ", 8 channels, SF7-SF9 in turn (at 125 kHz US915 carries the frame at no other SF),",
        ),
        (
            &["--region", "in865", "--bw", "125"],
            ", SF7-SF11 in turn (at 125 kHz a slower SF's frame outlasts the 1 s interval set),",
        ),
        (
            &["--adr", "tracking"],
            ", all starting on SF7 (at 250 kHz ADR can start at no other SF),",
        ),
    ];
    for (extra, expected) in cases {
        let args = [&["swarm", "--drones", "6", "--duration", "60"][..], extra].concat();
        let text = String::from_utf8_lossy(&cli(&args).stdout).into_owned();
        assert!(text.contains(expected), "{args:?}: {text}");
    }
}

/// A run long enough to show its progress does so on a terminal (`script` gives it one, where
/// the machine has util-linux) and erases it at the end; with stderr piped, as scripts and
/// these tests read it, it writes nothing there.
#[test]
fn progress_shows_on_a_terminal_only() {
    // A swarm shows its percentage; a sweep, whose number of runs is not known in advance,
    // counts them.
    let runs: [(&[&str], &str); 2] = [
        (
            &["swarm", "--drones", "60", "--duration", "1200", "--json"],
            "\rloratrack swarm: ",
        ),
        (
            &[
                "sweep",
                "--distances",
                "1000,3000",
                "--model",
                "3d-ctra",
                "--seeds",
                "2",
                "--json",
            ],
            "\rloratrack sweep: ",
        ),
    ];
    for (args, line) in runs {
        let piped = crate::cli(args);
        assert!(piped.status.success());
        assert_eq!(String::from_utf8_lossy(&piped.stderr), "", "{args:?}");
        let command = format!(
            "'{}' {} > /dev/null",
            env!("CARGO_BIN_EXE_loratrack"),
            args.join(" ")
        );
        let started = std::time::Instant::now();
        let Ok(tty) = Command::new("script")
            .args(["-qec", &command, "/dev/null"])
            .stdin(Stdio::null())
            .output()
        else {
            return;
        };
        assert!(tty.status.success());
        let shown = String::from_utf8_lossy(&tty.stdout);
        // A quick run shows nothing (the line waits half a second); these take ~1.2 s here.
        if started.elapsed() >= std::time::Duration::from_secs(1) {
            assert!(shown.contains(line), "{shown:?}");
            assert!(shown.ends_with("\r\x1b[K"), "{shown:?}");
        }
        assert!(!shown.contains("error"), "{shown:?}");
    }
}

#[test]
fn a_second_prediction_adds_its_own_verdicts_to_the_adr_document_and_other_sweeps_refuse_it() {
    let markdown = |args: &[&str]| {
        let out = cli(args);
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let sweep = ["sweep", "--distances", "2000", "--seeds", "2", "--markdown"];
    let both = markdown(&[&sweep[..], &["--held-out", "--prediction", "paper,bounded"]].concat());
    let paper = markdown(&[&sweep[..], &["--held-out"]].concat());
    let (first, bounded) = both
        .split_once("\n## The same runs with the bounded station\n")
        .expect(&both);
    // The paper station's document is as before but for the command it names.
    assert_eq!(
        first.replace(" --prediction paper,bounded", "").trim_end(),
        paper.trim_end(),
        "{both}"
    );
    assert!(
        first.contains("--bw 250 --prediction paper,bounded`"),
        "{first}"
    );
    // Each block's verdicts are what the bounded station alone reports on it.
    let verdicts = |text: &str| -> Vec<String> {
        text.lines()
            .take_while(|l| !l.starts_with("LoRaWAN's ADR"))
            .filter(|l| l.starts_with("- `"))
            .map(str::to_string)
            .collect()
    };
    let (one, two) = bounded.split_once("On seeds 3–4").expect(bounded);
    let alone = |seed: &str| {
        let md = markdown(&[&sweep[..], &["--seed", seed, "--prediction", "bounded"]].concat());
        verdicts(md.split_once("## What the table shows").unwrap().1)
    };
    assert_eq!(verdicts(one), alone("1"));
    assert_eq!(verdicts(two), alone("3"));
    assert_ne!(
        verdicts(one),
        verdicts(paper.split_once("## What the table shows").unwrap().1)
    );
    // A table or JSON is one prediction's, as is every other one-station sweep: a second is refused,
    // not dropped.
    for args in [
        &[
            "sweep",
            "--distances",
            "2000",
            "--prediction",
            "paper,bounded",
        ][..],
        &["sweep", "--senders", "--prediction", "paper,bounded"],
    ] {
        let out = cli(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("takes one --prediction, not paper,bounded"),
            "{err}"
        );
    }
}

/// The option types' docs are both the API documentation and `--help`: a link written for
/// rustdoc ("[`TrackingAdr`]", "([`LISTEN_S`] at [`THRESHOLD_DBM`])") meant nothing to a CLI
/// user, who now reads words and numbers in its place.
#[test]
fn no_help_shows_rustdoc_link_syntax() {
    for command in [
        "airtime", "predict", "encode", "decode", "simulate", "sweep", "swarm",
    ] {
        let out = crate::cli(&[command, "--help"]);
        assert!(out.status.success(), "{command}");
        let help = String::from_utf8(out.stdout).unwrap();
        for syntax in ["[`", "`]", "](", "crate::", "super::"] {
            assert!(!help.contains(syntax), "{command} --help shows {syntax:?}");
        }
    }
}

/// Two runs that differ in one setting do not print the same header: every numeric setting of
/// the options table changed from its default is named above `simulate`'s table (a new one
/// fails here until the text words it or this list says where it is worded instead).
#[test]
fn simulates_header_names_every_numeric_setting_changed_from_its_default() {
    // Worded elsewhere, or with no effect on one drone at the defaults.
    let elsewhere = [
        ("distance", "the gateway line under the table"),
        ("gateway", "the gateway line (a site of --gateway)"),
        ("gateways", "the gateway lines, one per --gateway"),
        ("drones", "a swarm's"),
        ("duration", "a swarm's"),
        ("channels", "a swarm's header"),
        (
            "threshold",
            "the stations line, with --sender error (refused without)",
        ),
        (
            "maxInterval",
            "the stations line, with --sender error (refused without)",
        ),
        (
            "burst",
            "the stations line, with --duty-cycle-mode budget (refused without)",
        ),
        (
            "interval",
            "a plan without a duty cycle's (EU868 refuses it)",
        ),
        (
            "adrMargin",
            "the header's ADR, with --adr lorawan (refused without)",
        ),
        (
            "adrHistory",
            "the header's ADR, with --adr lorawan (refused without)",
        ),
        (
            "planTolerance",
            "the mission station's (refused without it)",
        ),
    ];
    let header = |extra: &[&str]| {
        let out = cli(&[&["simulate", "--synthetic", "1"][..], extra].concat());
        assert_eq!(out.status.code(), Some(0), "{extra:?}");
        let text = String::from_utf8(out.stdout).unwrap();
        text.lines()
            .take_while(|l| !l.starts_with("model "))
            .collect::<Vec<_>>()
            .join("\n")
    };
    let base = header(&[]);
    for o in loratrack::options::OPTIONS {
        if elsewhere.iter().any(|(key, _)| *key == o.key) {
            continue;
        }
        let other = match o.values.iter().find(|&&v| v != o.default) {
            Some(&v) => v,
            None if o.default + 1.0 <= o.max => o.default + 1.0,
            None => (o.min + o.default) / 2.0,
        };
        let value = loratrack::options::as_given(other);
        let flag = loratrack::options::long_option(o.key);
        let changed = header(&[&flag, &value]);
        assert_ne!(changed, base, "{flag} {value} prints the default's header");
    }
}
