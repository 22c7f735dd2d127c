//! Cells and phrases more than one generated document prints (docs/senders.md, docs/swarm.md,
//! docs/adr.md, docs/mission.md, docs/payloads.md, docs/paper-reproduction.md), or a document
//! and the CLI's own tables.

use loratrack::{DataRateUse, ModelKind, ModelResult, Scenario, ShadowingModel, StationModel};

/// A data rate a drone sent at, by its EU868 name (`DR3`), or `SF8/500` where it has none.
pub(crate) fn rate_name(u: &DataRateUse) -> String {
    match u.dr {
        Some(dr) => format!("DR{dr}"),
        None => format!("SF{}/{}", u.sf, u.bw),
    }
}

/// The seeds a run pooled: "seed 1", or "seeds 1–8" when it repeats with `seeds` seeds from
/// `seed`.
pub(crate) fn seeds_words(seed: u64, seeds: u32) -> String {
    match seeds {
        0 | 1 => format!("seed {seed}"),
        n => format!("seeds {seed}–{}", seed + u64::from(n) - 1),
    }
}

/// The seeds whose runs a table's numbers pool: "seed 1", or "seeds 1–8 pooled".
pub(crate) fn pooled_seeds(seed: u64, seeds: u32) -> String {
    match seeds {
        0 | 1 => seeds_words(seed, seeds),
        _ => format!("{} pooled", seeds_words(seed, seeds)),
    }
}

/// The MAC overhead and shadowing of a trade-off sweep in words: no overhead, as the paper
/// sends, or LoRaWAN's; shadowing along the path unless fixed in space.
pub(crate) fn link_words(base: &Scenario) -> String {
    let overhead = match base.radio.overhead {
        0 => "no LoRaWAN overhead".into(),
        n => format!("{n} bytes of MAC overhead per packet"),
    };
    match base.channel.shadowing_model {
        ShadowingModel::Path => overhead,
        ShadowingModel::Field => format!("{overhead}, shadowing fixed in space"),
    }
}

/// The arguments beyond a trade-off sweep's own that reproduce it: `--overhead` and
/// `--shadowing-model` where they are not the defaults.
pub(crate) fn link_args(base: &Scenario) -> String {
    let mut args = match base.radio.overhead {
        0 => String::new(),
        n => format!(" --overhead {n}"),
    };
    if base.channel.shadowing_model != ShadowingModel::Path {
        args += &format!(" --shadowing-model {}", base.channel.shadowing_model.name());
    }
    args
}

/// One line of a plain-text table: each cell padded to its width, left-aligned where the width
/// is negative.
pub(crate) fn text_row(cells: &[String], widths: &[isize]) -> String {
    let padded: Vec<String> = cells
        .iter()
        .zip(widths)
        .map(|(c, &w)| {
            if w < 0 {
                format!("{c:<width$}", width = w.unsigned_abs())
            } else {
                format!("{c:>width$}", width = w.unsigned_abs())
            }
        })
        .collect();
    padded.join(" ") + "\n"
}

/// The largest p95 of a richer station (every one but DR) over DR's among `results`, and that
/// station's label: the real flight's test of "no richer station's p95 over 1.1× DR's". Not a
/// number when DR is missing, or a richer station has no p95, so that a check of it fails.
pub(crate) fn worst_p95_over_dr(results: &[ModelResult]) -> (f64, &'static str) {
    let dr = StationModel::Single(ModelKind::Dr);
    let dr_p95 = results
        .iter()
        .find(|m| m.model == dr)
        .map_or(f64::NAN, |m| m.error3d.p95);
    results
        .iter()
        .filter(|m| m.model != dr)
        .map(|m| (m.error3d.p95 / dr_p95, m.model.label()))
        .fold((f64::NEG_INFINITY, "—"), |worst, r| {
            // A ratio that is not a number stays; of equals the first does.
            if worst.0.is_nan() || r.0 <= worst.0 {
                worst
            } else {
                r
            }
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_documents_command_and_setting_name_the_overhead_and_fades_fixed_in_space() {
        let mut base = Scenario::default();
        base.radio.overhead = 0;
        assert_eq!(link_args(&base), "");
        assert_eq!(link_words(&base), "no LoRaWAN overhead");
        base.radio.overhead = 13;
        base.channel.shadowing_model = ShadowingModel::Field;
        assert_eq!(link_args(&base), " --overhead 13 --shadowing-model field");
        assert_eq!(
            link_words(&base),
            "13 bytes of MAC overhead per packet, shadowing fixed in space"
        );
    }
}
