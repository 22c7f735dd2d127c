//! Many drones sharing the air (the paper's future work; Mason et al.'s 2022 follow-up): the
//! one event loop ([`run_episode`]) with N drones around the gateways, then each drone's station
//! over what the network passed on.
//!
//! Without a flight chosen, each drone starts at `distance` from the centre in a random
//! direction and flies synthetic flights back to back for `duration` seconds from a random
//! first one, as before. With a flight chosen (`synthetic`, `sample`, `trajectory`), every drone
//! flies each of its flights in turn (one episode per flight), drone i starting at `distance`
//! from the centre at bearing 360°·i/N — so one drone flies exactly as `simulate` places it.

mod report;

pub use report::{DroneReport, LargestSwarm, SwarmEcho, SwarmReport};

use super::drone::{DroneFilter, Estimates};
use super::flier::Flier;
use super::network::{run_episode, Network};
use super::parallel::par_map;
use super::pooled::airtime;
use super::radio::DroneRadio;
use super::report::{ratio, Delivery, Energy};
use super::scenario::{SfPlan, SyntheticChoice, TrajectorySource, Validated};
use super::schedule::{self, aloha_collision_rate, Airtime, Schedule, Slot};
use super::simulator::load_flights;
use super::station::{new_tracker, track_station, Scoring, StationModel, StationSetup};
use super::streams::LAYOUT_STREAM;
use super::{SimError, Transmission};
use crate::lora::{time_on_air, AdrMode, LoraParams, Outcome};
use crate::math::sin_cos;
use crate::metrics::{percentile, sort_total, Summary, WholeFlightError};
use crate::options::MAX_SWARM_FILTER_STEPS;
use crate::rng::Rng;
use crate::trajectory::{chain_flights, Trajectory};
use core::f64::consts::TAU;
use std::sync::Arc;

/// Drones whose stations are computed between two progress reports.
const CHUNK: usize = 16;

/// One drone in one episode: which flight it flies, where that flight's first point lies from
/// the centre, and its random streams.
struct Seat {
    flight: usize,
    bearing: f64,
    stream: u64,
}

/// What every drone flies, episode by episode.
struct Plan {
    flights: Vec<Arc<Trajectory>>,
    episodes: Vec<Vec<Seat>>,
}

/// The episodes of a swarm (see the module documentation).
fn plan(cfg: &Validated) -> Result<Plan, SimError> {
    let s = cfg.s();
    let n = s.swarm.drones;
    let Some(source) = &cfg.source else {
        let set = load_flights(&TrajectorySource::Synthetic(SyntheticChoice::All))?;
        let mut layout = Rng::derive(s.run.seed, LAYOUT_STREAM);
        let firsts: Vec<(usize, f64)> = (0..n)
            .map(|_| {
                let first = ((layout.uniform() * set.len() as f64) as usize).min(set.len() - 1);
                (first, layout.uniform() * TAU)
            })
            .collect();
        // Drones chained from the same first flight fly the same chain: build each once.
        let stride = ((set[0].t[1] - set[0].t[0]).recip() / s.drone.sensor_rate)
            .round()
            .max(1.0) as usize;
        let mut chains: Vec<Option<usize>> = vec![None; set.len()];
        let mut flights = Vec::new();
        let mut seats = Vec::with_capacity(n);
        for (i, &(first, bearing)) in firsts.iter().enumerate() {
            let f = match chains[first] {
                Some(f) => f,
                None => {
                    flights.push(Arc::new(chain_flights(
                        &set,
                        first,
                        s.swarm.duration,
                        stride,
                    )?));
                    chains[first] = Some(flights.len() - 1);
                    flights.len() - 1
                }
            };
            seats.push(Seat {
                flight: f,
                bearing,
                stream: i as u64,
            });
        }
        return Ok(Plan {
            flights,
            episodes: vec![seats],
        });
    };
    let flights: Vec<Arc<Trajectory>> = load_flights(source)?.into_iter().map(Arc::new).collect();
    let count = flights.len();
    let episodes = (0..count)
        .map(|f| {
            (0..n)
                .map(|i| Seat {
                    flight: f,
                    bearing: TAU * i as f64 / n as f64,
                    stream: (i * count + f) as u64,
                })
                .collect()
        })
        .collect();
    Ok(Plan { flights, episodes })
}

/// The spreading factors the swarm deals out in turn, drone i taking entry i mod its length:
/// `fixed`, `sf` alone; `spread`, SF7..SF12, or those the plan has uplink data rates for at the
/// swarm's bandwidth (US915 at 125 kHz: SF7..SF10). A plan with none at that bandwidth gets `sf`,
/// which the plan then refuses with its reason.
fn swarm_sfs(cfg: &Validated) -> Vec<i64> {
    let s = cfg.s();
    let region = s.access.region;
    let spread: Vec<i64> = match s.swarm.sf_plan {
        SfPlan::Spread => (7..=12)
            .filter(|&sf| {
                region.allows_raw_lora()
                    || region
                        .rate(sf as u8, cfg.radio.bw)
                        .is_some_and(|r| r.max_payload.is_some())
            })
            .collect(),
        SfPlan::Fixed => Vec::new(),
    };
    if spread.is_empty() {
        vec![s.radio.sf]
    } else {
        spread
    }
}

/// The spreading factor of drone `i`, of the swarm's [`swarm_sfs`].
fn sf_of(sfs: &[i64], i: usize) -> i64 {
    sfs[i % sfs.len()]
}

/// Runs the swarm, calling `progress(done, total)` as episodes run and stations complete
/// (total = episodes + drones).
pub fn run_swarm(
    cfg: &Validated,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<SwarmReport, SimError> {
    let s = cfg.s();
    if s.run.seeds != 1 {
        return Err(SimError::Source(format!(
            "seeds repeats a simulate run; a swarm runs one seed (its drones already give its spread), got {}",
            s.run.seeds
        )));
    }
    let model = cfg.swarm_station()?;
    let n = s.swarm.drones;
    let plan = plan(cfg)?;
    let flown: f64 = plan
        .episodes
        .iter()
        .map(|e| {
            e.iter()
                .map(|seat| plan.flights[seat.flight].duration())
                .sum::<f64>()
        })
        .sum();
    let steps = flown * (s.drone.sensor_rate + 1.0 / s.station.step);
    if steps > MAX_SWARM_FILTER_STEPS as f64 {
        return Err(SimError::TooLong {
            flight_time: flown,
            steps,
        });
    }
    let bytes = model.payload_bytes() + s.radio.overhead;
    let sfs = swarm_sfs(cfg);
    let mut radios = Vec::with_capacity(n);
    let mut duty_cycles = Vec::with_capacity(n);
    for i in 0..n {
        let radio = LoraParams::from_settings(sf_of(&sfs, i), s.radio.bw, s.radio.cr)?;
        let (r, duty_cycle) = cfg.drone_radio(&radio, model)?;
        cfg.check_heartbeat(&r.current())?;
        radios.push(r);
        duty_cycles.push(duty_cycle);
    }
    let slots = slots(cfg, &radios)?;
    let setup = cfg.station_setup(0.0);
    let kits: Vec<Kit> = radios
        .iter()
        .enumerate()
        .map(|(i, r)| Kit {
            setup: StationSetup {
                interval: r.current().interval,
                ..setup
            },
            duty_cycle: duty_cycles[i],
            slot: slots.as_ref().map(|s| s[i]),
        })
        .collect();
    let mut net = Network::of(cfg, 0.0, radios);
    let total = plan.episodes.len() + n;
    let mut done = 0;
    // Per episode, per drone: its transmissions.
    let mut sent: Vec<Vec<Vec<Transmission>>> = Vec::new();
    // Listen-before-talk: deferrals, and collisions avoided.
    let mut lbt = (0, 0);
    for seats in &plan.episodes {
        sent.push(fly(cfg, &mut net, &plan, seats, model, &kits, &mut lbt)?);
        done += 1;
        progress(done, total);
    }
    let mut drones = Vec::with_capacity(n);
    let mut errors = Vec::new();
    let mut all_untracked = 0;
    let mut tx_all: Vec<&Transmission> = Vec::new();
    for chunk in (0..n.div_ceil(CHUNK)).map(|c| c * CHUNK..((c + 1) * CHUNK).min(n)) {
        let tracked = par_map(chunk.clone(), |i| {
            let (mut e3, mut untracked) = (Vec::new(), 0);
            for (seats, out) in plan.episodes.iter().zip(&sent) {
                let flight = &plan.flights[seats[i].flight];
                let mut tracker = new_tracker(model, kits[i].setup, None);
                // Only the error is kept: the covariance's calibration would change nothing.
                let scoring = Scoring {
                    step: s.station.step,
                    series: false,
                    calibrate: false,
                };
                let track = track_station(flight, tracker.as_mut(), &out[i], scoring);
                e3.extend(track.error3d);
                untracked += track.untracked;
            }
            (e3, untracked)
        });
        for (i, (mut e3, untracked)) in chunk.zip(tracked) {
            let mine: Vec<&Transmission> = sent.iter().flat_map(|ep| ep[i].iter()).collect();
            let mut channel_use = vec![0; usize::from(cfg.channels)];
            for t in &mine {
                channel_use[usize::from(t.channel)] += 1;
            }
            let time: f64 = plan
                .episodes
                .iter()
                .map(|ep| plan.flights[ep[i].flight].duration())
                .sum();
            errors.extend_from_slice(&e3);
            all_untracked += untracked;
            let error3d = Summary::of(&mut e3);
            drones.push(DroneReport {
                id: i,
                sf: sf_of(&sfs, i) as u8,
                bearing_deg: plan.episodes[0][i].bearing.to_degrees(),
                channel_use,
                packets_sent: mine.len(),
                packets_received: mine.iter().filter(|t| t.received).count(),
                packets_collided: mine
                    .iter()
                    .filter(|t| t.outcome == Outcome::Collided)
                    .count(),
                energy: Energy::of(mine.iter().copied(), time),
                duty_cycle_used: mine.iter().map(|t| t.time_on_air).sum::<f64>() / time,
                frame_length: kits[i].slot.map(|s| s.frame),
                error3d,
                // Summary::of left e3 sorted.
                whole_flight: WholeFlightError::of_sorted(&e3, untracked),
            });
            tx_all.extend(mine);
        }
        done = plan.episodes.len() + drones.len();
        progress(done, total);
    }
    let largest = largest_swarm(cfg, &sfs, bytes)?;
    let mut r = report(
        cfg,
        model,
        &net,
        &tx_all,
        drones,
        (errors, all_untracked),
        largest,
    );
    r.frame_length = slots.map(|s| s.iter().map(|s| s.frame).fold(0.0, f64::max));
    if net.listen_before_talk {
        (r.lbt_deferrals, r.lbt_collisions_avoided) = (Some(lbt.0), Some(lbt.1));
    }
    Ok(r)
}

/// [`LargestSwarm`] at `cfg`'s settings, the swarm dealing out `sfs`, for packets of `bytes`.
fn largest_swarm(cfg: &Validated, sfs: &[i64], bytes: usize) -> Result<LargestSwarm, SimError> {
    let s = cfg.s();
    let timing = s.access.swarm_timing();
    let (mut toa, mut interval, mut used) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    for &sf in sfs {
        let radio = LoraParams::from_settings(sf, s.radio.bw, s.radio.cr)?;
        let k = (sf - 7) as usize;
        toa[k] = time_on_air(&radio, bytes)?.time_on_air;
        interval[k] = toa[k] / cfg.duty_cycle_for(toa[k])?;
        // A random delay of up to J s lengthens the mean interval by J / 2.
        used[k] = toa[k] / (interval[k] + timing.jitter / 2.0);
    }
    let sf_of = |i: usize| sf_of(sfs, i) as u8;
    let ch = cfg.channels;
    Ok(LargestSwarm {
        aloha1: schedule::largest_aloha(sf_of, &toa, &used, ch, 0.01),
        aloha10: schedule::largest_aloha(sf_of, &toa, &used, ch, 0.10),
        slotted: schedule::largest_slotted(sf_of, &toa, &interval, ch, timing.clock_drift_ppm),
    })
}

/// What one drone of the swarm keeps through its episodes: its station's setup, the duty cycle
/// its rule enforces and its slot, if the schedule gives it one.
struct Kit {
    setup: StationSetup,
    duty_cycle: f64,
    slot: Option<Slot>,
}

/// Each drone's slot under a slotted schedule; `None` for ALOHA.
fn slots(cfg: &Validated, radios: &[DroneRadio]) -> Result<Option<Vec<Slot>>, SimError> {
    let s = cfg.s();
    if s.access.schedule == Schedule::Aloha {
        return Ok(None);
    }
    if cfg.adr.mode != AdrMode::Off {
        return Err(SimError::Source(
            "a slotted schedule sizes each slot for a drone's data rate: it cannot run with adr, which moves drones between rates".into(),
        ));
    }
    let air: Vec<Airtime> = radios
        .iter()
        .map(|r| Airtime {
            sf: r.current().sf.get(),
            time_on_air: r.current().time_on_air,
            interval: r.current().interval,
        })
        .collect();
    Ok(Some(schedule::assign(
        &air,
        cfg.channels,
        s.access.swarm_timing().clock_drift_ppm,
    )))
}

/// One episode: every drone's filter, sender and links through the event loop.
fn fly(
    cfg: &Validated,
    net: &mut Network,
    plan: &Plan,
    seats: &[Seat],
    model: StationModel,
    kits: &[Kit],
    lbt: &mut (usize, usize),
) -> Result<Vec<Vec<Transmission>>, SimError> {
    let s = cfg.s();
    let seed = s.run.seed;
    let mut fliers = Vec::with_capacity(seats.len());
    for (i, seat) in seats.iter().enumerate() {
        let flight: &Trajectory = &plan.flights[seat.flight];
        let (sb, cb) = sin_cos(seat.bearing);
        let p0 = flight.pos[0];
        // The centre, in this drone's flight frame: `distance` from its first point along the
        // bearing.
        let centre = [
            p0[0] + s.channel.distance * cb,
            p0[1] + s.channel.distance * sb,
        ];
        let now = net.radios[i].current();
        let filter = DroneFilter::new(
            flight,
            model.sent_model(),
            s.drone.sensor_rate,
            s.drone.q,
            &cfg.r_diagonal,
            seed,
            seat.stream,
        );
        let stream = seat.stream;
        let flier = Flier::new(
            i,
            flight,
            Estimates::live(filter),
            s.sending.sender(model, kits[i].setup, None),
            s.sending.rule(kits[i].duty_cycle, now.time_on_air)?,
            &net.gateways_at(centre),
            &net.channel,
            (seed, stream),
            cfg.channels,
            now.interval,
            s.access.swarm_timing(),
        );
        let flier = flier.with_origin([centre[0], centre[1], 0.0]);
        fliers.push(match &kits[i].slot {
            Some(slot) => flier.with_slot(slot),
            None => flier,
        });
    }
    run_episode(net, &mut fliers);
    for f in &fliers {
        lbt.0 += f.lbt_deferrals;
        lbt.1 += f.lbt_avoided;
    }
    Ok(fliers.into_iter().map(|f| f.tx).collect())
}

/// The swarm's report from its drones' reports, every drone's errors pooled with the number of
/// evaluation times before an episode's first packet (`errors`), and the network's counts.
fn report(
    cfg: &Validated,
    model: StationModel,
    net: &Network,
    tx: &[&Transmission],
    drones: Vec<DroneReport>,
    (mut errors, untracked): (Vec<f64>, usize),
    largest_swarm: LargestSwarm,
) -> SwarmReport {
    let s = cfg.s();
    let count = |o: Outcome| tx.iter().filter(|t| t.outcome == o).count();
    let packets_sent = tx.len();
    let received = count(Outcome::Received);
    // Theory per SF group at the duty cycle the group achieved, weighted by the packets each
    // group sent.
    let mut theory = 0.0;
    for sf in 7..=12u8 {
        let group: Vec<&DroneReport> = drones.iter().filter(|d| d.sf == sf).collect();
        if group.is_empty() {
            continue;
        }
        let packets: usize = group.iter().map(|d| d.packets_sent).sum();
        let used = group.iter().map(|d| d.duty_cycle_used).sum::<f64>() / group.len() as f64;
        theory += packets as f64 * aloha_collision_rate(used, cfg.channels, group.len());
    }
    let mut p75s: Vec<f64> = drones
        .iter()
        .filter(|d| d.error3d.count > 0)
        .map(|d| d.error3d.p75)
        .collect();
    sort_total(&mut p75s);
    let nd = drones.len().max(1) as f64;
    SwarmReport {
        config: SwarmEcho {
            settings: s.clone(),
            station: model,
            bandwidth_khz: s.radio.bw,
        },
        frame_length: None,
        largest_swarm,
        lbt_deferrals: None,
        lbt_collisions_avoided: None,
        collision_rate: ratio(count(Outcome::Collided), packets_sent),
        collision_rate_theory: if packets_sent == 0 {
            0.0
        } else {
            theory / packets_sent as f64
        },
        delivery: Delivery {
            packets_sent,
            packets_received: received,
            delivery_ratio: ratio(received, packets_sent),
            duplicates: net.duplicates,
            gateways: net.gateways.clone(),
        },
        packets_collided: count(Outcome::Collided),
        packets_below_sensitivity: count(Outcome::BelowSensitivity),
        packets_no_demodulator: count(Outcome::NoDemodulator),
        airtime: airtime(tx.iter().copied()),
        error3d: Summary::of(&mut errors),
        whole_flight: WholeFlightError::of_sorted(&errors, untracked),
        median_drone_p75: percentile(&p75s, 50.0),
        energy: Energy {
            charge_per_uplink: drones
                .iter()
                .map(|d| d.energy.charge_per_uplink)
                .sum::<f64>()
                / nd,
            charge_per_hour: drones.iter().map(|d| d.energy.charge_per_hour).sum::<f64>() / nd,
        },
        drones,
    }
}
