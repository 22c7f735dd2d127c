//! One drone–gateway link: log-distance path loss and shadowing correlated along the drone's
//! path, used in both directions (the downlink sees the reciprocal channel).

use crate::lora::{Channel, Shadowing, GATEWAY_TX_POWER_DBM};
use crate::math::distance;
use crate::rng::Rng;

/// The link between one drone and one gateway over an episode.
#[derive(Clone, Debug)]
pub struct Link {
    /// The gateway's antenna in the drone's flight frame, m.
    pub gateway: [f64; 3],
    shadowing: Shadowing,
    /// Where the drone was at the last shadowing draw.
    last_pos: Option<[f64; 3]>,
    rng: Rng,
    /// The downlinks' own draws ([`Shadowing::aside`]).
    downlink_rng: Rng,
}

/// A received power and the 3D distance it was received over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reception {
    /// 3D distance drone–gateway, m.
    pub distance: f64,
    /// Received power including shadowing, dBm.
    pub rx_dbm: f64,
}

impl Link {
    /// A link to a gateway at `gateway` (flight frame, m) whose uplinks' shadowing draws from
    /// `rng` and its downlinks' from `downlink_rng`.
    pub fn new(channel: &Channel, gateway: [f64; 3], rng: Rng, downlink_rng: Rng) -> Self {
        let p = channel.params();
        Link {
            gateway,
            shadowing: Shadowing::new(p.shadowing_sigma_db, p.decorrelation_distance),
            last_pos: None,
            rng,
            downlink_rng,
        }
    }

    /// The shadowing at `pos`, continuing the process over the distance moved since the last
    /// draw, dB.
    fn shadow_at(&mut self, pos: [f64; 3]) -> f64 {
        let moved = self.last_pos.map_or(0.0, |q| distance(&pos, &q));
        self.last_pos = Some(pos);
        self.shadowing.next(moved, &mut self.rng)
    }

    /// An uplink from `pos` sent `reduction_db` below the channel's transmit power.
    pub fn uplink(&mut self, channel: &Channel, pos: [f64; 3], reduction_db: f64) -> Reception {
        let d = distance(&pos, &self.gateway);
        let s = self.shadow_at(pos);
        Reception {
            distance: d,
            rx_dbm: channel.mean_rx_power_dbm(d) + s - reduction_db,
        }
    }

    /// A downlink at the gateway's power to the drone at `pos`: the reciprocal channel of the
    /// uplink before it, its shadowing continued over the metres flown since, drawn aside
    /// ([`Shadowing::aside`]) so that the uplinks after it meet the fades they would meet without
    /// it. A run whose network answers (ADR) and one whose network is silent (a fixed rate) are
    /// then paired frame by frame wherever their uplinks go at the same moments.
    pub fn downlink(&mut self, channel: &Channel, pos: [f64; 3]) -> Reception {
        let d = distance(&pos, &self.gateway);
        let moved = self.last_pos.map_or(0.0, |q| distance(&pos, &q));
        let s = self.shadowing.aside(moved, &mut self.downlink_rng);
        Reception {
            distance: d,
            rx_dbm: GATEWAY_TX_POWER_DBM - channel.path_loss_db(d) + s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lora::ChannelParams;

    #[test]
    fn downlinks_leave_the_uplinks_fades_as_they_were() {
        let channel = Channel::new(ChannelParams::default()).unwrap();
        let gateway = [3000.0, 0.0, 0.0];
        let link = |downlinks| Link::new(&channel, gateway, Rng::new(5), downlinks);
        let (mut answered, mut silent) = (link(Rng::new(6)), link(Rng::new(7)));
        let mut downlinks = Vec::new();
        for k in 0..200 {
            let pos = [k as f64 * 8.0, 0.0, 50.0];
            let up = answered.uplink(&channel, pos, 0.0);
            assert_eq!(up, silent.uplink(&channel, pos, 0.0), "uplink {k}");
            if k % 3 == 0 {
                // One second later, 8 m on: the reciprocal channel, nearly the uplink's fade.
                let next = [pos[0] + 8.0, 0.0, 50.0];
                let down = answered.downlink(&channel, next);
                let fade =
                    |r: Reception, tx: f64| r.rx_dbm - (tx - channel.path_loss_db(r.distance));
                downlinks.push((
                    fade(up, channel.params().tx_power_dbm),
                    fade(down, GATEWAY_TX_POWER_DBM),
                ));
            }
        }
        let n = downlinks.len() as f64;
        let corr = downlinks.iter().map(|(u, d)| u * d).sum::<f64>() / n / 16.0;
        assert!(corr > 0.8, "uplink–downlink fade correlation {corr}");
    }
}
