//! What the network server knows of the crowd on its channels: how often each device sends, at
//! which spreading factor, and so how likely a frame at each data rate is to meet another
//! device's frame (docs/reference.md §6.5, "The crowd").

use crate::lora::DataRate;
use crate::math::exp;

/// The weight a device's earlier gaps keep at each frame heard from it: its frame rate is
/// counted over about its last ten heard frames, so that a device that changes rate is soon
/// seen at its new one.
const FORGET: f64 = 0.9;

/// One device as the server has heard it.
#[derive(Clone, Copy, Debug, Default)]
struct Device {
    /// The frame counter and time (s) of the last frame heard.
    last: Option<(u32, f64)>,
    /// Frames sent (received or not, from the frame counter) and seconds, both forgotten by
    /// [`FORGET`] a heard frame.
    frames: f64,
    seconds: f64,
    /// What it adds to its SF's sums: (SF − 7, frames per second, their airtime per second).
    counted: Option<(usize, f64, f64)>,
}

/// The traffic of every device the server hears, by spreading factor: for each SF the sum of
/// the devices' frames per second and of their airtime per second.
///
/// A device's frames per second come from its frame counter (lost frames count too) over the
/// time between the frames heard; its airtime is that of its frames at the rate it was last
/// heard at. A frame of `T` s at an SF meets another device's frame at that SF, sent `r` times a
/// second with `T'` s on air over `C` channels hopped at random, with probability r (T + T') / C
/// (pure ALOHA: overlapping at all is a loss; the capture effect makes it an upper bound), so
/// the chance it meets none is exp(−Σ r (T + T') / C) over the other devices.
#[derive(Clone, Debug)]
pub struct CrowdLoad {
    devices: Vec<Device>,
    /// Per SF (7…12): frames per second, and seconds on air per second, of the devices heard.
    rate: [f64; 6],
    airtime: [f64; 6],
    /// Per SF: how many devices count toward it.
    count: [usize; 6],
}

impl CrowdLoad {
    /// A server that has heard none of `devices` yet.
    pub fn new(devices: usize) -> Self {
        CrowdLoad {
            devices: vec![Device::default(); devices],
            rate: [0.0; 6],
            airtime: [0.0; 6],
            count: [0; 6],
        }
    }

    /// Device `d`'s frame `fcnt` at `dr`, `time_on_air` s long, heard at `time` s. A time
    /// that runs backwards (a new flight's time axis) restarts the device's count.
    pub fn heard(&mut self, d: usize, fcnt: u32, dr: DataRate, time_on_air: f64, time: f64) {
        let Some(device) = self.devices.get_mut(d) else {
            return;
        };
        if let Some((last_fcnt, last_time)) = device.last {
            let (sent, elapsed) = (fcnt.wrapping_sub(last_fcnt), time - last_time);
            if elapsed > 0.0 && sent > 0 && sent < u32::MAX / 2 {
                device.frames = FORGET * device.frames + f64::from(sent);
                device.seconds = FORGET * device.seconds + elapsed;
            }
        }
        device.last = Some((fcnt, time));
        if device.seconds <= 0.0 {
            return;
        }
        let per_second = device.frames / device.seconds;
        let now = (
            usize::from(dr.sf().get() - 7),
            per_second,
            per_second * time_on_air,
        );
        if let Some((sf, rate, airtime)) = device.counted.replace(now) {
            self.rate[sf] -= rate;
            self.airtime[sf] -= airtime;
            self.count[sf] -= 1;
        }
        self.rate[now.0] += now.1;
        self.airtime[now.0] += now.2;
        self.count[now.0] += 1;
    }

    /// How many of the other devices' frames are expected to be on air at some moment of a
    /// transmission `seconds` long (a downlink, during which a half-duplex gateway hears none):
    /// Σ r (`seconds` + T′) over the devices other than `d`. Exactly 0 where no other device has
    /// been heard.
    pub fn others_on_air(&self, d: usize, seconds: f64) -> f64 {
        (0..6)
            .filter_map(|sf| self.others(d, sf))
            .map(|(rate, airtime)| (rate * seconds + airtime).max(0.0))
            .sum()
    }

    /// For device `d`, per EU868 data rate: the chance that its frame at that rate, lasting
    /// `time_on_air[rate]` s, on one of `channels` channels picked at random, overlaps another
    /// device's frame at the rate's SF (type docs). Exactly 0 where no other device has been
    /// heard at that SF.
    pub fn loss(&self, d: usize, time_on_air: &[f64; 7], channels: u8) -> [f64; 7] {
        let channels = f64::from(channels.max(1));
        DataRate::ALL.map(|dr| {
            let Some((rate, airtime)) = self.others(d, usize::from(dr.sf().get() - 7)) else {
                return 0.0;
            };
            let load = (time_on_air[usize::from(dr.index())] * rate + airtime).max(0.0);
            1.0 - exp(-load / channels)
        })
    }

    /// The frames per second and seconds on air per second at SF 7 + `sf` of the devices other
    /// than `d`; `None` where no other device has been heard there.
    fn others(&self, d: usize, sf: usize) -> Option<(f64, f64)> {
        let (mut rate, mut airtime, mut others) = (self.rate[sf], self.airtime[sf], self.count[sf]);
        if let Some((own_sf, own_rate, own_airtime)) =
            self.devices.get(d).and_then(|dev| dev.counted)
        {
            if own_sf == sf {
                rate -= own_rate;
                airtime -= own_airtime;
                others -= 1;
            }
        }
        (others > 0).then_some((rate, airtime))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Device `d` heard every `every` s for `n` frames at DR6, `toa` s each, from frame 0, time 0.
    fn steady(crowd: &mut CrowdLoad, d: usize, every: f64, toa: f64, n: u32) {
        for k in 0..n {
            crowd.heard(d, k, DataRate::DR6, toa, f64::from(k) * every);
        }
    }

    #[test]
    fn a_lone_device_meets_no_one() {
        let mut crowd = CrowdLoad::new(1);
        steady(&mut crowd, 0, 2.0, 0.02, 50);
        assert_eq!(crowd.loss(0, &[0.02; 7], 1), [0.0; 7]);
    }

    #[test]
    fn the_frames_on_air_during_a_transmission_are_the_others_at_every_sf() {
        // Device 0 alone: nothing to miss, whatever its own traffic.
        let mut crowd = CrowdLoad::new(3);
        steady(&mut crowd, 0, 2.0, 0.02, 20);
        assert_eq!(crowd.others_on_air(0, 1.0), 0.0);
        // Two others, each 0.5 frames a second of 0.02 s, one of them at SF12: a 1 s
        // transmission overlaps 2 · 0.5 · (1 + 0.02) of their frames, whichever SF they use.
        steady(&mut crowd, 1, 2.0, 0.02, 20);
        for k in 0..20 {
            crowd.heard(2, k, DataRate::DR0, 0.02, f64::from(k) * 2.0);
        }
        assert!((crowd.others_on_air(0, 1.0) - 1.02).abs() < 1e-9);
        assert!((crowd.others_on_air(1, 1.0) - 1.02).abs() < 1e-9);
    }

    #[test]
    fn others_at_the_same_sf_cost_what_pure_aloha_says() {
        // Eleven other devices on air 1 % of the time each (0.02 s every 2 s), three channels:
        // a frame of 0.02 s meets one with probability 2 · 0.01 / 3 per device.
        let mut crowd = CrowdLoad::new(12);
        for d in 0..12 {
            steady(&mut crowd, d, 2.0, 0.02, 40);
        }
        let loss = crowd.loss(0, &[0.02; 7], 3);
        let aloha = crate::aloha_collision_rate(0.01, 3, 12);
        // exp(−x) against (1 − x/n)^n: within a hundredth of a percent here.
        assert!((loss[6] - aloha).abs() < 0.01 * aloha, "{loss:?} {aloha}");
        // SF7 at 125 kHz meets the same SF7 frames; SF8 and slower meet no one.
        assert!(
            loss[5] > 0.0 && loss[4] == 0.0 && loss[0] == 0.0,
            "{loss:?}"
        );
    }

    #[test]
    fn lost_frames_count_toward_a_devices_rate_and_a_rate_change_moves_it() {
        let mut crowd = CrowdLoad::new(2);
        steady(&mut crowd, 1, 2.0, 0.02, 10);
        // Device 0 heard at frames 0 and 10, 20 s apart: one frame every 2 s, though one heard.
        crowd.heard(0, 0, DataRate::DR6, 0.02, 0.0);
        crowd.heard(0, 10, DataRate::DR6, 0.02, 20.0);
        let both = crowd.loss(1, &[0.02; 7], 1)[6];
        assert!((both - (1.0 - (-0.02f64).exp())).abs() < 1e-12, "{both}");
        // Heard next at SF8: it leaves SF7 and joins SF8.
        crowd.heard(0, 20, DataRate::new(4).unwrap(), 0.04, 40.0);
        let loss = crowd.loss(1, &[0.02; 7], 1);
        assert_eq!(loss[6], 0.0);
        assert!(loss[4] > 0.0);
    }

    #[test]
    fn a_new_time_axis_restarts_a_count_without_breaking_it() {
        let mut crowd = CrowdLoad::new(2);
        steady(&mut crowd, 0, 2.0, 0.02, 10);
        steady(&mut crowd, 1, 2.0, 0.02, 10);
        let before = crowd.loss(1, &[0.02; 7], 1);
        // Device 0's next flight starts at time 0 again.
        crowd.heard(0, 10, DataRate::DR6, 0.02, 0.0);
        assert_eq!(crowd.loss(1, &[0.02; 7], 1), before);
        assert!(before[6] > 0.0 && before[6].is_finite());
    }
}
