//! `loratrack sweep`: runs a grid of scenarios (the paper's, the trade-offs, the swarms) and
//! hands it to the document that prints it.

use crate::commands::{json, results_table, Output};
use crate::progress::RunCount;
use clap::Args;
use loratrack::api::{self, ApiError};
use loratrack::options as opt;
use loratrack::{
    AccessSettings, ChannelSense, ChannelSettings, DutyCycleMode, ModelChoice, ModelKind,
    NetworkSettings, Prediction, RadioSettings, RunSettings, Scenario, Schedule, SenderKind,
    Sending, SfPlan, ShadowingModel, SharedDroneRuns, StationSettings, SwarmReport, SwarmSettings,
    SyntheticChoice,
};

#[derive(Args)]
#[group(required = true, multiple = false)]
pub struct SweepKind {
    /// The paper's grid: SF 7/8, 250 kHz, d = 1/2/3 km, whole synthetic set, no LoRaWAN overhead.
    #[arg(long)]
    paper: bool,
    /// Swarms of 1..500 drones: collision rate (beside the ALOHA formula) and median per-drone p75 for both schedules (aloha, slotted), 1 and 3 channels, SF7 for all and spread SFs, periodic and error-triggered sending (300 s per drone, 3D-CTRA, --prediction, the swarm's default clocks and delays).
    #[arg(long)]
    swarm: bool,
    /// The mission station beside DR, CTRA+, 3D-CTRA and IMM at every EU868 data rate (SF7/250, SF7..SF12/125) at 1 and 3 km, on the whole synthetic set (each flight's own plan), --overhead bytes of MAC overhead (0 unless set).
    #[arg(long)]
    mission: bool,
    /// The airtime / error trade-off of error-triggered sending (thresholds 0.5..10 m, per-packet and budget rules) against periodic sending, on the whole synthetic set at --sf/--bw/--distance, --overhead bytes of MAC overhead (0 unless set), for the first model of --model (3d-ctra when --model is all).
    #[arg(long)]
    senders: bool,
    /// Full against lean payloads (--payload lean) at every EU868 data rate, bounded stations DR, CTRA+, 3D-CTRA and IMM: the whole synthetic set at 1 km without and with LoRaWAN's overhead (--seeds), the real Canberra flight at 1 and 3.3 km (64 seeds); printed as Markdown (docs/payloads.md). Its grid is fixed: it takes only --seed and --seeds.
    #[arg(long, conflicts_with_all = ["sf", "bw", "distance", "overhead", "model", "prediction", "held_out", "svg", "json"])]
    payloads: bool,
    /// Fixed data rates DR0..DR6 and both ADR modes (starting at --sf/--bw) at each distance, m, comma-separated (e.g. 1000,3000,5000,7000), on the whole synthetic set, --overhead bytes of MAC overhead (0 unless set), for the first model of --model (3d-ctra when --model is all).
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "M,M,...",
        allow_negative_numbers = true,
        value_parser = opt::number("distance")
    )]
    distances: Option<Vec<f64>>,
}

#[derive(Args)]
pub struct SweepArgs {
    #[command(flatten)]
    kind: SweepKind,
    /// --senders: spreading factor; --distances: the one ADR starts at.
    #[arg(long, default_value_t = opt::SF.default as i64, allow_negative_numbers = true, value_parser = opt::whole::<i64>("sf"))]
    sf: i64,
    /// --senders: bandwidth, kHz; --distances: the one ADR starts at.
    #[arg(long, default_value_t = opt::BW.default, allow_negative_numbers = true, value_parser = opt::number("bw"))]
    bw: f64,
    /// --senders: gateway distance, m; --swarm: the drones' distance from the gateway.
    #[arg(long, default_value_t = opt::DISTANCE.default, allow_negative_numbers = true, value_parser = opt::number("distance"))]
    distance: f64,
    /// --senders, --distances, --mission: MAC overhead added to each payload, bytes: 0 as the
    /// paper sends (these sweeps' default, which their documents use), 13 for LoRaWAN (the
    /// default of simulate and the page).
    #[arg(long, default_value_t = 0, conflicts_with_all = ["paper", "swarm"], allow_negative_numbers = true, value_parser = opt::whole::<usize>("overhead"))]
    overhead: usize,
    /// --senders, --distances, --mission: shadowing along the path (the default) or fixed in
    /// space, so that every run of the sweep meets the same fades at the same places.
    #[arg(long, value_enum, default_value_t, conflicts_with_all = ["paper", "swarm", "payloads"])]
    shadowing_model: ShadowingModel,
    /// --senders: the budget rule's capacity in packets.
    #[arg(long, default_value_t = loratrack::DEFAULT_BURST, allow_negative_numbers = true, value_parser = opt::whole::<u32>("burst"))]
    burst: u32,
    /// --senders: error-triggered sending's heartbeat, s (at least the duty-cycle interval at --sf/--bw).
    #[arg(long, default_value_t = opt::MAX_INTERVAL.default, allow_negative_numbers = true, value_parser = opt::number("maxInterval"))]
    max_interval: f64,
    /// Seed of all random draws, 0..2^53-1, or random for a fresh one (reported in the output).
    #[arg(long, default_value = "1", value_name = "N|random", value_parser = loratrack::parse_seed)]
    seed: u64,
    /// --distances, --senders: seeds each run pools (seed, seed + 1, ...), so that a comparison
    /// rests on more than one draw of the shadowing and noise.
    #[arg(long, default_value_t = opt::SEEDS.default as u32, allow_negative_numbers = true, value_parser = opt::whole::<u32>("seeds"))]
    seeds: u32,
    /// --distances --markdown: run everything again on the next block of as many seeds (seed +
    /// seeds, ...) and judge the ADR rows there too: a verdict read off one block of seeds is
    /// checked on seeds it was not read from.
    #[arg(long, requires = "markdown")]
    held_out: bool,
    /// Station model(s): dr, ctra-plus, 3d-ctra, imm, a comma list, or all (the paper's three).
    #[arg(long, default_value = "all")]
    model: String,
    /// Station prediction(s), comma-separated: paper, bounded. Several only with --paper, and with
    /// --distances --markdown (each after the first adds the ADR verdicts with that station).
    #[arg(long, value_enum, value_delimiter = ',', default_value = "paper")]
    prediction: Vec<Prediction>,
    /// Print the paper-reproduction document (Markdown) instead of a table.
    #[arg(long, conflicts_with = "json")]
    markdown: bool,
    /// --senders: print the trade-off chart (SVG: p75 and p95 against airtime) instead of a table.
    #[arg(long, conflicts_with_all = ["json", "markdown"])]
    svg: bool,
    #[command(flatten)]
    out: Output,
}

/// Runs the sweep `a` asks for, counting its runs on a terminal's progress line
/// ([`RunCount`]) until it returns.
pub(crate) fn sweep(a: SweepArgs) -> Result<String, ApiError> {
    let count = RunCount::on_stderr("sweep");
    let model = ModelChoice::parse(&a.model).map_err(ApiError::Invalid)?;
    let predictions: Vec<Prediction> = a.prediction.clone();
    // Only the paper's grid and the ADR document have room for several; elsewhere a second
    // would be dropped without a word.
    let several = a.kind.paper || (a.kind.distances.is_some() && a.markdown);
    if predictions.len() > 1 && !several {
        let names: Vec<&str> = predictions.iter().map(|p| p.name()).collect();
        return Err(ApiError::Invalid(format!(
            "this sweep takes one --prediction, not {} (--paper and --distances --markdown take several)",
            names.join(",")
        )));
    }
    refuse_unread(&a)?;
    if a.kind.senders {
        return sweep_senders(&a, model, predictions[0], &count);
    }
    if a.kind.swarm {
        return sweep_swarm(&a, predictions[0], &count);
    }
    if a.kind.mission {
        return sweep_mission(&a, predictions[0], &count);
    }
    if a.kind.payloads {
        return crate::payloads_doc::markdown(&mut count.simulator(), a.seed, a.seeds);
    }
    if let Some(distances) = &a.kind.distances {
        return sweep_distances(&a, model, &predictions, distances, &count);
    }
    let r = api::sweep_paper(&mut count.simulator(), a.seed, &predictions, &model)?;
    if a.out.json {
        return Ok(json(&r));
    }
    if a.markdown {
        let real = real_flight_runs(a.seed, &predictions, &model, &count)?;
        let (rates, variants) = if predictions.contains(&Prediction::Bounded) {
            // One simulator: the flight as flown at 3.3 km reuses the drone runs of the rates.
            let mut sim = count.simulator();
            let rates = crate::real_flight_rates::runs(&mut sim, a.seed, &model)?;
            let variants = crate::real_flight_variants::runs(&mut sim, a.seed, &model, &rates)?;
            (rates, variants)
        } else {
            (Vec::new(), Vec::new())
        };
        return Ok(crate::reproduction::markdown(&r, &real, &rates, &variants));
    }
    let mut out = format!(
        "paper sweep: synthetic set ({:.0} s), 250 kHz, no LoRaWAN overhead, seed {}\n",
        r.flight_time, r.seed
    );
    for run in &r.runs {
        out += &format!(
            "\nSF{} d = {} m, {} prediction\n{}\n",
            run.sf,
            run.distance,
            run.prediction.name(),
            results_table(&run.results)
        );
    }
    Ok(out.trim_end().to_string())
}

/// Which sweeps read each flag that not every sweep reads: `(flag, changed from its default,
/// the sweeps that read it)`. The others set their own grid (`--paper`, `--mission`), fly
/// their own drones (`--swarm`) or take only a seed (`--payloads`).
fn readers(a: &SweepArgs) -> [(&'static str, bool, &'static [&'static str]); 11] {
    const TRADE_OFFS: &[&str] = &["--senders", "--distances", "--mission"];
    [
        (
            "--sf",
            a.sf != opt::SF.default as i64,
            &["--senders", "--distances"],
        ),
        (
            "--bw",
            a.bw != opt::BW.default,
            &["--senders", "--distances"],
        ),
        (
            "--distance",
            a.distance != opt::DISTANCE.default,
            &["--senders", "--swarm"],
        ),
        ("--overhead", a.overhead != 0, TRADE_OFFS),
        (
            "--shadowing-model",
            a.shadowing_model != ShadowingModel::default(),
            TRADE_OFFS,
        ),
        (
            "--burst",
            a.burst != loratrack::DEFAULT_BURST,
            &["--senders"],
        ),
        (
            "--max-interval",
            a.max_interval != opt::MAX_INTERVAL.default,
            &["--senders"],
        ),
        (
            "--seeds",
            a.seeds != opt::SEEDS.default as u32,
            &["--senders", "--distances", "--mission", "--payloads"],
        ),
        (
            "--model",
            a.model != "all",
            &["--paper", "--senders", "--distances"],
        ),
        ("--held-out", a.held_out, &["--distances"]),
        ("--svg", a.svg, &["--senders"]),
    ]
}

/// The sweep `kind` asks for, as its flag.
fn kind_flag(kind: &SweepKind) -> &'static str {
    match kind {
        k if k.paper => "--paper",
        k if k.swarm => "--swarm",
        k if k.mission => "--mission",
        k if k.senders => "--senders",
        k if k.payloads => "--payloads",
        _ => "--distances",
    }
}

/// Refuses a flag changed from its default that the sweep asked for would drop without a word,
/// naming the sweeps that read it.
fn refuse_unread(a: &SweepArgs) -> Result<(), ApiError> {
    let kind = kind_flag(&a.kind);
    let dropped = readers(a)
        .into_iter()
        .find(|(_, changed, read_by)| *changed && !read_by.contains(&kind));
    match dropped {
        Some((flag, _, read_by)) => Err(ApiError::Invalid(format!(
            "{flag} is read only by sweep {}: sweep {kind} would drop it",
            read_by.join(", ")
        ))),
        None => Ok(()),
    }
}

/// The bundled real flight beside the paper's grid: SF7 / 250 kHz at [`REAL_DISTANCES`], without
/// and with the LoRaWAN overhead, [`REAL_SEEDS`] seeds pooled (one 162 s flight is one draw of the
/// shadowing), every prediction and model of the sweep.
fn real_flight_runs(
    seed: u64,
    predictions: &[Prediction],
    model: &ModelChoice,
    count: &RunCount,
) -> Result<Vec<crate::reproduction::RealRun>, ApiError> {
    let mut sim = count.simulator();
    let mut runs = Vec::new();
    for &prediction in predictions {
        for overhead in [0, Scenario::default().radio.overhead] {
            for distance in crate::reproduction::REAL_DISTANCES {
                let mut p = Scenario::default();
                p.flight.sample = Some("canberra".into());
                p.station.model = model.clone();
                p.station.prediction = prediction;
                (p.radio.sf, p.radio.bw, p.radio.overhead) = (7, 250.0, overhead);
                p.channel.distance = distance;
                (p.run.seed, p.run.seeds) = (seed, crate::reproduction::REAL_SEEDS);
                let results = api::simulate(&mut sim, &p)?.results;
                runs.push(crate::reproduction::RealRun {
                    overhead,
                    distance,
                    prediction,
                    results,
                });
            }
        }
    }
    Ok(runs)
}

/// The one station a trade-off sweep runs: `all` (the default) means the paper's best, 3D-CTRA.
fn one_station(model: ModelChoice) -> ModelChoice {
    if model == ModelChoice::all() {
        ModelChoice::one(ModelKind::Ctra3d)
    } else {
        ModelChoice::one(model.models()[0])
    }
}

/// The base of a trade-off sweep: the whole synthetic set, one station, `--overhead` bytes of MAC
/// overhead (none unless set, as the paper sends).
fn trade_off_base(a: &SweepArgs, model: ModelChoice, prediction: Prediction) -> Scenario {
    let mut p = Scenario::default();
    p.flight.synthetic = Some(SyntheticChoice::All);
    p.station.model = one_station(model);
    p.station.prediction = prediction;
    p.radio.sf = a.sf;
    p.radio.bw = a.bw;
    p.radio.overhead = a.overhead;
    p.channel.distance = a.distance;
    p.channel.shadowing_model = a.shadowing_model;
    p.sending.max_interval = a.max_interval;
    p.run.seed = a.seed;
    p.run.seeds = a.seeds;
    p
}

/// `sweep --distances`: the table or JSON at one prediction; docs/adr.md at the first, with the
/// same runs at each further one (`--prediction paper,bounded`) in a section of their own.
fn sweep_distances(
    a: &SweepArgs,
    model: ModelChoice,
    predictions: &[Prediction],
    distances: &[f64],
    count: &RunCount,
) -> Result<String, ApiError> {
    let blocks = |prediction| -> Result<Vec<Scenario>, ApiError> {
        let base = trade_off_base(a, model.clone(), prediction);
        if !(a.held_out && a.markdown) {
            return Ok(vec![base]);
        }
        let next = held_out_block(&base)?;
        Ok(vec![base, next])
    };
    // Every block checked before anything runs.
    let plans = predictions
        .iter()
        .map(|&p| blocks(p))
        .collect::<Result<Vec<_>, _>>()?;
    let mut sim = count.simulator();
    let mut runs = Vec::new();
    for plan in plans {
        let mut block = Vec::new();
        for base in plan {
            block.push((api::sweep_distances(&mut sim, &base, distances)?, base));
        }
        runs.push(block);
    }
    let r = &runs[0][0].0;
    if a.out.json {
        return Ok(json(r));
    }
    if a.markdown {
        return Ok(crate::adr_doc::distances_markdown(&runs));
    }
    Ok(crate::adr_doc::distances_table(&runs[0][0]))
}

/// `--held-out`'s runs: the next block of as many seeds. Refused before anything runs when that
/// block passes the seed limit, naming the seeds the user did not type.
fn held_out_block(base: &Scenario) -> Result<Scenario, ApiError> {
    let count = u64::from(base.run.seeds.max(1));
    let first = base.run.seed.saturating_add(count);
    if first.saturating_add(count - 1) <= loratrack::MAX_SEED {
        let mut next = base.clone();
        next.run.seed = first;
        return Ok(next);
    }
    Err(ApiError::Invalid(format!(
        "--held-out runs the next {count} seeds, {first}..{}, past the largest seed, {}; \
         with --held-out the seed can be at most {}",
        first.saturating_add(count - 1),
        loratrack::MAX_SEED,
        loratrack::MAX_SEED + 1 - 2 * count
    )))
}

fn sweep_mission(
    a: &SweepArgs,
    prediction: Prediction,
    count: &RunCount,
) -> Result<String, ApiError> {
    let base = trade_off_base(a, ModelChoice::all(), prediction);
    let r = api::sweep_mission(&mut count.simulator(), &base)?;
    if a.out.json {
        return Ok(json(&r));
    }
    if a.markdown {
        return Ok(crate::mission_doc::mission_markdown(&r, &base));
    }
    Ok(crate::mission_doc::mission_table(&r, &base))
}

fn sweep_senders(
    a: &SweepArgs,
    model: ModelChoice,
    prediction: Prediction,
    count: &RunCount,
) -> Result<String, ApiError> {
    let base = trade_off_base(a, model, prediction);
    let r = api::sweep_senders(&mut count.simulator(), &base, a.burst)?;
    if a.out.json {
        return Ok(json(&r));
    }
    if a.svg {
        return Ok(crate::senders_doc::senders_svg(&r, &base));
    }
    if a.markdown {
        // The whole synthetic set at every setting; the real flight (short: eight seeds pooled)
        // near and far; the paper's station at the first setting.
        let mut sim = count.simulator();
        let mut overview = Vec::new();
        let station = prediction.name();
        for at in api::SENDER_SETTINGS {
            let r = api::sweep_senders_at(&mut sim, &base, a.burst, at)?;
            overview.push((format!("synthetic set, {station}"), r));
        }
        let mut real = base.clone();
        (real.flight.synthetic, real.flight.sample) = (None, Some("canberra".into()));
        real.run.seeds = real.run.seeds.max(8);
        for at in [api::SENDER_SETTINGS[0], api::SENDER_SETTINGS[1]] {
            let r = api::sweep_senders_at(&mut sim, &real, a.burst, at)?;
            let label = format!("Canberra (real), {station}, {} seeds", real.run.seeds);
            overview.push((label, r));
        }
        if prediction != Prediction::Paper {
            let mut paper = base.clone();
            paper.station.prediction = Prediction::Paper;
            let r = api::sweep_senders_at(&mut sim, &paper, a.burst, api::SENDER_SETTINGS[0])?;
            overview.push(("synthetic set, paper".to_string(), r));
        }
        return Ok(crate::senders_doc::senders_markdown(&r, &base, &overview));
    }
    Ok(crate::senders_doc::senders_table(&r, &base))
}

/// Drone counts of `sweep --swarm`.
const SWARM_SIZES: [usize; 7] = [1, 12, 36, 72, 150, 300, 500];
/// The schedules, SF plans and senders of `sweep --swarm`, in the table's order.
const SCHEDULES: [Schedule; 2] = [Schedule::Aloha, Schedule::Slotted];
const SF_PLANS: [SfPlan; 2] = [SfPlan::Fixed, SfPlan::Spread];
const SENDERS: [SenderKind; 2] = [SenderKind::Periodic, SenderKind::Error];

fn sweep_swarm(
    a: &SweepArgs,
    prediction: Prediction,
    count: &RunCount,
) -> Result<String, ApiError> {
    // Every combination, flown family by family: a drone's station errs alike from the packets
    // that swarms of any size, either channel count and (the paper's station) either sender
    // deliver alike, and each drone keeps its station's errors for the last few swarms only
    // (`SharedDroneRuns`).
    let mut cases = Vec::new();
    for schedule in SCHEDULES {
        for plan in SF_PLANS {
            for channels in [1u8, 3] {
                for sender in SENDERS {
                    cases.extend(SWARM_SIZES.map(|n| (schedule, channels, plan, sender, n)));
                }
            }
        }
    }
    let scenarios = cases
        .iter()
        .map(|&(schedule, channels, plan, sender, drones)| {
            Scenario {
                access: AccessSettings {
                    schedule,
                    ..AccessSettings::default()
                },
                swarm: SwarmSettings {
                    drones,
                    duration: 300.0,
                    sf_plan: plan,
                },
                network: NetworkSettings {
                    channels: Some(channels),
                    ..NetworkSettings::default()
                },
                radio: RadioSettings {
                    sf: 7,
                    bw: 125.0,
                    ..RadioSettings::default()
                },
                station: StationSettings {
                    model: ModelChoice::one(ModelKind::Ctra3d),
                    prediction,
                    ..StationSettings::default()
                },
                sending: Sending {
                    sender,
                    // The heartbeat must cover the slowest drone's interval: SF12's with spread
                    // SFs (error-triggered sending's own: a periodic drone has none).
                    max_interval: if plan == SfPlan::Spread && sender == SenderKind::Error {
                        150.0
                    } else {
                        opt::MAX_INTERVAL.default
                    },
                    ..Sending::default()
                },
                channel: ChannelSettings {
                    distance: a.distance,
                    ..ChannelSettings::default()
                },
                run: RunSettings {
                    seed: a.seed,
                    ..RunSettings::default()
                },
                ..Scenario::default()
            }
        });
    let shared = SharedDroneRuns::new(SHARED_RUNS_BYTES).with_station_errors();
    let flown = swarms(scenarios.collect(), &shared, count)?;
    // Freed before the crowd comparisons below fly drones of their own.
    drop(shared);
    // Reported in the table's order: schedule, channels, SF plan, sender, size.
    fn place<T: PartialEq>(all: &[T], x: &T) -> Option<usize> {
        all.iter().position(|a| a == x)
    }
    let mut rows: Vec<_> = cases.iter().zip(flown).collect();
    rows.sort_by_key(|((schedule, channels, plan, sender, n), _)| {
        (
            place(&SCHEDULES, schedule),
            *channels,
            place(&SF_PLANS, plan),
            place(&SENDERS, sender),
            *n,
        )
    });
    let rows: Vec<SwarmReport> = rows.into_iter().map(|(_, r)| r).collect();
    if a.out.json {
        return Ok(json(&rows));
    }
    // The crowd comparisons are for the tables only (JSON gives the sweep's own rows). They fly
    // 72 of the grid's 500 drones again, and seven more seeds' 72: their own runs, so that the
    // grid's are freed first.
    let crowd = crowds(&rows, &SharedDroneRuns::new(SHARED_RUNS_BYTES), count)?;
    Ok(crate::swarm_doc::swarm_markdown(&rows, &crowd, a.markdown))
}

/// The most bytes of drone estimates a swarm sweep keeps to share between its swarms: its 112
/// swarms fly the same 500 drones for 300 s (108 MB of estimates, and up to 192 MB set aside for
/// their stations' errors), its crowd comparison 72 drones at eight seeds (124 MB).
const SHARED_RUNS_BYTES: usize = 320 << 20;

/// Each swarm of `scenarios`, in order; independent, so natively they share the cores (each
/// swarm alone leaves one idle for most of its loop). Drones flown alike share their filter
/// runs through `shared`; each swarm counts as a run on `count` as it ends.
fn swarms(
    scenarios: Vec<Scenario>,
    shared: &SharedDroneRuns,
    count: &RunCount,
) -> Result<Vec<SwarmReport>, ApiError> {
    use rayon::prelude::*;
    scenarios
        .par_iter()
        .map(|s| {
            let report = api::swarm_sharing(s, shared);
            count.done();
            report
        })
        .collect()
}

/// Seeds of the crowd comparison: one seed's swarm says little, since which packets collide
/// moves the median drone's p75 by ±5 m from seed to seed at 72 drones on one channel.
const CROWD_SEEDS: u64 = 8;

/// The thresholds (m) and the heartbeat (s) of the crowd comparison's budget-rule groups after the
/// defaults: on the scale of the errors a crowd of 72 drones on one channel allows (its median
/// drone's p75 is ~55 m), where the defaults (2 m, 10 s) are passed at nearly every chance to send.
/// Several thresholds, since a sender that saves airtime is judged at equal airtime, and how much
/// it wins there depends on how much it saves: the groups trace that trade-off.
const CROWD_THRESHOLDS_M: [f64; 4] = [20.0, 30.0, 40.0, 60.0];
const CROWD_HEARTBEAT_S: f64 = 60.0;

/// The thresholds (m) of the per-packet groups after the default, with the default heartbeat:
/// the default's 2 m is passed at nearly every chance to send, so there the sender is periodic in
/// all but name; these show from where a threshold above the lone drone's scale pays in a crowd.
const CROWD_PER_PACKET_THRESHOLDS_M: [f64; 2] = [5.0, 10.0];

/// An error-triggered setting of the crowd comparison: its schedule, its duty-cycle rule, its
/// threshold (m) and heartbeat (s) where they are not the defaults, and whether it listens to its
/// channel.
type CrowdSender = (Schedule, DutyCycleMode, Option<(f64, f64)>, ChannelSense);

/// The error-triggered settings the crowd comparison tries.
fn crowd_senders() -> Vec<CrowdSender> {
    use ChannelSense::{Cad, Off};
    let heartbeat = opt::MAX_INTERVAL.default;
    let mut senders = vec![(Schedule::Aloha, DutyCycleMode::PerPacket, None, Off)];
    senders.extend(CROWD_PER_PACKET_THRESHOLDS_M.map(|m| {
        (
            Schedule::Aloha,
            DutyCycleMode::PerPacket,
            Some((m, heartbeat)),
            Off,
        )
    }));
    senders.extend([
        (Schedule::Aloha, DutyCycleMode::PerPacket, None, Cad),
        (Schedule::Slotted, DutyCycleMode::PerPacket, None, Off),
        (Schedule::Aloha, DutyCycleMode::Budget, None, Off),
        (Schedule::Aloha, DutyCycleMode::Budget, None, Cad),
    ]);
    senders.extend(CROWD_THRESHOLDS_M.map(|m| {
        (
            Schedule::Aloha,
            DutyCycleMode::Budget,
            Some((m, CROWD_HEARTBEAT_S)),
            Off,
        )
    }));
    senders
}

/// The crowd comparisons: error-triggered sending under each duty-cycle rule against periodic
/// sending (per packet, the paper's) with 72 drones on one SF7 channel, ALOHA and slotted,
/// seed by seed from the sweep's own seed (whose per-packet runs are in `rows`), each with
/// periodic sending slowed by its duty cycle to the airtime error-triggered sending used: the
/// fair comparison for a sender that saves airtime. Under ALOHA the per-packet rule at the default
/// threshold without listening to its channel, then at each of [`CROWD_PER_PACKET_THRESHOLDS_M`],
/// then at the default, which listens ([`ChannelSense::Cad`]). The budget rule under ALOHA only: a
/// slotted drone sends in its slot whatever credit it holds; under it, the default threshold and
/// heartbeat, without and with listening, then each of [`CROWD_THRESHOLDS_M`] with
/// [`CROWD_HEARTBEAT_S`], without listening. Each schedule's periodic
/// runs serve every setting compared under it. A comparison is left out when `rows` lacks its
/// setting.
fn crowds(
    rows: &[SwarmReport],
    shared: &SharedDroneRuns,
    count: &RunCount,
) -> Result<Vec<crate::swarm_doc::Crowd>, ApiError> {
    let find = |schedule, sender| {
        rows.iter().find(|r: &&SwarmReport| {
            let c = &r.config.settings;
            c.access.schedule == schedule
                && c.channels() == 1
                && c.swarm.sf_plan == SfPlan::Fixed
                && c.sending.sender == sender
                && c.swarm.drones == 72
        })
    };
    let mut periodic: Vec<(Schedule, Vec<SwarmReport>)> = Vec::new();
    for schedule in [Schedule::Aloha, Schedule::Slotted] {
        if let Some(p) = find(schedule, SenderKind::Periodic) {
            periodic.push((schedule, crowd_runs(p, shared, count, |_| {})?));
        }
    }
    let mut crowd = Vec::new();
    for (schedule, rule, trigger, sense) in crowd_senders() {
        let (Some((_, periodic)), Some(e)) = (
            periodic.iter().find(|(s, _)| *s == schedule),
            find(schedule, SenderKind::Error),
        ) else {
            continue;
        };
        let error = crowd_runs(e, shared, count, |c| {
            c.sending.duty_cycle_mode = rule;
            c.sending.channel_sense = sense;
            if let Some((threshold, heartbeat)) = trigger {
                c.sending.threshold = threshold;
                c.sending.max_interval = heartbeat;
            }
        })?;
        // Periodic sending slowed by its duty cycle to the airtime error-triggered sending used.
        let slowed: Vec<Scenario> = periodic
            .iter()
            .zip(&error)
            .map(|(p, e)| {
                let mut c = p.config.settings.clone();
                c.radio.duty_cycle = (c.radio.duty_cycle * e.airtime / p.airtime)
                    .clamp(opt::DUTY_CYCLE.min, opt::DUTY_CYCLE.max);
                c
            })
            .collect();
        let seeds = periodic
            .iter()
            .zip(error)
            .zip(swarms(slowed, shared, count)?)
            .map(|((p, error), equal)| crate::swarm_doc::CrowdSeed {
                periodic: p.clone(),
                error,
                equal,
            })
            .collect();
        crowd.push(crate::swarm_doc::Crowd { schedule, seeds });
    }
    Ok(crowd)
}

/// The swarm of `row` with `change` made, at [`CROWD_SEEDS`] seeds from its own, in one
/// batch; `row` itself stands for the first when the change leaves it as it was.
fn crowd_runs(
    row: &SwarmReport,
    shared: &SharedDroneRuns,
    count: &RunCount,
    change: impl Fn(&mut Scenario),
) -> Result<Vec<SwarmReport>, ApiError> {
    let scenarios: Vec<Scenario> = (0..CROWD_SEEDS)
        .map(|k| {
            let mut c = row.config.settings.clone();
            c.run.seed += k;
            change(&mut c);
            c
        })
        .collect();
    if scenarios[0] != row.config.settings {
        return swarms(scenarios, shared, count);
    }
    let mut runs = vec![row.clone()];
    runs.extend(swarms(scenarios[1..].to_vec(), shared, count)?);
    Ok(runs)
}
