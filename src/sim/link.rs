//! One drone–gateway link: log-distance path loss and shadowing, used in both directions (the
//! downlink sees the reciprocal channel).

use crate::lora::{Channel, Shadowing, ShadowingField, ShadowingModel, GATEWAY_TX_POWER_DBM};
use crate::math::distance;
use crate::rng::Rng;

/// The link between one drone and one gateway over an episode.
#[derive(Clone, Debug)]
pub struct Link {
    /// The gateway's antenna in the drone's flight frame, m.
    pub gateway: [f64; 3],
    fades: Fades,
}

/// Where a link's shadowing comes from ([`ShadowingModel`]).
#[derive(Clone, Debug)]
enum Fades {
    /// Continued frame by frame along the path.
    Path {
        shadowing: Shadowing,
        /// Where the drone was at the last shadowing draw.
        last_pos: Option<[f64; 3]>,
        rng: Rng,
        /// The downlinks' own draws ([`Shadowing::aside`]).
        downlink_rng: Rng,
    },
    /// Fixed in space.
    Field(ShadowingField),
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
    /// `rng` and its downlinks' from `downlink_rng`; with shadowing fixed in space the field is
    /// drawn from `rng` and the downlinks need no draws of their own.
    pub fn new(channel: &Channel, gateway: [f64; 3], mut rng: Rng, downlink_rng: Rng) -> Self {
        let p = channel.params();
        let fades = match p.shadowing_model {
            ShadowingModel::Path => Fades::Path {
                shadowing: Shadowing::new(p.shadowing_sigma_db, p.decorrelation_distance),
                last_pos: None,
                rng,
                downlink_rng,
            },
            ShadowingModel::Field => Fades::Field(ShadowingField::new(
                p.shadowing_sigma_db,
                p.decorrelation_distance,
                &mut rng,
            )),
        };
        Link { gateway, fades }
    }

    /// The shadowing of an uplink from `pos`, dB: the field's there, or the path's process
    /// continued over the distance moved since the last draw.
    fn uplink_fade(&mut self, pos: [f64; 3]) -> f64 {
        match &mut self.fades {
            Fades::Field(field) => field.at(pos),
            Fades::Path {
                shadowing,
                last_pos,
                rng,
                ..
            } => {
                let moved = last_pos.map_or(0.0, |q| distance(&pos, &q));
                *last_pos = Some(pos);
                shadowing.next(moved, rng)
            }
        }
    }

    /// The shadowing of a downlink to `pos`, dB: the reciprocal channel. The field's there, or the
    /// uplink before it continued over the metres flown since, drawn aside
    /// ([`Shadowing::aside`]) so that the uplinks after it meet the fades they would meet without
    /// it: a run whose network answers (ADR) and one whose network is silent are then paired
    /// frame by frame wherever their uplinks go at the same moments.
    fn downlink_fade(&mut self, pos: [f64; 3]) -> f64 {
        match &mut self.fades {
            Fades::Field(field) => field.at(pos),
            Fades::Path {
                shadowing,
                last_pos,
                downlink_rng,
                ..
            } => {
                let moved = last_pos.map_or(0.0, |q| distance(&pos, &q));
                shadowing.aside(moved, downlink_rng)
            }
        }
    }

    /// An uplink from `pos` sent `reduction_db` below the channel's transmit power.
    pub fn uplink(&mut self, channel: &Channel, pos: [f64; 3], reduction_db: f64) -> Reception {
        let d = distance(&pos, &self.gateway);
        let s = self.uplink_fade(pos);
        Reception {
            distance: d,
            rx_dbm: channel.mean_rx_power_dbm(d) + s - reduction_db,
        }
    }

    /// A downlink at the gateway's power to the drone at `pos`.
    pub fn downlink(&mut self, channel: &Channel, pos: [f64; 3]) -> Reception {
        let d = distance(&pos, &self.gateway);
        let s = self.downlink_fade(pos);
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
    fn in_a_field_a_place_keeps_its_fade_for_every_frame_either_way() {
        let channel = Channel::new(ChannelParams {
            shadowing_model: ShadowingModel::Field,
            ..ChannelParams::default()
        })
        .unwrap();
        let mut link = Link::new(&channel, [3000.0, 0.0, 0.0], Rng::new(5), Rng::new(6));
        let here = [120.0, -40.0, 60.0];
        let first = link.uplink(&channel, here, 0.0);
        link.uplink(&channel, [900.0, 300.0, 60.0], 0.0);
        assert_eq!(link.uplink(&channel, here, 0.0), first);
        // The downlink's fade is the uplink's at the same place: the power differs only by the
        // transmitters' powers.
        let down = link.downlink(&channel, here);
        let tx = channel.params().tx_power_dbm;
        assert!((down.rx_dbm - (first.rx_dbm - tx + GATEWAY_TX_POWER_DBM)).abs() < 1e-9);
    }

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
