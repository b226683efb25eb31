//! `flockpath optimize`: the optimizer experiments of `flockpath::experiments::tables` with their
//! files, their text on stdout and a progress bar.

use crate::progress::Progress;
use crate::{in_range, out, usage, write_file, CliError};
use flockpath::experiments::tables::{self, Table};
use flockpath::optim::functions::Function;
use flockpath::optim::{Algorithm, UnknownName};
use flockpath::planners::igsa::path::{compare_paths, path_table_text, PathParams};
use flockpath::sim::limits::{CLI_LAB_DIMENSION, CLI_LAB_ITERATIONS, CLI_LAB_POPULATION};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// `flockpath optimize`.
#[derive(clap::Args, Debug)]
#[command(
    long_about = "Run swarm optimizers on benchmark functions (Liu & Liu 2022, Table 3)",
    after_help = "Runs use every core natively; results do not depend on the number of threads.",
    args_override_self = true
)]
pub struct OptimizeArgs {
    /// Comma-separated: gsa,igsa,pso,firefly,ga or `all` (default all)
    #[arg(long, value_name = "LIST")]
    algorithms: Option<String>,
    /// Comma-separated: sphere,ackley,griewank,rastrigin,rastrigin-5.12, rosenbrock, `paper` (the
    /// first four, default) or `all`
    #[arg(long, value_name = "LIST")]
    functions: Option<String>,
    /// Dimension (default 30)
    #[arg(long, value_name = "D", value_parser = in_range(1usize, CLI_LAB_DIMENSION))]
    dim: Option<usize>,
    /// Population size (default 50)
    #[arg(long, value_name = "N", value_parser = in_range(2usize, CLI_LAB_POPULATION))]
    pop: Option<usize>,
    /// Iterations per run (default 1000)
    #[arg(long, value_name = "T", value_parser = in_range(1u32, CLI_LAB_ITERATIONS))]
    iters: Option<u32>,
    /// Independent runs per algorithm and function (default 30)
    #[arg(long, value_name = "R", value_parser = in_range(1u32, 100_000))]
    runs: Option<u32>,
    /// Master seed; run r draws from stream r of it (default 1)
    #[arg(long, value_name = "S", value_parser = in_range(0u32, u32::MAX))]
    seed: Option<u32>,
    /// Override G0 of GSA and IGSA: a finite number in 0…1e12 (defaults GSA 100, IGSA 1)
    #[arg(long, value_name = "X", value_parser = in_range(0.0f64, 1e12))]
    g0: Option<f64>,
    /// Override α of GSA and IGSA: a finite number in 0…1e6 (defaults GSA 20, IGSA 30)
    #[arg(long, value_name = "X", value_parser = in_range(0.0f64, 1e6))]
    alpha: Option<f64>,
    /// Write one record per algorithm and function: {algorithm, function, dim, runs, best,
    /// worst, mean, median, seconds, ...}
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Convergence curves as CSV (algorithm,function,run,iteration,best): PATH ending in .csv is
    /// one file, otherwise a directory of one file per function
    #[arg(long, value_name = "PATH")]
    curves: Option<PathBuf>,
    /// Time the O(N²) GSA force step at N = 50 and 1000 (d = 30) and exit
    #[arg(long)]
    bench_force: bool,
    /// IGSA group path control, the paper's Table 4: the igsa-crowd scene with 100, 500 and 1000
    /// agents, path planned by IGSA and by GSA (planning time, path length, speed near the
    /// obstacle, collisions); --steps N sets the run length (default 6000)
    #[arg(long)]
    table4: bool,
    /// Steps of each --table4 run (default 6000)
    #[arg(long, value_name = "N", value_parser = in_range(1u32, 1_000_000))]
    steps: Option<u32>,
    /// Plan the igsa-path-1 and igsa-path-2 scenes with the chosen algorithms for seeds 0..R and
    /// print length / deflection / turning (e.g. --paths --algorithms gsa,igsa --runs 20 --iters
    /// 500)
    #[arg(long)]
    paths: bool,
}

/// Names from a comma-separated list, with group names (`all`, `paper`) expanded.
fn list<T: Copy>(
    flag: &str,
    value: &str,
    lookup: fn(&str) -> Result<T, UnknownName>,
    groups: &[(&str, &[T])],
) -> Result<Vec<T>, CliError> {
    let mut out = Vec::new();
    for name in value.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        if let Some((_, all)) = groups.iter().find(|(g, _)| *g == name) {
            out.extend_from_slice(all);
        } else {
            let groups: Vec<&str> = groups.iter().map(|(g, _)| *g).collect();
            out.push(lookup(name).map_err(|e| usage(format!("{flag}: {e}, or {}", groups.join(", "))))?);
        }
    }
    if out.is_empty() {
        return Err(usage(format!("{flag} needs at least one name")));
    }
    Ok(out)
}

impl OptimizeArgs {
    /// The library's options: the defaults of [`tables::OptimizeArgs`] with the flags given.
    fn settings(&self) -> Result<tables::OptimizeArgs, CliError> {
        let mut a = tables::OptimizeArgs::default();
        if let Some(value) = &self.algorithms {
            a.algorithms = list("--algorithms", value, Algorithm::parse, &[("all", Algorithm::ALL)])?;
        }
        if let Some(value) = &self.functions {
            let groups: &[(&str, &[Function])] = &[("all", Function::ALL), ("paper", Function::PAPER)];
            a.functions = list("--functions", value, Function::parse, groups)?;
        }
        a.dim = self.dim.unwrap_or(a.dim);
        a.settings.population = self.pop.unwrap_or(a.settings.population);
        a.settings.iterations = self.iters.unwrap_or(a.settings.iterations);
        a.runs = self.runs.unwrap_or(a.runs);
        a.seed = self.seed.unwrap_or(a.seed);
        a.settings.g0 = self.g0.or(a.settings.g0);
        a.settings.alpha = self.alpha.or(a.settings.alpha);
        a.json.clone_from(&self.json);
        a.curves.clone_from(&self.curves);
        a.bench_force = self.bench_force;
        a.paths = self.paths;
        a.table4 = self.table4;
        a.steps = self.steps.unwrap_or(a.steps);
        Ok(a)
    }
}

/// Runs the experiment asked for, writes its files and prints its text.
pub fn optimize(args: &OptimizeArgs) -> Result<(), CliError> {
    let parsed = args.settings()?;
    let start = std::time::Instant::now();
    let clock = move || start.elapsed().as_secs_f64();
    let text = if parsed.bench_force {
        tables::bench_force(&clock)
    } else if parsed.table4 {
        let progress = Progress::new(6, "runs");
        tables::table4(&[100, 500, 1000], parsed.steps, &clock, &mut |done, total| progress.set(done, total))
    } else if parsed.paths {
        paths(&parsed, &clock)?
    } else {
        table(&parsed, &clock)?
    };
    out(&text)
}

/// `--paths`: GSA against IGSA as group path planners on the two path scenes.
fn paths(parsed: &tables::OptimizeArgs, clock: &dyn Fn() -> f64) -> Result<String, CliError> {
    let scenes = [flockpath::model::presets::igsa_path_1(), flockpath::model::presets::igsa_path_2()];
    let start = clock();
    let progress = Progress::new(0, "plans");
    let rows = compare_paths(
        &scenes,
        &parsed.algorithms,
        parsed.runs,
        &parsed.settings,
        &PathParams::default(),
        &mut |done, total| progress.set(done, total),
    );
    drop(progress);
    let mut text = format!(
        "N = {}, T = {}, {} seeds per planner and scene\n",
        parsed.settings.population, parsed.settings.iterations, parsed.runs
    );
    text.push_str(&path_table_text(&rows));
    let _ = writeln!(text, "wall time {:.1} s on {} threads", clock() - start, tables::threads());
    if let Some(path) = &parsed.json {
        let json = serde_json::to_string_pretty(&rows)
            .map_err(|e| crate::failed(format!("cannot write the JSON report: {e}")))?;
        write_file("--json file", path, &(json + "\n"))?;
    }
    Ok(text)
}

/// The Table-3-style experiment with its JSON records and curves.
fn table(parsed: &tables::OptimizeArgs, clock: &(dyn Fn() -> f64 + Sync)) -> Result<String, CliError> {
    let start = clock();
    let progress = Progress::new(0, "runs");
    let table = tables::run_optimize(parsed, clock, &mut |done, total| progress.set(done, total))
        .map_err(crate::failed)?;
    drop(progress);
    let wall = clock() - start;
    if let Some(path) = &parsed.json {
        write_file("--json file", path, &(table.to_json() + "\n"))?;
    }
    if let Some(path) = &parsed.curves {
        write_curves(&table, path)?;
    }
    let mut text = table.to_text();
    let _ = writeln!(text, "wall time {wall:.1} s on {} threads", tables::threads());
    Ok(text)
}

/// Writes the curves to `path`: one file if it ends in `.csv`, otherwise a directory with
/// `curves-<function>.csv` per function.
fn write_curves(table: &Table, path: &Path) -> Result<(), CliError> {
    if path.extension().is_some_and(|e| e == "csv") {
        return write_file("--curves file", path, &table.curves_csv(None));
    }
    std::fs::create_dir_all(path)
        .map_err(|e| crate::failed(format!("cannot write --curves directory {path:?}: {e}")))?;
    for f in &table.args.functions {
        write_file(
            "--curves file",
            path.join(format!("curves-{}.csv", f.name())),
            &table.curves_csv(Some(f.name())),
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::cli::Cli;
    use clap::Parser as _;

    fn parse(args: &[&str]) -> Result<flockpath::experiments::tables::OptimizeArgs, String> {
        let cli =
            Cli::try_parse_from(["flockpath", "optimize"].iter().chain(args)).map_err(|e| e.to_string())?;
        match cli.command {
            crate::cli::Command::Optimize(args) => args.settings().map_err(|e| e.to_string()),
            other => Err(format!("parsed as {other:?}")),
        }
    }

    #[test]
    fn parses_lists_groups_and_numbers() {
        use flockpath::optim::{functions::Function, Algorithm};
        let a = parse(&["--algorithms", "gsa,pso", "--functions=all", "--dim", "10", "--runs=3"])
            .expect("parses");
        assert_eq!(a.algorithms, vec![Algorithm::Gsa, Algorithm::Pso]);
        assert_eq!(a.functions, Function::ALL.to_vec());
        assert_eq!((a.dim, a.runs), (10, 3));
        assert_eq!(parse(&["--runs", "3", "--runs", "4"]).expect("the last one wins").runs, 4);
        assert!(parse(&["--algorithms", "nope"]).expect_err("nope").contains("nope"));
        assert!(parse(&["--dim", "0"]).expect_err("0").contains("--dim"));
        assert!(parse(&["--dim"]).expect_err("no value").contains("--dim"));
        assert!(parse(&["--what", "1"]).expect_err("unknown").contains("--what"));
    }
}
