//! `flockpath tune`: GA-tuned force weights for one behaviour × environment pair, a score of
//! given weights, or the paper's whole experiment table (`flockpath::tune::experiment`).

use crate::progress::Progress;
use crate::{failed, out, usage, write_file, CliError};
use flockpath::model::forces_cases::{Behaviour, Environment};
use flockpath::tune::experiment::{self, Budget};

/// `flockpath tune`.
#[derive(clap::Args, Debug)]
#[command(
    long_about = "Tune the five virtual-force weights with the genetic algorithm (docs/forces.md)",
    override_usage = "flockpath tune --behaviour b1|b2|b3 --environment e1|e2|e3 --seed S \
                      [--generations G] [--population P] [--frames F] [--sample-every K] [--json FILE]\n       \
                      flockpath tune --behaviour b1|b2|b3 --environment e1|e2|e3 --score s1,s2,s3,s4,s5\n       \
                      flockpath tune --table [--seeds 1,2,3] [--generations G] [--population P] [--frames F] \
                      [--markdown FILE] [--json FILE]",
    after_help = "One run prints a JSON summary on stdout and one progress line per generation on stderr;\n\
                  --table prints one line per finished run on stderr and the Markdown table on stdout.",
    args_override_self = true
)]
pub struct TuneArgs {
    /// Behaviour to tune for: b1 (group moving), b2 (following) or b3 (guarding)
    #[arg(long, alias = "behavior", value_name = "b1|b2|b3", value_parser = Behaviour::parse)]
    behaviour: Option<Behaviour>,
    /// Environment to tune in: e1 (open), e2 (narrow) or e3 (cluttered)
    #[arg(long, value_name = "e1|e2|e3", value_parser = Environment::parse)]
    environment: Option<Environment>,
    /// Seed of the genetic algorithm (one run)
    #[arg(long, value_name = "S", value_parser = crate::whole_number::<u32>)]
    seed: Option<u32>,
    /// Seeds per pair of the table (default 1,2,3)
    #[arg(long, value_name = "LIST", value_parser = seeds)]
    seeds: Option<Seeds>,
    /// Generations at most (default 30)
    #[arg(long, value_name = "G", value_parser = crate::whole_number::<u32>)]
    generations: Option<u32>,
    /// Chromosomes per generation (default 200)
    #[arg(long, value_name = "P", value_parser = crate::whole_number::<u32>)]
    population: Option<u32>,
    /// Frames simulated per evaluation (1…100000, default 400)
    #[arg(long, value_name = "F", value_parser = crate::in_range(1u32, 100_000))]
    frames: Option<u32>,
    /// Measure every K frames (1…F, at most --frames; default 1)
    #[arg(long, value_name = "K", value_parser = crate::whole_number::<u32>)]
    sample_every: Option<u32>,
    /// Write the JSON report to FILE, or to stdout with `-`
    #[arg(long, value_name = "FILE|-")]
    json: Option<String>,
    /// Write the Markdown table to FILE, or to stdout with `-` (--table)
    #[arg(long, value_name = "FILE|-")]
    markdown: Option<String>,
    /// Run the whole experiment: every pair with every seed, then the cross-scene check
    #[arg(long)]
    table: bool,
    /// Only score these five weights in 0…1 on the pair (no tuning)
    #[arg(long, value_name = "s1,s2,s3,s4,s5", value_parser = weights)]
    score: Option<[f32; 5]>,
}

/// A list of seeds (a newtype so clap takes it as one value).
#[derive(Clone, Debug)]
struct Seeds(Vec<u32>);

fn seeds(list: &str) -> Result<Seeds, String> {
    let seeds = list
        .split(',')
        .map(|s| s.trim().parse().map_err(|_| format!("{s:?} is not a seed")))
        .collect::<Result<Vec<u32>, _>>()?;
    Ok(Seeds(seeds))
}

fn weights(list: &str) -> Result<[f32; 5], String> {
    let w: Vec<f32> = list
        .split(',')
        .map(|x| x.trim().parse::<f32>().ok().filter(|w| (0.0..=1.0).contains(w)))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("{list:?} is not five weights in 0…1"))?;
    w.try_into().map_err(|_| format!("{list:?} is not five weights"))
}

/// What to do, once the flags are checked together.
#[derive(Debug)]
enum Task {
    Table { seeds: Vec<u32> },
    Score { behaviour: Behaviour, environment: Environment, weights: [f32; 5] },
    Tune { behaviour: Behaviour, environment: Environment, seed: u32 },
}

impl TuneArgs {
    fn budget(&self) -> Result<Budget, CliError> {
        let mut budget = Budget::default();
        budget.ga.max_generations = self.generations.unwrap_or(budget.ga.max_generations);
        budget.ga.population = self.population.unwrap_or(budget.ga.population);
        budget.frames = self.frames.unwrap_or(budget.frames);
        budget.sample_every = self.sample_every.unwrap_or(budget.sample_every);
        if budget.ga.max_generations == 0 {
            return Err(usage("--generations must be at least 1"));
        }
        // A measure every K frames of the F an evaluation runs: K = 0 or K > F takes no sample,
        // and the GA would rank chromosomes that all score 0.
        if !(1..=budget.frames).contains(&budget.sample_every) {
            return Err(usage(format!(
                "--sample-every {} is outside 1…{} (at most --frames, the {} frames of an evaluation)",
                budget.sample_every, budget.frames, budget.frames
            )));
        }
        Ok(budget)
    }

    fn task(&self) -> Result<Task, CliError> {
        if self.table {
            let seeds = self.seeds.as_ref().map_or_else(|| vec![1, 2, 3], |s| s.0.clone());
            if seeds.is_empty() {
                return Err(usage("--seeds needs at least one seed"));
            }
            return Ok(Task::Table { seeds });
        }
        let behaviour = self.behaviour.ok_or_else(|| usage("tune: missing --behaviour (or --table)"))?;
        let environment =
            self.environment.ok_or_else(|| usage("tune: missing --environment (or --table)"))?;
        match (self.score, self.seed) {
            (Some(weights), _) => Ok(Task::Score { behaviour, environment, weights }),
            (None, Some(seed)) => Ok(Task::Tune { behaviour, environment, seed }),
            (None, None) => Err(usage("tune: missing --seed (or --score, or --table)")),
        }
    }
}

/// Writes `text` to `path`, or to stdout (with a newline) for `-`.
fn write_output(what: &str, path: &str, text: &str) -> Result<(), CliError> {
    if path == "-" {
        out(&format!("{text}\n"))
    } else {
        write_file(what, path, text)
    }
}

fn json(value: &impl serde::Serialize) -> Result<String, CliError> {
    serde_json::to_string_pretty(value).map_err(|e| failed(format!("cannot write the JSON report: {e}")))
}

/// Runs the task the flags ask for.
pub fn tune(args: &TuneArgs) -> Result<(), CliError> {
    let budget = args.budget()?;
    let start = std::time::Instant::now();
    let clock = move || start.elapsed().as_secs_f64();
    match args.task()? {
        Task::Table { seeds } => {
            let progress = Progress::new(seeds.len() * Behaviour::ALL.len() * Environment::ALL.len(), "runs");
            let report = experiment::run_table(&seeds, &budget, &clock, &mut |row| {
                progress.line(row);
                progress.inc();
            })
            .map_err(failed)?;
            drop(progress);
            let table = experiment::markdown(&report);
            match &args.markdown {
                Some(path) => write_output("--markdown file", path, &table)?,
                None => out(&format!("{table}\n"))?,
            }
            if let Some(path) = &args.json {
                write_output("--json file", path, &json(&report)?)?;
            }
        }
        Task::Score { behaviour, environment, weights } => {
            let e = experiment::score(behaviour, environment, weights, &budget);
            let summary = serde_json::json!({ "weights": e.weights, "gsum": e.gsum, "measures": e.measures });
            out(&format!("{summary}\n"))?;
        }
        Task::Tune { behaviour, environment, seed } => {
            let progress = Progress::new(budget.ga.max_generations as usize, "generations");
            let report = experiment::tune_pair(behaviour, environment, seed, &budget, &clock, &mut |line| {
                progress.line(line);
                progress.inc();
            })
            .map_err(failed)?;
            drop(progress);
            eprintln!(
                "{} agents × {} frames per evaluation: {} evaluations in {:.1} s = {:.1} evaluations/s ({} threads)",
                report.agents,
                report.frames,
                report.evaluations,
                report.seconds,
                report.evaluations_per_second,
                flockpath::experiments::tables::threads()
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
            out(&format!("{summary}\n"))?;
            if let Some(path) = &args.json {
                write_output("--json file", path, &json(&report)?)?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::cli::{Cli, Command};
    use clap::Parser as _;
    use flockpath::model::forces_cases::{Behaviour, Environment};

    fn parse(args: &str) -> Result<(super::Task, super::Budget), String> {
        let argv = ["flockpath", "tune"].into_iter().chain(args.split_whitespace());
        let cli = Cli::try_parse_from(argv).map_err(|e| e.to_string())?;
        let Command::Tune(tune) = cli.command else { return Err("not tune".into()) };
        Ok((tune.task().map_err(|e| e.to_string())?, tune.budget().map_err(|e| e.to_string())?))
    }

    #[test]
    fn arguments_parse_and_errors_name_the_problem() {
        let Ok((super::Task::Tune { behaviour, environment, seed }, budget)) =
            parse("--behaviour b2 --environment E3 --seed 7 --generations 4")
        else {
            panic!("a tuning run");
        };
        assert_eq!((behaviour, environment, seed), (Behaviour::Following, Environment::Cluttered, 7));
        assert_eq!((budget.ga.max_generations, budget.ga.population), (4, 200));
        assert!(parse("--behaviour b4 --environment e1 --seed 1").expect_err("b4").contains("b4"));
        assert!(parse("--behaviour b1 --environment e1").expect_err("seed").contains("--seed"));
        assert!(parse("--behaviour b1 --environment e1 --seed x").expect_err("x").contains("'x'"));
        assert!(parse("--frobnicate").expect_err("flag").contains("--frobnicate"));
        assert!(parse("--table --frames 0").expect_err("frames").contains("--frames"));
        assert!(parse("--table --generations 0").expect_err("generations").contains("--generations"));
        // A sample interval of 0 or beyond the frames would measure nothing (all-zero fitness).
        for (flags, range) in [
            ("--sample-every 0", "1…400"),
            ("--sample-every 1000000", "1…400"),
            ("--frames 50 --sample-every 51", "1…50"),
        ] {
            let e = parse(&format!("--behaviour b1 --environment e1 --seed 1 {flags}")).expect_err(flags);
            assert!(e.contains("--sample-every") && e.contains(range), "{flags}: {e}");
        }
        assert!(parse("--behaviour b1 --environment e1 --seed 1 --frames 50 --sample-every 50").is_ok());
        let Ok((super::Task::Score { weights, .. }, _)) =
            parse("--behavior b1 --environment e2 --score 0.1,0.2,0.3,0.4,1")
        else {
            panic!("a score");
        };
        assert_eq!(weights, [0.1, 0.2, 0.3, 0.4, 1.0]);
        assert!(parse("--behaviour b1 --environment e2 --score 0.1,0.2").is_err());
        assert!(parse("--behaviour b1 --environment e2 --score 0.1,0.2,0.3,0.4,2").is_err());
        let Ok((super::Task::Table { seeds }, _)) = parse("--table --seeds 4,5") else { panic!("a table") };
        assert_eq!(seeds, vec![4, 5]);
    }
}
