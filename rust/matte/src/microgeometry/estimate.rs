//! Running means of i.i.d. per-photon contributions, with the half-width of a 99 % normal
//! confidence interval (photon counts are large, so the central limit theorem applies).

/// Welford's running mean and sum of squared deviations.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunningMean {
    n: u64,
    mean: f64,
    m2: f64,
}

/// z-quantile 0.995 of the standard normal: a two-sided 99 % interval.
const Z_995: f64 = 2.575_829_303_548_901;

/// A measured value with its 99 % confidence half-width.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Estimate {
    pub mean: f64,
    pub half_width: f64,
}

impl Estimate {
    /// Whether `x` lies within the interval widened by `slack` (absolute).
    pub fn contains(&self, x: f64, slack: f64) -> bool {
        (x - self.mean).abs() <= self.half_width + slack
    }
}

impl RunningMean {
    pub fn push(&mut self, x: f64) {
        self.n += 1;
        let d = x - self.mean;
        self.mean += d / self.n as f64;
        self.m2 += d * (x - self.mean);
    }

    /// Chan et al.'s pairwise combination (parallel partial sums).
    pub fn merge(&mut self, other: &RunningMean) {
        if other.n == 0 {
            return;
        }
        if self.n == 0 {
            *self = *other;
            return;
        }
        let n = self.n + other.n;
        let d = other.mean - self.mean;
        self.mean += d * other.n as f64 / n as f64;
        self.m2 += other.m2 + d * d * (self.n as f64 * other.n as f64) / n as f64;
        self.n = n;
    }

    pub fn count(&self) -> u64 {
        self.n
    }

    pub fn estimate(&self) -> Estimate {
        let var = if self.n > 1 { self.m2 / (self.n - 1) as f64 } else { f64::INFINITY };
        Estimate { mean: self.mean, half_width: Z_995 * (var / self.n.max(1) as f64).sqrt() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merged_partial_means_equal_one_pass() {
        let xs: Vec<f64> = (0..1000).map(|i| ((i * 7919) % 1000) as f64 / 37.0).collect();
        let mut all = RunningMean::default();
        xs.iter().for_each(|x| all.push(*x));
        let (mut a, mut b) = (RunningMean::default(), RunningMean::default());
        xs[..300].iter().for_each(|x| a.push(*x));
        xs[300..].iter().for_each(|x| b.push(*x));
        a.merge(&b);
        let (ea, eb) = (all.estimate(), a.estimate());
        assert!((ea.mean - eb.mean).abs() < 1e-12 && (ea.half_width - eb.half_width).abs() < 1e-12);
        let mean = xs.iter().sum::<f64>() / xs.len() as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (xs.len() - 1) as f64;
        assert!((ea.mean - mean).abs() < 1e-12);
        assert!((ea.half_width - Z_995 * (var / 1000.0).sqrt()).abs() < 1e-12);
    }
}
