//! What every optimizer shares: the search box ([`Bounds`]), the function to minimise
//! ([`Objective`]), the [`Optimizer`] trait, the closed set of algorithms ([`Algorithm`]), run
//! [`Settings`], the particles ([`Population`]), the state every run carries ([`Swarm`]: the
//! particles, the iteration clock and the random stream) and small numeric helpers. The bottom of `optim`:
//! each optimizer imports this, never the folder's `mod.rs` that builds them.

use crate::rng::Rng;

/// An axis-aligned search box: `lower[d] ≤ x[d] ≤ upper[d]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds {
    /// Smallest value of each coordinate.
    pub lower: Vec<f64>,
    /// Largest value of each coordinate.
    pub upper: Vec<f64>,
}

impl Bounds {
    /// The same interval `[lo, hi]` in each of `dim` coordinates.
    pub fn uniform(dim: usize, lo: f64, hi: f64) -> Self {
        Self { lower: vec![lo; dim], upper: vec![hi; dim] }
    }

    /// Number of coordinates.
    pub fn dim(&self) -> usize {
        self.lower.len()
    }

    /// Width of coordinate `d`.
    pub fn range(&self, d: usize) -> f64 {
        self.upper[d] - self.lower[d]
    }
}

/// A function to minimise over a box.
pub trait Objective {
    /// The search box; its dimension is the problem's.
    fn bounds(&self) -> &Bounds;
    /// The value at `x` (length [`Bounds::dim`]); lower is better.
    fn evaluate(&self, x: &[f64]) -> f64;
}

/// Copies a boxed optimizer with all its state (the random stream included), so a copy steps
/// exactly as the original would. Implemented for every `Clone` optimizer.
pub trait OptimizerClone {
    /// A boxed deep copy of this run.
    fn clone_box(&self) -> Box<dyn Optimizer + Send>;
}

impl<T: Optimizer + Clone + Send + 'static> OptimizerClone for T {
    fn clone_box(&self) -> Box<dyn Optimizer + Send> {
        Box::new(self.clone())
    }
}

/// One optimizer run in progress.
pub trait Optimizer: OptimizerClone {
    /// Which algorithm this is.
    fn algorithm(&self) -> Algorithm;
    /// One iteration: move the population and evaluate it.
    fn step(&mut self, objective: &dyn Objective);
    /// The particles, the iteration clock and the random stream.
    fn swarm(&self) -> &Swarm;
    /// Iterations done so far (0 right after initialisation).
    fn iteration(&self) -> u32 {
        self.swarm().t
    }
    /// The particles, their best point and the evaluation count.
    fn population(&self) -> &Population {
        &self.swarm().pop
    }
    /// Best point found so far.
    fn best_position(&self) -> &[f64] {
        &self.population().best_x
    }
    /// Objective value at [`Optimizer::best_position`].
    fn best_value(&self) -> f64 {
        self.population().best_f
    }
    /// Current positions, row-major: particle `i` is `positions()[i * dim..(i + 1) * dim]`.
    fn positions(&self) -> &[f64] {
        &self.population().x
    }
    /// Objective evaluations so far (initialisation included).
    fn evaluations(&self) -> u64 {
        self.population().evaluations
    }
}

/// The closed set of optimizers, for the CLI and the lab page.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Algorithm {
    /// Gravitational search (Rashedi et al. 2009).
    Gsa,
    /// Improved gravitational search (Liu & Liu 2022).
    Igsa,
    /// Particle swarm with inertia decreasing 0.9 → 0.4 (the paper's OI-PSO baseline).
    Pso,
    /// Firefly algorithm (Yang 2008/2010).
    Firefly,
    /// Real-coded genetic algorithm.
    Ga,
}

impl Algorithm {
    /// Every algorithm, in table order.
    pub const ALL: &'static [Algorithm] =
        &[Algorithm::Gsa, Algorithm::Igsa, Algorithm::Pso, Algorithm::Firefly, Algorithm::Ga];

    /// The CLI name.
    pub fn name(self) -> &'static str {
        match self {
            Algorithm::Gsa => "gsa",
            Algorithm::Igsa => "igsa",
            Algorithm::Pso => "pso",
            Algorithm::Firefly => "firefly",
            Algorithm::Ga => "ga",
        }
    }

    /// Looks an algorithm up by its CLI name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|a| a.name() == name)
    }

    /// [`Self::from_name`] for user input: an unknown name is refused with the known ones.
    pub fn parse(name: &str) -> Result<Self, UnknownName> {
        Self::from_name(name).ok_or_else(|| UnknownName::Algorithm(name.chars().take(40).collect()))
    }
}

fn algorithm_names() -> String {
    Algorithm::ALL.iter().map(|a| a.name()).collect::<Vec<_>>().join(", ")
}

/// A name that names no optimizer or benchmark function; the page's lab and the CLI word it the
/// same way (`unknown algorithm "x"; known: gsa, igsa, pso, firefly, ga`).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum UnknownName {
    /// Not one of [`Algorithm::ALL`].
    #[error("unknown algorithm {0:?}; known: {known}", known = algorithm_names())]
    Algorithm(String),
    /// Not one of `Function::ALL` (the names it lists are given by the caller's table).
    #[error("unknown function {0:?}; known: {1}")]
    Function(String, String),
}

/// Run settings shared by every algorithm.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Population size N (paper: 50).
    pub population: usize,
    /// Iteration budget T; the schedules (G(t), inertia, c1/c2) run over it (paper: 1000).
    pub iterations: u32,
    /// Overrides G0 of GSA and IGSA (defaults: GSA 100, IGSA 1).
    pub g0: Option<f64>,
    /// Overrides α of GSA and IGSA (defaults: GSA 20, IGSA 30).
    pub alpha: Option<f64>,
}

impl Default for Settings {
    fn default() -> Self {
        Self { population: 50, iterations: 1000, g0: None, alpha: None }
    }
}

/// A population with its fitness and the best point seen: the state every algorithm shares.
#[derive(Clone, Debug)]
pub struct Population {
    /// Coordinates per particle.
    pub dim: usize,
    /// Positions, row-major (`size × dim`).
    pub x: Vec<f64>,
    /// Objective value of each particle at its current position.
    pub fitness: Vec<f64>,
    /// Best point seen so far.
    pub best_x: Vec<f64>,
    /// Value at `best_x`.
    pub best_f: f64,
    /// Objective evaluations so far.
    pub evaluations: u64,
}

impl Population {
    /// Particles drawn uniformly in the bounds, evaluated.
    pub fn uniform(objective: &dyn Objective, size: usize, rng: &mut Rng) -> Self {
        let b = objective.bounds();
        let dim = b.dim();
        let mut x = Vec::with_capacity(size * dim);
        for _ in 0..size {
            for d in 0..dim {
                x.push(b.lower[d] + rng.unit_f64() * b.range(d));
            }
        }
        Self::from_positions(objective, dim, x)
    }

    /// A population at the given row-major positions, evaluated.
    pub fn from_positions(objective: &dyn Objective, dim: usize, x: Vec<f64>) -> Self {
        let size = x.len() / dim.max(1);
        let mut pop = Self {
            dim,
            x,
            fitness: vec![f64::MAX; size],
            best_x: vec![0.0; dim],
            best_f: f64::INFINITY,
            evaluations: 0,
        };
        pop.evaluate_all(objective);
        pop
    }

    /// Number of particles.
    pub fn size(&self) -> usize {
        self.fitness.len()
    }

    /// Position of particle `i`.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.x[i * self.dim..(i + 1) * self.dim]
    }

    /// Evaluates every particle and updates the best; returns whether the best improved.
    pub fn evaluate_all(&mut self, objective: &dyn Objective) -> bool {
        let mut improved = false;
        for i in 0..self.size() {
            let f = sanitize(objective.evaluate(self.row(i)));
            self.fitness[i] = f;
            improved |= self.offer(i, f);
        }
        self.evaluations += self.size() as u64;
        improved
    }

    /// Evaluates one point, counting the evaluation.
    pub fn evaluate_point(&mut self, objective: &dyn Objective, x: &[f64]) -> f64 {
        self.evaluations += 1;
        sanitize(objective.evaluate(x))
    }

    /// Records particle `i` with value `f` as the best if it beats it (ties keep the older).
    pub fn offer(&mut self, i: usize, f: f64) -> bool {
        if f < self.best_f {
            self.best_f = f;
            let dim = self.dim;
            self.best_x.copy_from_slice(&self.x[i * dim..(i + 1) * dim]);
            true
        } else {
            false
        }
    }

    /// Index of the particle with the lowest current fitness (lowest index on ties).
    pub fn argmin(&self) -> usize {
        let mut best = 0;
        for (i, &f) in self.fitness.iter().enumerate() {
            if f < self.fitness[best] {
                best = i;
            }
        }
        best
    }
}

/// What every optimizer run carries besides its own parameters and buffers: the particles, the
/// iteration clock t of the budget T (which the schedules G(t), inertia, σ and α read) and the
/// run's random stream.
#[derive(Clone, Debug)]
pub struct Swarm {
    /// The particles.
    pub pop: Population,
    /// Iterations done so far.
    pub t: u32,
    /// The budget T (at least 1).
    pub iterations: u32,
    /// The run's random stream.
    pub rng: Rng,
}

impl Swarm {
    /// A run at iteration 0 of `iterations` over the given particles.
    pub fn new(pop: Population, iterations: u32, rng: Rng) -> Self {
        Self { pop, t: 0, iterations: iterations.max(1), rng }
    }

    /// `n` (at least 2) particles drawn uniformly in the bounds from `rng`, evaluated.
    pub fn uniform(objective: &dyn Objective, n: usize, iterations: u32, mut rng: Rng) -> Self {
        let pop = Population::uniform(objective, n.max(2), &mut rng);
        Self::new(pop, iterations, rng)
    }

    /// t / T: 0 at the start, 1 when the budget is spent.
    pub fn progress(&self) -> f64 {
        f64::from(self.t) / f64::from(self.iterations)
    }
}

/// Non-finite objective values would poison the mass and selection arithmetic: NaN and +∞
/// become the largest finite value, −∞ the smallest.
pub fn sanitize(f: f64) -> f64 {
    if f.is_nan() {
        f64::MAX
    } else {
        f.clamp(f64::MIN, f64::MAX)
    }
}

/// Clamps coordinate `d` of `x` into the bounds; returns whether it was outside.
#[inline]
pub fn clamp_coordinate(bounds: &Bounds, d: usize, x: &mut f64) -> bool {
    if *x < bounds.lower[d] {
        *x = bounds.lower[d];
        true
    } else if *x > bounds.upper[d] {
        *x = bounds.upper[d];
        true
    } else if x.is_nan() {
        *x = bounds.lower[d] + 0.5 * bounds.range(d);
        true
    } else {
        false
    }
}

/// A standard normal draw (Box–Muller with `libm`, so it is the same in wasm).
pub fn gaussian(rng: &mut Rng) -> f64 {
    // 1 − u lies in (0, 1], so the logarithm is finite.
    let u1 = 1.0 - rng.unit_f64();
    let u2 = rng.unit_f64();
    libm::sqrt(-2.0 * libm::log(u1)) * libm::cos(2.0 * std::f64::consts::PI * u2)
}

/// The random stream of run `run` under master seed `seed`: each run draws from its own PCG32
/// stream, so runs are independent and can execute in any order on any number of threads.
pub fn run_rng(seed: u32, run: u32) -> Rng {
    Rng::new(seed, run)
}
