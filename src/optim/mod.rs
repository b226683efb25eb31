//! Swarm optimizers on R^d (GSA, IGSA, PSO, firefly, GA), benchmark functions, and IGSA path
//! planning: the algorithms of DESIGN §3.4 as plain optimizers, with no web or clock types.
//!
//! Every optimizer implements [`Optimizer`]: it is built on an [`Objective`] (box bounds and a
//! function to minimise) with its own seeded [`Rng`], advanced one iteration at a time by
//! [`Optimizer::step`], and exposes the best point so far and the particles' positions (for the
//! lab view). All arithmetic is `f64`; transcendental functions go through `libm`, so a run is
//! bit-identical natively and in wasm.
//!
//! ```
//! use flockpath::optim::{Algorithm, Benchmark, Function, Settings};
//! use flockpath::rng::Rng;
//!
//! let sphere = Benchmark::new(Function::Sphere, 5);
//! let settings = Settings { population: 20, iterations: 200, ..Settings::default() };
//! let mut pso = Algorithm::Pso.build(&sphere, &settings, Rng::new(7, 0));
//! for _ in 0..settings.iterations {
//!     pso.step(&sphere);
//! }
//! assert!(pso.best_value() < 1e-3);
//! ```
//!
//! Layer: optim. Uses `rng` only: no scene, no crowd (IGSA's path planning, which needs the scene,
//! lives in `planners::igsa::path`; the papers' tables in `experiments`).

pub mod firefly;
pub mod functions;
pub mod ga;
pub mod gsa;
pub mod igsa;
pub mod lab;
pub mod problem;
pub mod pso;

use crate::rng::Rng;

pub use firefly::{Firefly, FireflyParams};
pub use functions::{Benchmark, Function};
pub use ga::{Ga, GaParams};
pub use gsa::{Gsa, GsaParams};
pub use igsa::{Igsa, IgsaParams};
pub use problem::{
    clamp_coordinate, gaussian, run_rng, sanitize, Algorithm, Bounds, Objective, Optimizer, OptimizerClone,
    Population, Settings, UnknownName,
};
pub use pso::{Pso, PsoParams};

/// Building a run is here, above the optimizers it builds; the enum itself is plain data.
impl Algorithm {
    /// A fresh run on `objective`, initialised from `rng` with this algorithm's default
    /// parameters (overridden by `settings` where it says so).
    pub fn build(
        self,
        objective: &dyn Objective,
        settings: &Settings,
        rng: Rng,
    ) -> Box<dyn Optimizer + Send> {
        let (n, t) = (settings.population.max(2), settings.iterations.max(1));
        match self {
            Algorithm::Gsa => {
                let mut p = GsaParams::default();
                p.g0 = settings.g0.unwrap_or(p.g0);
                p.alpha = settings.alpha.unwrap_or(p.alpha);
                Box::new(Gsa::new(p, objective, n, t, rng))
            }
            Algorithm::Igsa => {
                let mut p = IgsaParams::default();
                p.g0 = settings.g0.unwrap_or(p.g0);
                p.alpha = settings.alpha.unwrap_or(p.alpha);
                Box::new(Igsa::new(p, objective, n, t, rng))
            }
            Algorithm::Pso => Box::new(Pso::new(PsoParams::default(), objective, n, t, rng)),
            Algorithm::Firefly => Box::new(Firefly::new(FireflyParams::default(), objective, n, t, rng)),
            Algorithm::Ga => Box::new(Ga::new(GaParams::default(), objective, n, t, rng)),
        }
    }
}

/// Maps `f` over `jobs` in order, on every core natively (rayon) and sequentially in wasm.
/// Jobs run in chunks so `progress(done, total)` is called from this thread between chunks;
/// results never depend on the number of threads because each job owns its generator.
pub fn map_in_order<J: Sync, T: Send>(
    jobs: &[J],
    f: &(dyn Fn(&J) -> T + Sync),
    progress: &mut dyn FnMut(usize, usize),
) -> Vec<T> {
    let mut out = Vec::with_capacity(jobs.len());
    #[cfg(not(target_arch = "wasm32"))]
    {
        use rayon::prelude::*;
        let chunk = (rayon::current_num_threads() * 4).max(1);
        for part in jobs.chunks(chunk) {
            let done: Vec<T> = part.par_iter().map(f).collect();
            out.extend(done);
            progress(out.len(), jobs.len());
        }
    }
    #[cfg(target_arch = "wasm32")]
    for job in jobs {
        out.push(f(job));
        progress(out.len(), jobs.len());
    }
    out
}
