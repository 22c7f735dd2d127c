//! The native integration suites: one module per concern, built and linked as one test binary.
//!
//! Each file of `tests/` used to be a binary of its own, and every one of them linked the whole
//! crate and its dependencies, optimised (Cargo's `test` profile): fifteen links and fifteen
//! copies of the same generic code on a 2-core machine, most of `cargo test`'s build time.
#![cfg(not(target_arch = "wasm32"))]

use std::process::{Command, Output, Stdio};

/// The `loratrack` binary run with `args` (no input on stdin): its status and output.
pub(crate) fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_loratrack"))
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("the CLI runs")
}

/// `loratrack <command> --help` as one line: clap wraps the help to the terminal's width, so a
/// sentence in it may wrap anywhere.
pub(crate) fn cli_help(command: &str) -> String {
    let out = cli(&[command, "--help"]);
    assert!(out.status.success());
    String::from_utf8(out.stdout)
        .unwrap()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The network of one drone sending `bytes`-byte frames at `radio` under `duty_cycle`, without
/// ADR: one gateway 1 km east of the flight's first point, the default channel, capture and
/// inter-SF interference on.
pub(crate) fn one_gateway(
    radio: &loratrack::LoraParams,
    bytes: usize,
    duty_cycle: f64,
) -> loratrack::Network {
    use loratrack::{
        AdrMode, AdrParams, Channel, ChannelParams, DroneRadio, GatewaySite, InterferenceModel,
        Network, NetworkSetup,
    };
    let setup = NetworkSetup {
        sites: vec![GatewaySite {
            east: 1000.0,
            north: 0.0,
            height: None,
        }],
        default_height: 15.0,
        adr: AdrParams::default(),
        channel: Channel::new(ChannelParams::default()).unwrap(),
        interference: InterferenceModel {
            capture: true,
            inter_sf: true,
        },
        lorawan: false,
        listen_before_talk: false,
    };
    let drone = DroneRadio::new(radio, bytes, duty_cycle, AdrMode::Off).unwrap();
    Network::new(setup, vec![drone])
}

mod adr;
mod architecture;
mod codec;
mod docs;
mod filter;
mod lora;
mod mission;
mod models;
mod network;
mod payload;
mod region;
mod robustness;
mod schedule;
mod sender;
mod shadowing;
mod sim;
mod station;
mod swarm;
