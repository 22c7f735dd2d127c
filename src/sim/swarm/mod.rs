//! Many drones, one gateway (the paper's future work; Mason et al.'s 2022 follow-up): every drone
//! flies its own chain of synthetic flights, runs its own UKF and sender, and all share one
//! gateway, where overlapping packets collide.
//!
//! The drones' senders do not hear the gateway (unconfirmed uplinks, no ADR), so each drone's
//! transmissions can be scheduled on its own; the gateway then resolves every packet of every
//! drone on one time axis ([`Gateway::resolve`]), and each station sees only what survived. That
//! is exactly the time-ordered event loop, without its bookkeeping.

mod params;
mod report;

pub use params::{SfPlan, SwarmConfig, SwarmParams, MAX_DRONES, MAX_SWARM_DURATION};
pub use report::{aloha_collision_rate, DroneReport, SwarmEcho, SwarmReport};

use super::link::{schedule_transmissions, LinkSetup, Transmission};
use super::parallel::par_map;
use super::station::{new_tracker, track_station, Bounds, StationSetup};
use super::{run_drone, SimError};
use crate::lora::{
    min_interval, time_on_air, Gateway, LoraParams, Outcome, Uplink, SX1301_DEMODULATORS,
};
use crate::metrics::{percentile, Summary};
use crate::rng::Rng;
use crate::trajectory::{chain_flights, synthetic_set, Trajectory};
use core::f64::consts::TAU;

/// EU868's 1 % in 868.0–868.6 MHz, where the three default channels lie.
const DUTY_CYCLE: f64 = 0.01;
/// Drone sensor rate, Hz; the chained flights are kept at this rate.
const SENSOR_RATE: f64 = 10.0;
/// Station step T, s, and tilt decay (paper defaults).
const STEP: f64 = 0.1;
const ETA: f64 = 0.9;
/// Random streams, separate from the drones' sensor noise for the same seed.
const LAYOUT_STREAM: u64 = 0x4C41_594F; // "LAYO"
const LINK_STREAM: u64 = 0x4C49_4E4B; // "LINK", as in `simulate`
const CHANNEL_STREAM: u64 = 0x4348_414E; // "CHAN"
/// Drones computed between two progress reports.
const CHUNK: usize = 16;

/// Where drone `i` starts and what it flies.
struct Placement {
    first_flight: usize,
    bearing: f64,
}

/// What pass 1 leaves for the gateway and the stations.
struct Sent {
    sf: u8,
    time_on_air: f64,
    setup: StationSetup,
    tx: Vec<Transmission>,
    channels: Vec<u8>,
}

/// Runs the swarm, calling `progress(done, total)` as drones complete each of the two passes
/// (total = 2 × drones).
pub fn run_swarm(
    cfg: &SwarmConfig,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<SwarmReport, SimError> {
    let p = &cfg.params;
    let set = synthetic_set();
    let mut layout = Rng::derive(p.seed, LAYOUT_STREAM);
    let placements: Vec<Placement> = (0..p.drones)
        .map(|_| Placement {
            first_flight: ((layout.uniform() * set.len() as f64) as usize).min(set.len() - 1),
            bearing: layout.uniform() * TAU,
        })
        .collect();
    let total = 2 * p.drones;
    let mut sent: Vec<Sent> = Vec::with_capacity(p.drones);
    for chunk in chunked(p.drones) {
        for s in par_map(chunk, |i| send(cfg, &set, &placements[i], i)) {
            sent.push(s?);
        }
        progress(sent.len(), total);
    }
    let outcomes = resolve(cfg, &mut sent);
    let mut drones = Vec::with_capacity(p.drones);
    let mut errors = Vec::new();
    for chunk in chunked(p.drones) {
        for (i, e3) in chunk.clone().zip(par_map(chunk, |i| {
            track(cfg, &set, &placements[i], &sent[i])
        })) {
            let mut e3 = e3?;
            let s = &sent[i];
            let mut channel_use = vec![0; usize::from(p.channels)];
            for &c in &s.channels {
                channel_use[usize::from(c)] += 1;
            }
            errors.extend_from_slice(&e3);
            drones.push(DroneReport {
                id: i,
                sf: s.sf,
                bearing_deg: placements[i].bearing.to_degrees(),
                channel_use,
                packets_sent: s.tx.len(),
                packets_received: s.tx.iter().filter(|t| t.received).count(),
                packets_collided: outcomes[i]
                    .iter()
                    .filter(|o| **o == Outcome::Collided)
                    .count(),
                error3d: Summary::of(&mut e3),
            });
        }
        progress(p.drones + drones.len(), total);
    }
    Ok(report(cfg, &sent, &outcomes, drones, errors))
}

fn chunked(n: usize) -> impl Iterator<Item = core::ops::Range<usize>> {
    (0..n.div_ceil(CHUNK)).map(move |c| c * CHUNK..((c + 1) * CHUNK).min(n))
}

fn flight(set: &[Trajectory], cfg: &SwarmConfig, at: &Placement) -> Result<Trajectory, SimError> {
    let stride = ((set[0].t[1] - set[0].t[0]).recip() / SENSOR_RATE)
        .round()
        .max(1.0) as usize;
    Ok(chain_flights(
        set,
        at.first_flight,
        cfg.params.duration,
        stride,
    )?)
}

/// Pass 1 for drone `i`: its flight, UKF, sender under the duty-cycle rule, channel and power.
fn send(cfg: &SwarmConfig, set: &[Trajectory], at: &Placement, i: usize) -> Result<Sent, SimError> {
    let p = &cfg.params;
    let flight = flight(set, cfg, at)?;
    let sf = cfg.sf_of(i);
    let radio = LoraParams::from_settings(sf, p.bw, 1)?;
    let toa = time_on_air(&radio, cfg.model.payload_bytes() + p.overhead)?.time_on_air;
    let interval = min_interval(toa, DUTY_CYCLE)?;
    let (q, r) = cfg.noise();
    let setup = StationSetup {
        prediction: p.prediction,
        bounds: Bounds::default(),
        step: STEP,
        eta: ETA,
        q,
        r_diagonal: r,
        interval,
    };
    let link = LinkSetup {
        sf: radio.sf,
        bw: radio.bw,
        channel: cfg.channel,
        time_on_air: toa,
        interval,
        distance: p.distance,
        bearing: at.bearing,
    };
    let drone = run_drone(
        &flight,
        cfg.model.sent_model(),
        SENSOR_RATE,
        q,
        &r,
        p.seed,
        i as u64,
    );
    let sending = p.sending();
    let mut rule = sending.rule(DUTY_CYCLE, toa, flight.t[0])?;
    // Drones on slow SFs cannot send as often as the heartbeat asks: theirs is their interval.
    let heartbeat = p.max_interval.max(interval);
    let mut sender = sending.sender(cfg.model, setup, heartbeat);
    let mut rng = Rng::derive(p.seed ^ LINK_STREAM, i as u64);
    let tx = schedule_transmissions(
        &flight,
        &drone,
        &link,
        sender.as_mut(),
        &mut rule,
        &mut rng,
        None,
    );
    let mut hop = Rng::derive(p.seed ^ CHANNEL_STREAM, i as u64);
    let c = f64::from(p.channels);
    let channels = tx
        .iter()
        .map(|_| ((hop.uniform() * c) as u8).min(p.channels - 1))
        .collect();
    Ok(Sent {
        sf: radio.sf.get(),
        time_on_air: toa,
        setup,
        tx,
        channels,
    })
}

/// The gateway's verdict on every packet of every drone; marks the survivors received.
fn resolve(cfg: &SwarmConfig, sent: &mut [Sent]) -> Vec<Vec<Outcome>> {
    let uplinks: Vec<Uplink> = sent
        .iter()
        .flat_map(|s| {
            s.tx.iter().zip(&s.channels).map(|(t, &channel)| Uplink {
                start: t.sent,
                end: t.arrival,
                channel,
                sf: s.sf,
                rx_dbm: t.rx_power_dbm,
                audible: t.received,
            })
        })
        .collect();
    let gateway = Gateway {
        interference: cfg.interference,
        demodulators: SX1301_DEMODULATORS,
    };
    let mut all = gateway.resolve(&uplinks).into_iter();
    sent.iter_mut()
        .map(|s| {
            let mine: Vec<Outcome> = all.by_ref().take(s.tx.len()).collect();
            for (t, o) in s.tx.iter_mut().zip(&mine) {
                t.received = *o == Outcome::Received;
            }
            mine
        })
        .collect()
}

/// Pass 2 for one drone: its station over what the gateway received; the 3D errors.
fn track(
    cfg: &SwarmConfig,
    set: &[Trajectory],
    at: &Placement,
    s: &Sent,
) -> Result<Vec<f64>, SimError> {
    let flight = flight(set, cfg, at)?;
    let mut tracker = new_tracker(cfg.model, s.setup);
    Ok(track_station(&flight, tracker.as_mut(), &s.tx, STEP, false).error3d)
}

fn report(
    cfg: &SwarmConfig,
    sent: &[Sent],
    outcomes: &[Vec<Outcome>],
    drones: Vec<DroneReport>,
    mut errors: Vec<f64>,
) -> SwarmReport {
    let p = &cfg.params;
    let count = |o: Outcome| outcomes.iter().flatten().filter(|x| **x == o).count();
    let packets_sent: usize = sent.iter().map(|s| s.tx.len()).sum();
    let ratio = |n: usize| {
        if packets_sent == 0 {
            0.0
        } else {
            n as f64 / packets_sent as f64
        }
    };
    // Theory per SF group, weighted by the packets each group sent.
    let mut theory = 0.0;
    for sf in 7..=12u8 {
        let group: Vec<&Sent> = sent.iter().filter(|s| s.sf == sf).collect();
        let packets: usize = group.iter().map(|s| s.tx.len()).sum();
        theory += packets as f64 * aloha_collision_rate(DUTY_CYCLE, p.channels, group.len());
    }
    let mut p75s: Vec<f64> = drones
        .iter()
        .filter(|d| d.error3d.count > 0)
        .map(|d| d.error3d.p75)
        .collect();
    p75s.sort_by(f64::total_cmp);
    SwarmReport {
        config: SwarmEcho::of(p, DUTY_CYCLE),
        collision_rate: ratio(count(Outcome::Collided)),
        collision_rate_theory: if packets_sent == 0 {
            0.0
        } else {
            theory / packets_sent as f64
        },
        delivery_ratio: ratio(count(Outcome::Received)),
        packets_sent,
        packets_received: count(Outcome::Received),
        packets_collided: count(Outcome::Collided),
        packets_below_sensitivity: count(Outcome::BelowSensitivity),
        packets_no_demodulator: count(Outcome::NoDemodulator),
        airtime: sent.iter().map(|s| s.tx.len() as f64 * s.time_on_air).sum(),
        error3d: Summary::of(&mut errors),
        median_drone_p75: percentile(&p75s, 50.0),
        drones,
    }
}
