//! One station of a `simulate` run flying its flights: the drone's radio and sender, the one
//! event loop ([`run_episode`]) and the station's scoring, for one seed's drone runs.
//!
//! [`Simulator`](super::Simulator) prepares one [`StationPlan`] per station and one
//! [`StationRun`] per station and seed, groups the runs whose drones send the same
//! transmissions ([`StationRun::sends_as`]: one event loop then serves the group, and its
//! stations are scored on it side by side), and flies every (group, flight) pair in one
//! parallel batch, the costliest groups first: a long single flight with four stations keeps
//! both cores busy instead of one. A run whose drone adapts its data rate (ADR) carries the
//! device's state from flight to flight, so it flies its flights in order instead.

use super::drone::{DroneFilter, DroneTrack, Estimates};
use super::flier::{Aboard, Air, Flier};
use super::network::{run_episode, Network};
use super::packet::Transmission;
use super::pooled::model_series;
use super::radio::DroneRadio;
use super::report::{Delivery, ModelSeries};
use super::scenario::Validated;
use super::sender::{LeanPayload, SenderKind};
use super::station::{
    new_tracker, track_station, FlightChains, MissionPlan, Prediction, Scoring, StationModel,
    StationSetup, StationTrack,
};
use super::streams::DroneStreams;
use super::SimError;
use crate::parallel::par_map;
use crate::trajectory::Trajectory;
use std::sync::Mutex;

/// What one flight of one station gave.
pub(crate) struct FlightRun {
    /// Every transmission, received or not.
    pub tx: Vec<Transmission>,
    /// The station's errors.
    pub track: StationTrack,
    /// The plotted series (the first flight of the first seed, when asked).
    pub series: Option<ModelSeries>,
    /// What the network counted (each flight alone; the last flight of a run in order).
    pub delivery: Option<Delivery>,
    /// How often the drone's filter repaired its covariance over the flight.
    pub recoveries: u64,
}

/// What one station's drone sends with and how the station predicts, the same for every seed.
pub(crate) struct StationPlan {
    /// The station.
    pub model: StationModel,
    /// The drone's radio at the start of each flight (its data rate, ADR state).
    pub start: DroneRadio,
    /// The duty cycle the drone keeps (0..1).
    pub duty_cycle: f64,
    /// The station's prediction settings, at the starting data rate's interval.
    pub setup: StationSetup,
    /// Each flight's plan (a mission station's only; `None` otherwise).
    pub plans: Vec<Option<MissionPlan>>,
    /// Which payload each packet takes.
    pub payload: Option<LeanPayload>,
}

impl StationPlan {
    /// The plan of `model` over `flights`; refuses a heartbeat shorter than the interval.
    pub fn new(
        cfg: &Validated,
        model: StationModel,
        flights: &[Trajectory],
    ) -> Result<Self, SimError> {
        let (start, duty_cycle) = cfg.drone_radio(&cfg.radio, model)?;
        let frame = start.current();
        cfg.check_heartbeat(&frame)?;
        let interval = frame.interval;
        let setup = cfg.setup_for(
            model,
            StationSetup {
                interval,
                ..cfg.station_setup(0.0)
            },
        );
        Ok(StationPlan {
            model,
            start,
            duty_cycle,
            setup,
            plans: flights.iter().map(|f| cfg.mission_plan(model, f)).collect(),
            payload: cfg.lean_payload(model.sent_model()),
        })
    }
}

/// One station with one seed's drone runs: everything needed to fly any of its flights.
pub(crate) struct StationRun<'a> {
    /// The station.
    pub plan: &'a StationPlan,
    /// The run's settings.
    pub cfg: &'a Validated,
    /// The flights.
    pub flights: &'a [Trajectory],
    /// The drone's estimates on each flight, for this seed, or `None` to run its filter as the
    /// event loop reads it (a flight too long to remember them).
    pub drones: Option<&'a [DroneTrack]>,
    /// The remembered predictions of a single-model station, one entry per flight; `None` for
    /// the others and when too large to remember.
    pub chains: Option<&'a [Mutex<FlightChains>]>,
    /// The seed (the run's first seed's first flight gives the series).
    pub seed: u64,
}

impl StationRun<'_> {
    /// Whether the drone adapts its data rate: its ADR state then passes from one flight to the
    /// next, so the flights fly in order through one network ([`Self::fly_in_order`]).
    pub fn adaptive(&self) -> bool {
        self.plan.start.adaptive()
    }

    /// A network of the run's gateways for this station's drone.
    pub fn network(&self) -> Network {
        let distance = self.cfg.s().channel.distance;
        Network::of(self.cfg, distance, vec![self.plan.start.clone()])
    }

    /// Every flight in order through one network, calling `tick` after each; the last one
    /// carries what the network counted.
    pub fn fly_in_order(&self, tick: &mut dyn FnMut()) -> Vec<Result<FlightRun, SimError>> {
        let mut net = self.network();
        let mut runs: Vec<_> = (0..self.flights.len())
            .map(|i| {
                let r = self.fly(i, &mut net);
                tick();
                r
            })
            .collect();
        if let Some(Ok(last)) = runs.last_mut() {
            last.delivery = Some(Delivery::counted(&net));
        }
        runs
    }

    /// Whether `other`'s drone sends exactly this run's transmissions on every flight, so one
    /// event loop serves both ([`Self::fly_shared`]): the same seed, payload model, frame and duty
    /// cycle, a fixed data rate, and periodic sending, whose instants do not depend on the
    /// station (an error-triggered drone mirrors its own station). A 3D-CTRA, an IMM and a
    /// mission station all send 3D-CTRA's payload: their drone runs once instead of three times,
    /// which on a flight too long to remember its drone run is a whole filter run each.
    pub fn sends_as(&self, other: &StationRun) -> bool {
        let (a, b) = (self.plan, other.plan);
        self.seed == other.seed
            && self.cfg.s().sending.sender == SenderKind::Periodic
            && !self.adaptive()
            && !other.adaptive()
            && a.model.sent_model() == b.model.sent_model()
            && a.start.current() == b.start.current()
            && a.duty_cycle == b.duty_cycle
    }

    /// Flight `i` for every run of `members` (this one first; each [`Self::sends_as`] this
    /// one): the drone sends once through a network of its own, then each station is scored on
    /// those transmissions, in parallel.
    pub fn fly_shared(
        &self,
        i: usize,
        members: &[&StationRun],
    ) -> Vec<Result<FlightRun, SimError>> {
        let mut net = self.network();
        let sent = self.send(i, &mut net);
        let delivery = Delivery::counted(&net);
        let (tx, recoveries) = match sent {
            Ok(sent) => sent,
            Err(e) => return members.iter().map(|_| Err(e.clone())).collect(),
        };
        par_map(0..members.len(), |k| {
            let (track, series) = members[k].score(i, &tx);
            FlightRun {
                tx: tx.clone(),
                track,
                series,
                delivery: Some(delivery.clone()),
                recoveries,
            }
        })
        .into_iter()
        .map(Ok)
        .collect()
    }

    /// Flight `i` through `net`: the drone sends over the event loop, the station is scored.
    fn fly(&self, i: usize, net: &mut Network) -> Result<FlightRun, SimError> {
        let (tx, recoveries) = self.send(i, net)?;
        let (track, series) = self.score(i, &tx);
        Ok(FlightRun {
            tx,
            track,
            series,
            delivery: None,
            recoveries,
        })
    }

    /// Flight `i`'s transmissions through `net`, and how often the drone's filter repaired its
    /// covariance over the flight.
    fn send(&self, i: usize, net: &mut Network) -> Result<(Vec<Transmission>, u64), SimError> {
        let s = self.cfg.s();
        let (flight, plan) = (&self.flights[i], self.plan.plans[i].as_ref());
        let (model, setup) = (self.plan.model, self.plan.setup);
        let now = net.radios[0].current();
        let rule = s.sending.rule(self.plan.duty_cycle, now.time_on_air)?;
        let gateways = net.gateways_at([flight.pos[0][0], flight.pos[0][1]]);
        // The same streams for every station: stations that send the same payload see the same
        // packets, so their comparison is paired.
        let streams = DroneStreams {
            seed: self.seed,
            stream: i as u64,
        };
        let estimates = match self.drones {
            Some(d) => Estimates::Stored(&d[i]),
            None => Estimates::live(DroneFilter::new(
                flight,
                model.sent_model(),
                &self.cfg.sensing(streams),
            )),
        };
        let aboard = Aboard {
            flight,
            estimates,
            sender: s.sending.sender(model, setup, plan),
            rule,
            payload: self.plan.payload,
        };
        let air = Air {
            gateways: &gateways,
            channel: &net.channel,
            streams,
            channels: self.cfg.channels,
            interval: now.interval,
            timing: s.access.single_timing(),
        };
        let mut flier = Flier::new(0, aboard, &air);
        // A lone flier's episode asks no progress, so it always flies to its end.
        let whole = run_episode(net, core::slice::from_mut(&mut flier), &mut |_| true);
        debug_assert!(whole);
        // A live filter runs to the flight's end, as a stored run did: the same repair count.
        flier.estimates.prefetch(flier.estimates.len());
        Ok((flier.tx, flier.estimates.recoveries()))
    }

    /// The station scored on flight `i`'s transmissions `tx`, with the plotted series when this
    /// is the series' flight.
    fn score(&self, i: usize, tx: &[Transmission]) -> (StationTrack, Option<ModelSeries>) {
        let s = self.cfg.s();
        let (flight, plan) = (&self.flights[i], self.plan.plans[i].as_ref());
        let (model, setup) = (self.plan.model, self.plan.setup);
        let with_series = s.run.series && i == 0 && self.seed == s.run.seed;
        let scoring = Scoring {
            step: s.station.step,
            series: with_series,
            axes: true,
            calibrate: setup.prediction == Prediction::Bounded,
            uncertainty: true,
        };
        let st = match self.chains {
            Some(c) => c[i].lock().unwrap_or_else(|e| e.into_inner()).track(
                flight,
                &|| new_tracker(model, setup, None),
                tx,
                scoring,
            ),
            None => {
                let mut tracker = new_tracker(model, setup, plan);
                track_station(flight, tracker.as_mut(), tx, scoring)
            }
        };
        let series = with_series.then(|| model_series(model, &st, tx));
        (st, series)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::drone::run_drone;
    use crate::sim::Scenario;
    use crate::trajectory::synthetic_flight;

    /// Flight 3 at SF7 / 3 km (packets lost), with `settings` on top.
    fn flown(settings: serde_json::Value, stored: bool) -> FlightRun {
        let cfg = Scenario::default()
            .with(&serde_json::json!({"synthetic": 3, "distance": 3000, "seed": 9}))
            .and_then(|s| s.with(&settings))
            .unwrap()
            .validate()
            .unwrap();
        let flights = vec![synthetic_flight(3).unwrap()];
        let plan = StationPlan::new(&cfg, cfg.models[0], &flights).unwrap();
        let drones = vec![run_drone(
            &flights[0],
            plan.model.sent_model(),
            &cfg.sensing(DroneStreams { seed: 9, stream: 0 }),
        )];
        let run = StationRun {
            plan: &plan,
            cfg: &cfg,
            flights: &flights,
            drones: stored.then_some(drones.as_slice()),
            chains: None,
            seed: 9,
        };
        run.fly_shared(0, &[&run]).remove(0).unwrap()
    }

    #[test]
    fn a_drone_filter_run_live_gives_what_its_stored_run_gives() {
        for settings in [
            serde_json::json!({"model": "imm"}),
            serde_json::json!({"model": "ctra-plus", "sender": "error", "threshold": 3}),
        ] {
            let (stored, live) = (flown(settings.clone(), true), flown(settings, false));
            assert!(stored.tx.iter().any(|t| !t.received), "some packets lost");
            assert_eq!(stored.tx.len(), live.tx.len());
            for (a, b) in stored.tx.iter().zip(&live.tx) {
                assert_eq!((a.sent, a.received, a.state), (b.sent, b.received, b.state));
            }
            assert_eq!(stored.track.error3d, live.track.error3d);
            assert_eq!(stored.recoveries, live.recoveries);
        }
    }

    #[test]
    fn stations_that_send_alike_share_one_event_loop_and_keep_their_own_numbers() {
        for (sender, shared) in [("periodic", true), ("error", false)] {
            let cfg = Scenario::default()
                .with(&serde_json::json!({
                    "synthetic": 3, "distance": 3000, "seed": 9, "series": true,
                    "model": "3d-ctra,imm,mission,ctra-plus", "sender": sender,
                }))
                .unwrap()
                .validate()
                .unwrap();
            let flights = vec![synthetic_flight(3).unwrap()];
            let plans: Vec<StationPlan> = cfg
                .models
                .iter()
                .map(|&m| StationPlan::new(&cfg, m, &flights).unwrap())
                .collect();
            let runs: Vec<StationRun> = plans
                .iter()
                .map(|plan| StationRun {
                    plan,
                    cfg: &cfg,
                    flights: &flights,
                    drones: None,
                    chains: None,
                    seed: 9,
                })
                .collect();
            // IMM and mission send 3D-CTRA's payload; CTRA+ sends its own.
            assert_eq!(runs[1].sends_as(&runs[0]), shared, "{sender}");
            assert_eq!(runs[2].sends_as(&runs[0]), shared, "{sender}");
            assert!(!runs[3].sends_as(&runs[0]));
            if !shared {
                continue;
            }
            let members = [&runs[0], &runs[1], &runs[2]];
            let together = runs[0].fly_shared(0, &members);
            for (run, got) in members.iter().zip(together) {
                let (got, alone) = (got.unwrap(), run.fly_shared(0, &[run]).remove(0).unwrap());
                assert!(got.tx.iter().any(|t| !t.received), "some packets lost");
                assert_eq!(got.tx.len(), alone.tx.len());
                assert!(got
                    .tx
                    .iter()
                    .zip(&alone.tx)
                    .all(|(a, b)| (a.sent, a.received, a.state) == (b.sent, b.received, b.state)));
                assert_eq!(
                    got.track.error3d, alone.track.error3d,
                    "{:?}",
                    run.plan.model
                );
                assert_eq!(got.series.map(|s| s.model), alone.series.map(|s| s.model));
                assert_eq!(got.delivery, alone.delivery);
            }
        }
    }
}
