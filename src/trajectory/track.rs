//! A ground-truth flight sampled in time.

use super::kinematics::{kinematic_state, Directions};
use super::TrajectoryError;
use crate::math::{distance, wrap_angle};

/// A flight: times (s) and, at each, position (m), velocity (m/s) and acceleration (m/s²) in
/// local ENU, from which the 3D-CTRA state `x y z theta phi v a omega psi` (reference §2) is
/// derived at each sample ([`Trajectory::state`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory {
    /// A short name ("synthetic 3", "canberra", a file name).
    pub name: String,
    /// Sample times, strictly increasing, s.
    pub t: Vec<f64>,
    /// Positions, m.
    pub pos: Vec<[f64; 3]>,
    /// Velocities, m/s.
    pub vel: Vec<[f64; 3]>,
    /// Accelerations, m/s².
    pub acc: Vec<[f64; 3]>,
    /// Where the direction of motion `[theta, phi]` at each sample comes from
    /// ([`super::heading_angles`]): the whole state is derived when asked, so a 10⁶-row flight
    /// holds 8 bytes per sample for its states instead of 72.
    directions: Directions,
}

impl Trajectory {
    /// Builds a trajectory and derives its model states. Refuses fewer than two samples,
    /// columns of different lengths, non-finite values and times that do not strictly increase.
    pub fn new(
        name: String,
        t: Vec<f64>,
        pos: Vec<[f64; 3]>,
        vel: Vec<[f64; 3]>,
        acc: Vec<[f64; 3]>,
    ) -> Result<Self, TrajectoryError> {
        if t.len() < 2 {
            return Err(TrajectoryError::TooFewRows {
                rows: t.len(),
                min: 2,
            });
        }
        if pos.len() != t.len() || vel.len() != t.len() || acc.len() != t.len() {
            return Err(TrajectoryError::Inconsistent(
                "time, position, velocity and acceleration differ in length".into(),
            ));
        }
        let finite = |rows: &[[f64; 3]]| rows.iter().flatten().all(|v| v.is_finite());
        if !(t.iter().all(|v| v.is_finite()) && finite(&pos) && finite(&vel) && finite(&acc)) {
            return Err(TrajectoryError::Inconsistent(
                "a value is not a finite number".into(),
            ));
        }
        if let Some(i) = t.windows(2).position(|w| w[1] <= w[0]) {
            return Err(TrajectoryError::TimeNotIncreasing { line: i + 2 });
        }
        let directions = Directions::of(&vel);
        Ok(Trajectory {
            name,
            t,
            pos,
            vel,
            acc,
            directions,
        })
    }

    /// The flight as CSV text that [`parse_csv`](super::parse_csv) reads back to the same
    /// samples: `t,x,y,z,vx,vy,vz,ax,ay,az`, every number in its shortest round-trip form.
    pub fn to_csv(&self) -> String {
        let mut s = String::from("t,x,y,z,vx,vy,vz,ax,ay,az\n");
        for i in 0..self.t.len() {
            let (p, v, a) = (self.pos[i], self.vel[i], self.acc[i]);
            s += &format!(
                "{},{},{},{},{},{},{},{},{},{}\n",
                self.t[i], p[0], p[1], p[2], v[0], v[1], v[2], a[0], a[1], a[2]
            );
        }
        s
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether the flight has no samples (never, once built: at least two).
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The model state `x y z theta phi v a omega psi` at sample `i` (reference §2;
    /// [`kinematic_state`]). Panics if `i` is out of range, like indexing.
    pub fn state(&self, i: usize) -> [f64; 9] {
        let angles = self.directions.at(&self.vel, i);
        kinematic_state(&self.pos[i], &self.vel[i], &self.acc[i], angles)
    }

    /// Seconds from the first to the last sample.
    pub fn duration(&self) -> f64 {
        self.t[self.t.len() - 1] - self.t[0]
    }

    /// Index `i` with t[i] ≤ time < t[i+1] (clamped), searching forward from `hint` — the
    /// simulation asks for increasing times, so the search is amortised O(1).
    fn segment(&self, time: f64, hint: &mut usize) -> (usize, f64) {
        let last = self.t.len() - 1;
        if *hint > last || self.t[*hint] > time {
            *hint = self.t.partition_point(|&x| x <= time).saturating_sub(1);
        }
        while *hint + 1 < last && self.t[*hint + 1] <= time {
            *hint += 1;
        }
        let i = (*hint).min(last - 1);
        let w = ((time - self.t[i]) / (self.t[i + 1] - self.t[i])).clamp(0.0, 1.0);
        (i, w)
    }

    /// Position at `time` by linear interpolation (clamped to the ends).
    pub fn position_at(&self, time: f64, hint: &mut usize) -> [f64; 3] {
        let (i, w) = self.segment(time, hint);
        core::array::from_fn(|k| self.pos[i][k] + w * (self.pos[i + 1][k] - self.pos[i][k]))
    }

    /// The full model state at `time`, interpolating angles along the shorter arc.
    pub fn state_at(&self, time: f64, hint: &mut usize) -> [f64; 9] {
        let (i, w) = self.segment(time, hint);
        let (a, b) = (self.state(i), self.state(i + 1));
        core::array::from_fn(|k| {
            if k == 3 || k == 4 {
                wrap_angle(a[k] + w * wrap_angle(b[k] - a[k]))
            } else {
                a[k] + w * (b[k] - a[k])
            }
        })
    }

    /// Path length, m.
    pub fn path_length(&self) -> f64 {
        self.pos.windows(2).map(|p| distance(&p[1], &p[0])).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line() -> Trajectory {
        let t: Vec<f64> = (0..5).map(f64::from).collect();
        let pos = t.iter().map(|&s| [2.0 * s, 0.0, 10.0]).collect();
        let vel = vec![[2.0, 0.0, 0.0]; 5];
        let acc = vec![[0.0; 3]; 5];
        Trajectory::new("line".into(), t, pos, vel, acc).unwrap()
    }

    #[test]
    fn csv_text_reads_back_to_the_same_flight() {
        let f = crate::trajectory::synthetic_flight(3).unwrap();
        let back = crate::trajectory::parse_csv(&f.to_csv(), &f.name).unwrap();
        assert_eq!(back, f);
    }

    #[test]
    fn refuses_inconsistent_columns() {
        let t = vec![0.0, 1.0];
        let ok = vec![[0.0; 3]; 2];
        assert!(Trajectory::new(
            "x".into(),
            vec![0.0],
            vec![[0.0; 3]],
            vec![[0.0; 3]],
            vec![[0.0; 3]]
        )
        .is_err());
        assert!(Trajectory::new(
            "x".into(),
            t.clone(),
            ok.clone(),
            vec![[0.0; 3]],
            ok.clone()
        )
        .is_err());
        assert!(Trajectory::new(
            "x".into(),
            vec![1.0, 1.0],
            ok.clone(),
            ok.clone(),
            ok.clone()
        )
        .is_err());
        assert!(Trajectory::new("x".into(), t, vec![[f64::NAN; 3]; 2], ok.clone(), ok).is_err());
    }

    #[test]
    fn interpolates_position_and_clamps_at_the_ends() {
        let tr = line();
        let mut h = 0;
        assert_eq!(tr.position_at(1.5, &mut h), [3.0, 0.0, 10.0]);
        assert_eq!(tr.position_at(-1.0, &mut h), [0.0, 0.0, 10.0]);
        assert_eq!(tr.position_at(9.0, &mut h), [8.0, 0.0, 10.0]);
        assert_eq!(tr.position_at(0.5, &mut h), [1.0, 0.0, 10.0]);
        assert_eq!(tr.duration(), 4.0);
        assert!((tr.path_length() - 8.0).abs() < 1e-12);
    }
}
