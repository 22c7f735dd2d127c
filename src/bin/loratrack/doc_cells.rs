//! Cells and phrases more than one generated document prints (docs/senders.md, docs/swarm.md,
//! docs/adr.md, docs/mission.md).

/// The MAC overhead of a trade-off sweep in words: none, as the paper sends, or LoRaWAN's.
pub(crate) fn overhead_words(bytes: usize) -> String {
    match bytes {
        0 => "no LoRaWAN overhead".into(),
        n => format!("{n} bytes of MAC overhead per packet"),
    }
}

/// The `--overhead` argument that reproduces a trade-off sweep: none for the default 0.
pub(crate) fn overhead_arg(bytes: usize) -> String {
    match bytes {
        0 => String::new(),
        n => format!(" --overhead {n}"),
    }
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
