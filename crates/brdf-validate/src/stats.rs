//! Monte Carlo estimates with their standard errors.

/// A simulated mean with its statistical uncertainty.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Estimate {
    /// The sample mean.
    pub mean: f64,
    /// Standard error from batch means: sd(batch means)/√B.
    pub se_batch: f64,
    /// Binomial standard error √(p(1 − p)/n) (meaningful for 0/1 samples only).
    pub se_binom: f64,
    /// Number of samples.
    pub n: u64,
}

impl Estimate {
    /// The larger of the two standard errors (the one the report quotes).
    pub fn se(&self) -> f64 {
        self.se_batch.max(self.se_binom)
    }
}

/// Accumulates per-batch sums of a 0/1 (or bounded) quantity.
#[derive(Clone, Debug, Default)]
pub struct Batches {
    sums: Vec<f64>,
    counts: Vec<u64>,
}

impl Batches {
    /// Records one batch's sum of values and count.
    pub fn push(&mut self, sum: f64, count: u64) {
        self.sums.push(sum);
        self.counts.push(count);
    }
    /// The estimate over all batches (batches with no samples are skipped).
    pub fn estimate(&self) -> Estimate {
        let n: u64 = self.counts.iter().sum();
        if n == 0 {
            return Estimate {
                mean: f64::NAN,
                se_batch: f64::NAN,
                se_binom: f64::NAN,
                n: 0,
            };
        }
        let mean = self.sums.iter().sum::<f64>() / n as f64;
        let means: Vec<f64> = self
            .sums
            .iter()
            .zip(&self.counts)
            .filter(|(_, &c)| c > 0)
            .map(|(&s, &c)| s / c as f64)
            .collect();
        let b = means.len() as f64;
        let se_batch = if means.len() > 1 {
            let m = means.iter().sum::<f64>() / b;
            (means.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (b - 1.0) / b).sqrt()
        } else {
            f64::NAN
        };
        let p = mean.clamp(0.0, 1.0);
        Estimate {
            mean,
            se_batch,
            se_binom: (p * (1.0 - p) / n as f64).sqrt(),
            n,
        }
    }
}

/// Ratio of two estimated sums Σa/Σb over batches, with a batch-means standard error.
pub fn ratio_estimate(a: &[f64], b: &[f64]) -> Estimate {
    let sa: f64 = a.iter().sum();
    let sb: f64 = b.iter().sum();
    let mean = sa / sb;
    let k = a.len() as f64;
    let rs: Vec<f64> = a.iter().zip(b).map(|(x, y)| x / y).collect();
    let m = rs.iter().sum::<f64>() / k;
    let se = (rs.iter().map(|r| (r - m) * (r - m)).sum::<f64>() / (k - 1.0) / k).sqrt();
    Estimate {
        mean,
        se_batch: se,
        se_binom: 0.0,
        n: 0,
    }
}
