//! One station of a `simulate` run flying its flights: the drone's radio and sender, the one
//! event loop ([`run_episode`]) and the station's scoring, for one seed's drone runs.
//!
//! [`Simulator`](super::Simulator) prepares one [`StationPlan`] per station and one
//! [`StationRun`] per station and seed, then flies every (run, flight) pair in one parallel
//! batch: a long single flight with four stations keeps both cores busy instead of one.

use super::drone::{DroneTrack, Estimates};
use super::flier::Flier;
use super::network::{run_episode, Network};
use super::packet::Transmission;
use super::pooled::model_series;
use super::radio::DroneRadio;
use super::report::{Delivery, ModelSeries};
use super::scenario::Validated;
use super::station::{
    new_tracker, track_station, FlightChains, MissionPlan, Prediction, Scoring, StationModel,
    StationSetup, StationTrack,
};
use super::SimError;
use crate::trajectory::Trajectory;
use std::sync::Mutex;

/// One flight's transmissions, station track, (first flight of the first seed, when asked)
/// plotted series, and what the network counted.
pub(crate) type FlightRun = (
    Vec<Transmission>,
    StationTrack,
    Option<ModelSeries>,
    Option<Delivery>,
);

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
}

impl StationPlan {
    /// The plan of `model` over `flights`; refuses a heartbeat shorter than the interval.
    pub fn new(
        cfg: &Validated,
        model: StationModel,
        flights: &[Trajectory],
    ) -> Result<Self, SimError> {
        let (start, duty_cycle) = cfg.drone_radio(&cfg.radio, model)?;
        let interval = start.current().interval;
        cfg.check_heartbeat(interval)?;
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
    /// The drone's estimates on each flight, for this seed.
    pub drones: &'a [DroneTrack],
    /// The remembered predictions of a single-model station, one entry per flight; `None` for
    /// the others and when too large to remember.
    pub chains: Option<&'a [Mutex<FlightChains>]>,
    /// The seed.
    pub seed: u64,
    /// Whether this is the run's first seed (whose first flight gives the series).
    pub first_seed: bool,
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

    /// Flight `i` alone, through a network of its own.
    pub fn fly_alone(&self, i: usize) -> Result<FlightRun, SimError> {
        let mut net = self.network();
        let mut run = self.fly(i, &mut net)?;
        run.3 = Some(Delivery::counted(&net));
        Ok(run)
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
            last.3 = Some(Delivery::counted(&net));
        }
        runs
    }

    /// Flight `i` through `net`: the drone sends over the event loop, the station is scored.
    fn fly(&self, i: usize, net: &mut Network) -> Result<FlightRun, SimError> {
        let s = self.cfg.s();
        let (flight, plan) = (&self.flights[i], self.plan.plans[i].as_ref());
        let (model, setup) = (self.plan.model, self.plan.setup);
        let now = net.radios[0].current();
        let rule = s
            .sending
            .rule(self.plan.duty_cycle, now.time_on_air, flight.t[0])?;
        let gateways = net.gateways_at([flight.pos[0][0], flight.pos[0][1]]);
        // The same streams for every station: stations that send the same payload see the same
        // packets, so their comparison is paired.
        let mut flier = Flier::new(
            0,
            flight,
            Estimates::Stored(&self.drones[i]),
            s.sending.sender(model, setup, plan),
            rule,
            &gateways,
            &net.channel,
            (self.seed, i as u64),
            self.cfg.channels,
            now.interval,
            s.access.single_timing(),
        );
        run_episode(net, core::slice::from_mut(&mut flier));
        let tx = flier.tx;
        let with_series = s.run.series && i == 0 && self.first_seed;
        let scoring = Scoring {
            step: s.station.step,
            series: with_series,
            calibrate: setup.prediction == Prediction::Bounded,
        };
        let st = match self.chains {
            Some(c) => c[i].lock().unwrap_or_else(|e| e.into_inner()).track(
                flight,
                &|| new_tracker(model, setup, None),
                &tx,
                scoring,
            ),
            None => {
                let mut tracker = new_tracker(model, setup, plan);
                track_station(flight, tracker.as_mut(), &tx, scoring)
            }
        };
        let series = with_series.then(|| model_series(model, &st, &tx));
        Ok((tx, st, series, None))
    }
}
