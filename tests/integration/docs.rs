//! Generated documents stay what their commands generate: a checked-in table that the code no
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
