//! The output of `swarm`.

use super::SfLimit;
use crate::codec::SaturatedFields;
use crate::metrics::{Summary, WholeFlightError};
use crate::sim::caveats::Caveats;
use crate::sim::report::{DataRateUse, Delivery, Energy};
use crate::sim::scenario::Scenario;
use crate::sim::station::StationModel;
use crate::trajectory::Cornering;
use serde::Serialize;

/// One drone of the swarm.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct DroneReport {
    /// 0-based index.
    pub id: usize,
    /// Its spreading factor (with ADR, the one it starts at: `dataRateUse` says where its
    /// packets went).
    pub sf: u8,
    /// Direction from its starting point to the centre, degrees counter-clockwise from east.
    pub bearing_deg: f64,
    /// Packets it sent on each channel.
    pub channel_use: Vec<usize>,
    /// The packets it sent at each data rate, slowest first, as a station's result counts them:
    /// one entry without ADR, each rate the network moved it to with.
    pub data_rate_use: Vec<DataRateUse>,
    /// The fraction of its flight time it was on air at each spreading factor, SF7 first:
    /// what the ALOHA formula groups it by ([`SwarmReport::collision_rate_theory`]).
    #[serde(skip)]
    pub(crate) duty_cycle_by_sf: [f64; 6],
    /// Packets sent.
    pub packets_sent: usize,
    /// Packets the gateway received.
    pub packets_received: usize,
    /// Packets lost to interference.
    pub packets_collided: usize,
    /// Its radio's charge.
    pub energy: Energy,
    /// The fraction of its flight time it was on air: its achieved duty cycle (the limit, or
    /// less where random delays lengthen the intervals).
    pub duty_cycle_used: f64,
    /// Its slot's frame under a slotted schedule, s: its sending interval (`null` for ALOHA).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub frame_length: Option<f64>,
    /// Its station's 3D error, m, after each episode's first packet (`count` 0: nothing arrived,
    /// nothing counted).
    pub error3d: Summary,
    /// The share of its flight time after each episode's first packet, and its error's
    /// percentiles over the whole flight time ([`WholeFlightError`]).
    pub whole_flight: WholeFlightError,
    /// What its numbers rest on, as a station's result says it ([`Caveats::of`]): in a swarm of
    /// two-minute flights an SF12 drone's p75 rests on a packet or two.
    pub caveats: Caveats,
}

/// The output of `swarm`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct SwarmReport {
    /// The settings.
    pub config: SwarmEcho,
    /// Seconds each drone flew (the mean over the drones): `duration` where the drones chain
    /// synthetic flights, else the flights chosen, whole (the real Canberra flight's 162 s).
    pub flight_time: f64,
    /// Packets lost to interference at every gateway that could hear them / packets sent
    /// (`null` when no packet was sent).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub collision_rate: f64,
    /// Pure ALOHA's collision rate (`aloha_collision_rate`) per SF group at the group's mean
    /// achieved duty cycle, weighted by the packets each group sent: what the formula predicts
    /// for senders at random phases without capture or inter-SF effects (one gateway). With ADR
    /// a group is every drone that sent at that SF, at the share of its time it was on air there.
    pub collision_rate_theory: f64,
    /// Why the `spread` SF plan dealt fewer SFs than the swarm had drones for (`"adr"`,
    /// `"region"`; `null` where it dealt each drone its own up to six): the drones' `sf` say
    /// which it dealt.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "SfLimit | null"))]
    pub sf_limit: Option<SfLimit>,
    /// The schedule's longest frame, s: the slowest drone's sending interval (`null` for
    /// ALOHA).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub frame_length: Option<f64>,
    /// How many drones one gateway serves under each schedule at these settings.
    pub largest_swarm: LargestSwarm,
    /// Listen-before-talk: how often a drone found its channel busy and moved to another or
    /// backed off (`null` without it).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub lbt_deferrals: Option<usize>,
    /// Of those, how often the busy channel carried a packet on the drone's own SF, which its
    /// packet would have overlapped: collisions avoided. The collisions that remain
    /// (`packetsCollided`) are those listening could not avoid: hidden drones, too far apart
    /// to hear each other, and packets that start within one listen time.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub lbt_collisions_avoided: Option<usize>,
    /// Packets, copies and gateways (`packetsSent`, `packetsReceived` — distinct packets the
    /// network server passed on —, `deliveryRatio`, `duplicates`, `gateways`).
    #[serde(flatten)]
    pub delivery: Delivery,
    /// Packets no gateway received though one locked on (lost to interference).
    pub packets_collided: usize,
    /// Packets below every gateway's sensitivity.
    pub packets_below_sensitivity: usize,
    /// Packets audible somewhere but finding no free demodulation path where they were.
    pub packets_no_demodulator: usize,
    /// Packets audible somewhere but on air, wherever they were, while that gateway transmitted
    /// a downlink (half-duplex gateways, reference §6.3); only with ADR, whose answers are the
    /// downlinks.
    pub packets_gateway_transmitting: usize,
    /// Packets sent with a smaller payload than the station's model sends (`--payload lean`).
    pub lean_packets: usize,
    /// Packets sent at SF7..SF12, every drone's summed: each drone's SF, or with ADR the SFs the
    /// network moved it to (the drones' `dataRateUse`, SF7 at either bandwidth as one). The
    /// CLI's "ADR sent them at" and the page's note give these as shares.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number[]"))]
    pub packets_by_sf: [usize; 6],
    /// Seconds on air, all drones.
    pub airtime: f64,
    /// Every drone's errors pooled, m (after each episode's first packet).
    pub error3d: Summary,
    /// Every drone's tracked share and errors over the whole flight time, pooled.
    pub whole_flight: WholeFlightError,
    /// The drones whose received packets carried a value beyond the payload's range, pooled from
    /// their `caveats` ([`SwarmSaturation`]).
    pub saturation: SwarmSaturation,
    /// The median over drones of each drone's p75, m (`null` when no drone received anything).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub median_drone_p75: f64,
    /// The drone radio's charge, averaged over the drones: per uplink over those that sent one,
    /// per hour over all.
    pub energy: Energy,
    /// Per drone.
    pub drones: Vec<DroneReport>,
}

/// A swarm's drones whose received packets carried a value beyond the payload's range, sent as
/// the range's edge (each drone's [`Caveats`]' `saturated_packets`, pooled; reference §5): their
/// stations started from a state other than the drone's estimate. A swarm flying the real
/// Canberra flight saturates the turn and tilt rate in its ACRO end; the synthetic set seldom
/// does (one packet each of 21 of 500 drones in an hour).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct SwarmSaturation {
    /// Drones with at least one such received packet.
    pub drones: usize,
    /// Their received packets that carried one, every drone's summed.
    pub packets: usize,
    /// The fields those packets saturated, in state order (empty when none did).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "string[]"))]
    pub fields: SaturatedFields,
}

impl SwarmSaturation {
    /// `drones`' saturated packets pooled.
    pub fn of(drones: &[DroneReport]) -> Self {
        drones
            .iter()
            .map(|d| d.caveats)
            .filter(|c| c.saturated_packets > 0)
            .fold(SwarmSaturation::default(), |s, c| SwarmSaturation {
                drones: s.drones + 1,
                packets: s.packets + c.saturated_packets,
                fields: s.fields.union(c.saturated),
            })
    }
}

/// The largest swarm one gateway serves at a swarm's settings (its SF plan, channels, payload,
/// duty cycle and random delays), each drone sending as often as its duty cycle allows:
/// by the pure-ALOHA formula at ≤ 1 % and ≤ 10 % collisions, and with a slotted schedule with
/// none (and no drone slowed by crowding). Computed, not simulated; the swarm's own collision
/// rate shows how closely the simulation follows the formula (reference §13).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct LargestSwarm {
    /// ALOHA at ≤ 1 % collisions, drones.
    pub aloha1: usize,
    /// ALOHA at ≤ 10 % collisions, drones.
    pub aloha10: usize,
    /// Slotted, with no collisions, drones.
    pub slotted: usize,
}

/// The echo of a swarm's settings: every key of [`Scenario`], flat, plus the station it ran.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct SwarmEcho {
    /// The settings as given, but for `duration` with a chosen flight, which its drones fly
    /// whole: then how long they flew (the mean over the drones, as `flightTime`), as
    /// `simulate`'s echo gives it.
    #[serde(flatten)]
    pub settings: Scenario,
    /// The one station every drone's ground station ran.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "ModelName"))]
    pub station: StationModel,
    /// Bandwidth, kHz (as `bw`).
    pub bandwidth_khz: f64,
    /// How the plan the drones fly (`plan`) is flown, as [`RunConfig::plan_cornering`]
    /// says it for `simulate`; `null` without a plan.
    ///
    /// [`RunConfig::plan_cornering`]: crate::sim::RunConfig::plan_cornering
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "Cornering | null"))]
    pub plan_cornering: Option<Cornering>,
}
