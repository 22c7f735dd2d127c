//! The bundled real flight (`data/ardupilot-log171-quad-canberra.csv`).

use super::{parse_csv, Trajectory};

/// Credit that must accompany the bundled flight wherever it is shown (CC BY-SA 3.0).
pub const CANBERRA_CREDIT: &str =
    "ArduCopter log171 (Canberra), from dronekit/dronekit-la-testdata, CC BY-SA 3.0";

/// The file without its roll, pitch and yaw columns, which loratrack does not read (`build.rs`).
const CANBERRA_CSV: &str = include_str!(concat!(env!("OUT_DIR"), "/canberra.csv"));

/// A real outdoor quadcopter flight: 162 s at 10 Hz from an ArduCopter EKF, local ENU, with
/// velocities (see `data/README.md`). Credit: [`CANBERRA_CREDIT`].
pub fn canberra_flight() -> Trajectory {
    // The file is part of the crate and covered by a test; it always parses.
    parse_csv(CANBERRA_CSV, "canberra")
        .unwrap_or_else(|e| unreachable!("bundled flight does not parse: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bundled_flight_parses_with_its_documented_extent() {
        let f = canberra_flight();
        assert!((f.duration() - 162.0).abs() < 1.0, "{}", f.duration());
        let vmax = (0..f.len()).map(|i| f.state(i)[5]).fold(0.0, f64::max);
        assert!((vmax - 12.2).abs() < 1.0, "max speed {vmax}");
    }
}
