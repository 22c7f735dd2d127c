//! The model state `theta phi v a omega psi` from velocity and acceleration (reference §2, §7).

use crate::math::{atan2, hypot};

/// Below this speed (m/s) the direction of motion is undefined (hover): theta and phi hold their
/// last defined value, and the rates are regularised towards zero by this scale.
pub const HOVER_SPEED: f64 = 0.2;

/// Derives `[x y z theta phi v a omega psi]` at every sample: [`heading_angles`] and
/// [`kinematic_state`] at each.
///
/// * theta = atan2(vy, vx), phi = atan2(vz, |v_h|), v = |v| (reference §3 erratum: with the root).
/// * a = v·acc / |v| (tangential acceleration), omega = dtheta/dt = (vx ay − vy ax) / |v_h|²,
///   psi = dphi/dt = (|v_h|² az − vz (vx ax + vy ay)) / (|v_h| |v|²).
///
/// The denominators are regularised with [`HOVER_SPEED`]² (e.g. |v_h|² + s²) so hovering gives
/// finite rates that fade to zero instead of NaN; above a few m/s the effect is negligible.
pub fn kinematic_states(pos: &[[f64; 3]], vel: &[[f64; 3]], acc: &[[f64; 3]]) -> Vec<[f64; 9]> {
    let angles = heading_angles(vel);
    (0..pos.len())
        .map(|i| kinematic_state(&pos[i], &vel[i], &acc[i], angles[i]))
        .collect()
}

/// The direction of motion `[theta, phi]` (rad) at every sample: the velocity's, or, below
/// [`HOVER_SPEED`], the last defined one (the first defined one before any). The only part of
/// a sample's state that depends on the samples before it, so a flight stores these and derives
/// the rest of each state when asked ([`kinematic_state`]).
pub fn heading_angles(vel: &[[f64; 3]]) -> Vec<[f64; 2]> {
    let directions = Directions::of(vel);
    (0..vel.len()).map(|i| directions.at(vel, i)).collect()
}

/// Where each sample's direction of motion ([`heading_angles`]) comes from, without computing
/// it: the form a flight stores (8 bytes a sample instead of 16, and no arctangent for the
/// samples no one asks about: a synthetic flight is sampled at 100 Hz and read at 10).
#[derive(Clone, Debug, PartialEq)]
pub struct Directions {
    /// The angles before the first sample that defines them: the first defined ones (or 0).
    initial: [f64; 2],
    /// Per sample, the sample whose velocity gives theta and the one that gives phi
    /// ([`Directions::INITIAL`]: `initial`'s).
    sources: Vec<[u32; 2]>,
}

impl Directions {
    /// The source of an angle no sample has defined yet.
    const INITIAL: u32 = u32::MAX;

    /// The sources of the directions of motion at `vel`: a sample defines phi from a speed of
    /// [`HOVER_SPEED`], and theta from that horizontal speed; below, the last defined one holds,
    /// and before the first, the first (tested as `hypot(hypot(vx, vy), vz)`). At most
    /// `u32::MAX` samples (flights are at most 10⁶ rows).
    pub fn of(vel: &[[f64; 3]]) -> Self {
        let first_moving = vel
            .iter()
            .find(|v| hypot(hypot(v[0], v[1]), v[2]) >= HOVER_SPEED);
        let initial = first_moving
            .map(|v| [atan2(v[1], v[0]), atan2(v[2], hypot(v[0], v[1]))])
            .unwrap_or([0.0, 0.0]);
        let mut source = [Self::INITIAL; 2];
        let sources = vel
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let vh = (v[0] * v[0] + v[1] * v[1]).sqrt();
                if hypot(vh, v[2]) >= HOVER_SPEED {
                    source[1] = i as u32;
                    if vh >= HOVER_SPEED {
                        source[0] = i as u32;
                    }
                }
                source
            })
            .collect();
        Directions { initial, sources }
    }

    /// `[theta, phi]` (rad) at sample `i` of the flight whose velocities are `vel` (those
    /// [`Directions::of`] was given).
    pub fn at(&self, vel: &[[f64; 3]], i: usize) -> [f64; 2] {
        let [theta, phi] = self.sources[i];
        [
            match theta {
                Self::INITIAL => self.initial[0],
                j => {
                    let v = vel[j as usize];
                    atan2(v[1], v[0])
                }
            },
            match phi {
                Self::INITIAL => self.initial[1],
                j => {
                    let v = vel[j as usize];
                    atan2(v[2], (v[0] * v[0] + v[1] * v[1]).sqrt())
                }
            },
        ]
    }
}

/// One sample's state `[x y z theta phi v a omega psi]` from its position (m), velocity (m/s),
/// acceleration (m/s²) and direction of motion (rad, [`heading_angles`]); the formulas are
/// [`kinematic_states`]'.
pub fn kinematic_state(p: &[f64; 3], v: &[f64; 3], a: &[f64; 3], angles: [f64; 2]) -> [f64; 9] {
    let eps2 = HOVER_SPEED * HOVER_SPEED;
    let vh2 = v[0] * v[0] + v[1] * v[1];
    let speed = hypot(vh2.sqrt(), v[2]);
    let along = v[0] * a[0] + v[1] * a[1] + v[2] * a[2];
    let tangential = along / (speed * speed + eps2).sqrt();
    let omega = (v[0] * a[1] - v[1] * a[0]) / (vh2 + eps2);
    let psi = (vh2 * a[2] - v[2] * (v[0] * a[0] + v[1] * a[1]))
        / ((vh2 + eps2).sqrt() * (speed * speed + eps2));
    let [theta, phi] = angles;
    [p[0], p[1], p[2], theta, phi, speed, tangential, omega, psi]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_level_turn_has_the_right_turn_rate_and_no_tilt() {
        // Circle of radius 20 m at 5 m/s: omega = v / r = 0.25 rad/s, centripetal a = v²/r.
        let (r, v) = (20.0, 5.0);
        let th: f64 = 0.3;
        let vel = [[-v * th.sin(), v * th.cos(), 0.0]];
        let acc = [[-v * v / r * th.cos(), -v * v / r * th.sin(), 0.0]];
        let s = kinematic_states(&[[0.0; 3]], &vel, &acc)[0];
        assert!((s[5] - v).abs() < 1e-12);
        assert!(s[6].abs() < 1e-12);
        assert!((s[7] - v / r).abs() < 0.01 * v / r);
        assert!(s[8].abs() < 1e-12);
    }

    #[test]
    fn hover_gives_finite_values_and_holds_the_last_direction() {
        let vel = [[3.0, 3.0, 0.0], [0.0, 0.0, 0.0], [1e-9, -1e-9, 1e-9]];
        let acc = [[0.0; 3], [0.5, -0.2, 0.1], [0.0; 3]];
        let s = kinematic_states(&[[0.0; 3]; 3], &vel, &acc);
        for row in &s {
            assert!(row.iter().all(|v| v.is_finite()));
        }
        assert!((s[1][3] - core::f64::consts::FRAC_PI_4).abs() < 1e-12);
        assert!((s[2][3] - core::f64::consts::FRAC_PI_4).abs() < 1e-12);
    }

    #[test]
    fn a_steady_climb_has_constant_pitch() {
        let s = kinematic_states(&[[0.0; 3]], &[[4.0, 0.0, 3.0]], &[[0.0; 3]])[0];
        assert!((s[4] - (0.75f64).atan()).abs() < 1e-12);
        assert!((s[5] - 5.0).abs() < 1e-12);
    }

    #[test]
    fn a_vertical_climb_keeps_the_course_and_a_hover_keeps_both_angles() {
        let vel = [
            // Hovering before any direction: the first defined one serves.
            [0.0, 0.0, 0.01],
            [3.0, 3.0, 0.0],
            // Straight up: the climb angle follows, the course holds.
            [0.0, 0.05, 3.0],
            // Hovering again: both hold.
            [0.1, 0.0, -0.05],
            [-2.0, 0.0, 0.0],
        ];
        let a = heading_angles(&vel);
        let (east, north_east) = (0.0, core::f64::consts::FRAC_PI_4);
        assert_eq!(a[0], [north_east, 0.0]);
        assert_eq!(a[1], [north_east, 0.0]);
        assert_eq!(a[2][0], north_east);
        assert!((a[2][1] - (3.0f64).atan2(0.05)).abs() < 1e-15);
        assert_eq!(a[3], a[2]);
        assert_eq!(a[4], [core::f64::consts::PI, 0.0]);
        assert_eq!(Directions::of(&vel).at(&vel, 3), a[3]);
        assert_eq!(heading_angles(&[[0.0; 3]; 2]), vec![[east, 0.0]; 2]);
    }
}
