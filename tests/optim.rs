//! Optimizers on R^d and IGSA path planning: accuracy within a budget, the chaotic
//! initialisation's coverage, determinism (same seed, any thread count), valid planned paths.
//! Budgets are small so the file stays fast in debug builds.

use flockpath::experiments::tables::{run_optimize, OptimizeArgs};
use flockpath::model::presets;
use flockpath::optim::igsa::{chaotic_positions, logistic_tent_points};
use flockpath::optim::{Algorithm, Benchmark, Bounds, Function, Objective, Settings};
use flockpath::planners::igsa::path::{PathParams, PathProblem};
use flockpath::rng::Rng;

fn run(algorithm: Algorithm, objective: &dyn Objective, settings: &Settings, seed: u32) -> (f64, f64) {
    let mut opt = algorithm.build(objective, settings, Rng::new(seed, 0));
    let initial = opt.best_value();
    for _ in 0..settings.iterations {
        opt.step(objective);
    }
    assert_eq!(opt.iteration(), settings.iterations);
    let best = opt.best_value();
    // The reported best really is the value at the reported point.
    assert_eq!(objective.evaluate(opt.best_position()), best);
    (initial, best)
}

/// Sphere, d = 10, [−80, 80]: N = 30, T = 300. Stated accuracies (the worst of three seeds must
/// reach them): GSA 1e-10, PSO 1e-2, firefly 1e-3, GA 1e-3. IGSA with the paper's G0 = 1,
/// α = 30 only reaches a tenth of its initial best (see docs/optimizers.md); with Rashedi's
/// G0 = 100, α = 20 it reaches 1e-10 like GSA.
#[test]
fn each_optimizer_reaches_its_stated_accuracy_on_sphere_d10() {
    let sphere = Benchmark::new(Function::Sphere, 10);
    let settings = Settings { population: 30, iterations: 300, ..Settings::default() };
    let cases =
        [(Algorithm::Gsa, 1e-10), (Algorithm::Pso, 1e-2), (Algorithm::Firefly, 1e-3), (Algorithm::Ga, 1e-3)];
    for (alg, target) in cases {
        for seed in 1..=3 {
            let (_, best) = run(alg, &sphere, &settings, seed);
            assert!(best < target, "{} seed {seed}: {best:e} ≥ {target:e}", alg.name());
        }
    }
    for seed in 1..=3 {
        let (initial, best) = run(Algorithm::Igsa, &sphere, &settings, seed);
        assert!(best < 0.1 * initial, "igsa seed {seed}: {best:e} vs initial {initial:e}");
        let rashedi = Settings { g0: Some(100.0), alpha: Some(20.0), ..settings.clone() };
        let (_, best) = run(Algorithm::Igsa, &sphere, &rashedi, seed);
        assert!(best < 1e-10, "igsa (G0 100) seed {seed}: {best:e}");
    }
}

/// Eq. 10's Logistic–Tent points stay in [0, 1) and fill it evenly: per coordinate, every bin of
/// a 20-bin histogram of 4000 points holds 65–135 % of its share (the bare logistic map, whose
/// density piles up at both ends, fails this), and the chi-square statistic is far below the
/// bare logistic map's. (It is not a perfect iid uniform: chi² is ~50 against 43.8 at 0.1 %.)
#[test]
fn chaotic_initialisation_stays_in_bounds_and_covers_them() {
    let (count, dim, bins) = (4000usize, 4usize, 20usize);
    let pts = logistic_tent_points(count, dim, 4.0, &mut Rng::new(11, 0));
    assert!(pts.iter().all(|v| (0.0..1.0).contains(v)));
    for d in 0..dim {
        let mut hist = vec![0usize; bins];
        for i in 0..count {
            hist[(pts[i * dim + d] * bins as f64) as usize] += 1;
        }
        let expected = count as f64 / bins as f64;
        let chi2: f64 = hist.iter().map(|&h| (h as f64 - expected).powi(2) / expected).sum();
        for &h in &hist {
            assert!((0.65..=1.35).contains(&(h as f64 / expected)), "coordinate {d}: {hist:?}");
        }
        // The bare logistic map x' = 4x(1 − x) from the same start, for contrast.
        let mut x = pts[d];
        let mut logistic = vec![0usize; bins];
        for _ in 0..count {
            x = 4.0 * x * (1.0 - x);
            logistic[((x * bins as f64) as usize).min(bins - 1)] += 1;
        }
        assert!(logistic.iter().any(|&h| !(0.65..=1.35).contains(&(h as f64 / expected))));
        let chi2_logistic: f64 = logistic.iter().map(|&h| (h as f64 - expected).powi(2) / expected).sum();
        assert!(chi2 < 0.25 * chi2_logistic, "coordinate {d}: chi² {chi2:.1} vs logistic {chi2_logistic:.1}");
    }
    // Denormalised into asymmetric bounds, every coordinate stays inside and spans most of it.
    let bounds = Bounds { lower: vec![-5.0, 10.0], upper: vec![3.0, 400.0] };
    let x = chaotic_positions(&bounds, 50, 4.0, &mut Rng::new(3, 0));
    for d in 0..2 {
        let col: Vec<f64> = x.iter().skip(d).step_by(2).copied().collect();
        assert!(col.iter().all(|&v| v >= bounds.lower[d] && v <= bounds.upper[d]));
        let (lo, hi) = col.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        assert!(hi - lo > 0.8 * bounds.range(d), "coordinate {d}: spread {lo}…{hi}");
    }
}

#[test]
fn same_seed_same_result_and_different_seed_differs() {
    let ackley = Benchmark::new(Function::Ackley, 5);
    let settings = Settings { population: 12, iterations: 40, ..Settings::default() };
    for &alg in Algorithm::ALL {
        let a = run(alg, &ackley, &settings, 9);
        let b = run(alg, &ackley, &settings, 9);
        assert_eq!(a.1.to_bits(), b.1.to_bits(), "{}", alg.name());
        let c = run(alg, &ackley, &settings, 10);
        assert_ne!(a.1.to_bits(), c.1.to_bits(), "{}", alg.name());
    }
}

/// The table (every run's curve included) is bit-identical on one thread and on four.
#[test]
#[cfg(not(target_arch = "wasm32"))] // rayon is native-only
fn thread_count_does_not_change_results() {
    let args = OptimizeArgs {
        functions: vec![Function::Rastrigin, Function::Griewank],
        dim: 4,
        settings: Settings { population: 8, iterations: 15, ..Settings::default() },
        runs: 5,
        seed: 77,
        ..OptimizeArgs::default()
    };
    let clock = || 0.0;
    let table_on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        let mut calls = 0;
        let table = pool.install(|| run_optimize(&args, &clock, &mut |_, _| calls += 1)).expect("runs");
        assert!(calls > 0);
        table
    };
    let (one, four) = (table_on(1), table_on(4));
    assert_eq!(one.cells.len(), Algorithm::ALL.len() * 2);
    for (a, b) in one.cells.iter().zip(&four.cells) {
        assert_eq!((a.algorithm, a.function), (b.algorithm, b.function));
        let bits = |c: &flockpath::experiments::tables::Cell| {
            c.curves.iter().flatten().map(|v| v.to_bits()).collect::<Vec<_>>()
        };
        assert_eq!(bits(a), bits(b), "{} on {}", a.algorithm, a.function);
        assert_eq!(a.best.to_bits(), b.best.to_bits());
        // Curves are best-so-far: never increasing.
        for curve in &a.curves {
            assert!(curve.windows(2).all(|w| w[1] <= w[0]));
        }
    }
}

/// IGSA (the paper's planner, its default settings) plans a path on both path scenes that
/// never crosses an obstacle and keeps some clearance, for every seed tried; a path that does
/// cross (GSA's, sometimes) always pays more than the crossing penalty, so a crossing path is
/// never preferred to a valid one.
#[test]
fn planned_paths_never_cross_obstacles_on_the_path_scenes() {
    let settings = Settings { population: 30, iterations: 300, ..Settings::default() };
    for scene in [presets::igsa_path_1(), presets::igsa_path_2()] {
        let name = scene.name.clone();
        let problem = PathProblem::from_scene(&scene, 0, PathParams::default()).expect("group with goal");
        let straight = ((problem.goal[0] - problem.start[0]).powi(2)
            + (problem.goal[1] - problem.start[1]).powi(2))
        .sqrt();
        // The straight line is blocked on both scenes: the test is not trivial.
        assert!(problem.segment_crosses(problem.start, problem.goal), "{name}");
        for seed in 0..3 {
            let path = problem.plan(Algorithm::Igsa, &settings, seed);
            assert_eq!(path.points.len(), PathParams::default().waypoints + 2);
            for w in path.points.windows(2) {
                assert!(!problem.segment_crosses(w[0], w[1]), "{name} seed {seed}: {:?}", path.points);
            }
            assert_eq!(path.measures.crossings, 0);
            assert!(path.measures.min_clearance > 0.0, "{name} seed {seed}: {:?}", path.measures);
            assert!(path.measures.length < 2.0 * straight, "{name} seed {seed}: {:?}", path.measures);
            let gsa = problem.plan(Algorithm::Gsa, &settings, seed);
            if gsa.measures.crossings > 0 {
                assert!(gsa.fitness > problem.params.crossing_penalty && gsa.fitness > path.fitness);
            }
        }
    }
}
