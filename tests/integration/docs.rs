//! Generated documents stay what their commands generate, and the README says what the CLI and the
//! flights give (its transcript, its network numbers, its flights' statistics): a checked-in table that the code no
//! longer produces would be a claim nobody can reproduce. The commands are read from
//! `package.json`'s scripts (`cargo run --release --quiet -- ARGS > FILE`), so the test runs
//! exactly what `npm run NAME` runs. Only the quickest one is checked here (`reproduce`, ~30 s); the
//! sweeps that take from 20 s to minutes (`adr`, `senders`, `mission`, `payloads`, `swarm`) are regenerated
//! by running their scripts.

use std::path::Path;

/// Each `cargo run ... -- ARGS > FILE` of the script `name`: the CLI's arguments and the file.
fn generators(name: &str) -> Vec<(Vec<String>, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let package: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("package.json")).unwrap()).unwrap();
    let script = package["scripts"][name]
        .as_str()
        .unwrap_or_else(|| panic!("package.json has no script {name}"));
    script
        .split("&&")
        .map(|command| {
            let (run, file) = command
                .split_once('>')
                .unwrap_or_else(|| panic!("{name}: {command:?} writes no file"));
            let (_, args) = run
                .split_once(" -- ")
                .unwrap_or_else(|| panic!("{name}: {command:?} is not `cargo run ... -- ARGS`"));
            let args = args.split_whitespace().map(str::to_string).collect();
            (args, file.trim().to_string())
        })
        .collect()
}

#[test]
fn the_paper_reproduction_document_is_what_npm_run_reproduce_writes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for (args, file) in generators("reproduce") {
        let out = crate::cli(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let checked_in = std::fs::read_to_string(root.join(&file)).unwrap();
        assert!(
            String::from_utf8_lossy(&out.stdout) == checked_in,
            "{file} is not what `npm run reproduce` writes now: run it and commit the result"
        );
    }
}

/// `file` (from the crate's root) with each run of whitespace one space, so that a sentence found
/// in it may wrap anywhere.
fn prose(file: &str) -> String {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(file)).unwrap();
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The CLI's JSON for `args`.
fn json(args: &[&str]) -> serde_json::Value {
    let out = crate::cli(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn every_readme_transcript_is_what_the_cli_prints() {
    // In a ```sh block, "$ loratrack ARGS" and the lines up to the next "$" or the block's end.
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"));
    let readme = readme.unwrap();
    let mut transcripts = 0;
    for block in readme.split("```sh\n").skip(1) {
        let block = block.split("```").next().unwrap();
        for transcript in block.split("$ loratrack ").skip(1) {
            let (command, shown) = transcript.split_once('\n').unwrap();
            let args: Vec<&str> = command.split_whitespace().collect();
            let out = crate::cli(&args);
            assert!(out.status.success(), "loratrack {command}");
            assert_eq!(
                String::from_utf8_lossy(&out.stdout),
                shown,
                "the README shows another output for `loratrack {command}`"
            );
            transcripts += 1;
        }
    }
    assert!(transcripts > 0, "the README shows no `$ loratrack` run");
}

#[test]
fn the_readme_gateway_and_downlink_numbers_are_what_the_cli_prints() {
    let one = json(&["swarm", "--drones", "72", "--distance", "2000", "--json"]);
    let three = json(&[
        "swarm",
        "--drones",
        "72",
        "--distance",
        "2000",
        "--gateway",
        "0,0",
        "--gateway",
        "3000,0",
        "--gateway",
        "-1500,2600",
        "--json",
    ]);
    let percent = |r: &serde_json::Value| 100.0 * r["deliveryRatio"].as_f64().unwrap();
    let (readme, beyond) = (prose("README.md"), prose("docs/beyond-the-paper.md"));
    let claims = [
        (
            &readme,
            format!(
                "`loratrack swarm --drones 72 --distance 2000` (10 minutes, SF7–SF12 in turn, three channels): one \
                 gateway at the centre delivers {} of {} packets ({:.1} %); with `--gateway 0,0 --gateway 3000,0 \
                 --gateway -1500,2600` {} ({:.1} %), and the server removes {} duplicate copies",
                one["packetsReceived"],
                one["packetsSent"],
                percent(&one),
                three["packetsReceived"],
                percent(&three),
                three["duplicates"],
            ),
        ),
        (
            &readme,
            format!(
                "72 drones at 2 km, {:.1} % → {:.1} % with three",
                percent(&one),
                percent(&three)
            ),
        ),
        (
            &beyond,
            format!(
                "72 drones at 2 km: {:.1} % with one gateway, {:.1} % with three",
                percent(&one),
                percent(&three)
            ),
        ),
    ];
    let adr = json(&[
        "swarm",
        "--drones",
        "60",
        "--duration",
        "600",
        "--adr",
        "lorawan",
        "--sf-plan",
        "fixed",
        "--sf",
        "7",
        "--bw",
        "125",
        "--json",
    ]);
    let count = |key: &str| -> u64 {
        adr["gateways"]
            .as_array()
            .unwrap()
            .iter()
            .map(|g| g[key].as_u64().unwrap())
            .sum()
    };
    let (sent, dropped) = (count("downlinksSent"), count("downlinksDropped"));
    let downlinks = [
        format!(
            "`swarm --drones 60 --duration 600 --adr lorawan --sf-plan fixed --sf 7 --bw 125`, of the {} downlinks \
             the network server wants to send",
            sent + dropped
        ),
        format!("the gateway's duty cycle lets {sent} go in RX1 or RX2 and drops {dropped}"),
    ];
    for (text, claim) in claims
        .iter()
        .map(|(text, claim)| (*text, claim))
        .chain(downlinks.iter().map(|claim| (&readme, claim)))
    {
        assert!(
            text.contains(claim.as_str()),
            "the docs no longer say what the CLI prints: {claim}"
        );
    }
}

/// The mean, the 95th percentile and the largest of `values`.
fn spread(mut values: Vec<f64>) -> (f64, f64, f64) {
    values.sort_by(f64::total_cmp);
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let p95 = loratrack::percentile(&values, 95.0);
    (mean, p95, values[values.len() - 1])
}

#[test]
fn the_readme_describes_the_flights_as_they_are() {
    let set = loratrack::synthetic_set();
    let states = || set.iter().flat_map(|f| (0..f.len()).map(|i| f.state(i)));
    let (speed, speed_p95, speed_max) = spread(states().map(|s| s[5]).collect());
    let (_, turn_p95, turn_max) = spread(states().map(|s| s[7].abs()).collect());
    let (_, climb_p95, climb_max) = spread(
        set.iter()
            .flat_map(|f| f.vel.iter().map(|v| v[2].abs()))
            .collect(),
    );
    let hovering = states().filter(|s| s[5] < 0.5).count() as f64 / states().count() as f64;
    let durations: Vec<f64> = set.iter().map(|f| f.duration()).collect();
    let (shortest, longest) = durations
        .iter()
        .fold((f64::MAX, 0.0f64), |(lo, hi), &d| (lo.min(d), hi.max(d)));
    let canberra = loratrack::canberra_flight();
    let rate = (canberra.len() - 1) as f64 / canberra.duration();
    let fastest = (0..canberra.len())
        .map(|i| canberra.state(i)[5])
        .fold(0.0, f64::max);
    let readme = prose("README.md");
    for claim in [
        format!(
            "30 seeded flights, {:.0} s ({:.0} min) in all, {:.0}–{:.0} s each, at 100 Hz",
            durations.iter().sum::<f64>(),
            durations.iter().sum::<f64>() / 60.0,
            shortest,
            longest
        ),
        format!(
            "Speed mean {speed:.1} m/s, p95 {speed_p95:.1}, max {speed_max:.1}; |turn rate| p95 \
             {turn_p95:.2} rad/s, max {turn_max:.2}; |climb rate| p95 {climb_p95:.1} m/s, max \
             {climb_max:.1}; hovering (< 0.5 m/s) {:.1} % of the time",
            100.0 * hovering
        ),
        format!(
            "{:.0} s at {rate:.0} Hz, speeds to {fastest:.1} m/s",
            canberra.duration()
        ),
    ] {
        assert!(
            readme.contains(&claim),
            "the README's Flights no longer say: {claim}"
        );
    }
}
