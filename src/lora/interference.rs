//! Which of two overlapping LoRa packets survives: same-SF capture and inter-SF rejection.

use crate::math::log10;

/// Same-SF capture threshold, dB: a packet survives same-SF interference when it is at least this
/// much stronger than the sum of the interferers (Bor et al., "Do LoRa low-power wide-area
/// networks scale?", MSWiM 2016 — LoRaSim).
pub const CAPTURE_THRESHOLD_DB: f64 = 6.0;

/// Signal-to-interference ratio (dB) a packet at SF `7 + row` needs against interference at SF
/// `7 + column` (Goursaud & Gorce 2015, as used by ns-3's `lorawan` module; Croce et al., IEEE
/// Commun. Letters 2018 measured the same order). The diagonal is the same-SF capture threshold;
/// off the diagonal, other SFs are rejected down to these (negative) ratios.
pub const INTER_SF_SIR_DB: [[f64; 6]; 6] = [
    [6.0, -16.0, -18.0, -19.0, -19.0, -20.0],
    [-24.0, 6.0, -20.0, -22.0, -22.0, -22.0],
    [-27.0, -27.0, 6.0, -23.0, -25.0, -25.0],
    [-30.0, -30.0, -30.0, 6.0, -26.0, -28.0],
    [-33.0, -33.0, -33.0, -33.0, 6.0, -29.0],
    [-36.0, -36.0, -36.0, -36.0, -36.0, 6.0],
];

/// How interference is judged (`--capture`, `--inter-sf`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InterferenceModel {
    /// Same SF: the stronger packet survives by [`CAPTURE_THRESHOLD_DB`] (on), or every
    /// overlapping packet is lost (off: pure ALOHA).
    pub capture: bool,
    /// Different SFs interfere as [`INTER_SF_SIR_DB`] says (on), or not at all (off: the SFs are
    /// treated as perfectly orthogonal).
    pub inter_sf: bool,
}

/// Whether a packet at `sf` received at `signal_dbm` survives `interference_dbm[k]`, the summed
/// power (dBm; `-inf` for none) of the overlapping packets at SF `7 + k` on its channel.
///
/// ```
/// use loratrack::{survives, InterferenceModel};
/// let none = f64::NEG_INFINITY;
/// let model = InterferenceModel { capture: true, inter_sf: true };
/// // 7 dB above a same-SF packet: captured; 5 dB: lost.
/// assert!(survives(7, -100.0, &[-107.0, none, none, none, none, none], model));
/// assert!(!survives(7, -100.0, &[-105.0, none, none, none, none, none], model));
/// ```
pub fn survives(
    sf: u8,
    signal_dbm: f64,
    interference_dbm: &[f64; 6],
    model: InterferenceModel,
) -> bool {
    let row = usize::from(sf - 7);
    interference_dbm.iter().enumerate().all(|(k, &i)| {
        if i == f64::NEG_INFINITY {
            return true;
        }
        if k == row {
            model.capture && signal_dbm - i >= CAPTURE_THRESHOLD_DB
        } else {
            !model.inter_sf || signal_dbm - i >= INTER_SF_SIR_DB[row][k]
        }
    })
}

/// The sum of powers given in dBm, in dBm (`-inf` for none).
pub fn sum_dbm(powers_dbm: impl IntoIterator<Item = f64>) -> f64 {
    let mw: f64 = powers_dbm
        .into_iter()
        .map(|p| crate::math::pow(10.0, p / 10.0))
        .sum();
    if mw > 0.0 {
        10.0 * log10(mw)
    } else {
        f64::NEG_INFINITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const NONE: f64 = f64::NEG_INFINITY;

    #[test]
    fn without_capture_any_same_sf_overlap_is_fatal() {
        let aloha = InterferenceModel {
            capture: false,
            inter_sf: false,
        };
        assert!(!survives(
            9,
            -90.0,
            &[NONE, NONE, -140.0, NONE, NONE, NONE],
            aloha
        ));
        assert!(
            survives(9, -90.0, &[-80.0, NONE, NONE, NONE, NONE, -80.0], aloha),
            "other SFs are orthogonal"
        );
    }

    #[test]
    fn other_sfs_are_rejected_down_to_the_matrix() {
        let m = InterferenceModel {
            capture: true,
            inter_sf: true,
        };
        // SF12 signal against SF7 interference needs -36 dB.
        assert!(survives(
            12,
            -120.0,
            &[-85.0, NONE, NONE, NONE, NONE, NONE],
            m
        ));
        assert!(!survives(
            12,
            -120.0,
            &[-83.0, NONE, NONE, NONE, NONE, NONE],
            m
        ));
    }

    #[test]
    fn powers_add_in_milliwatts() {
        assert!((sum_dbm([-100.0, -100.0]) - (-100.0 + 10.0 * 2f64.log10())).abs() < 1e-12);
        assert_eq!(sum_dbm([]), f64::NEG_INFINITY);
    }
}
