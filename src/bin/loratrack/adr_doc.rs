//! `loratrack sweep --distances`: fixed data rates against ADR by distance, as a table or
//! docs/adr.md.

use crate::doc_cells::{link_args, link_words, pooled_seeds, rate_name, seeds_words};
use loratrack::api::{DistanceRun, DistanceSweepReport, VersusBestFixed};
use loratrack::{
    tracking_ack_limits, AdrMode, Scenario, ADR_ACK_DELAY, ADR_ACK_LIMIT, DEFAULT_ADR_HISTORY,
    DEFAULT_ADR_MARGIN_DB, TRACKING_HYSTERESIS, TRACKING_WINDOW,
};

fn distance_label(run: &DistanceRun) -> String {
    match run.dr {
        Some(dr) => {
            let u = &run.result.data_rate_use[0];
            format!("DR{dr} SF{}/{}", u.sf, u.bw)
        }
        None => format!("{} from DR{}", run.adr.name(), run.start.unwrap_or(0)),
    }
}

/// The packets per data rate, e.g. `DR6 310, DR5 12`.
fn rate_use(run: &DistanceRun) -> String {
    let parts: Vec<String> = run
        .result
        .data_rate_use
        .iter()
        .rev()
        .map(|u| format!("{} {}", rate_name(u), u.packets))
        .collect();
    parts.join(", ")
}

/// `run`'s p75 over the whole flight time (time before a flight's first packet counted as the
/// largest error), m; `None` when a quarter of the time or more had no packet.
fn flight_p75(run: &DistanceRun) -> Option<f64> {
    run.result.whole_flight.p75
}

/// The fixed data rates' runs at `distance`.
fn fixed_at(r: &DistanceSweepReport, distance: f64) -> impl Iterator<Item = &DistanceRun> {
    r.runs
        .iter()
        .filter(move |x| x.distance == distance && x.dr.is_some())
}

/// " (0.98–1.13)": a ratio's interval, ∞ where some draws leave the row's p75 in the untracked
/// time, 0 where they leave only the best fixed rate's there.
fn interval_words(interval: Option<[f64; 2]>) -> String {
    let end = |v: f64| {
        if v.is_infinite() {
            "∞".to_string()
        } else if v == 0.0 {
            "0".to_string()
        } else {
            format!("{v:.2}")
        }
    };
    interval.map_or(String::new(), |[lo, hi]| {
        format!(" ({}–{})", end(lo), end(hi))
    })
}

/// A percentile over the flight time, or "—" where the untracked time reaches it.
fn metres(v: Option<f64>) -> String {
    v.map_or("—".to_string(), |v| format!("{v:.2}"))
}

fn distance_rows(r: &DistanceSweepReport, markdown: bool) -> String {
    let mut out = if markdown {
        "| distance | rate | delivery | tracked | p50 | p75 | p95 | p75 / best fixed | packets per data rate |\n|---|---|---|---|---|---|---|---|---|\n".to_string()
    } else {
        "distance  rate                delivery  tracked    p50     p75     p95  p75/best  packets per data rate\n".to_string()
    };
    for run in &r.runs {
        let e = &run.result.whole_flight;
        let vs = match run.p75_vs_best_fixed {
            Some(v) if v.ratio.is_finite() => format!("{:.2}", v.ratio),
            _ => "—".to_string(),
        };
        let cells = [
            format!("{:.0} m", run.distance),
            distance_label(run),
            format!("{:.1} %", 100.0 * run.delivery),
            format!("{:.1} %", 100.0 * e.tracked),
            metres(e.p50),
            metres(e.p75),
            metres(e.p95),
            vs,
            rate_use(run),
        ];
        out += &if markdown {
            format!("| {} |\n", cells.join(" | "))
        } else {
            format!(
                "{:<9} {:<18} {:>8} {:>8} {:>7} {:>7} {:>7} {:>9}  {}\n",
                cells[0],
                cells[1],
                cells[2],
                cells[3],
                cells[4],
                cells[5],
                cells[6],
                cells[7],
                cells[8]
            )
        };
    }
    out
}

/// `sweep --distances`: the table, under what it rests on.
pub fn distances_table((r, base): &(DistanceSweepReport, Scenario)) -> String {
    format!(
        "fixed data rates and ADR by distance (3D error in m): the whole synthetic set, {} station, {} \
         prediction, {}, {}\n{}",
        base.station.model.models()[0].label(),
        base.station.prediction.name(),
        link_words(base),
        pooled_seeds(base.run.seed, base.run.seeds),
        distance_rows(r, false).trim_end()
    )
}

/// One prediction's sweeps for docs/adr.md: its block of seeds, then with `--held-out` the next.
pub type Blocks = Vec<(DistanceSweepReport, Scenario)>;

/// `sweep --distances --markdown`: docs/adr.md from `runs`, one entry per `--prediction`: the
/// first prediction's table and findings, with `--held-out` the ADR verdicts on the next block
/// of seeds, then for each further prediction the same verdicts on every block.
pub fn distances_markdown(runs: &[Blocks]) -> String {
    let mut s = first_prediction(runs);
    for blocks in &runs[1..] {
        s += &other_prediction(blocks);
    }
    s
}

/// The table, what it shows and the held-out block, at the first prediction; the command line
/// names every prediction of `runs`.
fn first_prediction(runs: &[Blocks]) -> String {
    let (r, base) = &runs[0][0];
    let held_out = runs[0].get(1).map(|(r, b)| (r, b));
    let distances: Vec<String> = sweep_distances(r)
        .iter()
        .map(|x| format!("{x:.0}"))
        .collect();
    let model = base.station.model.models()[0];
    let lone = tracking_ack_limits(1, 1);
    let mut s = String::from(
        "# Adaptive data rate: fixed data rates against LoRaWAN's ADR and a tracking-aware one\n\n",
    );
    let predictions: Vec<&str> = runs
        .iter()
        .map(|b| b[0].1.station.prediction.name())
        .collect();
    s += &format!(
        "Generated by `npm run adr` (`loratrack sweep --distances {} --seeds {}{} --markdown --model {} --sf {} --bw {}{}{}`); do not edit by hand.\n\n",
        distances.join(","),
        base.run.seeds,
        if held_out.is_some() { " --held-out" } else { "" },
        model.name(),
        base.radio.sf,
        base.radio.bw,
        link_args(base),
        if runs.len() > 1 {
            format!(" --prediction {}", predictions.join(","))
        } else {
            String::new()
        }
    );
    s += &format!(
        "Setting: the whole synthetic set (30 flights, 44 min, flown one after another by one drone that stays joined, \
         so ADR carries over between flights), {} station, {} prediction, periodic sending at the 1 % duty cycle, \
         {}, shadowing 4 dB, {}. Fixed rows keep one EU868 data rate throughout; ADR rows \
         start at SF{} / {} kHz or at DR0 (SF12, the safe start of a device that knows nothing of its link). `lorawan` is the network server's ADR (best SNR of the last {} uplinks, device margin \
         {} dB, 3 dB steps, never slowing the rate itself; the device backs off after {} + {} uplinks without a \
         downlink). `tracking` picks the rate with the least expected cost, the time mean of age⁴ of the station's \
         newest packet (error growing with the square of that age), from each rate's interval and its delivery ratio \
         estimated from the last {} frames (received ones' power and, censored, the lost ones' known from the frame \
         counter); that long-run choice changes when the best rate costs {:.0} % less. Within it the network follows \
         fades: a received frame's shadowing, carried forward by its correlation over the metres the drone flies in \
         one interval (at the speed its payload reports), forecasts the next frame's delivery at each rate, and the \
         network asks for the cheapest rate under that forecast, never faster than the long-run choice. The network \
         sets a lone tracking drone's back-off to {} + {} uplinks without a downlink (LoRaWAN 1.1 `ADRParamSetupReq`; \
         in a swarm twice the drones per gateway, up to the regional 64 + 32, so that the gateway can answer), so it \
         finds a lost link within seconds, not minutes. Commands travel in \
         a downlink after a received uplink, which the reciprocal channel may lose. The station restarts with each \
         flight, so every flight is untracked until its first packet arrives: `tracked` is the share of the flight \
         time after it, and p50, p75 and p95 are over the whole flight time, a moment without any packet counting as \
         an error larger than all others (docs/reference.md §12; — where the untracked time reaches the percentile). \
         Without that, a rate that reaches the station in one flight of ten could show the smallest p75. `p75 / best \
         fixed` compares with the fixed rate of lowest p75 at that distance.{}\n\n",
        model.label(),
        base.station.prediction.name(),
        link_words(base),
        seeds_phrase(base),
        base.radio.sf,
        base.radio.bw,
        DEFAULT_ADR_HISTORY,
        DEFAULT_ADR_MARGIN_DB,
        ADR_ACK_LIMIT,
        ADR_ACK_DELAY,
        TRACKING_WINDOW,
        100.0 * TRACKING_HYSTERESIS,
        lone.limit,
        lone.delay,
        interval_setting(base)
    );
    s += &distance_rows(r, true);
    s += &adr_findings(r, base);
    if let Some((r, b)) = held_out {
        s += &held_out_findings(r, b);
    }
    s
}

/// What the intervals beside the verdicts' ratios are, where the seeds give them.
fn interval_setting(base: &Scenario) -> String {
    if base.run.seeds < 2 {
        return String::new();
    }
    format!(
        " Below the table each ratio carries its 95 % interval from resampling the {} seeds together, the ADR row's \
         and the best fixed rate's alike, each seed a whole pass over the set, which ADR carries from flight to \
         flight (a paired bootstrap, docs/reference.md §12; ∞ where some draws leave the row's p75 in the \
         untracked time, 0 where they leave only the best fixed rate's there): a ratio above 1.05 whose interval reaches down to 1.05 may be the seeds' luck.",
        base.run.seeds
    )
}

/// The distances the sweep ran, m, in its order (its runs come grouped by distance).
fn sweep_distances(r: &DistanceSweepReport) -> Vec<f64> {
    let mut d: Vec<f64> = r.runs.iter().map(|x| x.distance).collect();
    d.dedup();
    d
}

/// `--held-out`: the best fixed rate and every ADR row's verdict on seeds the table above was
/// not read from.
fn held_out_findings(r: &DistanceSweepReport, base: &Scenario) -> String {
    format!(
        "\n## The same runs on {}\n\nEverything above rests on one block of seeds; the same runs on the next \
         block (`--held-out`) show which verdicts hold beyond it. Where two rates are close, the best fixed rate \
         itself can change between blocks. {}",
        seeds_range(base),
        block_verdicts("The best fixed rate", r)
    )
}

/// A further prediction's section: on each block of seeds, the best fixed rates and the ADR
/// verdicts. The station changes what a lost packet costs, not which packets arrive: `tracked`
/// and the packets per data rate are the first table's.
fn other_prediction(blocks: &Blocks) -> String {
    let name = blocks[0].1.station.prediction.name();
    let mut s = format!(
        "\n## The same runs with the {name} station\n\nThe network and the link are the table's; only the station's \
         forecast between packets differs ({name} prediction, docs/beyond-the-paper.md), so every packet arrives as \
         above and the tracked share is the same, while the errors, and with them the best fixed rate's p75 and \
         each ratio, are the {name} station's.\n"
    );
    for (r, b) in blocks {
        let lead = format!("On {}, the best fixed rate", seeds_range(b));
        s += &format!("\n{}", block_verdicts(&lead, r));
    }
    s
}

/// `lead` ("The best fixed rate") at each distance of `r`, then each ADR row's verdict.
fn block_verdicts(lead: &str, r: &DistanceSweepReport) -> String {
    let best: Vec<String> = sweep_distances(r)
        .iter()
        .map(
            |&d| match r.best_fixed(d).or_else(|| most_tracked_fixed(r, d)) {
                Some(b) => format!("{d:.0} m {}, {}", distance_label(b), p75_phrase(b)),
                None => format!("{d:.0} m none"),
            },
        )
        .collect();
    format!(
        "{lead} at each distance: {}.\n\n{}",
        best.join("; "),
        adr_verdicts(r)
    )
}

/// "seed 1", or "seeds 1–8 pooled (…)" when a run repeats.
fn seeds_phrase(base: &Scenario) -> String {
    match base.run.seeds {
        0 | 1 => seeds_range(base),
        n => format!(
            "{} pooled (every statistic is over all {n} runs of the set, so the best fixed rate is not \
             one lucky draw of the shadowing)",
            seeds_range(base)
        ),
    }
}

/// "seed 1", or "seeds 1–8" when a run repeats.
fn seeds_range(base: &Scenario) -> String {
    seeds_words(base.run.seed, base.run.seeds)
}

/// What `docs/adr.md`'s table shows: each ADR row judged against the tracking ADR's aim, and
/// LoRaWAN ADR's figure explained with its own numbers.
fn adr_findings(r: &DistanceSweepReport, base: &Scenario) -> String {
    let lone = tracking_ack_limits(1, 1);
    format!(
        "\n## What the table shows\n\n{}\nThe tracking ADR aims to stay within 5 % of the best fixed rate at every \
         distance, since it may always choose that rate. Where the list above says otherwise it does not reach that \
         aim. Its cost describes a station that is always tracking; here every flight starts untracked, so time at a \
         slow rate also delays each flight's first packet, which the cost does not count. Its delivery estimate treats \
         every frame of its window as an independent draw of the shadowing, but the shadowing is correlated along \
         the path and stands still while the drone does: a drone waiting in a deep fade (at the start of a flight, \
         say) loses a run of frames that reads as a poor link and sends it to a slower \
         rate (see the packets per data rate), and the hysteresis, about as large as the true difference in cost \
         between neighbouring rates, holds it there until the window has forgotten those frames; at the slowest \
         rates each frame, and so each chance to move again, is minutes apart. Starting from DR0 costs the first flight's start: a drone's first packet goes out at a random \
         moment within its starting rate's interval (as in every run, so that no setting starts in step with the \
         flight), at DR0 up to about two minutes in, the first flight untracked until it arrives, and that frame's \
         off-time holds the next one back as long; starting \
         too fast for the link, as at SF7 at 5 and 7 km, costs the device's back-off before the network hears it \
         at all ({} silent uplinks a rate). A back-off that short also steps the drone down when two requests in \
         a row go unanswered on a link that still delivers most frames (at 5 km, DR3's two in three): the \
         network brings it back with the next frame it hears, one slow interval later.{}\n\n{}",
        adr_verdicts(r),
        lone.limit + lone.delay,
        edge_of_tracking(r),
        lorawan_explained(r, base)
    )
}

/// Where the best fixed rate has a packet for less than 80 % of the flight time, its p75 lies
/// near the untracked quarter: a few flights' first packets decide it, and the intervals say so.
fn edge_of_tracking(r: &DistanceSweepReport) -> String {
    let edge: Vec<String> = sweep_distances(r)
        .into_iter()
        .filter_map(|d| {
            let tracked = r.best_fixed(d)?.result.whole_flight.tracked;
            (tracked < 0.8).then(|| format!("{:.1} % at {d:.0} m", 100.0 * tracked))
        })
        .collect();
    if edge.is_empty() {
        return String::new();
    }
    format!(
        " Where even the best fixed rate has a packet for less than 80 % of the flight time ({}), its p75 lies \
         near the untracked quarter, so a few flights' first packets move it far: the ratios' intervals there \
         are wide, and a ratio is a weak verdict.",
        edge.join(", ")
    )
}

/// One line per ADR row: at each distance its p75 over the best fixed rate's, or why there is
/// none, then where it misses the 5 % aim.
fn adr_verdicts(r: &DistanceSweepReport) -> String {
    let mut labels: Vec<String> = r
        .runs
        .iter()
        .filter(|x| x.dr.is_none())
        .map(distance_label)
        .collect();
    labels.sort_by_key(|l| (!l.starts_with("tracking"), l.clone()));
    labels.dedup();
    let mut out = String::new();
    for label in labels {
        let mut parts = Vec::new();
        let mut misses = Vec::new();
        for x in r
            .runs
            .iter()
            .filter(|x| x.dr.is_none() && distance_label(x) == label)
        {
            let d = x.distance;
            let tracked = 100.0 * x.result.whole_flight.tracked;
            let vs = x.p75_vs_best_fixed.filter(|v| v.ratio.is_finite());
            match (r.best_fixed(d), vs) {
                (
                    Some(_),
                    Some(VersusBestFixed {
                        ratio: v, interval, ..
                    }),
                ) => {
                    parts.push(format!("{v:.2}×{} at {d:.0} m", interval_words(interval)));
                    if v > 1.05 {
                        misses.push(match interval {
                            Some([lo, _]) if lo <= 1.05 => {
                                format!("{d:.0} m (though its interval reaches down to 1.05)")
                            }
                            _ => format!("{d:.0} m"),
                        });
                    }
                }
                (Some(b), _) => {
                    parts.push(format!(
                        "no p75 at {d:.0} m (a packet for {tracked:.1} % of the flight time; {} {:.1} %)",
                        distance_label(b),
                        100.0 * b.result.whole_flight.tracked
                    ));
                    misses.push(format!("{d:.0} m"));
                }
                (None, _) => {
                    if let Some(most) = most_tracked_fixed(r, d) {
                        parts.push(format!(
                            "at {d:.0} m no fixed rate has a packet for three quarters of the flight time: it has one \
                             for {tracked:.1} %, the best fixed rate ({}) for {:.1} %",
                            distance_label(most),
                            100.0 * most.result.whole_flight.tracked
                        ));
                    }
                }
            }
        }
        let verdict = if misses.is_empty() {
            "Within 5 % of the best fixed rate wherever one has a p75".to_string()
        } else {
            format!(
                "More than 5 % worse than the best fixed rate at {}",
                misses.join(", ")
            )
        };
        out += &format!(
            "- `{label}`: p75 / best fixed: {}. {verdict}.\n",
            parts.join("; ")
        );
    }
    out
}

/// "a p75 of 4.20 m", or why there is none.
fn p75_phrase(run: &DistanceRun) -> String {
    match flight_p75(run) {
        Some(p) => format!("a p75 of {p:.2} m"),
        None => format!(
            "no p75 (a packet for {:.1} % of the flight time)",
            100.0 * run.result.whole_flight.tracked
        ),
    }
}

/// The fixed data rate with a packet for the largest share of the flight time at `distance`.
fn most_tracked_fixed(r: &DistanceSweepReport, distance: f64) -> Option<&DistanceRun> {
    fixed_at(r, distance).max_by(|a, b| {
        a.result
            .whole_flight
            .tracked
            .total_cmp(&b.result.whole_flight.tracked)
    })
}

/// Why LoRaWAN's ADR lands where it does, with the sweep's own numbers.
fn lorawan_explained(r: &DistanceSweepReport, base: &Scenario) -> String {
    let start = r.runs.iter().find_map(|x| x.start).unwrap_or(0);
    let dr0_interval = r
        .runs
        .iter()
        .find(|x| x.dr == Some(0))
        .map_or(f64::NAN, |x| x.result.interval);
    let at: Vec<String> = r
        .runs
        .iter()
        .filter(|x| x.adr == AdrMode::Lorawan && x.start == Some(start))
        .filter_map(|x| {
            let b = r.best_fixed(x.distance)?;
            Some(format!(
                "at {:.0} m it delivers {:.1} % for {} where the best fixed rate, {}, delivers {:.1} % for {}",
                x.distance,
                100.0 * x.delivery,
                p75_phrase(x),
                distance_label(b),
                100.0 * b.delivery,
                p75_phrase(b)
            ))
        })
        .collect();
    format!(
        "LoRaWAN's ADR is built for delivery and battery, not for a young newest packet: it only speeds a device \
         up (or lowers its power) while the best SNR of its last {DEFAULT_ADR_HISTORY} uplinks leaves a {DEFAULT_ADR_MARGIN_DB} dB \
         margin, and a device slows down only by its own back-off after {ADR_ACK_LIMIT} + {ADR_ACK_DELAY} uplinks \
         without a downlink, one data rate per {ADR_ACK_DELAY} more. From DR{start}: {}. Its p75 follows from how long \
         it spends at rates too fast for the link before backing off, and how far the margin keeps it from the rate \
         that tracks best. The station ({} prediction) pays for every second without a packet. From DR0 it \
         first needs {DEFAULT_ADR_HISTORY} uplinks at DR0's {:.0} s interval ({:.0} min) before its first step up.\n",
        at.join("; "),
        base.station.prediction.name(),
        dr0_interval,
        dr0_interval * DEFAULT_ADR_HISTORY as f64 / 60.0
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An interval's ends say where some draws leave a p75 in the untracked time: the row's (∞)
    /// or only the best fixed rate's (0), not as a number.
    #[test]
    fn an_intervals_ends_name_the_draws_without_a_p75() {
        assert_eq!(interval_words(Some([0.876, 1.134])), " (0.88–1.13)");
        assert_eq!(interval_words(Some([0.0, 1.45])), " (0–1.45)");
        assert_eq!(interval_words(Some([1.87, f64::INFINITY])), " (1.87–∞)");
        assert_eq!(interval_words(None), "");
    }
}
