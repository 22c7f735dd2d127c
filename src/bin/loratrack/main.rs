//! `loratrack`: the command-line skin over [`loratrack::api`] (SPEC §8).
//!
//! Every command prints a human summary, or with `--json` exactly one JSON object on stdout.
//! Bad input exits with status 2 and one line `error: ...` on stderr.

#[cfg(not(target_arch = "wasm32"))]
mod commands;
#[cfg(not(target_arch = "wasm32"))]
mod reproduction;

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    use clap::Parser;
    use std::process::ExitCode;

    /// Remote UAV tracking over LoRa: airtime, motion models, payload codec and tracking
    /// simulation (Mason et al., LoRaWAN + 3D-CTRA).
    #[derive(Parser)]
    #[command(name = "loratrack", version, about, propagate_version = true)]
    struct Cli {
        #[command(subcommand)]
        command: commands::Command,
    }

    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // --help and --version are not errors; clap prints them and exits 0.
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match commands::run(cli.command) {
        Ok(text) => {
            println!("{text}");
            ExitCode::SUCCESS
        }
        Err(msg) => {
            eprintln!("error: {msg}");
            ExitCode::from(2)
        }
    }
}

/// The CLI is native only; `cargo test --target wasm32-unknown-unknown` builds every binary
/// target, so wasm32 gets this stub.
#[cfg(target_arch = "wasm32")]
fn main() {}
