//! Embeds the bundled real flight without the columns loratrack does not read (roll, pitch,
//! yaw): a third less text in every binary and in the WebAssembly module, the same flight. Sets
//! `cfg(cli)` for the command line's derives.

use std::{env, fs, path::Path};

const SOURCE: &str = "data/ardupilot-log171-quad-canberra.csv";
const UNUSED: [&str; 3] = ["roll_rad", "pitch_rad", "yaw_rad"];

fn main() {
    // `cfg(cli)`: the command line's derives on the core's option types, natively, with the `cli`
    // feature (clap is not a WebAssembly dependency).
    println!("cargo::rustc-check-cfg=cfg(cli)");
    let wasm = env::var("CARGO_CFG_TARGET_ARCH").is_ok_and(|arch| arch == "wasm32");
    if env::var_os("CARGO_FEATURE_CLI").is_some() && !wasm {
        println!("cargo::rustc-cfg=cli");
    }
    println!("cargo:rerun-if-changed={SOURCE}");
    let text = fs::read_to_string(SOURCE).expect("the bundled flight is part of the crate");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let keep: Vec<usize> = (0..header.len())
        .filter(|&i| !UNUSED.contains(&header[i].trim()))
        .collect();
    let pick = |line: &str| {
        let cells: Vec<&str> = line.split(',').collect();
        keep.iter()
            .map(|&i| cells.get(i).copied().unwrap_or(""))
            .collect::<Vec<_>>()
            .join(",")
    };
    let mut out = pick(&header.join(","));
    for line in lines {
        out.push('\n');
        out.push_str(&pick(line));
    }
    out.push('\n');
    let dest = Path::new(&env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("canberra.csv");
    fs::write(dest, out).expect("OUT_DIR is writable");
}
