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
mod sf_plan;
mod shared_runs;

pub use report::{DroneReport, LargestSwarm, SwarmEcho, SwarmReport, SwarmSaturation};
pub use sf_plan::SfLimit;
pub use shared_runs::SharedDroneRuns;
use shared_runs::SharedRun;

use super::drone::{DroneFilter, Estimates, Sensing};
use super::flier::{Aboard, Air, Flier};
use super::network::{run_episode, Network};
use super::pooled::{airtime, RateTally};
use super::radio::DroneRadio;
use super::report::{ratio, Delivery, Energy};
use super::scenario::{SfPlan, SyntheticChoice, TrajectorySource, Validated};
use super::schedule::{self, aloha_collision_rate, Airtime, Schedule, Slot};
use super::sender::LeanPayload;
use super::simulator::load_flights;
use super::station::{
    new_tracker, track_station_recalling, ForecastMemo, Scoring, StationModel, StationSetup,
};
use super::streams::{DroneStreams, LAYOUT_STREAM};
use super::{Caveats, LongRun, Saturation, SimError, Transmission};
use crate::lora::{time_on_air, AdrMode, LoraParams, Outcome};
use crate::math::sin_cos;
use crate::metrics::{percentile, sort_total, Summary, WholeFlightError};
use crate::options::{DURATION, MAX_SWARM_FILTER_STEPS, SF};
use crate::parallel::par_map;
use crate::rng::Rng;
use crate::trajectory::{chain_flights, FlightPlan, Trajectory};
use core::f64::consts::TAU;
use sf_plan::SfDeal;
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

impl Plan {
    /// Seconds each drone flies, over all its episodes, the mean over the drones (a chained
    /// flight lasts `duration`, give or take a sample).
    fn flight_time(&self) -> f64 {
        let drones = self.episodes.first().map_or(0, Vec::len).max(1);
        let total: f64 = self
            .episodes
            .iter()
            .flatten()
            .map(|seat| self.flights[seat.flight].duration())
            .sum();
        total / drones as f64
    }
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

/// Runs the swarm, calling `progress(done, total)` as episodes run and stations complete. The
/// two halves weigh alike (each is about half a swarm's work: the drones' filters in the loop,
/// their stations after it): each episode counts `drones` units, by its clock, and each drone's
/// station `episodes` units (total = 2 · episodes · drones).
pub fn run_swarm(
    cfg: &Validated,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<SwarmReport, SimError> {
    run_swarm_stoppable(cfg, &mut |done, total| {
        progress(done, total);
        true
    })
}

/// [`run_swarm`], where `progress` also says whether to go on: once it returns `false` the swarm
/// stops where it is (in its event loop, after the group of drones whose estimates it is
/// computing ahead; among its stations, before the next chunk of drones) with
/// [`SimError::Stopped`]. Nothing of a swarm outlives it, so the next one runs as it would have.
/// The page stops this way a swarm its panel's Stop button ends, that its panel runs again, or
/// whose page closed (`docs/reference.md` §9).
pub fn run_swarm_stoppable(
    cfg: &Validated,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<SwarmReport, SimError> {
    run_swarm_sharing(cfg, None, progress)
}

/// [`run_swarm_stoppable`], its drones' filter runs taken from `shared` (and left there for the
/// next swarm) where it holds them: the same report, bit for bit, with less work for a family of
/// swarms over the same drones.
pub fn run_swarm_sharing(
    cfg: &Validated,
    shared: Option<&SharedDroneRuns>,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<SwarmReport, SimError> {
    let (mut swarm, mut net) = Swarm::new(cfg)?;
    swarm.shared = shared;
    let (episodes, n) = (swarm.plan.episodes.len(), swarm.kits.len());
    let total = 2 * episodes * n;
    // Per episode, per drone: its transmissions, and its filter run where shared.
    let mut sent: Vec<Vec<Vec<Transmission>>> = Vec::with_capacity(episodes);
    let mut runs: Vec<Vec<Option<Arc<SharedRun>>>> = Vec::with_capacity(episodes);
    // Listen-before-talk: deferrals, and collisions avoided.
    let mut lbt = (0, 0);
    for seats in &swarm.plan.episodes {
        let before = sent.len() * n;
        let mut clock = |share: f64| progress(before + (share * n as f64) as usize, total);
        runs.push(swarm.shared_runs(seats));
        sent.push(swarm.fly(&mut net, seats, &runs[sent.len()], &mut lbt, &mut clock)?);
        if !progress(sent.len() * n, total) {
            return Err(SimError::Stopped);
        }
    }
    let scored = swarm
        .score(&sent, &runs, &mut |drones| {
            progress(episodes * n + drones * episodes, total)
        })
        .ok_or(SimError::Stopped)?;
    let mut r = swarm.report(&net, scored)?;
    if net.listen_before_talk {
        (r.lbt_deferrals, r.lbt_collisions_avoided) = (Some(lbt.0), Some(lbt.1));
    }
    Ok(r)
}

/// A swarm about to fly: its settings, what each drone flies, the station its packets go to,
/// the spreading factors it deals out, and each drone's kit.
struct Swarm<'a> {
    cfg: &'a Validated,
    plan: Plan,
    model: StationModel,
    deal: SfDeal,
    kits: Vec<Kit>,
    /// A slotted schedule's longest period, s.
    frame_length: Option<f64>,
    /// Which payload each packet takes, the same for every drone and episode.
    payload: Option<LeanPayload>,
    /// Drone filter runs shared with other swarms.
    shared: Option<&'a SharedDroneRuns>,
}

/// What the drones' stations made of the packets that reached them.
struct Scored<'s> {
    /// Each drone's report, in drone order.
    drones: Vec<DroneReport>,
    /// Every drone's errors, pooled, m.
    errors: Vec<f64>,
    /// Evaluation times before an episode's first packet, over every drone.
    untracked: usize,
    /// Every drone's transmissions.
    tx: Vec<&'s Transmission>,
}

impl<'a> Swarm<'a> {
    /// The swarm `cfg` describes, with its network: checked against the limits, each drone given
    /// its radio, duty cycle and (slotted) slot.
    fn new(cfg: &'a Validated) -> Result<(Self, Network), SimError> {
        let s = cfg.s();
        if s.run.seeds != 1 {
            return Err(SimError::Parameter(
                "seeds",
                f64::from(s.run.seeds),
                "1 in a swarm (a swarm runs one seed: its drones already give its spread)",
            ));
        }
        SimError::unless_read(
            false,
            &[("series", s.run.series)],
            "simulate's (the first flight's error and tracks over time)",
            "a swarm reports each drone's statistics; leave `series` out",
        )?;
        // Spread deals SF7..SF12 in turn (`SfDeal::of`): `sf` then only names the SF of a
        // refusal where none of them carries the frame.
        SimError::unless_read(
            s.swarm.sf_plan == SfPlan::Fixed,
            &[("sf", s.radio.sf != SF.default as i64)],
            "a fixed SF plan's (spread deals SF7..SF12 in turn)",
            "set `sfPlan` to fixed",
        )?;
        let model = cfg.swarm_station()?;
        let plan = plan(cfg)?;
        check_duration(cfg, &plan)?;
        check_length(cfg, &plan)?;
        let deal = SfDeal::of(cfg, model);
        let mut radios = Vec::with_capacity(s.swarm.drones);
        let mut duty_cycles = Vec::with_capacity(s.swarm.drones);
        for i in 0..s.swarm.drones {
            let radio = LoraParams::from_settings(deal.sf_of(i), s.radio.bw, s.radio.cr)?;
            let (r, duty_cycle) = cfg.drone_radio(&radio, model)?;
            radios.push(r);
            duty_cycles.push(duty_cycle);
        }
        // The heartbeat is every drone's, so it is checked against the slowest drone's frame:
        // naming the first drone that fails (SF9 where SFs are dealt in turn) would leave a
        // reader who raised it to that interval to meet SF10, SF11 and SF12 in turn.
        let slowest = radios
            .iter()
            .map(|r| r.current())
            .max_by(|a, b| a.interval.total_cmp(&b.interval));
        if let Some(frame) = slowest {
            cfg.check_heartbeat(&frame)?;
        }
        let slots = slots(cfg, &radios)?;
        let setup = cfg.station_setup(0.0);
        let kits = radios
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
        let frame_length = slots.map(|s| s.iter().map(|s| s.frame).fold(0.0, f64::max));
        let swarm = Swarm {
            cfg,
            plan,
            model,
            deal,
            kits,
            frame_length,
            payload: cfg.lean_payload(model.sent_model()),
            shared: None,
        };
        Ok((swarm, Network::of(cfg, 0.0, radios)))
    }

    /// One episode: every drone's filter (read from `shared`, its run where another swarm made
    /// it or this one keeps it), sender and links through the event loop, calling
    /// `progress(share)` as its clock passes each stretch of its time span ([`run_episode`]);
    /// [`SimError::Stopped`] where it says stop.
    fn fly(
        &self,
        net: &mut Network,
        seats: &[Seat],
        shared: &[Option<Arc<SharedRun>>],
        lbt: &mut (usize, usize),
        progress: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Vec<Vec<Transmission>>, SimError> {
        let s = self.cfg.s();
        let model = self.model.sent_model();
        let sensing: Vec<Sensing> = seats.iter().map(|seat| self.sensing(seat)).collect();
        let mut fliers = Vec::with_capacity(seats.len());
        for (i, seat) in seats.iter().enumerate() {
            let flight: &Trajectory = &self.plan.flights[seat.flight];
            let (sb, cb) = sin_cos(seat.bearing);
            let p0 = flight.pos[0];
            // The centre, in this drone's flight frame: `distance` from its first point along
            // the bearing.
            let centre = [
                p0[0] + s.channel.distance * cb,
                p0[1] + s.channel.distance * sb,
            ];
            let now = net.radios[i].current();
            let kit = &self.kits[i];
            let streams = sensing[i].streams;
            let estimates = match &shared[i] {
                Some(run) => Estimates::Stored(&run.track),
                None => Estimates::live(DroneFilter::new(flight, model, &sensing[i])),
            };
            let aboard = Aboard {
                flight,
                estimates,
                sender: s.sending.sender(self.model, kit.setup, None),
                rule: s.sending.rule(kit.duty_cycle, now.time_on_air)?,
                payload: self.payload,
            };
            let air = Air {
                gateways: &net.gateways_at(centre),
                channel: &net.channel,
                streams,
                channels: self.cfg.channels,
                interval: now.interval,
                timing: s.access.swarm_timing(),
            };
            let flier = Flier::new(i, aboard, &air).with_origin([centre[0], centre[1], 0.0]);
            fliers.push(match &kit.slot {
                Some(slot) => flier.with_slot(slot),
                None => flier,
            });
        }
        if !run_episode(net, &mut fliers, progress) {
            return Err(SimError::Stopped);
        }
        for f in &fliers {
            lbt.0 += f.lbt_deferrals;
            lbt.1 += f.lbt_avoided;
        }
        Ok(fliers.into_iter().map(|f| f.tx).collect())
    }

    /// Each drone's station over what the network passed on in every episode (`sent`: per
    /// episode, per drone), drones in parallel, calling `progress(drones done)` after each
    /// chunk of them; `None` where it says stop.
    fn score<'s>(
        &self,
        sent: &'s [Vec<Vec<Transmission>>],
        runs: &[Vec<Option<Arc<SharedRun>>>],
        progress: &mut dyn FnMut(usize) -> bool,
    ) -> Option<Scored<'s>> {
        let n = self.kits.len();
        let mut scored = Scored {
            drones: Vec::with_capacity(n),
            errors: Vec::new(),
            untracked: 0,
            tx: Vec::new(),
        };
        for chunk in (0..n.div_ceil(CHUNK)).map(|c| c * CHUNK..((c + 1) * CHUNK).min(n)) {
            let tracked = par_map(chunk.clone(), |i| self.track(i, sent, runs));
            for (i, (mut e3, untracked)) in chunk.zip(tracked) {
                let mine: Vec<&Transmission> = sent.iter().flat_map(|ep| ep[i].iter()).collect();
                scored.errors.extend_from_slice(&e3);
                scored.untracked += untracked;
                let error3d = Summary::of(&mut e3);
                // Summary::of left e3 sorted.
                let whole_flight = WholeFlightError::of_sorted(&e3, untracked);
                scored
                    .drones
                    .push(self.drone_report(i, &mine, error3d, whole_flight));
                scored.tx.extend(mine);
            }
            if !progress(scored.drones.len()) {
                return None;
            }
        }
        Some(scored)
    }

    /// Drone `i`'s station over its transmissions in every episode: its errors, m, and the
    /// evaluation times before each episode's first packet. Where the drone's filter run is
    /// shared with other swarms, so are its station's errors from each packet they deliver
    /// alike ([`SharedDroneRuns`]).
    fn track(
        &self,
        i: usize,
        sent: &[Vec<Vec<Transmission>>],
        runs: &[Vec<Option<Arc<SharedRun>>>],
    ) -> (Vec<f64>, usize) {
        let (mut e3, mut untracked) = (Vec::new(), 0);
        let setup = self.kits[i].setup;
        let step = self.cfg.s().station.step;
        let station = self
            .shared
            .filter(|runs| runs.keeps_station_errors())
            .map(|runs| {
                runs.station(format!(
                    "{:?} {:?} {step:?}",
                    self.model,
                    setup.estimate_inputs()
                ))
            });
        for ((seats, out), runs) in self.plan.episodes.iter().zip(sent).zip(runs) {
            let flight = &self.plan.flights[seats[i].flight];
            let memo = runs[i].as_ref().zip(station).map(|(r, id)| r.forecasts(id));
            // Only the error is kept: a station need not propagate a covariance its estimate
            // no longer depends on (an overdue bounded station, or one whose error-triggered
            // drone's silence it trusts).
            let mut tracker = new_tracker(self.model, setup, None);
            let scoring = Scoring::errors_only(step);
            let memo = memo.as_ref().map(|m| m as &dyn ForecastMemo);
            let track = track_station_recalling(flight, tracker.as_mut(), &out[i], scoring, memo);
            e3.extend(track.error3d);
            untracked += track.untracked;
        }
        (e3, untracked)
    }

    /// What drone `seat`'s sensors and filter run on.
    fn sensing(&self, seat: &Seat) -> Sensing {
        self.cfg.sensing(DroneStreams {
            seed: self.cfg.s().run.seed,
            stream: seat.stream,
        })
    }

    /// Each drone's filter run in an episode (`seats`), where another swarm has made it or this
    /// one may keep it: the loop reads its estimates, the station its kept errors.
    fn shared_runs(&self, seats: &[Seat]) -> Vec<Option<Arc<SharedRun>>> {
        let model = self.model.sent_model();
        seats
            .iter()
            .map(|seat| {
                let flight = &self.plan.flights[seat.flight];
                self.shared
                    .and_then(|runs| runs.get(flight, model, &self.sensing(seat)))
            })
            .collect()
    }

    /// Drone `i`'s report from its transmissions `mine` and its station's errors.
    fn drone_report(
        &self,
        i: usize,
        mine: &[&Transmission],
        error3d: Summary,
        whole_flight: WholeFlightError,
    ) -> DroneReport {
        let mut channel_use = vec![0; usize::from(self.cfg.channels)];
        let mut rates = RateTally::default();
        for t in mine {
            channel_use[usize::from(t.channel)] += 1;
            rates.add(t);
        }
        let plan = &self.plan;
        let time: f64 = plan
            .episodes
            .iter()
            .map(|ep| plan.flights[ep[i].flight].duration())
            .sum();
        // Summed in the packets' order, as the whole duty cycle is: a drone at one SF has the
        // same number at it.
        let duty_cycle_by_sf = core::array::from_fn(|k| {
            let at = mine.iter().filter(|t| usize::from(t.sf.get() - 7) == k);
            at.map(|t| t.time_on_air).sum::<f64>() / time
        });
        let received = mine.iter().filter(|t| t.received).count();
        DroneReport {
            id: i,
            sf: self.deal.sf_of(i) as u8,
            bearing_deg: plan.episodes[0][i].bearing.to_degrees(),
            channel_use,
            data_rate_use: rates.into_vec(),
            duty_cycle_by_sf,
            packets_sent: mine.len(),
            packets_received: received,
            packets_collided: mine
                .iter()
                .filter(|t| t.outcome == Outcome::Collided)
                .count(),
            energy: Energy::of(mine.iter().copied(), time),
            duty_cycle_used: mine.iter().map(|t| t.time_on_air).sum::<f64>() / time,
            frame_length: self.kits[i].slot.map(|s| s.frame),
            error3d,
            whole_flight,
            caveats: Caveats::of(
                received,
                mine.len(),
                self.cfg.s().sending.sender,
                Saturation::of(mine.iter().copied()),
            ),
        }
    }

    /// The swarm's report: every drone's errors pooled (with the evaluation times before an
    /// episode's first packet), the network's counts, and the largest swarm the settings allow.
    fn report(&self, net: &Network, scored: Scored<'_>) -> Result<SwarmReport, SimError> {
        let (cfg, model) = (self.cfg, self.model);
        let bytes = model.payload_bytes() + cfg.s().radio.overhead;
        let largest_swarm = largest_swarm(cfg, &self.deal, bytes)?;
        let Scored {
            drones,
            mut errors,
            untracked,
            tx,
        } = scored;
        let s = cfg.s();
        let count = |o: Outcome| tx.iter().filter(|t| t.outcome == o).count();
        let packets_sent = tx.len();
        let packets_by_sf = packets_by_sf(&drones);
        let received = count(Outcome::Received);
        let mut settings = s.clone();
        if cfg.source.is_some() {
            // As `simulate`'s echo: how long the drones flew, not the chained synthetic flights'
            // duration, which a chosen flight leaves unread.
            settings.swarm.duration = self.plan.flight_time();
        }
        Ok(SwarmReport {
            config: SwarmEcho {
                settings,
                station: model,
                bandwidth_khz: s.radio.bw,
                plan_cornering: cfg.plan.as_ref().map(FlightPlan::cornering),
            },
            flight_time: self.plan.flight_time(),
            sf_limit: self.deal.limit,
            frame_length: self.frame_length,
            largest_swarm,
            lbt_deferrals: None,
            lbt_collisions_avoided: None,
            collision_rate: ratio(count(Outcome::Collided), packets_sent),
            collision_rate_theory: collision_theory(&drones, &packets_by_sf, cfg.channels),
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
            packets_gateway_transmitting: count(Outcome::GatewayTransmitting),
            lean_packets: tx.iter().filter(|t| t.payload.is_some()).count(),
            packets_by_sf,
            airtime: airtime(tx.iter().copied()),
            error3d: Summary::of(&mut errors),
            whole_flight: WholeFlightError::of_sorted(&errors, untracked),
            saturation: SwarmSaturation::of(&drones),
            median_drone_p75: median_drone_p75(&drones),
            energy: mean_energy(&drones),
            drones,
        })
    }
}

/// The median over the drones of each drone's p75 3D error, m (drones without an error, none
/// of whose packets arrived, left out).
fn median_drone_p75(drones: &[DroneReport]) -> f64 {
    let mut p75s: Vec<f64> = drones
        .iter()
        .filter(|d| d.error3d.count > 0)
        .map(|d| d.error3d.p75)
        .collect();
    sort_total(&mut p75s);
    percentile(&p75s, 50.0)
}

/// A drone's energy, averaged over the drones: the charge per uplink over those that sent one (a
/// drone that sent nothing, as most do in a short swarm at SF12, has no uplink to average in:
/// counted as 0 it divided the others' charge by the swarm's size), the charge per hour over all.
fn mean_energy(drones: &[DroneReport]) -> Energy {
    // NaN (JSON `null`) over no drones: no drone, no mean.
    let mean = |of: fn(&Energy) -> f64, over: &[&DroneReport]| {
        over.iter().map(|d| of(&d.energy)).sum::<f64>() / over.len() as f64
    };
    let all: Vec<&DroneReport> = drones.iter().collect();
    let sending: Vec<&DroneReport> = drones.iter().filter(|d| d.packets_sent > 0).collect();
    Energy {
        charge_per_uplink: mean(|e| e.charge_per_uplink, &sending),
        charge_per_hour: mean(|e| e.charge_per_hour, &all),
    }
}

/// The packets `drones` sent at SF7..SF12 ([`SwarmReport::packets_by_sf`]).
fn packets_by_sf(drones: &[DroneReport]) -> [usize; 6] {
    let mut sent = [0; 6];
    for u in drones.iter().flat_map(|d| &d.data_rate_use) {
        sent[usize::from(u.sf - 7)] += u.packets;
    }
    sent
}

/// Pure ALOHA's collision rate for `drones` on `channels` channels: per SF group at the duty
/// cycle the group achieved, weighted by the packets each group sent (`by_sf`; reference §10).
/// A group is the drones at that SF and, with ADR, every drone that sent there, each at the
/// share of its time on air at that SF.
fn collision_theory(drones: &[DroneReport], by_sf: &[usize; 6], channels: u8) -> f64 {
    let mut theory = 0.0;
    for (sf, &packets) in (7..=12u8).zip(by_sf) {
        let k = usize::from(sf - 7);
        let group: Vec<&DroneReport> = drones
            .iter()
            .filter(|d| d.sf == sf || d.data_rate_use.iter().any(|u| u.sf == sf && u.packets > 0))
            .collect();
        if group.is_empty() {
            continue;
        }
        let used = group.iter().map(|d| d.duty_cycle_by_sf[k]).sum::<f64>() / group.len() as f64;
        theory += packets as f64 * aloha_collision_rate(used, channels, group.len());
    }
    let sent: usize = drones.iter().map(|d| d.packets_sent).sum();
    if sent == 0 {
        0.0
    } else {
        theory / sent as f64
    }
}

/// Refuses a `duration` given with a chosen flight, which every drone flies whole: the duration
/// only sets how long chained synthetic flights last (as `simulate` refuses a swarm's settings),
/// so a swarm never says it flew for a time it did not.
fn check_duration(cfg: &Validated, plan: &Plan) -> Result<(), SimError> {
    let duration = cfg.s().swarm.duration;
    if cfg.source.is_some() && duration != DURATION.default {
        let chosen = match plan.flights.len() {
            1 => "the chosen flight".to_string(),
            n => format!("the {n} chosen flights"),
        };
        return Err(SimError::Source(format!(
            "`duration` ({duration} s) is how long chained synthetic flights last; every drone flies {chosen} whole ({:.0} s): leave `duration` out",
            plan.flight_time()
        )));
    }
    Ok(())
}

/// Refuses a swarm whose filters would take more than [`MAX_SWARM_FILTER_STEPS`] steps, with how
/// many of its drones fit: the first drones of a swarm fly what they fly in a larger one (the
/// layout is drawn drone by drone), so as many as the longest-flying drone fits fly no more.
fn check_length(cfg: &Validated, plan: &Plan) -> Result<(), SimError> {
    let s = cfg.s();
    let drones = s.swarm.drones;
    let mut per_drone = vec![0.0; drones];
    for seats in &plan.episodes {
        for (flown, seat) in per_drone.iter_mut().zip(seats) {
            *flown += plan.flights[seat.flight].duration();
        }
    }
    let flown: f64 = per_drone.iter().sum();
    let rate = s.drone.sensor_rate + 1.0 / s.station.step;
    let steps = flown * rate;
    if steps > MAX_SWARM_FILTER_STEPS as f64 {
        let longest = per_drone.iter().fold(0.0, |a: f64, &b| a.max(b)) * rate;
        let fit = (MAX_SWARM_FILTER_STEPS as f64 / longest)
            .floor()
            .min(drones as f64) as u32;
        return Err(SimError::TooLong {
            flight_time: flown,
            steps,
            run: LongRun::Swarm { drones, fit },
        });
    }
    Ok(())
}

/// [`LargestSwarm`] at `cfg`'s settings, the swarm dealing out `deal`'s SFs, for packets of
/// `bytes`.
fn largest_swarm(cfg: &Validated, deal: &SfDeal, bytes: usize) -> Result<LargestSwarm, SimError> {
    let s = cfg.s();
    let timing = s.access.swarm_timing();
    let (mut toa, mut interval, mut used) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    for &sf in &deal.sfs {
        let radio = LoraParams::from_settings(sf, s.radio.bw, s.radio.cr)?;
        let k = (sf - 7) as usize;
        toa[k] = time_on_air(&radio, bytes)?.time_on_air;
        interval[k] = toa[k] / cfg.duty_cycle_for(toa[k])?;
        // A random delay of up to J s lengthens the mean interval by J / 2.
        used[k] = toa[k] / (interval[k] + timing.jitter / 2.0);
    }
    let sf_of = |i: usize| deal.sf_of(i) as u8;
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
            "a slotted schedule sizes each slot for a drone's data rate: it cannot run with `adr`, which moves drones between rates".into(),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::report::DataRateUse;
    use crate::sim::sender::SenderKind;
    use crate::Scenario;

    /// Whether `check_length` lets a swarm of `drones` × 3600 s at 20 Hz sensors go ahead, and
    /// its refusal where it does not.
    fn length_check(drones: usize) -> Result<(), SimError> {
        let mut s = Scenario::default();
        (s.swarm.drones, s.swarm.duration, s.drone.sensor_rate) = (drones, 3600.0, 20.0);
        let cfg = s.validate().unwrap();
        check_length(&cfg, &plan(&cfg).unwrap())
    }

    #[test]
    fn a_swarm_too_long_for_its_drones_names_as_many_as_fit_and_that_many_do() {
        let e = length_check(500).unwrap_err();
        assert_eq!(e.setting(), Some("drones"));
        let fit = e.value_that_fits().unwrap();
        assert!(e
            .to_string()
            .contains(&format!("(at most {fit} drones, or shorter flights")));
        let fit = fit as usize;
        assert!(length_check(fit).is_ok());
        assert_eq!(
            length_check(fit + 1).unwrap_err().value_that_fits(),
            Some(fit as f64)
        );
    }

    /// A drone on `sf` that sent `packets_sent` packets, on air `duty_cycle_used` of the time.
    fn drone(sf: u8, packets_sent: usize, duty_cycle_used: f64) -> DroneReport {
        let mut duty_cycle_by_sf = [0.0; 6];
        duty_cycle_by_sf[usize::from(sf - 7)] = duty_cycle_used;
        DroneReport {
            id: 0,
            sf,
            bearing_deg: 0.0,
            channel_use: vec![packets_sent],
            data_rate_use: vec![use_at(sf, packets_sent)],
            duty_cycle_by_sf,
            packets_sent,
            packets_received: packets_sent,
            packets_collided: 0,
            // Zeros, as the tests below read them (a real silent drone's would be no charge per
            // uplink and its sleeping radio's per hour: `Energy::from_sums`).
            energy: Energy {
                charge_per_uplink: 0.0,
                charge_per_hour: 0.0,
            },
            duty_cycle_used,
            frame_length: None,
            error3d: Summary::of(&mut Vec::new()),
            whole_flight: WholeFlightError::of_sorted(&[], 0),
            caveats: Caveats::of(
                packets_sent,
                packets_sent,
                SenderKind::Periodic,
                Saturation::default(),
            ),
        }
    }

    /// `packets` sent at `sf` (125 kHz).
    fn use_at(sf: u8, packets: usize) -> DataRateUse {
        DataRateUse {
            dr: None,
            sf,
            bw: 125.0,
            packets,
            received: packets,
            time_on_air: 0.1,
            interval: 10.0,
        }
    }

    /// [`collision_theory`] of `drones`, with their packets by SF as the report sums them.
    fn theory(drones: &[DroneReport], channels: u8) -> f64 {
        collision_theory(drones, &packets_by_sf(drones), channels)
    }

    #[test]
    fn a_swarms_saturated_packets_are_its_drones_pooled_with_the_drones_that_sent_them() {
        use crate::models::{OMEGA, PSI, V};
        let with = |packets: usize, fields: &[usize]| {
            let mut d = drone(7, 10, 0.01);
            d.caveats.saturated_packets = packets;
            fields.iter().for_each(|&f| d.caveats.saturated.insert(f));
            d
        };
        let s = SwarmSaturation::of(&[with(2, &[OMEGA]), with(0, &[]), with(3, &[PSI, V])]);
        assert_eq!((s.drones, s.packets), (2, 5));
        assert_eq!(s.fields.names().collect::<Vec<_>>(), ["v", "omega", "psi"]);
        assert_eq!(
            SwarmSaturation::of(&[with(0, &[])]),
            SwarmSaturation::default()
        );
    }

    #[test]
    fn the_mean_charge_per_uplink_leaves_out_drones_that_sent_none() {
        let mut sent = drone(12, 1, 0.01);
        sent.energy = Energy {
            charge_per_uplink: 69.0,
            charge_per_hour: 0.4,
        };
        let silent = drone(12, 0, 0.0);
        let mean = mean_energy(&[sent, silent.clone(), silent]);
        assert_eq!(mean.charge_per_uplink, 69.0);
        assert!((mean.charge_per_hour - 0.4 / 3.0).abs() < 1e-15);
        // A swarm in which no drone sent has no charge per uplink, and its charge per hour is
        // its sleeping radios'.
        let mut asleep = drone(7, 0, 0.0);
        asleep.energy = Energy::from_sums(0, 0.0, 0.0, 60.0);
        let mean = mean_energy(&[asleep]);
        assert!(mean.charge_per_uplink.is_nan());
        assert!((mean.charge_per_hour - crate::lora::SX1276_SLEEP_CURRENT_MA).abs() < 1e-18);
    }

    #[test]
    fn packets_by_sf_count_every_drone_and_sf7_at_either_bandwidth_as_one() {
        let mut both = drone(7, 4, 0.01);
        let mut wide = use_at(7, 1);
        wide.bw = 250.0;
        both.data_rate_use = vec![use_at(7, 3), wide];
        let mut moved = drone(7, 5, 0.01);
        moved.data_rate_use = vec![use_at(12, 1), use_at(8, 4)];
        assert_eq!(packets_by_sf(&[both, moved]), [4, 4, 0, 0, 0, 1]);
    }

    #[test]
    fn the_collision_theory_is_alohas_per_sf_group_weighted_by_packets() {
        // One group: pure ALOHA at the group's mean duty cycle.
        let one = [drone(7, 10, 0.01), drone(7, 30, 0.03)];
        let expected = aloha_collision_rate(0.02, 1, 2);
        assert!((theory(&one, 1) - expected).abs() < 1e-15);
        // Two groups do not collide with each other: each group's rate, weighted by its packets.
        let two = [drone(7, 10, 0.01), drone(7, 10, 0.01), drone(9, 30, 0.01)];
        let sf7 = aloha_collision_rate(0.01, 1, 2);
        let sf9 = aloha_collision_rate(0.01, 1, 1);
        assert_eq!(sf9, 0.0, "a drone alone on its SF collides with no one");
        let mixed = theory(&two, 1);
        assert!((mixed - (20.0 * sf7 + 30.0 * sf9) / 50.0).abs() < 1e-15);
        assert!(mixed < sf7);
        // More channels, fewer collisions; no packets, no rate.
        assert!(theory(&one, 3) < theory(&one, 1));
        assert_eq!(theory(&[drone(7, 0, 0.0)], 1), 0.0);
    }

    #[test]
    fn with_adr_the_collision_theory_groups_drones_by_where_their_packets_went() {
        // Two drones started on SF7; ADR moved one to SF8 for half its packets (and half its
        // time on air there). SF7's group: both, the moved one at its remaining share.
        let stayed = drone(7, 20, 0.02);
        let mut moved = drone(7, 20, 0.02);
        moved.data_rate_use = vec![use_at(8, 10), use_at(7, 10)];
        moved.duty_cycle_by_sf = [0.01, 0.01, 0.0, 0.0, 0.0, 0.0];
        let sf7 = aloha_collision_rate(0.015, 1, 2);
        // On SF8 it is alone: no collision there.
        let expected = 30.0 * sf7 / 40.0;
        let rate = theory(&[stayed.clone(), moved], 1);
        assert!((rate - expected).abs() < 1e-15, "{rate} vs {expected}");
        // Counted by the SF they started at, both would share SF7 at 2 %: a higher rate.
        assert!(rate < theory(&[stayed.clone(), stayed], 1));
    }
}
