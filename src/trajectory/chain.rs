//! Flights flown back to back, for runs longer than one flight (swarms).

use super::{Trajectory, TrajectoryError};

/// `flights` flown back to back from `first` on (wrapping around), each translated to start where
/// the previous one ended and timed to follow it one sample later, until `duration` seconds are
/// covered; every `stride`-th sample is kept (the synthetic flights are sampled at 100 Hz; a
/// 10 Hz drone needs every tenth). The velocity may jump where two flights meet (the drone's
/// filter sees a sudden manoeuvre), and the altitude wanders as the flights' climbs add up.
///
/// ```
/// let set = loratrack::synthetic_set();
/// let long = loratrack::chain_flights(&set, 3, 600.0, 10).unwrap();
/// assert!((long.duration() - 600.0).abs() < 1e-6);
/// ```
pub fn chain_flights(
    flights: &[Trajectory],
    first: usize,
    duration: f64,
    stride: usize,
) -> Result<Trajectory, TrajectoryError> {
    if flights.is_empty() || duration.is_nan() || duration <= 0.0 || stride == 0 {
        return Err(TrajectoryError::Inconsistent(
            "a chain needs flights, a positive duration and a stride of at least 1".into(),
        ));
    }
    let (mut t, mut pos, mut vel, mut acc) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut k = first % flights.len();
    // The first flight keeps its own start; each later one starts where the previous ended.
    let (mut t_off, mut p_off) = (0.0, flights[k].pos[0]);
    'chain: loop {
        let f = &flights[k];
        let period = f.t[1] - f.t[0];
        let start = f.pos[0];
        let shift = |p: &[f64; 3], o: &[f64; 3]| {
            [
                p[0] - start[0] + o[0],
                p[1] - start[1] + o[1],
                p[2] - start[2] + o[2],
            ]
        };
        let mut last = None;
        for i in (0..f.t.len()).step_by(stride) {
            let time = f.t[i] - f.t[0] + t_off;
            if time > duration + 1e-9 {
                break 'chain;
            }
            t.push(time);
            pos.push(shift(&f.pos[i], &p_off));
            vel.push(f.vel[i]);
            acc.push(f.acc[i]);
            last = Some(i);
        }
        let Some(i) = last else { break };
        t_off = t[t.len() - 1] + period * stride as f64;
        p_off = shift(&f.pos[i], &p_off);
        k = (k + 1) % flights.len();
        if t_off > duration + 1e-9 {
            break;
        }
    }
    Trajectory::new(
        format!("chain from synthetic {}", first % flights.len() + 1),
        t,
        pos,
        vel,
        acc,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trajectory::synthetic_flight;

    #[test]
    fn chained_flights_are_continuous_in_position_and_cover_the_duration() {
        let set: Vec<Trajectory> = (1..=3).map(|i| synthetic_flight(i).unwrap()).collect();
        let total: f64 = set.iter().map(Trajectory::duration).sum();
        let c = chain_flights(&set, 1, total + 50.0, 10).unwrap();
        assert!(c.duration() > total && c.duration() <= total + 50.0);
        assert!(c.t.windows(2).all(|w| (w[1] - w[0] - 0.1).abs() < 1e-9));
        // No jump in position where flights meet: at most one step at top speed.
        assert!(c
            .pos
            .windows(2)
            .all(|w| crate::math::distance(&w[0], &w[1]) < 2.0));
        assert_eq!(c.pos[0], set[1].pos[0]);
    }
}
