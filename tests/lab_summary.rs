//! The lab's 30-run table row and Table 3's cells come from one `Summary::of`: its statistics on
//! known values, and on real runs the same numbers `run_optimize` puts in its cells (the lab's
//! worker computes the finals one `best_of_run` at a time and hands them to `lab_summary_json`).

use flockpath::experiments::tables::{run_optimize, OptimizeArgs, Summary};
use flockpath::optim::lab::best_of_run;
use flockpath::optim::{Algorithm, Function, Settings};

#[test]
fn summary_of_known_values_in_any_order() {
    let odd = Summary::of(&[5.0, 1.0, 3.0]);
    assert_eq!((odd.best, odd.worst, odd.mean, odd.median, odd.runs), (1.0, 5.0, 3.0, 3.0, 3));
    let even = Summary::of(&[4.0, 10.0, 1.0, 2.0]);
    assert_eq!((even.best, even.worst, even.mean, even.median, even.runs), (1.0, 10.0, 4.25, 3.0, 4));
    let one = Summary::of(&[7.5]);
    assert_eq!((one.best, one.worst, one.mean, one.median, one.runs), (7.5, 7.5, 7.5, 7.5, 1));
}

#[test]
fn summary_of_nothing_is_nan_with_zero_runs() {
    let empty = Summary::of(&[]);
    assert_eq!(empty.runs, 0);
    assert!(empty.best.is_nan() && empty.worst.is_nan() && empty.mean.is_nan() && empty.median.is_nan());
}

#[test]
fn summary_json_has_the_fields_the_lab_worker_reads() {
    let json: serde_json::Value = serde_json::to_value(Summary::of(&[2.0, 1.0])).expect("serializes");
    assert_eq!(json, serde_json::json!({ "best": 1.0, "worst": 2.0, "mean": 1.5, "median": 1.5, "runs": 2 }));
}

/// The lab's way (one run at a time, then `Summary::of`) and the CLI's `run_optimize` agree to
/// the bit on every statistic.
#[test]
fn lab_runs_summarised_match_the_table_cells() {
    let settings = Settings { population: 10, iterations: 20, ..Settings::default() };
    let args = OptimizeArgs {
        algorithms: vec![Algorithm::Pso, Algorithm::Gsa],
        functions: vec![Function::Rastrigin],
        dim: 3,
        settings: settings.clone(),
        runs: 6,
        seed: 9,
        ..OptimizeArgs::default()
    };
    let table = run_optimize(&args, &|| 0.0, &mut |_, _| {}).expect("runs");
    for cell in &table.cells {
        let algorithm = Algorithm::from_name(cell.algorithm).expect("known algorithm");
        let finals: Vec<f64> = (0..args.runs)
            .map(|run| best_of_run(algorithm, Function::Rastrigin, 3, &settings, 9, run))
            .collect();
        let summary = Summary::of(&finals);
        let bits = |s: [f64; 4]| s.map(f64::to_bits);
        assert_eq!(
            bits([summary.best, summary.worst, summary.mean, summary.median]),
            bits([cell.best, cell.worst, cell.mean, cell.median]),
            "{}",
            cell.algorithm
        );
        assert_eq!(summary.runs, cell.runs as usize);
        assert!(summary.best < summary.worst, "{}: six seeded runs differ", cell.algorithm);
    }
}
