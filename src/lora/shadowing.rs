//! Log-normal shadowing correlated along the flight path (Gudmundson, Electronics Letters 1991).

use crate::math;
use crate::rng::Rng;

/// A first-order autoregressive shadowing process over travelled distance:
/// `s_n = rho s_{n-1} + sqrt(1 - rho^2) sigma N(0,1)`, `rho = exp(-delta_d / d_corr)`.
/// Two transmissions far apart along the path see independent shadowing; close ones see
/// almost the same. Marginally every sample is N(0, sigma^2) in dB.
#[derive(Clone, Debug)]
pub struct Shadowing {
    sigma_db: f64,
    decorrelation_m: f64,
    last: Option<f64>,
}

impl Shadowing {
    /// A process with standard deviation `sigma_db` (dB) and decorrelation distance (m).
    pub fn new(sigma_db: f64, decorrelation_m: f64) -> Self {
        Shadowing {
            sigma_db,
            decorrelation_m,
            last: None,
        }
    }

    /// The shadowing (dB) after travelling `moved_m` metres since the previous sample.
    pub fn next(&mut self, moved_m: f64, rng: &mut Rng) -> f64 {
        if self.sigma_db == 0.0 {
            return 0.0;
        }
        let z = rng.normal();
        let s = match self.last {
            None => self.sigma_db * z,
            Some(prev) => {
                let rho = math::exp(-moved_m.abs() / self.decorrelation_m);
                rho * prev + (1.0 - rho * rho).sqrt() * self.sigma_db * z
            }
        };
        self.last = Some(s);
        s
    }

    /// The shadowing (dB) `moved_m` metres past the previous sample, drawn from `rng` as
    /// [`Self::next`] draws it, but left out of the process: the next sample follows the
    /// previous one as if this one had not been drawn. A side path's draw (the downlink a gateway
    /// sends between two uplinks: it sees the reciprocal channel of the uplink before it) then
    /// leaves every later uplink's shadowing as it was, so runs with and without downlinks meet
    /// the same fades (common random numbers). What it gives up: the samples after it are no
    /// longer conditioned on it, though in the process they would correlate with it as
    /// ρ = e^(−d / d₀) over the d metres between.
    pub fn aside(&self, moved_m: f64, rng: &mut Rng) -> f64 {
        self.clone().next(moved_m, rng)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marginal_is_gaussian_with_sigma_and_far_samples_are_uncorrelated() {
        let mut rng = Rng::new(9);
        let mut s = Shadowing::new(4.0, 110.0);
        let xs: Vec<f64> = (0..50_000).map(|_| s.next(1000.0, &mut rng)).collect();
        let n = xs.len() as f64;
        let var = xs.iter().map(|x| x * x).sum::<f64>() / n;
        assert!((var.sqrt() - 4.0).abs() < 0.1);
        let lag1 = xs.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / (n - 1.0) / var;
        assert!(lag1.abs() < 0.03, "lag-1 correlation {lag1}");
    }

    #[test]
    fn close_samples_are_strongly_correlated() {
        let mut rng = Rng::new(10);
        let mut s = Shadowing::new(4.0, 110.0);
        let xs: Vec<f64> = (0..50_000).map(|_| s.next(5.0, &mut rng)).collect();
        let n = xs.len() as f64;
        let var = xs.iter().map(|x| x * x).sum::<f64>() / n;
        let lag1 = xs.windows(2).map(|w| w[0] * w[1]).sum::<f64>() / (n - 1.0) / var;
        let expected = (-5.0f64 / 110.0).exp();
        assert!((lag1 - expected).abs() < 0.02, "lag-1 {lag1} vs {expected}");
    }

    #[test]
    fn a_draw_aside_leaves_the_process_as_it_was_and_follows_the_last_sample() {
        let (mut with, mut without) = (Shadowing::new(4.0, 110.0), Shadowing::new(4.0, 110.0));
        let (mut a, mut b) = (Rng::new(3), Rng::new(3));
        let mut side = Rng::new(4);
        let mut pairs = Vec::new();
        for _ in 0..20_000 {
            let up = with.next(20.0, &mut a);
            assert_eq!(up, without.next(20.0, &mut b));
            pairs.push((up, with.aside(1.0, &mut side)));
        }
        // One metre on, the side draw is the uplink's to within ρ = e^(-1/110).
        let n = pairs.len() as f64;
        let corr = pairs.iter().map(|(u, d)| u * d).sum::<f64>() / n / 16.0;
        assert!(corr > 0.97, "correlation {corr}");
    }

    #[test]
    fn zero_sigma_disables_shadowing() {
        let mut rng = Rng::new(1);
        let mut s = Shadowing::new(0.0, 110.0);
        assert_eq!(s.next(10.0, &mut rng), 0.0);
    }
}
