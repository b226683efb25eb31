//! `flockpath run`: simulate a scene (a `Run` without a timeline), report its metrics and how
//! its activity check stands (when the scene has one), write the exports asked for.

use crate::scenes::load_scene;
use crate::{failed, finite, out, usage, whole_number, write_file, CliError};
use flockpath::experiments::validation::{jupedsim, pedpy};
use flockpath::export::{self, ExportOptions};
use flockpath::sim::activity_check::{Report, Status};
use flockpath::sim::limits::{CLI_MAX_STEPS as MAX_STEPS, CLI_RECORDING_BUDGET_BYTES};
use flockpath::sim::recording::Recording;
use flockpath::sim::run::{Run, RunOptions};
use flockpath::{PlannerKind, Scene, World};

/// `flockpath run`.
#[derive(clap::Args, Debug)]
#[command(
    long_about = "Simulate a scene and report its metrics (and its activity check, if it has one)",
    after_help = "Every step is recorded up to 1 GiB (agents × steps × 16 bytes); beyond that every other\n\
                  step is dropped and a note says so on stderr."
)]
pub struct RunArgs {
    /// A scene JSON file, `-` for stdin, a URL fragment value (2.…), a #s=… fragment or a whole
    /// page URL
    #[arg(long, value_name = "SCENE")]
    scene: String,
    /// Steps to simulate (1 step = 1/60 s), at most 1000000
    #[arg(long, value_name = "N", value_parser = whole_number::<u32>, allow_negative_numbers = true)]
    steps: u32,
    /// Give every group this planner with its default parameters
    #[arg(long, value_name = "NAME", value_parser = PlannerKind::parse)]
    planner: Option<PlannerKind>,
    /// Replace the scene's seed (0…4294967295)
    #[arg(long, value_name = "S", value_parser = whole_number::<u32>, allow_negative_numbers = true)]
    seed: Option<u32>,
    /// Write the metrics JSON to FILE, or to stdout with `-`; without it a one-line summary is
    /// printed
    #[arg(long, value_name = "FILE|-")]
    metrics: Option<String>,
    /// Write the metrics over time as CSV: step,time_s,group,<series…>, a row per sample (every
    /// 5 steps, halved beyond 4096 samples) for the whole run (group `all`) and per group
    #[arg(long, value_name = "FILE")]
    metrics_history: Option<String>,
    /// Write every agent's path as CSV: agent,group,step,time,x,y,vx,vy (one row per agent per
    /// recorded step, step 0 included)
    #[arg(long, value_name = "FILE")]
    paths: Option<String>,
    /// Write the paths as JSON
    #[arg(long, value_name = "FILE")]
    paths_json: Option<String>,
    /// Write a Maya MEL script: one keyframed locator per agent (x-z plane)
    #[arg(long, value_name = "FILE")]
    maya: Option<String>,
    /// Write a Blender Python script: one keyframed empty per agent
    #[arg(long, value_name = "FILE")]
    blender: Option<String>,
    /// Write the trails as SVG
    #[arg(long, value_name = "FILE")]
    svg: Option<String>,
    /// Write the paths for PedPy (`pedpy.load_trajectory_from_txt`): `id frame x y z` in metres
    /// (at the scene's px_per_metre, default 20), with the frame rate in the header
    #[arg(long, value_name = "FILE")]
    pedpy: Option<String>,
    /// Write a Python script that runs the scene in JuPedSim 1.4.2 (collision-free speed model)
    /// from the same starts: walkable area = world minus obstacles, every goal an exit, each
    /// group's body and desired speed; it writes the trajectories in the --pedpy format
    #[arg(long, value_name = "FILE")]
    jupedsim: Option<String>,
    /// Keyframes per second of the MEL/Python exports (1…240, default 24)
    #[arg(long, value_name = "F", value_parser = finite::<f32>, allow_negative_numbers = true)]
    fps: Option<f32>,
    /// Scene px → 3-D units in the MEL/Python exports (default 0.01)
    #[arg(long, value_name = "S", value_parser = finite::<f32>, allow_negative_numbers = true)]
    scale: Option<f32>,
}

/// Makes one export file's text.
type Export = fn(&Scene, &Recording, ExportOptions) -> String;

impl RunArgs {
    /// Every export: its flag, the file asked for, and what it writes.
    fn exports(&self) -> [(&'static str, Option<&str>, Export); 7] {
        [
            ("--paths", self.paths.as_deref(), |scene, rec, _| export::paths_csv(scene, rec)),
            ("--paths-json", self.paths_json.as_deref(), |scene, rec, _| export::paths_json(scene, rec)),
            ("--maya", self.maya.as_deref(), export::maya_mel),
            ("--blender", self.blender.as_deref(), export::blender_py),
            ("--svg", self.svg.as_deref(), |scene, rec, _| export::trails_svg(scene, rec)),
            ("--pedpy", self.pedpy.as_deref(), |scene, rec, _| pedpy::recording_text(scene, rec)),
            ("--jupedsim", self.jupedsim.as_deref(), |scene, rec, _| jupedsim::recording_script(scene, rec)),
        ]
    }
}

/// Runs the scene and prints the summary or the metrics JSON.
pub fn run(args: &RunArgs) -> Result<(), CliError> {
    let steps = args.steps;
    if steps > MAX_STEPS {
        return Err(usage(format!("--steps {steps} is over the limit of {MAX_STEPS}")));
    }
    let defaults = ExportOptions::default();
    let export_options =
        ExportOptions::checked(args.fps.unwrap_or(defaults.fps), args.scale.unwrap_or(defaults.scale))
            .map_err(|m| usage(format!("--fps/--scale: {m}")))?;
    let recording_wanted = args.exports().iter().any(|(_, file, _)| file.is_some());

    let mut scene = load_scene(&args.scene)?;
    if let Some(kind) = args.planner {
        for g in &mut scene.groups {
            g.planner = kind.default_config();
        }
    }
    if let Some(seed) = args.seed {
        scene.seed = seed;
    }
    let history_file = args.metrics_history.as_deref();
    let options = RunOptions::command_line(recording_wanted, history_file.is_some());
    let mut run = Run::new(scene, options).map_err(|e| failed(format!("cannot run the scene: {e}")))?;
    run.step(steps);
    let world = run.world();
    if recording_wanted {
        write_exports(args, world, run.recording(), export_options)?;
    }
    if let Some(file) = history_file {
        let names: Vec<String> = world.scene().groups.iter().map(|g| g.name.clone()).collect();
        write_file("metrics history file", file, &run.metric_series().to_csv(&names))?;
    }
    let metrics = world.metrics();
    let json = serde_json::to_string_pretty(&metrics)
        .map_err(|e| failed(format!("cannot write the metrics: {e}")))?;
    let activity = run.activity_report().map(|report| activity_line(&report)).unwrap_or_default();
    match args.metrics.as_deref() {
        Some("-") => {
            // stdout holds the JSON alone: the check goes to stderr.
            if !activity.is_empty() {
                eprint!("flockpath: {activity}");
            }
            out(&format!("{json}\n"))
        }
        Some(file) => {
            write_file("metrics file", file, &format!("{json}\n"))?;
            out(&format!("{}{activity}", summary(world)))
        }
        None => out(&format!("{}{activity}", summary(world))),
    }
}

/// The line that follows the summary for a scene with an activity check: how the check stands
/// at the last step (decided at which step, or not yet) and how many conditions hold there.
fn activity_line(report: &Report) -> String {
    let holding = report.conditions.iter().filter(|c| c.holds).count();
    let stands = match report.status {
        Status::Met => format!("met at step {}", report.step),
        Status::Missed => format!("missed at step {}", report.step),
        Status::Running => format!("not decided by step {}", report.step),
        Status::Unavailable => {
            return "activity: not checked here (a condition names a pane of the compare page)\n".into()
        }
    };
    format!(
        "activity: {stands} (limit {}), {holding} of {} conditions hold\n",
        report.limit,
        report.conditions.len()
    )
}

/// Writes each export file asked for; a thinned recording is reported on stderr.
fn write_exports(
    args: &RunArgs,
    world: &World,
    recording: &Recording,
    options: ExportOptions,
) -> Result<(), CliError> {
    let scene = world.scene();
    if recording.thinned() > 0 {
        eprintln!(
            "flockpath: note: the recording outgrew its {} GiB budget and keeps every {}th step",
            CLI_RECORDING_BUDGET_BYTES >> 30,
            recording.every()
        );
    }
    for (flag, file, make) in args.exports() {
        if let Some(file) = file {
            write_file(&format!("{flag} file"), file, &make(scene, recording, options))?;
        }
    }
    Ok(())
}

fn summary(world: &World) -> String {
    let m = world.metrics();
    let o = &m.overall;
    format!(
        "{}: {} agents, {} steps, arrived {:.1}%, collisions {}, penetrations {}, stuck {}, digest {:016x}\n",
        if world.scene().name.is_empty() { "scene" } else { &world.scene().name },
        o.agents,
        m.steps,
        100.0 * o.arrived_share,
        o.collisions_agent_agent,
        o.penetrations_agent_obstacle,
        o.stuck_agents,
        world.digest()
    )
}
