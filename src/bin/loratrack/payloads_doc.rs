//! `loratrack sweep --payloads`: the model's own payload against lean payloads at every EU868
//! data rate, on the whole synthetic set and on the real flight; the document docs/payloads.md
//! (`--markdown`, `npm run payloads`; docs/beyond-the-paper.md, "Lean payloads").

use crate::doc_cells::worst_p95_over_dr;
use loratrack::api::{self, ApiError, MISSION_RATES};
use loratrack::{
    ModelChoice, ModelKind, ModelResult, PayloadChoice, Prediction, Scenario, Simulator,
    StationModel, SyntheticChoice, LEAN_SIGNIFICANCE,
};

/// The stations compared: the three motion models and the IMM over them.
const MODELS: &str = "dr,ctra-plus,3d-ctra,imm";
/// The MAC overheads of the synthetic set's runs: none, as the paper sends, and LoRaWAN's 13
/// bytes, the page's default.
const OVERHEADS: [usize; 2] = [0, 13];
/// Gateway distance of the synthetic set's runs, m.
const SYNTHETIC_DISTANCE: f64 = 1000.0;
/// The real flight's gateway distances, m (as docs/beyond-the-paper.md's other real-flight rows).
const REAL_DISTANCES: [f64; 2] = [1000.0, 3300.0];
/// Seeds pooled on the real flight: one 162 s flight brings one to a few packets a seed from
/// SF10 on.
const REAL_SEEDS: u32 = 64;

/// One setting run with both payloads.
pub struct PayloadRun {
    /// MAC overhead, bytes.
    pub overhead: usize,
    /// Gateway distance, m.
    pub distance: f64,
    /// Spreading factor.
    pub sf: i64,
    /// Bandwidth, kHz.
    pub bw: f64,
    /// Per station with the model's own payload.
    pub full: Vec<ModelResult>,
    /// The same with lean payloads.
    pub lean: Vec<ModelResult>,
}

impl PayloadRun {
    /// `kind`'s result among `results`.
    fn of(results: &[ModelResult], kind: StationModel) -> Option<&ModelResult> {
        results.iter().find(|m| m.model == kind)
    }

    fn p75(results: &[ModelResult], kind: StationModel) -> f64 {
        Self::of(results, kind).map_or(f64::NAN, |m| m.error3d.p75)
    }

    fn p95(results: &[ModelResult], kind: StationModel) -> f64 {
        Self::of(results, kind).map_or(f64::NAN, |m| m.error3d.p95)
    }

    /// The IMM's p75 over the best single model's.
    fn imm_ratio(results: &[ModelResult]) -> f64 {
        let best = results
            .iter()
            .filter(|m| m.model != StationModel::Imm)
            .map(|m| m.error3d.p75)
            .fold(f64::INFINITY, f64::min);
        Self::p75(results, StationModel::Imm) / best
    }

    fn lean_share(&self) -> String {
        Self::of(&self.lean, StationModel::Imm).map_or("—".into(), |m| {
            format!("{}/{}", m.lean_packets, m.delivery.packets_sent)
        })
    }

    fn rate(&self) -> String {
        format!("SF{}/{}", self.sf, self.bw)
    }
}

/// `p` run with each payload.
fn both(sim: &mut Simulator, p: &Scenario) -> Result<[Vec<ModelResult>; 2], ApiError> {
    let mut run = |payload| {
        let mut q = p.clone();
        q.sending.payload = payload;
        api::simulate(sim, &q).map(|r| r.results)
    };
    Ok([run(PayloadChoice::Full)?, run(PayloadChoice::Lean)?])
}

/// Every setting of the document: the synthetic set at 1 km at each of [`OVERHEADS`] and
/// [`MISSION_RATES`] (`seeds` seeds from `seed`), and the Canberra flight at [`REAL_DISTANCES`]
/// with the default overhead ([`REAL_SEEDS`] seeds); bounded stations throughout; on `sim`.
pub fn runs(
    sim: &mut Simulator,
    seed: u64,
    seeds: u32,
) -> Result<(Vec<PayloadRun>, Vec<PayloadRun>), ApiError> {
    let mut base = Scenario::default();
    base.station.model = ModelChoice::parse(MODELS).map_err(ApiError::Invalid)?;
    base.station.prediction = Prediction::Bounded;
    base.run.seed = seed;
    let mut at = |p: &Scenario, (sf, bw): (i64, f64)| -> Result<PayloadRun, ApiError> {
        let mut q = p.clone();
        (q.radio.sf, q.radio.bw) = (sf, bw);
        let [full, lean] = both(sim, &q)?;
        Ok(PayloadRun {
            overhead: q.radio.overhead,
            distance: q.channel.distance,
            sf,
            bw,
            full,
            lean,
        })
    };
    let mut synthetic = Vec::new();
    for overhead in OVERHEADS {
        let mut p = base.clone();
        p.flight.synthetic = Some(SyntheticChoice::All);
        p.radio.overhead = overhead;
        p.channel.distance = SYNTHETIC_DISTANCE;
        p.run.seeds = seeds;
        for &rate in &MISSION_RATES {
            synthetic.push(at(&p, rate)?);
        }
    }
    let mut real = Vec::new();
    for distance in REAL_DISTANCES {
        let mut p = base.clone();
        p.flight.sample = Some("canberra".into());
        p.channel.distance = distance;
        p.run.seeds = REAL_SEEDS;
        for &rate in &MISSION_RATES {
            real.push(at(&p, rate)?);
        }
    }
    Ok((synthetic, real))
}

fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.2}")
    } else {
        "—".into()
    }
}

/// `a → b`, each with two decimals.
fn change(a: f64, b: f64) -> String {
    format!("{} → {}", num(a), num(b))
}

/// The rates (with their overhead) where `ratio` of the IMM exceeds 1.02.
fn beyond_two_percent(runs: &[PayloadRun], lean: bool) -> String {
    let over: Vec<String> = runs
        .iter()
        .filter_map(|r| {
            let v = PayloadRun::imm_ratio(if lean { &r.lean } else { &r.full });
            (v > 1.02).then(|| format!("{} with {} B ({v:.3}×)", r.rate(), r.overhead))
        })
        .collect();
    if over.is_empty() {
        "at none".into()
    } else {
        format!("at {}", over.join(", "))
    }
}

/// docs/payloads.md, its runs on `sim`.
pub fn markdown(sim: &mut Simulator, seed: u64, seeds: u32) -> Result<String, ApiError> {
    let (synthetic, real) = runs(sim, seed, seeds)?;
    let last = seed.saturating_add(u64::from(seeds) - 1);
    let mut s = String::from("# Lean payloads: the model's own payload against the smallest that carries its manoeuvres\n\n");
    s += &format!(
        "Generated by `npm run payloads` (`loratrack sweep --payloads --markdown --seeds {seeds}`); do not edit by hand.\n\n"
    );
    s += &format!(
        "Setting: bounded stations ({MODELS}), periodic sending at the 1 % duty cycle, shadowing 4 dB. \
         `full` sends each model's own payload (9, 11 or 12 bytes, the paper's Table II); `lean` \
         (`--payload lean`, reference §5) sends DR's or CTRA+'s smaller payload where every \
         manoeuvre field it leaves out lies within {LEAN_SIGNIFICANCE} standard deviations of zero and its frame is \
         shorter on air. The synthetic set: 30 flights, 44 min, {SYNTHETIC_DISTANCE:.0} m, seeds \
         {seed}–{last} pooled, without and with LoRaWAN's 13-byte overhead. Each station cell: the \
         p75 of the 3D error (m), full → lean. `IMM / best`: the IMM's p75 over the best single \
         model's, with the same payload rule. `lean`: the IMM's packets that went lean, of those \
         sent (0 where no shorter frame exists at that rate).\n\n"
    );
    s += "| overhead | rate | DR | CTRA+ | 3D-CTRA | IMM | IMM / best | lean |\n";
    s += "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
    let dr = StationModel::Single(ModelKind::Dr);
    let cp = StationModel::Single(ModelKind::CtraPlus);
    let c3 = StationModel::Single(ModelKind::Ctra3d);
    for r in &synthetic {
        let cell = |kind| {
            change(
                PayloadRun::p75(&r.full, kind),
                PayloadRun::p75(&r.lean, kind),
            )
        };
        let ratio = format!(
            "{:.3} → {:.3}",
            PayloadRun::imm_ratio(&r.full),
            PayloadRun::imm_ratio(&r.lean)
        );
        s += &format!(
            "| {} B | {} | {} | {} | {} | {} | {ratio} | {} |\n",
            r.overhead,
            r.rate(),
            num(PayloadRun::p75(&r.full, dr)),
            cell(cp),
            cell(c3),
            cell(StationModel::Imm),
            r.lean_share()
        );
    }
    s += "\n## What the table shows\n\n";
    s += &format!(
        "- The IMM's p75 is more than 1.02× the best single model's with full payloads {}; with lean payloads {}.\n",
        beyond_two_percent(&synthetic, false),
        beyond_two_percent(&synthetic, true)
    );
    let unchanged: Vec<String> = synthetic
        .iter()
        .filter(|r| r.lean.iter().all(|m| m.lean_packets == 0))
        .map(|r| format!("{} with {} B", r.rate(), r.overhead))
        .collect();
    s += &format!(
        "- No frame shortens, so nothing changes, at {}.\n",
        unchanged.join(", ")
    );
    s += &format!(
        "\n## The real flight\n\nThe bundled Canberra flight (a loitering ArduCopter, 162 s), the \
         same stations, {REAL_SEEDS} seeds pooled, the default 13-byte overhead. `worst p95 / DR`: \
         the largest p95 of CTRA+, 3D-CTRA and the IMM over DR's (#24's check on a loitering \
         multicopter: at most 1.1), full → lean.\n\n\
         | distance | rate | DR p95 | worst p95 / DR | 3D-CTRA p75 | IMM p75 | lean |\n\
         | --- | --- | --- | --- | --- | --- | --- |\n"
    );
    for r in &real {
        s += &format!(
            "| {:.0} m | {} | {} | {} | {} | {} | {} |\n",
            r.distance,
            r.rate(),
            num(PayloadRun::p95(&r.full, dr)),
            change(worst_p95_over_dr(&r.full).0, worst_p95_over_dr(&r.lean).0),
            change(PayloadRun::p75(&r.full, c3), PayloadRun::p75(&r.lean, c3)),
            change(
                PayloadRun::p75(&r.full, StationModel::Imm),
                PayloadRun::p75(&r.lean, StationModel::Imm)
            ),
            r.lean_share()
        );
    }
    let within = |lean: bool| -> String {
        let over: Vec<String> = real
            .iter()
            .filter(|r| worst_p95_over_dr(if lean { &r.lean } else { &r.full }).0 > 1.1)
            .map(|r| format!("{} at {:.0} m", r.rate(), r.distance))
            .collect();
        if over.is_empty() {
            "nowhere".into()
        } else {
            over.join(", ")
        }
    };
    s += &format!(
        "\nA richer station's p95 exceeds 1.1× DR's with full payloads at {}; with lean payloads at {}.\n",
        within(false),
        within(true)
    );
    Ok(s)
}
