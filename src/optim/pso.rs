//! Global-best particle swarm with linearly decreasing inertia (Shi & Eberhart 1998/1999): the
//! "OI-PSO" baseline of Liu & Liu 2022 (inertia 0.9 → 0.4, acceleration constants 2).
//!
//! `v = w(t)·v + c1 r1 (pbest − x) + c2 r2 (gbest − x)`, r1, r2 uniform per coordinate,
//! `w(t) = w_start − (w_start − w_end) t/T`; `|v_d| ≤ vmax_share · range_d`; `x = x + v`,
//! and a coordinate leaving the box is clamped with its velocity zeroed (absorbing walls).
//! The paper gives no velocity limit; 20 % of the range is the customary choice.

use super::problem::{clamp_coordinate, Algorithm, Objective, Optimizer, Swarm};
use crate::rng::Rng;

/// Parameters of PSO.
#[derive(Clone, Debug, PartialEq)]
pub struct PsoParams {
    /// Inertia at t = 0. Default 0.9.
    pub w_start: f64,
    /// Inertia at t = T. Default 0.4.
    pub w_end: f64,
    /// Cognitive constant c1. Default 2.
    pub c1: f64,
    /// Social constant c2. Default 2.
    pub c2: f64,
    /// Velocity limit as a share of each coordinate's range. Default 0.2.
    pub vmax_share: f64,
}

impl Default for PsoParams {
    fn default() -> Self {
        Self { w_start: 0.9, w_end: 0.4, c1: 2.0, c2: 2.0, vmax_share: 0.2 }
    }
}

/// A PSO run.
#[derive(Clone)]
pub struct Pso {
    params: PsoParams,
    swarm: Swarm,
    velocity: Vec<f64>,
    pbest_x: Vec<f64>,
    pbest_f: Vec<f64>,
    vmax: Vec<f64>,
}

impl Pso {
    /// `n` particles uniform in the bounds with velocities uniform in ±vmax.
    pub fn new(params: PsoParams, objective: &dyn Objective, n: usize, iterations: u32, rng: Rng) -> Self {
        let mut swarm = Swarm::uniform(objective, n, iterations, rng);
        let b = objective.bounds();
        let vmax: Vec<f64> = (0..b.dim()).map(|d| params.vmax_share * b.range(d)).collect();
        let dim = b.dim();
        let velocity =
            (0..swarm.pop.x.len()).map(|k| vmax[k % dim] * (2.0 * swarm.rng.unit_f64() - 1.0)).collect();
        Self {
            pbest_x: swarm.pop.x.clone(),
            pbest_f: swarm.pop.fitness.clone(),
            params,
            swarm,
            velocity,
            vmax,
        }
    }
}

impl Optimizer for Pso {
    fn algorithm(&self) -> Algorithm {
        Algorithm::Pso
    }

    fn step(&mut self, objective: &dyn Objective) {
        let p = &self.params;
        let w =
            p.w_start - (p.w_start - p.w_end) * f64::from(self.swarm.t) / f64::from(self.swarm.iterations);
        let (n, dim) = (self.swarm.pop.size(), self.swarm.pop.dim);
        let bounds = objective.bounds();
        for i in 0..n {
            for d in 0..dim {
                let k = i * dim + d;
                let (r1, r2) = (self.swarm.rng.unit_f64(), self.swarm.rng.unit_f64());
                let x = self.swarm.pop.x[k];
                let v = w * self.velocity[k]
                    + p.c1 * r1 * (self.pbest_x[k] - x)
                    + p.c2 * r2 * (self.swarm.pop.best_x[d] - x);
                let v = v.clamp(-self.vmax[d], self.vmax[d]);
                let mut nx = x + v;
                self.velocity[k] = if clamp_coordinate(bounds, d, &mut nx) { 0.0 } else { v };
                self.swarm.pop.x[k] = nx;
            }
        }
        self.swarm.pop.evaluate_all(objective);
        for i in 0..n {
            if self.swarm.pop.fitness[i] < self.pbest_f[i] {
                self.pbest_f[i] = self.swarm.pop.fitness[i];
                self.pbest_x[i * dim..(i + 1) * dim].copy_from_slice(self.swarm.pop.row(i));
            }
        }
        self.swarm.t += 1;
    }

    fn swarm(&self) -> &Swarm {
        &self.swarm
    }
}
