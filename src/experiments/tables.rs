//! The optimizer experiments as data (`flockpath optimize` prints them): independent seeded
//! runs (in parallel natively), the Table-3-style summary, JSON records, convergence-curve CSV,
//! the force-step timing and the paper's Table 4.
//!
//! The core has no clock: the caller passes one (`clock()` = seconds since any fixed instant)
//! and a progress callback, both used only for reporting.

use crate::optim::functions::{Benchmark, Function};
use crate::optim::gsa::{gravity_accelerations, GravityScratch};
use crate::optim::{map_in_order, run_rng, Algorithm, Settings};
use crate::rng::Rng;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::PathBuf;

/// What the optimizer experiments run (`flockpath optimize` fills it from its flags).
#[derive(Clone, Debug, PartialEq)]
pub struct OptimizeArgs {
    /// Algorithms to run, in table order.
    pub algorithms: Vec<Algorithm>,
    /// Functions to run, in table order.
    pub functions: Vec<Function>,
    /// Dimension.
    pub dim: usize,
    /// Population size and iteration budget (plus G0/α overrides).
    pub settings: Settings,
    /// Runs per cell.
    pub runs: u32,
    /// Master seed.
    pub seed: u32,
    /// Where to write JSON records.
    pub json: Option<PathBuf>,
    /// Where to write convergence curves.
    pub curves: Option<PathBuf>,
    /// Only time the force step.
    pub bench_force: bool,
    /// Run the GSA-vs-IGSA path experiment (`igsa-path-1`, `igsa-path-2`) instead.
    pub paths: bool,
    /// Run the crowd experiment (Table 4) instead.
    pub table4: bool,
    /// Steps of each Table 4 run.
    pub steps: u32,
}

impl Default for OptimizeArgs {
    fn default() -> Self {
        Self {
            algorithms: Algorithm::ALL.to_vec(),
            functions: Function::PAPER.to_vec(),
            dim: 30,
            settings: Settings::default(),
            runs: 30,
            seed: 1,
            json: None,
            curves: None,
            bench_force: false,
            paths: false,
            table4: false,
            steps: 6000,
        }
    }
}

/// Why the optimizer experiments could not run.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum OptimizeError {
    /// No algorithm, no function or zero runs: the table would be empty.
    #[error("optimize: nothing to run (no algorithm, function or run)")]
    NothingToRun,
}

impl crate::model::refusal::Refusal for crate::optim::UnknownName {
    fn message(&self) -> crate::model::refusal::Message {
        use crate::model::refusal::{Code, Message};
        match self {
            crate::optim::UnknownName::Algorithm(name) => {
                let known: Vec<&str> = crate::optim::Algorithm::ALL.iter().map(|a| a.name()).collect();
                Message::new(Code::LabUnknownAlgorithm).with("name", name.clone()).with("known", known)
            }
            crate::optim::UnknownName::Function(name, known) => Message::new(Code::LabUnknownFunction)
                .with("name", name.clone())
                .with("known", known.split(", ").collect::<Vec<_>>()),
        }
    }
}

impl crate::model::refusal::Refusal for OptimizeError {
    fn message(&self) -> crate::model::refusal::Message {
        crate::model::refusal::Message::new(crate::model::refusal::Code::OptimizeNothing)
    }
}

/// One independent run: its final best value, best-so-far per iteration (index 0 = after
/// initialisation), evaluations and time.
#[derive(Clone, Debug, PartialEq)]
pub struct RunOutcome {
    /// Best value at the end.
    pub best: f64,
    /// Best value so far after initialisation and after each iteration (T + 1 values).
    pub curve: Vec<f64>,
    /// Objective evaluations used.
    pub evaluations: u64,
    /// Wall time of this run (seconds, from the caller's clock).
    pub seconds: f64,
}

/// One algorithm on one function over all runs: a cell of the table and a JSON record.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cell {
    /// Algorithm name.
    pub algorithm: &'static str,
    /// Function name.
    pub function: &'static str,
    /// Dimension.
    pub dim: usize,
    /// Number of runs.
    pub runs: u32,
    /// Lowest final value over the runs.
    pub best: f64,
    /// Highest final value over the runs.
    pub worst: f64,
    /// Mean final value.
    pub mean: f64,
    /// Median final value.
    pub median: f64,
    /// Sum of the runs' wall times: the cell's cost on one core, whatever the thread count.
    pub seconds: f64,
    /// Objective evaluations per run (mean).
    pub evaluations: f64,
    /// Population size.
    pub population: usize,
    /// Iterations per run.
    pub iterations: u32,
    /// Master seed.
    pub seed: u32,
    /// Every run's convergence curve, in run order.
    #[serde(skip)]
    pub curves: Vec<Vec<f64>>,
}

/// The whole table, cells in algorithm-major order.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// The options it was run with.
    pub args: OptimizeArgs,
    /// One cell per algorithm and function.
    pub cells: Vec<Cell>,
}

/// Runs one seeded optimization of `algorithm` on `function`.
pub fn run_once(
    algorithm: Algorithm,
    function: Function,
    dim: usize,
    settings: &Settings,
    rng: Rng,
    clock: &dyn Fn() -> f64,
) -> RunOutcome {
    let start = clock();
    let objective = Benchmark::new(function, dim);
    let mut opt = algorithm.build(&objective, settings, rng);
    let mut curve = Vec::with_capacity(settings.iterations as usize + 1);
    curve.push(opt.best_value());
    for _ in 0..settings.iterations {
        opt.step(&objective);
        curve.push(opt.best_value());
    }
    RunOutcome { best: opt.best_value(), curve, evaluations: opt.evaluations(), seconds: clock() - start }
}

/// Best, worst, mean and median of a set of final values (one table cell's statistics), and how
/// many there were: the numbers of Table 3, also reported by the lab page's 30-run table.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// Lowest value.
    pub best: f64,
    /// Highest value.
    pub worst: f64,
    /// Mean (summed in ascending order).
    pub mean: f64,
    /// Median (the mean of the middle two for an even count).
    pub median: f64,
    /// How many values.
    pub runs: usize,
}

impl Summary {
    /// The statistics of `values` (any order; NaN sorts last, as `f64::total_cmp` puts it). An
    /// empty slice gives NaN statistics and `runs` 0.
    pub fn of(values: &[f64]) -> Summary {
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let (Some(&best), Some(&worst)) = (sorted.first(), sorted.last()) else {
            return Summary { best: f64::NAN, worst: f64::NAN, mean: f64::NAN, median: f64::NAN, runs: 0 };
        };
        let mean = sorted.iter().sum::<f64>() / sorted.len() as f64;
        Summary { best, worst, mean, median: median(&sorted), runs: sorted.len() }
    }
}

fn median(sorted: &[f64]) -> f64 {
    let n = sorted.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    }
}

/// Runs the whole table: `runs` independent runs per algorithm × function.
pub fn run_optimize(
    args: &OptimizeArgs,
    clock: &(dyn Fn() -> f64 + Sync),
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Table, OptimizeError> {
    if args.algorithms.is_empty() || args.functions.is_empty() || args.runs == 0 {
        return Err(OptimizeError::NothingToRun);
    }
    let mut jobs = Vec::new();
    for &a in &args.algorithms {
        for &f in &args.functions {
            for r in 0..args.runs {
                jobs.push((a, f, r));
            }
        }
    }
    let outcomes = map_in_order(
        &jobs,
        &|&(a, f, r)| run_once(a, f, args.dim, &args.settings, run_rng(args.seed, r), clock),
        progress,
    );
    let mut cells = Vec::new();
    for (k, chunk) in outcomes.chunks(args.runs as usize).enumerate() {
        let (a, f, _) = jobs[k * args.runs as usize];
        let finals: Vec<f64> = chunk.iter().map(|o| o.best).collect();
        let summary = Summary::of(&finals);
        let n = finals.len() as f64;
        cells.push(Cell {
            algorithm: a.name(),
            function: f.name(),
            dim: args.dim,
            runs: args.runs,
            best: summary.best,
            worst: summary.worst,
            mean: summary.mean,
            median: summary.median,
            seconds: chunk.iter().map(|o| o.seconds).sum(),
            evaluations: chunk.iter().map(|o| o.evaluations as f64).sum::<f64>() / n,
            population: args.settings.population,
            iterations: args.settings.iterations,
            seed: args.seed,
            curves: chunk.iter().map(|o| o.curve.clone()).collect(),
        });
    }
    Ok(Table { args: args.clone(), cells })
}

impl Table {
    /// The cell of `algorithm` on `function`, if it was run.
    pub fn cell(&self, algorithm: &str, function: &str) -> Option<&Cell> {
        self.cells.iter().find(|c| c.algorithm == algorithm && c.function == function)
    }

    /// The Table-3-style text: per function, rows best / worst / mean / median, one column per
    /// algorithm, five significant digits.
    pub fn to_text(&self) -> String {
        let a = &self.args;
        let mut s = format!(
            "d = {}, N = {}, T = {}, {} runs, seed {}\n",
            a.dim, a.settings.population, a.settings.iterations, a.runs, a.seed
        );
        let _ = write!(s, "{:<16}{:<8}", "function", "");
        for alg in &a.algorithms {
            let _ = write!(s, "{:>13}", alg.name());
        }
        s.push('\n');
        for f in &a.functions {
            for (k, stat) in ["best", "worst", "mean", "median"].iter().enumerate() {
                let name = if k == 0 { f.name() } else { "" };
                let _ = write!(s, "{name:<16}{stat:<8}");
                for alg in &a.algorithms {
                    let v = self.cell(alg.name(), f.name()).map_or(f64::NAN, |c| match k {
                        0 => c.best,
                        1 => c.worst,
                        2 => c.mean,
                        _ => c.median,
                    });
                    let _ = write!(s, "{v:>13.4e}");
                }
                s.push('\n');
            }
        }
        let _ = write!(s, "{:<24}", "evaluations/run");
        for alg in &a.algorithms {
            let e = self.cells.iter().find(|c| c.algorithm == alg.name()).map_or(0.0, |c| c.evaluations);
            let _ = write!(s, "{e:>13.0}");
        }
        s.push('\n');
        let _ = write!(s, "{:<24}", "seconds (1 core)");
        for alg in &a.algorithms {
            let t: f64 = self.cells.iter().filter(|c| c.algorithm == alg.name()).map(|c| c.seconds).sum();
            let _ = write!(s, "{t:>13.2}");
        }
        s.push('\n');
        s
    }

    /// The JSON records (an array, one object per cell).
    pub fn to_json(&self) -> String {
        // Cells are plain derived records with string keys: writing them cannot fail (a
        // non-finite value is written as null), so a failure is a bug and panics loudly.
        serde_json::to_string_pretty(&self.cells).expect("optimizer cells always serialise")
    }

    /// Convergence curves of `function` (or all functions) as CSV with a header.
    pub fn curves_csv(&self, function: Option<&str>) -> String {
        let mut s = String::from("algorithm,function,run,iteration,best\n");
        for c in self.cells.iter().filter(|c| function.is_none_or(|f| f == c.function)) {
            for (run, curve) in c.curves.iter().enumerate() {
                for (it, v) in curve.iter().enumerate() {
                    let _ = writeln!(s, "{},{},{run},{it},{v:e}", c.algorithm, c.function);
                }
            }
        }
        s
    }
}

/// Times the O(N²·d) force step ([`gravity_accelerations`] with every particle attracting) at
/// N = 50 and 1000, d = 30, and returns one line per N.
pub fn bench_force(clock: &dyn Fn() -> f64) -> String {
    let mut s = String::new();
    let dim = 30;
    for n in [50usize, 1000] {
        let mut rng = Rng::new(1, 0);
        let x: Vec<f64> = (0..n * dim).map(|_| rng.unit_f64() * 160.0 - 80.0).collect();
        let fitness: Vec<f64> = (0..n).map(|i| Function::Sphere.value(&x[i * dim..(i + 1) * dim])).collect();
        let mut acc = vec![0.0; n * dim];
        let mut scratch = GravityScratch::default();
        let mut reps = 0u32;
        let start = clock();
        let mut elapsed = 0.0;
        while elapsed < 0.5 || reps < 3 {
            gravity_accelerations(&x, &fitness, dim, 1.0, n, &mut rng, &mut scratch, &mut acc);
            reps += 1;
            elapsed = clock() - start;
        }
        let per = elapsed / f64::from(reps);
        let pairs = (n * (n - 1)) as f64;
        let _ = writeln!(
            s,
            "gsa force step  N = {n:>4}  d = {dim}: {:>10.1} µs/iteration  ({:.2} ns per pair, {} reps)",
            per * 1e6,
            per * 1e9 / pairs,
            reps
        );
    }
    s
}

/// One row of Table 4: a crowd of `agents` following a path planned by `optimizer`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CrowdRow {
    /// Group size.
    pub agents: u32,
    /// Path optimizer (`igsa` or `gsa`).
    pub optimizer: &'static str,
    /// Planning time (ms, median of three plans; the caller's clock).
    pub planning_ms: f64,
    /// Path length (px).
    pub path_length: f64,
    /// Largest deflection of the path (degrees).
    pub max_turn_deg: f64,
    /// Segments of the path that cross an obstacle.
    pub crossing_segments: usize,
    /// Mean speed of agents within 30 px of the obstacle (px/step).
    pub speed_near_obstacle: Option<f64>,
    /// Mean speed over all agents and steps (px/step).
    pub mean_speed: f64,
    /// Share of agents that reached the goal.
    pub arrived_share: f64,
    /// Mean steps to the goal over arrived agents.
    pub mean_time_to_goal: Option<f64>,
    /// Overlapping pairs summed over steps (the metric).
    pub collisions: u64,
    /// The part of it from the random spawn: counted until the first step with no overlap.
    pub spawn_collisions: u64,
    /// Penetrations of obstacles.
    pub penetrations: u64,
}

/// The paper's Table 4, measured: the `igsa-crowd` scene with each group size, the path
/// planned by IGSA and by GSA, `steps` steps each. Planning is timed alone (it never sees the
/// agents); the path is the same for every size.
pub fn table4_rows(
    sizes: &[u32],
    steps: u32,
    clock: &dyn Fn() -> f64,
    progress: &mut dyn FnMut(usize, usize),
) -> Vec<CrowdRow> {
    use crate::model::params::PathOptimizer;
    use crate::model::params::{IgsaParams, PlannerConfig};
    use crate::planners::igsa::plan_group_path;
    let mut rows = Vec::new();
    let total = sizes.len() * 2;
    for (k, (&agents, optimizer)) in
        sizes.iter().flat_map(|n| [(n, PathOptimizer::Igsa), (n, PathOptimizer::Gsa)]).enumerate()
    {
        let mut scene = crate::model::presets::igsa_crowd(agents);
        let params = IgsaParams { optimizer, ..IgsaParams::default() };
        scene.groups[0].planner = PlannerConfig::Igsa(params.clone());
        let mut times = Vec::new();
        let mut path = None;
        for _ in 0..3 {
            let start = clock();
            path = plan_group_path(&scene, 0, &params);
            times.push(clock() - start);
        }
        times.sort_by(f64::total_cmp);
        let Some(path) = path else { continue };
        let Ok(mut world) = crate::World::new(scene) else { continue };
        let mut spawn_collisions = None;
        for _ in 0..steps {
            world.step();
            if spawn_collisions.is_none() {
                let m = world.metrics();
                if m.collisions_last_step == 0 {
                    spawn_collisions = Some(m.overall.collisions_agent_agent);
                }
            }
        }
        let m = world.metrics();
        rows.push(CrowdRow {
            agents,
            optimizer: match optimizer {
                PathOptimizer::Igsa => "igsa",
                PathOptimizer::Gsa => "gsa",
            },
            planning_ms: times[1] * 1e3,
            path_length: path.length,
            max_turn_deg: path.max_turn_deg,
            crossing_segments: path.crossing.iter().filter(|&&c| c).count(),
            speed_near_obstacle: m.overall.mean_speed_near_obstacles,
            mean_speed: m.overall.mean_speed,
            arrived_share: m.overall.arrived_share,
            mean_time_to_goal: m.overall.mean_time_to_goal,
            collisions: m.overall.collisions_agent_agent,
            spawn_collisions: spawn_collisions.unwrap_or(m.overall.collisions_agent_agent),
            penetrations: m.overall.penetrations_agent_obstacle,
        });
        progress(k + 1, total);
    }
    rows
}

/// [`table4_rows`] as text.
pub fn table4(
    sizes: &[u32],
    steps: u32,
    clock: &dyn Fn() -> f64,
    progress: &mut dyn FnMut(usize, usize),
) -> String {
    let rows = table4_rows(sizes, steps, clock, progress);
    let mut s = format!(
        "igsa-crowd, {steps} steps (1 step = 1/60 s), path planner N = 30, T = 300, seed 1\n{:>6} {:>6} {:>9} {:>8} {:>6} {:>6} {:>10} {:>8} {:>8} {:>9} {:>10} {:>8} {:>6}\n",
        "agents", "path", "plan ms", "length", "turn°", "cross", "v@obst", "v mean", "arrived", "t goal", "collisions", "spawn", "penetr"
    );
    for r in &rows {
        let _ = writeln!(
            s,
            "{:>6} {:>6} {:>9.1} {:>8.1} {:>6.1} {:>6} {:>10} {:>8.3} {:>7.1}% {:>9} {:>10} {:>8} {:>6}",
            r.agents,
            r.optimizer,
            r.planning_ms,
            r.path_length,
            r.max_turn_deg,
            r.crossing_segments,
            r.speed_near_obstacle.map_or("-".into(), |v| format!("{v:.3}")),
            r.mean_speed,
            100.0 * r.arrived_share,
            r.mean_time_to_goal.map_or("-".into(), |t| format!("{t:.0}")),
            r.collisions,
            r.spawn_collisions,
            r.penetrations
        );
    }
    s
}

/// Worker threads the runs use.
pub fn threads() -> usize {
    #[cfg(not(target_arch = "wasm32"))]
    {
        rayon::current_num_threads()
    }
    #[cfg(target_arch = "wasm32")]
    {
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_even_and_odd() {
        assert_eq!(median(&[1.0, 2.0, 3.0]), 2.0);
        assert_eq!(median(&[1.0, 2.0, 3.0, 5.0]), 2.5);
    }
}
