//! `flockpath tune`: argument parsing, progress lines, the JSON report and the paper's experiment
//! table (9 behaviour × environment pairs × seeds, and the cross-scene check).
//!
//! The core has no clock: the binary passes one in, used only for the evaluations-per-second figure.

use crate::fitness::{Behaviour, Environment};
use crate::tune::{Evaluation, GaParams, GenerationStats, TuneTask, Tuner};
use serde::Serialize;
use std::fmt::Write as _;

/// Usage text of `flockpath tune`.
pub const USAGE: &str = "usage: flockpath tune --behaviour b1|b2|b3 --environment e1|e2|e3 --seed S \
[--generations G] [--population P] [--frames F] [--sample-every K] [--json FILE]\n       \
flockpath tune --behaviour b1|b2|b3 --environment e1|e2|e3 --score s1,s2,s3,s4,s5\n       \
flockpath tune --table [--seeds 1,2,3] [--generations G] [--population P] [--frames F] \
[--markdown FILE] [--json FILE]";

/// Parsed `tune` arguments.
#[derive(Clone, Debug, PartialEq)]
pub struct TuneArgs {
    /// Behaviour to tune for (single run).
    pub behaviour: Behaviour,
    /// Environment to tune in (single run).
    pub environment: Environment,
    /// Seed of the genetic algorithm (single run).
    pub seed: u32,
    /// Seeds per pair (table).
    pub seeds: Vec<u32>,
    /// Run the whole experiment table instead of one pair.
    pub table: bool,
    /// Genetic-algorithm settings.
    pub ga: GaParams,
    /// Frames per evaluation.
    pub frames: u32,
    /// Measure every this many frames.
    pub sample_every: u32,
    /// Where to write the JSON report (`-` for stdout).
    pub json: Option<String>,
    /// Where to write the Markdown table (table mode).
    pub markdown: Option<String>,
    /// Only score these weights `[s1…s5]` on the pair (no tuning).
    pub score: Option<[f32; 5]>,
}

fn number<T: std::str::FromStr>(flag: &str, value: Option<&String>) -> Result<T, String> {
    let value = value.ok_or_else(|| format!("{flag} needs a value"))?;
    value.parse().map_err(|_| format!("{flag}: {value:?} is not a valid number"))
}

/// Parses the arguments after `tune`.
pub fn parse(args: &[String]) -> Result<TuneArgs, String> {
    let mut behaviour = None;
    let mut environment = None;
    let mut seed = None;
    let mut parsed = TuneArgs {
        behaviour: Behaviour::GroupMoving,
        environment: Environment::Open,
        seed: 1,
        seeds: vec![1, 2, 3],
        table: false,
        ga: GaParams::default(),
        frames: crate::tune::DEFAULT_FRAMES,
        sample_every: crate::tune::DEFAULT_SAMPLE_EVERY,
        json: None,
        markdown: None,
        score: None,
    };
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        match flag.as_str() {
            "--behaviour" | "--behavior" => {
                let v = it.next().ok_or("--behaviour needs b1, b2 or b3")?;
                behaviour = Some(
                    Behaviour::from_code(v)
                        .ok_or_else(|| format!("unknown behaviour {v:?}: use b1, b2 or b3"))?,
                );
            }
            "--environment" => {
                let v = it.next().ok_or("--environment needs e1, e2 or e3")?;
                environment = Some(
                    Environment::from_code(v)
                        .ok_or_else(|| format!("unknown environment {v:?}: use e1, e2 or e3"))?,
                );
            }
            "--seed" => seed = Some(number(flag, it.next())?),
            "--seeds" => {
                let v = it.next().ok_or("--seeds needs a list such as 1,2,3")?;
                parsed.seeds = v
                    .split(',')
                    .map(|s| s.trim().parse().map_err(|_| format!("--seeds: {s:?} is not a seed")))
                    .collect::<Result<_, _>>()?;
            }
            "--generations" => parsed.ga.max_generations = number(flag, it.next())?,
            "--population" => parsed.ga.population = number(flag, it.next())?,
            "--frames" => parsed.frames = number(flag, it.next())?,
            "--sample-every" => parsed.sample_every = number(flag, it.next())?,
            "--json" => parsed.json = Some(it.next().ok_or("--json needs a file name or -")?.clone()),
            "--markdown" => parsed.markdown = Some(it.next().ok_or("--markdown needs a file name")?.clone()),
            "--table" => parsed.table = true,
            "--score" => {
                let v = it.next().ok_or("--score needs five weights such as 0.4,0.1,0.2,0.8,0.4")?;
                let w: Vec<f32> = v
                    .split(',')
                    .map(|x| x.trim().parse::<f32>().ok().filter(|w| (0.0..=1.0).contains(w)))
                    .collect::<Option<_>>()
                    .ok_or_else(|| format!("--score: {v:?} is not five weights in 0…1"))?;
                parsed.score = Some(w.try_into().map_err(|_| format!("--score: {v:?} is not five weights"))?);
            }
            other => return Err(format!("unknown option {other:?}\n{USAGE}")),
        }
    }
    if parsed.frames == 0 || parsed.frames > 100_000 {
        return Err(format!("--frames {} is outside 1…100000", parsed.frames));
    }
    if parsed.ga.max_generations == 0 {
        return Err("--generations must be at least 1".into());
    }
    if !parsed.table {
        parsed.behaviour = behaviour.ok_or_else(|| format!("missing --behaviour\n{USAGE}"))?;
        parsed.environment = environment.ok_or_else(|| format!("missing --environment\n{USAGE}"))?;
        parsed.seed = match (seed, parsed.score) {
            (Some(seed), _) => seed,
            (None, Some(_)) => 1,
            (None, None) => return Err(format!("missing --seed\n{USAGE}")),
        };
    } else if parsed.seeds.is_empty() {
        return Err("--seeds needs at least one seed".into());
    }
    Ok(parsed)
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

/// Tunes one pair, printing progress to stderr.
pub fn tune_pair(
    behaviour: Behaviour,
    environment: Environment,
    seed: u32,
    args: &TuneArgs,
    clock: &dyn Fn() -> f64,
    log: &mut dyn FnMut(&str),
) -> Result<TuneReport, String> {
    let mut task = TuneTask::new(behaviour, environment);
    task.frames = args.frames;
    task.sample_every = args.sample_every;
    let agents = task.scene.agent_count();
    let start = clock();
    let mut tuner = Tuner::new(task, args.ga.clone(), seed).map_err(|e| e.to_string())?;
    let best = tuner.run(|s| log(&progress_line(s, clock() - start))).ok_or("the run evaluated nothing")?;
    let seconds = clock() - start;
    let evaluations = tuner.history().last().map_or(0, |s| s.evaluations);
    Ok(TuneReport {
        behaviour: behaviour.code(),
        environment: environment.code(),
        seed,
        agents,
        frames: args.frames,
        ga: args.ga.clone(),
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

/// Runs the whole table.
pub fn run_table(
    args: &TuneArgs,
    clock: &dyn Fn() -> f64,
    log: &mut dyn FnMut(&str),
) -> Result<TableReport, String> {
    let mut runs = Vec::new();
    // Seed-major: after the first seed every pair and the cross-scene check have a result.
    for &seed in &args.seeds {
        for b in Behaviour::ALL {
            for e in Environment::ALL {
                let mut quiet = |_: &str| {};
                let r = tune_pair(b, e, seed, args, clock, &mut quiet)?;
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
            let mut task = TuneTask::new(b, e);
            task.frames = args.frames;
            task.sample_every = args.sample_every;
            cross.push(CrossCheck {
                behaviour: b.code(),
                environment: e.code(),
                e1_weights_gsum: task.evaluate(e1.best.weights).gsum,
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

fn write_output(path: &str, text: &str) -> Result<(), String> {
    if path == "-" {
        println!("{text}");
        Ok(())
    } else {
        std::fs::write(path, text).map_err(|e| format!("cannot write {path}: {e}"))
    }
}

/// Runs `flockpath tune ARGS` and returns the exit code: 0, 2 for a usage mistake, 1 for a
/// failure. `clock` gives seconds (the core has no clock of its own).
pub fn main(args: &[String], clock: &dyn Fn() -> f64) -> u8 {
    if args.iter().any(|a| a == "-h" || a == "--help") {
        println!("{USAGE}");
        return 0;
    }
    let args = match parse(args) {
        Ok(a) => a,
        Err(message) => {
            eprintln!("flockpath tune: {message}");
            return 2;
        }
    };
    match run(&args, clock) {
        Ok(()) => 0,
        Err(message) => {
            eprintln!("flockpath tune: {message}");
            1
        }
    }
}

fn run(args: &TuneArgs, clock: &dyn Fn() -> f64) -> Result<(), String> {
    let mut log = |line: &str| eprintln!("{line}");
    if args.table {
        let report = run_table(args, clock, &mut log)?;
        let table = markdown(&report);
        match &args.markdown {
            Some(path) => write_output(path, &table)?,
            None => println!("{table}"),
        }
        if let Some(path) = &args.json {
            write_output(path, &serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?)?;
        }
        return Ok(());
    }
    if let Some(weights) = args.score {
        let mut task = TuneTask::new(args.behaviour, args.environment);
        task.frames = args.frames;
        task.sample_every = args.sample_every;
        let e = task.evaluate(weights);
        println!("{}", serde_json::json!({ "weights": e.weights, "gsum": e.gsum, "measures": e.measures }));
        return Ok(());
    }
    let report = tune_pair(args.behaviour, args.environment, args.seed, args, clock, &mut log)?;
    eprintln!(
        "{} agents × {} frames per evaluation: {} evaluations in {:.1} s = {:.1} evaluations/s ({} threads)",
        report.agents,
        report.frames,
        report.evaluations,
        report.seconds,
        report.evaluations_per_second,
        rayon_threads()
    );
    let summary = serde_json::json!({
        "behaviour": report.behaviour,
        "environment": report.environment,
        "seed": report.seed,
        "weights": report.best.weights,
        "gsum": report.best.gsum,
        "measures": report.best.measures,
        "generations": report.generations,
        "evaluations": report.evaluations,
    });
    println!("{summary}");
    if let Some(path) = &args.json {
        write_output(path, &serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?)?;
    }
    Ok(())
}

#[cfg(not(target_arch = "wasm32"))]
fn rayon_threads() -> usize {
    rayon::current_num_threads()
}

#[cfg(target_arch = "wasm32")]
fn rayon_threads() -> usize {
    1
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strings(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn arguments_parse_and_errors_name_the_problem() {
        let a = parse(&strings("--behaviour b2 --environment E3 --seed 7 --generations 4")).expect("ok");
        assert_eq!((a.behaviour, a.environment, a.seed), (Behaviour::Following, Environment::Cluttered, 7));
        assert_eq!(a.ga.max_generations, 4);
        assert_eq!(a.ga.population, 200);
        assert!(parse(&strings("--behaviour b4 --environment e1 --seed 1")).expect_err("b4").contains("b4"));
        assert!(parse(&strings("--behaviour b1 --environment e1")).expect_err("seed").contains("--seed"));
        assert!(parse(&strings("--behaviour b1 --environment e1 --seed x"))
            .expect_err("x")
            .contains("\"x\""));
        assert!(parse(&strings("--frobnicate")).expect_err("flag").contains("--frobnicate"));
        let s = parse(&strings("--behaviour b1 --environment e2 --seed 1 --score 0.1,0.2,0.3,0.4,1"))
            .expect("ok");
        assert_eq!(s.score, Some([0.1, 0.2, 0.3, 0.4, 1.0]));
        assert!(parse(&strings("--behaviour b1 --environment e2 --seed 1 --score 0.1,0.2")).is_err());
        assert!(
            parse(&strings("--behaviour b1 --environment e2 --seed 1 --score 0.1,0.2,0.3,0.4,2")).is_err()
        );
        let t = parse(&strings("--table --seeds 4,5")).expect("table");
        assert!(t.table);
        assert_eq!(t.seeds, vec![4, 5]);
    }

    #[test]
    fn a_tiny_table_has_every_pair_and_the_cross_check() {
        let args = TuneArgs {
            frames: 20,
            seeds: vec![1],
            ga: GaParams { population: 4, max_generations: 1, ..GaParams::default() },
            ..parse(&strings("--table")).expect("table")
        };
        let report = run_table(&args, &|| 0.0, &mut |_| {}).expect("runs");
        assert_eq!(report.runs.len(), 9);
        assert_eq!(report.cross.len(), 6);
        let md = markdown(&report);
        assert!(md.contains("| B3-E3 | 1 |"), "{md}");
        assert_eq!(md.lines().filter(|l| l.starts_with("| B")).count(), 9 + 6);
    }
}
