//! Adaptive data rate (issue: LoRaWAN ADR and a tracking-aware choice of spreading factor): the
//! LoRaWAN network settles where its margin says and never slows the rate itself, a lost downlink
//! delays a change by exactly one uplink, a constant channel never makes ADR oscillate, and where
//! a naive rule flips with the shadowing the tracking-aware one only steps down through fades and
//! back to its long-run rate, and a lone tracking drone out of reach backs off within seconds.

use loratrack::api::simulate;
use loratrack::{
    chain_flights, demodulation_floor_db, fly_alone, noise_floor_dbm, run_drone, snr_db,
    synthetic_set, tracking_ack_limits, Aboard, AdrDevice, AdrMode, AdrNetwork, AdrParams, Channel,
    ChannelParams, DataRate, DroneRadio, DroneStreams, DutyCycle, DutyCycleMode, Estimates,
    GatewaySite, InterferenceModel, LinkAdrReq, LoraParams, LorawanAdr, ModelKind, Network,
    NetworkSetup, Periodic, Scenario, Sensing, Simulator, TrackingAdr, Transmission, UplinkReport,
};
use serde_json::{json, Value};

/// `base` with the flat JSON settings of `changes` applied.
fn set(base: &Scenario, changes: Value) -> Scenario {
    base.with(&changes).unwrap()
}

/// One drone flying `seconds` of the synthetic set at `distance` m, with ADR `mode` from
/// `start` (or the network `custom`), over a channel with `shadowing` dB.
fn fly(
    mode: AdrMode,
    custom: Option<Box<dyn AdrNetwork>>,
    start: DataRate,
    distance: f64,
    shadowing: f64,
    seconds: f64,
) -> Vec<Transmission> {
    let flight = chain_flights(&synthetic_set(), 0, seconds, 1).unwrap();
    let drone = run_drone(&flight, ModelKind::Ctra3d, &Sensing::paper(1, 0));
    let radio = LoraParams::new(start.sf(), start.bw());
    let params = AdrParams {
        mode,
        ..AdrParams::default()
    };
    let channel = Channel::new(ChannelParams {
        shadowing_sigma_db: shadowing,
        ..ChannelParams::default()
    })
    .unwrap();
    let drone_radio = DroneRadio::new(&radio, 12, 0.01, mode).unwrap();
    let toa = drone_radio.current().time_on_air;
    let setup = NetworkSetup {
        sites: vec![GatewaySite {
            east: distance,
            north: 0.0,
            height: None,
        }],
        default_height: 15.0,
        adr: params,
        channel,
        interference: InterferenceModel {
            capture: true,
            inter_sf: true,
        },
        lorawan: false,
        listen_before_talk: false,
    };
    let mut net = Network::new(setup, vec![drone_radio]);
    if let Some(n) = custom {
        net.set_adr_network(0, n);
    }
    let rule = DutyCycle::new(DutyCycleMode::PerPacket, 0.01, toa, 1, flight.t[0]).unwrap();
    let aboard = Aboard {
        flight: &flight,
        estimates: Estimates::Stored(&drone),
        sender: Box::new(Periodic),
        rule,
        payload: None,
    };
    fly_alone(&mut net, aboard, DroneStreams { seed: 7, stream: 0 })
}

fn rates(tx: &[Transmission]) -> Vec<u8> {
    tx.iter().map(|t| t.data_rate().unwrap().index()).collect()
}

fn changes(tx: &[Transmission]) -> usize {
    rates(tx).windows(2).filter(|w| w[0] != w[1]).count()
}

#[test]
fn without_shadowing_lorawan_never_raises_the_sf_and_loses_nothing_once_settled() {
    let tx = fly(AdrMode::Lorawan, None, DataRate::DR0, 2500.0, 0.0, 3000.0);
    let r = rates(&tx);
    assert!(r.windows(2).all(|w| w[1] >= w[0]), "the SF went up: {r:?}");
    assert!(r.last() > r.first(), "never left DR0");
    assert!(
        tx.iter().all(|t| t.received),
        "a rate with margin loses nothing"
    );
}

/// The margin LoRaWAN's ADR counts at `dr` for a packet received at `rssi` dBm, dB.
fn margin(rssi: f64, dr: DataRate) -> f64 {
    snr_db(rssi, dr.bw()) - demodulation_floor_db(dr.sf()) - 10.0
}

#[test]
fn on_a_constant_channel_lorawan_settles_on_the_fastest_rate_its_margin_allows() {
    for rssi in [-95.0, -105.0, -110.0, -113.0, -116.0, -120.0] {
        let seq = constant_channel(Box::new(LorawanAdr::new(10.0, 20)), rssi);
        let settled = *seq.last().unwrap();
        let fastest = DataRate::ALL
            .into_iter()
            .rev()
            .find(|&d| margin(rssi, d) >= 0.0)
            .unwrap_or(DataRate::DR0);
        assert!(
            margin(rssi, settled) >= 0.0 || settled == DataRate::DR0,
            "rssi {rssi}"
        );
        // 3 dB steps over rates 2.5 dB apart may stop one rate short, never more.
        assert!(
            settled == fastest || settled.faster() == Some(fastest),
            "rssi {rssi}: settled {settled}, margin allows {fastest}"
        );
    }
}

#[test]
fn a_lost_downlink_delays_the_change_by_exactly_one_uplink() {
    let report = |d: &mut AdrDevice| {
        let f = d.uplink();
        UplinkReport {
            fcnt: f.fcnt,
            dr: f.dr,
            power_reduction_db: f.power_reduction_db,
            rssi_dbm: -100.0,
            snr_db: snr_db(-100.0, f.dr.bw()),
            adr_ack_req: f.adr_ack_req,
            speed_mps: 0.0,
            crowd_loss: [0.0; 7],
        }
    };
    let first_change = |lost: &[usize]| {
        let mut device = AdrDevice::new(DataRate::DR0);
        let mut network = LorawanAdr::new(10.0, 1);
        for k in 0..10 {
            if device.dr() != DataRate::DR0 {
                return k;
            }
            let command = network.on_uplink(&report(&mut device));
            if command.is_some() && !lost.contains(&k) {
                device.downlink(command);
            } else {
                device.no_downlink();
            }
        }
        usize::MAX
    };
    assert_eq!(first_change(&[]), 1);
    assert_eq!(first_change(&[0]), 2);
    assert_eq!(first_change(&[0, 1]), 3);
}

/// Drives a device and a network over a channel that never changes, every frame received and
/// every downlink heard; returns the data rate before each uplink.
fn constant_channel(mut network: Box<dyn AdrNetwork>, rssi: f64) -> Vec<DataRate> {
    let mut device = AdrDevice::new(DataRate::DR0);
    (0..400)
        .map(|_| {
            let dr = device.dr();
            let f = device.uplink();
            let rx = rssi - f.power_reduction_db;
            let sensitivity = Channel::sensitivity_dbm(f.dr.sf(), f.dr.bw());
            if rx < sensitivity {
                device.no_downlink();
                return dr;
            }
            let command = network.on_uplink(&UplinkReport {
                fcnt: f.fcnt,
                dr: f.dr,
                power_reduction_db: f.power_reduction_db,
                rssi_dbm: rx,
                snr_db: snr_db(rx, f.dr.bw()),
                adr_ack_req: f.adr_ack_req,
                speed_mps: 0.0,
                crowd_loss: [0.0; 7],
            });
            if command.is_some() || f.adr_ack_req {
                device.downlink(command);
            } else {
                device.no_downlink();
            }
            dr
        })
        .collect()
}

#[test]
fn a_constant_channel_never_makes_either_adr_oscillate() {
    let toa = [1.15, 0.66, 0.29, 0.16, 0.09, 0.05, 0.025];
    for rssi in [-95.0, -115.0, -125.0, -131.0, -138.0] {
        let networks: [Box<dyn AdrNetwork>; 2] = [
            Box::new(LorawanAdr::new(10.0, 20)),
            Box::new(TrackingAdr::new(toa, toa.map(|t| t / 0.01), 0.0, 110.0)),
        ];
        for network in networks {
            let seq = constant_channel(network, rssi);
            let mut runs = seq.clone();
            runs.dedup();
            let reversals = runs
                .windows(3)
                .filter(|w| (w[1] > w[0] && w[2] < w[1]) || (w[1] < w[0] && w[2] > w[1]))
                .count();
            assert_eq!(reversals, 0, "rssi {rssi}: {runs:?}");
            let moves = seq.windows(2).filter(|w| w[0] != w[1]).count();
            assert!(moves <= 6, "rssi {rssi}: {moves} moves");
        }
    }
}

/// A naive network: after every uplink, the fastest rate whose demodulation floor lies below the
/// last SNR, at once, both ways.
struct Naive;

impl AdrNetwork for Naive {
    fn on_uplink(&mut self, up: &UplinkReport) -> Option<LinkAdrReq> {
        let rx = up.snr_db + noise_floor_dbm(up.dr.bw());
        let dr = DataRate::ALL
            .into_iter()
            .rev()
            .find(|d| snr_db(rx, d.bw()) >= demodulation_floor_db(d.sf()))
            .unwrap_or(DataRate::DR0);
        (dr != up.dr).then_some(LinkAdrReq {
            dr,
            power_reduction_db: 0.0,
        })
    }
}

#[test]
fn where_a_naive_rule_flips_with_the_shadowing_tracking_only_steps_down_through_fades_and_back() {
    let naive = fly(
        AdrMode::Lorawan,
        Some(Box::new(Naive)),
        DataRate::DR6,
        3000.0,
        4.0,
        1800.0,
    );
    let tracking = fly(AdrMode::Tracking, None, DataRate::DR6, 3000.0, 4.0, 1800.0);
    let (n, t) = (changes(&naive), changes(&tracking));
    assert!(n >= 20, "naive changed only {n} times");
    // A lone drone backs off after four silent uplinks (`tracking_ack_limits`), so a fade takes
    // it a rate down and the network brings it back: it changes too, but less often than the
    // naive rule, and only below its long-run rate (with the regional 64 + 32 it changed less
    // than half as often, and waited out every fade at the fast rate).
    assert!(t < n, "tracking changed {t} times, naive {n}");
    // Its long-run rate is the one it keeps most; a fade takes it slower for a while, never
    // faster (a frame lost at a faster rate could not bring it back).
    let r = rates(&tracking);
    let count = |dr: &u8| r.iter().filter(|x| *x == dr).count();
    let most = r.iter().max_by_key(|dr| count(dr)).unwrap();
    assert_eq!(r.iter().max(), Some(most), "{r:?}");
    assert!(count(most) * 10 >= r.len() * 6, "{r:?}");
}

#[test]
fn adr_is_reported_per_data_rate_and_off_by_default() {
    let mut sim = Simulator::new();
    let base = set(
        &Scenario::default(),
        json!({"synthetic": 3, "model": "3d-ctra", "distance": 5000.0, "series": true}),
    );
    let off = simulate(&mut sim, &base).unwrap();
    assert_eq!(off.config.settings.network.adr, AdrMode::Off);
    assert_eq!(off.results[0].data_rate_use.len(), 1);
    let on = simulate(&mut sim, &set(&base.clone(), json!({"adr": "tracking"}))).unwrap();
    let use_ = &on.results[0].data_rate_use;
    let total: usize = use_.iter().map(|u| u.packets).sum();
    assert_eq!(total, on.results[0].delivery.packets_sent);
    let s = &on.series.as_ref().unwrap().models[0];
    assert_eq!(s.arrival_dr.len(), s.arrivals.len());
    assert_eq!(s.lost_dr.len(), s.lost.len());
    let bad = set(&base, json!({"adr": "lorawan", "sf": 8, "bw": 500.0}));
    let err = simulate(&mut sim, &bad).unwrap_err().to_string();
    assert!(err.contains("EU868"), "{err}");
}

#[test]
fn tracking_adr_matches_the_best_fixed_rate_where_one_rate_serves_the_whole_set() {
    let base = set(
        &Scenario::default(),
        json!({"synthetic": "all", "model": "3d-ctra", "overhead": 0}),
    );
    let r = loratrack::api::sweep_distances(&mut Simulator::new(), &base, &[1000.0]).unwrap();
    assert_eq!(r.runs.len(), 7 + 4);
    let p75 = |pick: &dyn Fn(&loratrack::api::DistanceRun) -> bool| {
        r.runs.iter().find(|x| pick(x)).unwrap().result.error3d.p75
    };
    let best = r
        .runs
        .iter()
        .filter(|x| x.dr.is_some())
        .map(|x| x.result.error3d.p75)
        .fold(f64::INFINITY, f64::min);
    let tracking = p75(&|x| x.adr == AdrMode::Tracking && x.start == Some(6));
    let lorawan = p75(&|x| x.adr == AdrMode::Lorawan && x.start == Some(6));
    assert!(tracking <= 1.05 * best, "tracking {tracking} best {best}");
    assert!(lorawan <= 1.25 * best, "lorawan {lorawan} best {best}");
    // From DR0 the tracking-aware network reaches the fast rate; LoRaWAN's waits for 20 uplinks
    // of two minutes each.
    let tracking0 = p75(&|x| x.adr == AdrMode::Tracking && x.start == Some(0));
    let lorawan0 = p75(&|x| x.adr == AdrMode::Lorawan && x.start == Some(0));
    assert!(tracking0 < 0.1 * lorawan0, "{tracking0} vs {lorawan0}");
}

#[test]
fn a_lone_tracking_drone_out_of_reach_backs_off_within_seconds_where_lorawans_waits_minutes() {
    // 7 km from SF7/250 kHz: DR6 delivers ~0.3 % of frames, so the network hears the drone only
    // once it has backed off on its own (`tracking_ack_limits`: 2 + 2 for one drone, against the
    // regional 64 + 32).
    let first_heard = |mode| {
        let tx = fly(mode, None, DataRate::DR6, 7000.0, 4.0, 900.0);
        tx.iter().position(|t| t.received)
    };
    let tracking = first_heard(AdrMode::Tracking).expect("tracking heard");
    assert!(tracking < 30, "tracking first heard at uplink {tracking}");
    let lorawan = first_heard(AdrMode::Lorawan).map_or(usize::MAX, |i| i);
    assert!(lorawan >= 90, "LoRaWAN first heard at uplink {lorawan}");
    assert_eq!(
        tracking_ack_limits(1, 1),
        loratrack::AckLimits { limit: 2, delay: 2 }
    );
}

#[test]
fn simulate_with_adr_lists_each_rates_packets_and_interval_under_its_row() {
    // 3 km from SF7/250 kHz: the tracking network moves the drone down through the fades.
    let args = [
        "simulate",
        "--synthetic",
        "all",
        "--model",
        "3d-ctra",
        "--adr",
        "tracking",
        "--distance",
        "3000",
    ];
    let out = crate::cli(&args);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let json: Value =
        serde_json::from_slice(&crate::cli(&[&args[..], &["--json"]].concat()).stdout).unwrap();
    let rates = json["results"][0]["dataRateUse"].as_array().unwrap();
    assert!(rates.len() > 1, "ADR moved the rate at 3 km: {rates:?}");
    // Fastest first, as received / sent, each with the duty-cycle interval of its own frame: 12
    // bytes of 3D-CTRA state and the 13-byte overhead at 1 %.
    let parts: Vec<String> = rates
        .iter()
        .rev()
        .map(|u| {
            let dr = DataRate::ALL[u["dr"].as_u64().unwrap() as usize];
            let radio = LoraParams::new(dr.sf(), dr.bw());
            let toa = loratrack::time_on_air(&radio, 12 + 13).unwrap().time_on_air;
            let interval = loratrack::min_interval(toa, 0.01).unwrap();
            assert!(
                (u["interval"].as_f64().unwrap() - interval).abs() < 1e-9,
                "{u}"
            );
            format!(
                "DR{} {}/{} every {interval:.2} s",
                u["dr"], u["received"], u["packets"]
            )
        })
        .collect();
    let line = format!(
        "ADR: {}; the interval column is their mean over the packets sent",
        parts.join(", ")
    );
    assert!(text.lines().any(|l| l.trim() == line), "{text}\n/ {line}");
    // That mean weighs each rate by its packets, and is not the starting rate's interval.
    let sent: f64 = rates.iter().map(|u| u["packets"].as_f64().unwrap()).sum();
    let mean = rates
        .iter()
        .map(|u| u["packets"].as_f64().unwrap() * u["interval"].as_f64().unwrap())
        .sum::<f64>()
        / sent;
    let result = &json["results"][0];
    assert!((result["meanInterval"].as_f64().unwrap() - mean).abs() < 1e-9);
    assert!(mean > result["interval"].as_f64().unwrap());
    let row = text.lines().find(|l| l.starts_with("3D-CTRA")).unwrap();
    assert!(row.contains(&format!(" {mean:.2}s ")), "{row} / {mean:.2}");
    // A fixed rate has one, which the interval column already shows.
    let fixed = crate::cli(&args[..5]);
    assert!(fixed.status.success());
    let fixed = String::from_utf8(fixed.stdout).unwrap();
    assert!(
        fixed.contains("3D-CTRA") && !fixed.contains("ADR:"),
        "{fixed}"
    );
}
