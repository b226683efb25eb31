//! The command line of `flockpath bench` and of the hidden `density-scene` (the bench page's
//! scenes); the measurements themselves live in `bench.rs`.

use crate::{bench, out, usage, whole_number, CliError};
use flockpath::scene_to_json;

/// `flockpath bench`.
#[derive(clap::Args, Debug)]
#[command(
    long_about = "ns per agent-step of World::step and render time per frame\n\n\
                  Usage: taskset -c 0 flockpath bench [--quick|--smoke] [--only step|grid|planners|render|packed|metrics] [--json FILE]",
    after_help = "Scenes are presets::constant_density(N, 9.0): about 9 neighbours per agent at every N.\n\
                  Pin to one core (taskset -c 0) so the figures are comparable between runs."
)]
pub struct BenchArgs {
    /// Fewer and shorter repetitions (figures are rougher)
    #[arg(long)]
    quick: bool,
    /// One short repetition at a hundredth of every size: checks that the benchmark runs (the
    /// test command's smoke run); its figures mean nothing
    #[arg(long, conflicts_with = "quick")]
    smoke: bool,
    /// Run only the step benchmarks (grid, brute force, per planner), only the Boids grid step
    /// benchmark, only the per-planner table, only the render benchmark, only the
    /// packed-vs-spread table, or only the cost of one metrics summary against N
    #[arg(
        long,
        value_name = "step|grid|planners|render|packed|metrics",
        value_parser = ["step", "grid", "planners", "render", "packed", "metrics"]
    )]
    only: Option<String>,
    /// Also write the figures as JSON
    #[arg(long, value_name = "FILE")]
    json: Option<String>,
}

impl BenchArgs {
    /// The measurements to run.
    pub fn options(&self) -> bench::Options {
        let mut options = bench::Options {
            quick: self.quick,
            smoke: self.smoke,
            json: self.json.clone(),
            ..bench::Options::default()
        };
        if let Some(only) = self.only.as_deref() {
            let o = &mut options;
            (o.step, o.brute, o.planners, o.render, o.packed, o.metrics) = match only {
                "step" => (true, true, true, false, false, false),
                "grid" => (true, false, false, false, false, false),
                "planners" => (false, false, true, false, false, false),
                "render" => (false, false, false, true, false, false),
                "packed" => (false, false, false, false, true, false),
                // clap accepts only the listed values: this is "metrics".
                _ => (false, false, false, false, false, true),
            };
        }
        options
    }
}

/// `flockpath density-scene N [--planner NAME] | --planners`.
#[derive(clap::Args, Debug)]
pub struct DensitySceneArgs {
    /// Agents in the scene
    #[arg(value_parser = whole_number::<u32>, required_unless_present = "planners")]
    n: Option<u32>,
    /// The per-planner row's scene (heads for a central goal)
    #[arg(long, value_name = "NAME")]
    planner: Option<String>,
    /// List the per-planner rows
    #[arg(long, conflicts_with_all = ["n", "planner"])]
    planners: bool,
}

/// Prints the benchmark scene with N agents, or the per-planner row names.
pub fn density_scene(args: &DensitySceneArgs) -> Result<(), CliError> {
    let Some(n) = args.n else {
        let names: Vec<&str> = bench::planner_configs().into_iter().map(|(name, _)| name).collect();
        return out(&format!("{}\n", names.join("\n")));
    };
    if n == 0 || n > flockpath::model::scene::MAX_AGENTS {
        return Err(usage(format!("N = {n} is outside 1…{}", flockpath::model::scene::MAX_AGENTS)));
    }
    let scene = match &args.planner {
        None => bench::bench_scene(n),
        Some(name) => {
            let config = bench::planner_configs()
                .into_iter()
                .find(|(row, _)| row == name)
                .map(|(_, config)| config)
                .ok_or_else(|| usage(format!("no bench row {name:?}; see --planners")))?;
            bench::planner_scene(n, &config)
        }
    };
    out(&format!("{}\n", scene_to_json(&scene)))
}
