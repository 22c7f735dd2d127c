//! EU868 data rates DR0–DR6 (LoRaWAN Regional Parameters RP002-1.0.3 §2.4.3, Table 14).

use super::{Bandwidth, SpreadingFactor};
use serde::Serialize;

/// An EU868 LoRa data rate: DR0 = SF12/125 kHz … DR5 = SF7/125 kHz, DR6 = SF7/250 kHz. A higher
/// index is faster (shorter time on air) and less robust.
///
/// ```
/// use loratrack::{Bandwidth, DataRate, SpreadingFactor};
/// let dr = DataRate::of(SpreadingFactor::new(9).unwrap(), Bandwidth::Khz125).unwrap();
/// assert_eq!(dr.index(), 3);
/// assert_eq!(dr.faster().unwrap().sf().get(), 8);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(transparent)]
pub struct DataRate(u8);

impl DataRate {
    /// The slowest, most robust rate: SF12 at 125 kHz.
    pub const DR0: DataRate = DataRate(0);
    /// SF7 at 125 kHz, the fastest 125 kHz rate.
    pub const DR5: DataRate = DataRate(5);
    /// The fastest EU868 LoRa rate: SF7 at 250 kHz.
    pub const DR6: DataRate = DataRate(6);
    /// DR0..=DR6, slowest first.
    pub const ALL: [DataRate; 7] = [
        DataRate(0),
        DataRate(1),
        DataRate(2),
        DataRate(3),
        DataRate(4),
        DataRate(5),
        DataRate(6),
    ];

    /// DR`index` for 0..=6.
    pub fn new(index: u8) -> Option<Self> {
        (index <= 6).then_some(DataRate(index))
    }

    /// The data rate of a spreading factor and bandwidth, if EU868 defines one (SF7–12 at
    /// 125 kHz, SF7 at 250 kHz).
    pub fn of(sf: SpreadingFactor, bw: Bandwidth) -> Option<Self> {
        match bw {
            Bandwidth::Khz125 => Some(DataRate(12 - sf.get())),
            Bandwidth::Khz250 if sf.get() == 7 => Some(DataRate::DR6),
            _ => None,
        }
    }

    /// The index 0..=6.
    pub fn index(self) -> u8 {
        self.0
    }

    /// Its spreading factor.
    pub fn sf(self) -> SpreadingFactor {
        SpreadingFactor::new(i64::from(12 - self.0.min(5))).expect("DR0..DR6 map to SF7..SF12")
    }

    /// Its bandwidth.
    pub fn bw(self) -> Bandwidth {
        if self.0 == 6 {
            Bandwidth::Khz250
        } else {
            Bandwidth::Khz125
        }
    }

    /// The next faster rate, if any.
    pub fn faster(self) -> Option<Self> {
        Self::new(self.0 + 1)
    }

    /// The next slower rate, if any.
    pub fn slower(self) -> Option<Self> {
        self.0.checked_sub(1).map(DataRate)
    }
}

impl core::fmt::Display for DataRate {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "DR{}", self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_rate_round_trips_through_its_sf_and_bandwidth() {
        for dr in DataRate::ALL {
            assert_eq!(DataRate::of(dr.sf(), dr.bw()), Some(dr));
        }
    }

    #[test]
    fn rates_outside_eu868_have_no_index() {
        let sf8 = SpreadingFactor::new(8).unwrap();
        assert_eq!(DataRate::of(sf8, Bandwidth::Khz250), None);
        assert_eq!(DataRate::of(sf8, Bandwidth::Khz500), None);
    }

    #[test]
    fn faster_and_slower_stop_at_the_ends() {
        assert_eq!(DataRate::DR6.faster(), None);
        assert_eq!(DataRate::DR0.slower(), None);
        assert_eq!(DataRate::DR0.faster(), DataRate::new(1));
    }
}
