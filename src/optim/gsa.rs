//! Gravitational search (Rashedi, Nezamabadi-pour & Saryazdi 2009), as digested in DESIGN §3.4.
//!
//! Masses from fitness: `m_i = (fit_i − worst)/(best − worst)` for minimisation (best = lowest,
//! worst = highest value). Liu & Liu 2022 print `(fit_i + worst)/(best − worst)` (their eq. 2):
//! that is a typo — it is not translation-invariant in the fitness and gives negative masses —
//! so we use Rashedi's standard form. `M_i = m_i / Σ m_j`; `G(t) = G0 · exp(−α t / T)`;
//! `a_i = Σ_{j ∈ Kbest, j ≠ i} rand_j · G · M_j · (x_j − x_i) / (R_ij + ε)` (the force
//! `F_ij = G M_i M_j (x_j − x_i)/(R_ij + ε)` divided by `M_i`); `v_i = rand_i · v_i + a_i`;
//! `x_i = x_i + v_i`. One `rand_j` per pair (scaling the whole pull of `j` on `i`), and a fresh
//! `rand_i` for every coordinate of every particle's velocity (as Rashedi's reference code
//! draws it).

use super::problem::{Algorithm, Bounds, Objective, Optimizer, Swarm};
use crate::rng::Rng;

/// ε in the force denominator (keeps coincident particles finite).
pub const FORCE_EPSILON: f64 = f64::EPSILON;

/// Parameters of plain GSA.
#[derive(Clone, Debug, PartialEq)]
pub struct GsaParams {
    /// Initial gravitational constant G0. Default 100 (Rashedi 2009). Liu & Liu 2022 state
    /// G0 = 1 for both their GSA and IGSA: `flockpath optimize --g0 1 --alpha 30` runs that.
    pub g0: f64,
    /// Decay α of `G(t) = G0 exp(−α t/T)`. Default 20 (Rashedi 2009); Liu & Liu use 30.
    pub alpha: f64,
    /// Only the Kbest heaviest particles attract, Kbest falling linearly from N to
    /// `final_kbest_share · N` over the run (Rashedi's elitism). Default on.
    pub kbest: bool,
    /// Share of the population that still attracts at the end when `kbest` is on. Default 0.02.
    pub final_kbest_share: f64,
}

impl Default for GsaParams {
    fn default() -> Self {
        Self { g0: 100.0, alpha: 20.0, kbest: true, final_kbest_share: 0.02 }
    }
}

/// `G(t) = G0 · exp(−α t / T)`.
pub fn gravity_constant(g0: f64, alpha: f64, t: u32, iterations: u32) -> f64 {
    g0 * libm::exp(-alpha * f64::from(t) / f64::from(iterations.max(1)))
}

/// How many particles attract at iteration `t`: linearly from `n` down to `final_share · n`
/// (at least 1), Rashedi's `round(N · (final + (1 − t/T)(1 − final)))`.
pub fn kbest_count(n: usize, t: u32, iterations: u32, final_share: f64) -> usize {
    let progress = f64::from(t) / f64::from(iterations.max(1));
    let share = final_share + (1.0 - progress).max(0.0) * (1.0 - final_share);
    (libm::round(n as f64 * share) as usize).clamp(1, n)
}

/// Normalised masses `M_i` from the fitness (minimisation). Equal fitness everywhere gives
/// equal masses.
pub fn masses(fitness: &[f64], out: &mut Vec<f64>) {
    out.clear();
    let best = fitness.iter().copied().fold(f64::INFINITY, f64::min);
    let worst = fitness.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let spread = best - worst;
    if spread.is_finite() && spread < 0.0 {
        out.extend(fitness.iter().map(|&f| (f - worst) / spread));
    } else {
        out.extend(fitness.iter().map(|_| 1.0));
    }
    let total: f64 = out.iter().sum();
    if total > 0.0 {
        out.iter_mut().for_each(|m| *m /= total);
    } else {
        let n = out.len().max(1) as f64;
        out.iter_mut().for_each(|m| *m = 1.0 / n);
    }
}

/// Scratch buffers of the force step, kept between iterations so a step does not allocate.
#[derive(Clone, Debug, Default)]
pub struct GravityScratch {
    mass: Vec<f64>,
    order: Vec<usize>,
}

/// The O(N²·d) gravitational step: writes every particle's acceleration `a_i` into `acc`
/// (row-major like `x`). `attractors` is Kbest (N for all particles). Random draws: one per
/// ordered pair (i, j ≠ i, j among the attractors), i-major, j in mass order.
#[allow(clippy::too_many_arguments, reason = "the step's inputs are all distinct arrays")]
pub fn gravity_accelerations(
    x: &[f64],
    fitness: &[f64],
    dim: usize,
    g: f64,
    attractors: usize,
    rng: &mut Rng,
    scratch: &mut GravityScratch,
    acc: &mut [f64],
) {
    let n = fitness.len();
    masses(fitness, &mut scratch.mass);
    scratch.order.clear();
    scratch.order.extend(0..n);
    if attractors < n {
        // Heaviest first; ties by index so the set is the same everywhere.
        let mass = &scratch.mass;
        scratch.order.sort_by(|&a, &b| mass[b].total_cmp(&mass[a]).then(a.cmp(&b)));
        scratch.order.truncate(attractors.max(1));
    }
    acc.iter_mut().for_each(|a| *a = 0.0);
    for i in 0..n {
        let xi = &x[i * dim..(i + 1) * dim];
        let ai = &mut acc[i * dim..(i + 1) * dim];
        for &j in &scratch.order {
            if j == i {
                continue;
            }
            let xj = &x[j * dim..(j + 1) * dim];
            let mut r2 = 0.0;
            for d in 0..dim {
                let e = xj[d] - xi[d];
                r2 += e * e;
            }
            let w = rng.unit_f64() * g * scratch.mass[j] / (libm::sqrt(r2) + FORCE_EPSILON);
            for d in 0..dim {
                ai[d] += w * (xj[d] - xi[d]);
            }
        }
    }
}

/// What GSA and IGSA carry besides the swarm: each particle's velocity, the accelerations of
/// the last force step and that step's scratch buffers (all row-major like the positions).
#[derive(Clone, Debug)]
pub struct Gravity {
    /// Velocities, starting at rest.
    pub velocity: Vec<f64>,
    /// Accelerations written by [`Gravity::pull`].
    pub acc: Vec<f64>,
    scratch: GravityScratch,
}

impl Gravity {
    /// `len` coordinates at rest.
    pub fn at_rest(len: usize) -> Self {
        Self { velocity: vec![0.0; len], acc: vec![0.0; len], scratch: GravityScratch::default() }
    }

    /// One force step at iteration t of the swarm: G(t) from `g0` and `alpha`, the `attractors`
    /// heaviest particles pulling every particle; the accelerations land in [`Gravity::acc`].
    pub fn pull(&mut self, swarm: &mut Swarm, g0: f64, alpha: f64, attractors: usize) {
        let g = gravity_constant(g0, alpha, swarm.t, swarm.iterations);
        let pop = &swarm.pop;
        gravity_accelerations(
            &pop.x,
            &pop.fitness,
            pop.dim,
            g,
            attractors,
            &mut swarm.rng,
            &mut self.scratch,
            &mut self.acc,
        );
    }
}

/// GSA's boundary rule (Rashedi's reference code): a coordinate that leaves the box is drawn
/// again uniformly inside it, which keeps diversity where clamping would pile particles on
/// the walls.
pub fn redraw_outside(bounds: &Bounds, x: &mut [f64], rng: &mut Rng) {
    let dim = bounds.dim();
    for (k, v) in x.iter_mut().enumerate() {
        let d = k % dim;
        if !(*v >= bounds.lower[d] && *v <= bounds.upper[d]) {
            *v = bounds.lower[d] + rng.unit_f64() * bounds.range(d);
        }
    }
}

/// A plain GSA run.
#[derive(Clone)]
pub struct Gsa {
    params: GsaParams,
    swarm: Swarm,
    gravity: Gravity,
}

impl Gsa {
    /// `n` particles drawn uniformly in the bounds; `iterations` is T of the G(t) schedule.
    pub fn new(params: GsaParams, objective: &dyn Objective, n: usize, iterations: u32, rng: Rng) -> Self {
        let swarm = Swarm::uniform(objective, n, iterations, rng);
        let gravity = Gravity::at_rest(swarm.pop.x.len());
        Self { params, swarm, gravity }
    }
}

impl Optimizer for Gsa {
    fn algorithm(&self) -> Algorithm {
        Algorithm::Gsa
    }

    fn step(&mut self, objective: &dyn Objective) {
        let n = self.swarm.pop.size();
        let k = if self.params.kbest {
            kbest_count(n, self.swarm.t, self.swarm.iterations, self.params.final_kbest_share)
        } else {
            n
        };
        let dim = self.swarm.pop.dim;
        self.gravity.pull(&mut self.swarm, self.params.g0, self.params.alpha, k);
        let Gravity { velocity, acc, .. } = &mut self.gravity;
        for k in 0..n * dim {
            let r = self.swarm.rng.unit_f64();
            velocity[k] = r * velocity[k] + acc[k];
            self.swarm.pop.x[k] += velocity[k];
        }
        redraw_outside(objective.bounds(), &mut self.swarm.pop.x, &mut self.swarm.rng);
        self.swarm.pop.evaluate_all(objective);
        self.swarm.t += 1;
    }

    fn swarm(&self) -> &Swarm {
        &self.swarm
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masses_follow_the_standard_formula() {
        let mut m = Vec::new();
        masses(&[1.0, 3.0, 2.0], &mut m);
        // m = (f − worst)/(best − worst) = [1, 0, 0.5] → normalised by 1.5.
        let expect = [1.0 / 1.5, 0.0, 0.5 / 1.5];
        for (a, b) in m.iter().zip(expect) {
            assert!((a - b).abs() < 1e-15, "{m:?}");
        }
        masses(&[4.0, 4.0], &mut m);
        assert_eq!(m, vec![0.5, 0.5]);
    }

    #[test]
    fn kbest_falls_from_n_to_the_final_share() {
        assert_eq!(kbest_count(50, 0, 1000, 0.02), 50);
        assert_eq!(kbest_count(50, 1000, 1000, 0.02), 1);
        assert_eq!(kbest_count(50, 500, 1000, 0.02), 26);
    }

    #[test]
    fn two_particles_attract_each_other_along_their_line() {
        let x = [0.0, 0.0, 3.0, 4.0];
        let mut acc = [0.0; 4];
        let mut scratch = GravityScratch::default();
        gravity_accelerations(&x, &[0.0, 1.0], 2, 1.0, 2, &mut Rng::new(1, 0), &mut scratch, &mut acc);
        // Particle 1 (worse, mass 0) is pulled towards particle 0; particle 0 feels nothing.
        assert_eq!(&acc[..2], &[0.0, 0.0]);
        assert!(acc[2] < 0.0 && acc[3] < 0.0);
        assert!((acc[2] / acc[3] - 0.75).abs() < 1e-12);
    }
}
