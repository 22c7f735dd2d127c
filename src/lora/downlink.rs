//! LoRaWAN class A downlinks: the two receive windows after an uplink (LoRaWAN 1.0.3 §3.3; EU868
//! RX2 defaults from the LoRaWAN Regional Parameters RP002-1.0.3 §2.4.7) and the frame a network
//! server sends in them.

use super::{time_on_air, DataRate, LoraError, LoraParams, SubBand};

/// The device opens its second receive window this long after an uplink ends, s (LoRaWAN
/// `RECEIVE_DELAY2`).
pub const RECEIVE_DELAY2_S: f64 = 2.0;
/// A downlink frame carrying one `LinkADRReq`: MHDR 1 + FHDR 7 + FOpts 5 (the command's CID and
/// its 4 bytes) + MIC 4, no FPort and no application payload, bytes.
pub const ADR_DOWNLINK_BYTES: usize = 17;
/// A downlink frame with no command (the answer to `ADRACKReq`): MHDR 1 + FHDR 7 + MIC 4, bytes.
pub const ACK_DOWNLINK_BYTES: usize = 12;

/// One of the two class A receive windows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Window {
    /// `RECEIVE_DELAY1` (1 s) after the uplink, at the uplink's data rate and channel, in the
    /// uplink's 1 % sub-band.
    Rx1,
    /// `RECEIVE_DELAY2` (2 s) after the uplink, at SF12/125 kHz (DR0) on 869.525 MHz, in the
    /// 10 % sub-band.
    Rx2,
}

impl Window {
    /// Seconds after the uplink's end that the window opens.
    pub fn delay_s(self) -> f64 {
        match self {
            Window::Rx1 => super::RECEIVE_DELAY1_S,
            Window::Rx2 => RECEIVE_DELAY2_S,
        }
    }

    /// The data rate of a downlink in this window after an uplink at `uplink`.
    pub fn data_rate(self, uplink: DataRate) -> DataRate {
        match self {
            Window::Rx1 => uplink,
            Window::Rx2 => DataRate::DR0,
        }
    }

    /// The sub-band whose duty cycle the gateway spends.
    pub fn sub_band(self) -> SubBand {
        match self {
            Window::Rx1 => SubBand::G1,
            Window::Rx2 => SubBand::G3,
        }
    }

    /// Index for per-window tables (0 RX1, 1 RX2).
    pub fn index(self) -> usize {
        match self {
            Window::Rx1 => 0,
            Window::Rx2 => 1,
        }
    }
}

/// Time on air of a downlink frame of `bytes` at `dr`, s: explicit header, coding rate 4/5, no
/// payload CRC (LoRaWAN downlinks carry none).
pub fn downlink_time_on_air(dr: DataRate, bytes: usize) -> Result<f64, LoraError> {
    let mut p = LoraParams::new(dr.sf(), dr.bw());
    p.crc = false;
    Ok(time_on_air(&p, bytes)?.time_on_air)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rx2_is_the_slow_robust_window() {
        assert_eq!(Window::Rx2.data_rate(DataRate::DR5), DataRate::DR0);
        assert_eq!(Window::Rx1.data_rate(DataRate::DR5), DataRate::DR5);
        let fast = downlink_time_on_air(DataRate::DR5, ADR_DOWNLINK_BYTES).unwrap();
        let slow = downlink_time_on_air(DataRate::DR0, ADR_DOWNLINK_BYTES).unwrap();
        assert!(slow > 20.0 * fast, "{slow} vs {fast}");
    }
}
