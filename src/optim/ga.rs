//! A real-coded genetic algorithm: binary tournament selection, simulated binary crossover
//! (SBX, Deb & Agrawal 1995), Gaussian mutation, elitism.
//!
//! Each generation keeps the `elites` best unchanged, then fills the rest with children: two
//! parents by binary tournament (lower value wins, the lower index on ties), SBX with
//! probability `crossover_rate` (each coordinate crossed with probability ½, distribution index
//! η), then every coordinate mutated with probability 1/d by `σ(t) · N(0, 1)`, where σ shrinks
//! geometrically from `sigma_start` to `sigma_end` (shares of the range) over T so the search
//! can refine late. Children are clamped to the box. One generation = one iteration; only the
//! children are evaluated.

use super::problem::{clamp_coordinate, gaussian, Algorithm, Objective, Optimizer, Swarm};
use crate::rng::Rng;

/// Parameters of the GA.
#[derive(Clone, Debug, PartialEq)]
pub struct GaParams {
    /// Probability that a pair of parents is crossed. Default 0.9.
    pub crossover_rate: f64,
    /// SBX distribution index η (higher = children closer to parents). Default 15.
    pub eta: f64,
    /// Mutation step at t = 0, as a share of the range. Default 0.1.
    pub sigma_start: f64,
    /// Mutation step at t = T, as a share of the range. Default 10⁻⁵.
    pub sigma_end: f64,
    /// Individuals copied unchanged into the next generation. Default 2.
    pub elites: usize,
}

impl Default for GaParams {
    fn default() -> Self {
        Self { crossover_rate: 0.9, eta: 15.0, sigma_start: 0.1, sigma_end: 1e-5, elites: 2 }
    }
}

/// A GA run.
#[derive(Clone)]
pub struct Ga {
    params: GaParams,
    swarm: Swarm,
    next: Vec<f64>,
}

impl Ga {
    /// `n` individuals uniform in the bounds.
    pub fn new(params: GaParams, objective: &dyn Objective, n: usize, iterations: u32, rng: Rng) -> Self {
        Self { params, swarm: Swarm::uniform(objective, n, iterations, rng), next: Vec::new() }
    }

    fn tournament(&mut self) -> usize {
        let n = self.swarm.pop.size() as u32;
        let a = self.swarm.rng.below(n) as usize;
        let b = self.swarm.rng.below(n) as usize;
        let (fa, fb) = (self.swarm.pop.fitness[a], self.swarm.pop.fitness[b]);
        if fa < fb || (fa == fb && a < b) {
            a
        } else {
            b
        }
    }

    /// SBX spread factor β for a uniform draw `u`.
    fn sbx_beta(&self, u: f64) -> f64 {
        let e = 1.0 / (self.params.eta + 1.0);
        if u <= 0.5 {
            libm::pow(2.0 * u, e)
        } else {
            libm::pow(1.0 / (2.0 * (1.0 - u)), e)
        }
    }
}

impl Optimizer for Ga {
    fn algorithm(&self) -> Algorithm {
        Algorithm::Ga
    }

    fn step(&mut self, objective: &dyn Objective) {
        let (n, dim) = (self.swarm.pop.size(), self.swarm.pop.dim);
        let bounds = objective.bounds();
        let progress = self.swarm.progress();
        let sigma = self.params.sigma_start
            * libm::pow(self.params.sigma_end / self.params.sigma_start.max(f64::MIN_POSITIVE), progress);
        let elites = self.params.elites.min(n - 1);
        // Elites: the best by value, lower index on ties.
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| {
            self.swarm.pop.fitness[a].total_cmp(&self.swarm.pop.fitness[b]).then(a.cmp(&b))
        });
        self.next.clear();
        let mut next_f = Vec::with_capacity(n);
        for &e in &order[..elites] {
            self.next.extend_from_slice(self.swarm.pop.row(e));
            next_f.push(self.swarm.pop.fitness[e]);
        }
        let mut child_a = vec![0.0; dim];
        let mut child_b = vec![0.0; dim];
        while self.next.len() < n * dim {
            let (pa, pb) = (self.tournament(), self.tournament());
            child_a.copy_from_slice(self.swarm.pop.row(pa));
            child_b.copy_from_slice(self.swarm.pop.row(pb));
            if self.swarm.rng.unit_f64() < self.params.crossover_rate {
                for d in 0..dim {
                    if self.swarm.rng.unit_f64() < 0.5 {
                        let u = self.swarm.rng.unit_f64();
                        let beta = self.sbx_beta(u);
                        let (a, b) = (child_a[d], child_b[d]);
                        child_a[d] = 0.5 * ((1.0 + beta) * a + (1.0 - beta) * b);
                        child_b[d] = 0.5 * ((1.0 - beta) * a + (1.0 + beta) * b);
                    }
                }
            }
            for child in [&mut child_a, &mut child_b] {
                for (d, gene) in child.iter_mut().enumerate() {
                    if self.swarm.rng.below(dim as u32) == 0 {
                        *gene += sigma * bounds.range(d) * gaussian(&mut self.swarm.rng);
                    }
                    clamp_coordinate(bounds, d, gene);
                }
            }
            self.next.extend_from_slice(&child_a);
            if self.next.len() < n * dim {
                self.next.extend_from_slice(&child_b);
            }
        }
        std::mem::swap(&mut self.swarm.pop.x, &mut self.next);
        for i in 0..n {
            let f = if let Some(&kept) = next_f.get(i) {
                kept
            } else {
                let row = self.swarm.pop.x[i * dim..(i + 1) * dim].to_vec();
                self.swarm.pop.evaluate_point(objective, &row)
            };
            self.swarm.pop.fitness[i] = f;
            self.swarm.pop.offer(i, f);
        }
        self.swarm.t += 1;
    }

    fn swarm(&self) -> &Swarm {
        &self.swarm
    }
}
