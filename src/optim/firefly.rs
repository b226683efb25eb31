//! The firefly algorithm (Yang 2008, "Nature-Inspired Metaheuristic Algorithms"; the
//! reference code `fa_ndim.m`, 2010).
//!
//! Each iteration every firefly `i` moves towards every brighter one `j` (lower objective),
//! using the positions and values at the start of the iteration:
//! `x_i ← (1 − β) x_i + β x_j + α (rand − ½) · range`, `β = (β0 − βmin) exp(−γ r²) + βmin`,
//! then positions are clamped to the box and evaluated. The brightest firefly does not move.
//! α shrinks geometrically from `alpha` to `alpha · 10⁻⁴/0.9` over T, as in `fa_ndim.m`.
//!
//! Distance `r` is measured in units of the search range per coordinate (`(x_i − x_j)/range`):
//! with γ = 1 in raw units, `exp(−γ r²)` vanishes beyond a few units on [−250, 250] and the
//! attraction is βmin everywhere. Yang recommends γ ~ 1/L² for a domain of size L, which is the
//! same thing.

use super::problem::{clamp_coordinate, Algorithm, Objective, Optimizer, Swarm};
use crate::rng::Rng;

/// Parameters of the firefly algorithm.
#[derive(Clone, Debug, PartialEq)]
pub struct FireflyParams {
    /// Initial randomisation α (share of the range). Default 0.2 (`fa_ndim.m`).
    pub alpha: f64,
    /// Final α as a factor of the initial one. Default 10⁻⁴/0.9 (`fa_ndim.m`).
    pub alpha_final_factor: f64,
    /// Attractiveness at r = 0. Default 1.
    pub beta0: f64,
    /// Smallest attractiveness. Default 0.2 (`fa_ndim.m`).
    pub beta_min: f64,
    /// Light absorption γ (per squared normalised distance). Default 1.
    pub gamma: f64,
}

impl Default for FireflyParams {
    fn default() -> Self {
        Self { alpha: 0.2, alpha_final_factor: 1e-4 / 0.9, beta0: 1.0, beta_min: 0.2, gamma: 1.0 }
    }
}

/// A firefly run.
#[derive(Clone)]
pub struct Firefly {
    params: FireflyParams,
    swarm: Swarm,
    old_x: Vec<f64>,
    old_f: Vec<f64>,
}

impl Firefly {
    /// `n` fireflies uniform in the bounds.
    pub fn new(
        params: FireflyParams,
        objective: &dyn Objective,
        n: usize,
        iterations: u32,
        rng: Rng,
    ) -> Self {
        let swarm = Swarm::uniform(objective, n, iterations, rng);
        Self { params, swarm, old_x: Vec::new(), old_f: Vec::new() }
    }
}

impl Optimizer for Firefly {
    fn algorithm(&self) -> Algorithm {
        Algorithm::Firefly
    }

    fn step(&mut self, objective: &dyn Objective) {
        let p = &self.params;
        let progress = self.swarm.progress();
        let alpha = p.alpha * libm::pow(p.alpha_final_factor, progress);
        let bounds = objective.bounds();
        let (n, dim) = (self.swarm.pop.size(), self.swarm.pop.dim);
        self.old_x.clone_from(&self.swarm.pop.x);
        self.old_f.clone_from(&self.swarm.pop.fitness);
        for i in 0..n {
            for j in 0..n {
                if self.old_f[j] >= self.old_f[i] {
                    continue;
                }
                let mut r2 = 0.0;
                for d in 0..dim {
                    let e = (self.swarm.pop.x[i * dim + d] - self.old_x[j * dim + d]) / bounds.range(d);
                    r2 += e * e;
                }
                let beta = (p.beta0 - p.beta_min) * libm::exp(-p.gamma * r2) + p.beta_min;
                for d in 0..dim {
                    let k = i * dim + d;
                    let step = alpha * (self.swarm.rng.unit_f64() - 0.5) * bounds.range(d);
                    self.swarm.pop.x[k] =
                        (1.0 - beta) * self.swarm.pop.x[k] + beta * self.old_x[j * dim + d] + step;
                }
            }
            for d in 0..dim {
                clamp_coordinate(bounds, d, &mut self.swarm.pop.x[i * dim + d]);
            }
        }
        self.swarm.pop.evaluate_all(objective);
        self.swarm.t += 1;
    }

    fn swarm(&self) -> &Swarm {
        &self.swarm
    }
}
