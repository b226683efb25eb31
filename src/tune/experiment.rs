//! The paper's tuning experiment as data (`flockpath tune` prints it): one tuning run with its
//! report, the experiment table (9 behaviour × environment pairs × seeds) with the cross-scene
//! check, and their text forms (progress line, Markdown table).
//!
//! The core has no clock: the caller passes one, used only for the seconds and
//! evaluations-per-second figures.

use super::{Evaluation, GaParams, GenerationStats, TuneError, TuneTask, Tuner};
use crate::model::forces_cases::{Behaviour, Environment};
use serde::Serialize;
use std::fmt::Write as _;

/// What one tuning run may spend: the GA settings and the simulation per evaluation.
#[derive(Clone, Debug, PartialEq)]
pub struct Budget {
    /// Genetic-algorithm settings.
    pub ga: GaParams,
    /// Frames per evaluation.
    pub frames: u32,
    /// Measure every this many frames.
    pub sample_every: u32,
}

impl Default for Budget {
    fn default() -> Self {
        Self {
            ga: GaParams::default(),
            frames: super::DEFAULT_FRAMES,
            sample_every: super::DEFAULT_SAMPLE_EVERY,
        }
    }
}

/// Scores `weights` `[s1…s5]` on a pair without tuning.
pub fn score(
    behaviour: Behaviour,
    environment: Environment,
    weights: [f32; 5],
    budget: &Budget,
) -> Evaluation {
    let mut task = TuneTask::new(behaviour, environment);
    task.frames = budget.frames;
    task.sample_every = budget.sample_every;
    task.evaluate(weights)
}

/// One tuning run's outcome, as written by `--json`.
#[derive(Clone, Debug, Serialize)]
pub struct TuneReport {
    /// `b1`…`b3`.
    pub behaviour: &'static str,
    /// `e1`…`e3`.
    pub environment: &'static str,
    /// GA seed.
    pub seed: u32,
    /// Agents in the scene.
    pub agents: u64,
    /// Frames per evaluation.
    pub frames: u32,
    /// The GA settings.
    pub ga: GaParams,
    /// Generations run.
    pub generations: u32,
    /// Simulations run.
    pub evaluations: u64,
    /// Wall-clock seconds (from the binary's clock).
    pub seconds: f64,
    /// Simulations per second.
    pub evaluations_per_second: f64,
    /// The best weights found with their measures.
    pub best: Evaluation,
    /// Per-generation progress.
    pub history: Vec<GenerationStats>,
}

/// One progress line for stderr.
pub fn progress_line(s: &GenerationStats, seconds: f64) -> String {
    let w = s.best.weights;
    format!(
        "gen {:>2}: best {:7.3} mean {:7.3} | best so far {:7.3} s=[{:.2} {:.2} {:.2} {:.2} {:.2}] | {} evals, {:.1} s{}",
        s.generation,
        s.best_gsum,
        s.mean_gsum,
        s.best.gsum,
        w[0],
        w[1],
        w[2],
        w[3],
        w[4],
        s.evaluations,
        seconds,
        if s.finished { " (done)" } else { "" }
    )
}

/// Tunes one pair; `log` receives one [`progress_line`] per generation.
pub fn tune_pair(
    behaviour: Behaviour,
    environment: Environment,
    seed: u32,
    budget: &Budget,
    clock: &dyn Fn() -> f64,
    log: &mut dyn FnMut(&str),
) -> Result<TuneReport, TuneError> {
    let mut task = TuneTask::new(behaviour, environment);
    task.frames = budget.frames;
    task.sample_every = budget.sample_every;
    let agents = task.scene.agent_count();
    let start = clock();
    let mut tuner = Tuner::new(task, budget.ga.clone(), seed)?;
    let best = tuner.run(|s| log(&progress_line(s, clock() - start))).ok_or(TuneError::NothingEvaluated)?;
    let seconds = clock() - start;
    let evaluations = tuner.history().last().map_or(0, |s| s.evaluations);
    Ok(TuneReport {
        behaviour: behaviour.code(),
        environment: environment.code(),
        seed,
        agents,
        frames: budget.frames,
        ga: budget.ga.clone(),
        generations: tuner.history().len() as u32,
        evaluations,
        seconds,
        evaluations_per_second: if seconds > 0.0 { evaluations as f64 / seconds } else { 0.0 },
        best,
        history: tuner.history().to_vec(),
    })
}

/// The experiment: every pair with every seed, then the cross-scene check.
#[derive(Clone, Debug, Serialize)]
pub struct TableReport {
    /// Every tuning run.
    pub runs: Vec<TuneReport>,
    /// Per behaviour: E1's best weights scored on E2 and E3 against the weights tuned there.
    pub cross: Vec<CrossCheck>,
}

/// Weights tuned on E1 applied to another environment, against the weights tuned there.
#[derive(Clone, Debug, Serialize)]
pub struct CrossCheck {
    /// `b1`…`b3`.
    pub behaviour: &'static str,
    /// `e2` or `e3`.
    pub environment: &'static str,
    /// Gsum of E1's best weights in this environment.
    pub e1_weights_gsum: f64,
    /// Gsum of this environment's own best weights.
    pub own_weights_gsum: f64,
}

fn best_run(runs: &[TuneReport], b: Behaviour, e: Environment) -> Option<&TuneReport> {
    runs.iter()
        .filter(|r| r.behaviour == b.code() && r.environment == e.code())
        .max_by(|x, y| x.best.gsum.total_cmp(&y.best.gsum))
}

/// Runs the whole table; `log` receives one [`run_row`] per finished run.
pub fn run_table(
    seeds: &[u32],
    budget: &Budget,
    clock: &dyn Fn() -> f64,
    log: &mut dyn FnMut(&str),
) -> Result<TableReport, TuneError> {
    let mut runs = Vec::new();
    // Seed-major: after the first seed every pair and the cross-scene check have a result.
    for &seed in seeds {
        for b in Behaviour::ALL {
            for e in Environment::ALL {
                let mut quiet = |_: &str| {};
                let r = tune_pair(b, e, seed, budget, clock, &mut quiet)?;
                log(&run_row(&r));
                runs.push(r);
            }
        }
    }
    runs.sort_by_key(|r| (r.behaviour, r.environment, r.seed));
    let mut cross = Vec::new();
    for b in Behaviour::ALL {
        let Some(e1) = best_run(&runs, b, Environment::Open) else { continue };
        for e in [Environment::Narrow, Environment::Cluttered] {
            let Some(own) = best_run(&runs, b, e) else { continue };
            cross.push(CrossCheck {
                behaviour: b.code(),
                environment: e.code(),
                e1_weights_gsum: score(b, e, e1.best.weights, budget).gsum,
                own_weights_gsum: own.best.gsum,
            });
        }
    }
    Ok(TableReport { runs, cross })
}

/// One run as a row of the Markdown table.
pub fn run_row(r: &TuneReport) -> String {
    let w = r.best.weights;
    let m = r.best.measures;
    format!(
        "| {}-{} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.2} | {} | {} | {:.1} |",
        r.behaviour.to_uppercase(),
        r.environment.to_uppercase(),
        r.seed,
        w[0],
        w[1],
        w[2],
        w[3],
        w[4],
        m.gm,
        m.gg,
        m.gc,
        m.ga,
        m.gd,
        r.best.gsum,
        r.generations,
        r.evaluations,
        r.seconds
    )
}

/// The table as Markdown.
pub fn markdown(report: &TableReport) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "| pair | seed | s1 sep | s2 align | s3 coh | s4 fol | s5 col | Gm | Gg | Gc | Ga | Gd | Gsum | gens | evals | s |");
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for r in &report.runs {
        let _ = writeln!(out, "{}", run_row(r));
    }
    let _ = writeln!(
        out,
        "\n| behaviour | environment | Gsum with E1's weights | Gsum with its own weights | own better |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|");
    for c in &report.cross {
        let _ = writeln!(
            out,
            "| {} | {} | {:.2} | {:.2} | {} |",
            c.behaviour.to_uppercase(),
            c.environment.to_uppercase(),
            c.e1_weights_gsum,
            c.own_weights_gsum,
            if c.own_weights_gsum > c.e1_weights_gsum { "yes" } else { "no" }
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tiny_table_has_every_pair_and_the_cross_check() {
        let budget = Budget {
            frames: 20,
            ga: GaParams { population: 4, max_generations: 1, ..GaParams::default() },
            ..Budget::default()
        };
        let mut rows = 0;
        let report = run_table(&[1], &budget, &|| 0.0, &mut |_| rows += 1).expect("runs");
        assert_eq!(rows, 9);
        assert_eq!(report.runs.len(), 9);
        assert_eq!(report.cross.len(), 6);
        let md = markdown(&report);
        assert!(md.contains("| B3-E3 | 1 |"), "{md}");
        assert_eq!(md.lines().filter(|l| l.starts_with("| B")).count(), 9 + 6);
    }
}
