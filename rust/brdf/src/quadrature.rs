//! Gauss–Legendre quadrature (nodes by Newton iteration on P_n, Numerical Recipes `gauleg`).
//! Used for hemispherical Fresnel averages, directional albedo and the van Ginneken integral.

/// Nodes and weights of an `n`-point Gauss–Legendre rule on `[a, b]`.
#[derive(Clone, Debug)]
pub struct GaussLegendre {
    pub nodes: Vec<f64>,
    pub weights: Vec<f64>,
}

impl GaussLegendre {
    /// Rule on `[-1, 1]`; exact for polynomials of degree `2n - 1`.
    pub fn new(n: usize) -> Self {
        assert!(n >= 1, "Gauss-Legendre rule needs at least one node");
        let mut nodes = vec![0.0; n];
        let mut weights = vec![0.0; n];
        let m = n.div_ceil(2);
        for i in 0..m {
            // Tricomi's initial guess for the i-th root, then Newton on P_n.
            let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0f64, 0.0f64);
                for j in 0..n {
                    let p2 = p1;
                    p1 = p0;
                    p0 = ((2 * j + 1) as f64 * z * p1 - j as f64 * p2) / (j + 1) as f64;
                }
                dp = n as f64 * (z * p0 - p1) / (z * z - 1.0);
                let dz = p0 / dp;
                z -= dz;
                if dz.abs() < 1e-15 {
                    break;
                }
            }
            let w = 2.0 / ((1.0 - z * z) * dp * dp);
            nodes[i] = -z;
            nodes[n - 1 - i] = z;
            weights[i] = w;
            weights[n - 1 - i] = w;
        }
        if n % 2 == 1 {
            nodes[n / 2] = 0.0;
        }
        Self { nodes, weights }
    }

    /// `∫_a^b f(x) dx`.
    pub fn integrate(&self, a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (a + b);
        let mut sum = 0.0;
        for (x, w) in self.nodes.iter().zip(&self.weights) {
            sum += w * f(mid + half * x);
        }
        sum * half
    }

    /// Nodes and weights mapped to `[a, b]`.
    pub fn mapped(&self, a: f64, b: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (a + b);
        self.nodes.iter().zip(&self.weights).map(move |(x, w)| (mid + half * x, w * half))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_for_polynomials_up_to_degree_2n_minus_1() {
        for n in [1usize, 2, 5, 16, 64] {
            let gl = GaussLegendre::new(n);
            let deg = 2 * n - 1;
            // ∫_0^2 x^deg dx = 2^(deg+1)/(deg+1)
            let exact = 2f64.powi(deg as i32 + 1) / (deg as f64 + 1.0);
            let got = gl.integrate(0.0, 2.0, |x| x.powi(deg as i32));
            assert!((got - exact).abs() <= 1e-12 * exact, "n={n}: {got} vs {exact}");
        }
    }

    #[test]
    fn weights_sum_to_interval_length() {
        let gl = GaussLegendre::new(33);
        let s: f64 = gl.weights.iter().sum();
        assert!((s - 2.0).abs() < 1e-13);
    }
}
