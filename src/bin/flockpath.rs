//! The flockpath command line: presets, batch runs with metrics, scene ↔ URL strings, benchmarks.
//!
//! A stable contract (DESIGN §5): output formats and flag names are scripted against. Every error
//! goes to stderr as one line naming the problem, with exit code 2 for a usage mistake and 1 for
//! a failure (unreadable file, invalid scene).

#[path = "flockpath/bench.rs"]
mod bench;

use flockpath::export::{self, ExportOptions};
use flockpath::history::{self, MetricsHistory};
use flockpath::recording::Recording;
use flockpath::{presets, scene_from_any, scene_to_fragment, scene_to_json, PlannerKind, Scene, World};
use std::io::{Read as _, Write as _};
use std::path::Path;
use std::process::ExitCode;

/// Most samples `run --metrics-history` keeps before halving its sampling rate.
const HISTORY_CAP: usize = 4096;
/// Most steps one `run` may ask for (about 4.6 hours of simulated time at 60 steps/s).
const MAX_STEPS: u32 = 1_000_000;

/// Subcommands the DESIGN names that this build does not have yet.
const LATER_COMMANDS: &[&str] = &[];
/// `run` flags the DESIGN names that this build does not have yet.
const LATER_RUN_FLAGS: &[&str] = &[];
/// `run` export flags: flag, what it writes.
const EXPORT_FLAGS: &[&str] = &["--paths", "--paths-json", "--maya", "--blender", "--svg"];
/// Memory the CLI's recording of a run may use before it thins (a note goes to stderr).
const RECORDING_BUDGET_BYTES: usize = 1 << 30;

const HELP: &str = "\
flockpath — swarm-intelligence crowd planners on the command line

USAGE:
    flockpath <COMMAND> [OPTIONS]

COMMANDS:
    presets          List the preset scenes (name and description)
    preset NAME      Print a preset scene as JSON
    run              Run a scene for N steps and report its metrics
    url FILE         Print the URL fragment value (the part after #s=) for a scene JSON file
    scene STRING     Print the scene JSON for a URL fragment value, #s= fragment or URL
    bench            Measure step and render speed (prints figures)
    optimize         Run swarm optimizers on benchmark functions (table, JSON, curves)
    help [COMMAND]   Show this help, or a command's help

Run `flockpath <COMMAND> --help` for a command's options.
Errors go to stderr; the exit code is 2 for a usage mistake, 1 for a failure.
";

const RUN_HELP: &str = "\
flockpath run — simulate a scene and report its metrics

USAGE:
    flockpath run --scene SCENE --steps N [--planner NAME] [--seed S] [--metrics FILE|-]
                  [--paths out.csv] [--paths-json out.json] [--maya out.mel]
                  [--blender out.py] [--svg out.svg] [--fps F] [--scale S]
                  [--metrics-history out.csv]

OPTIONS:
    --scene SCENE      A scene JSON file, `-` for stdin, a URL fragment value (1.…),
                       a #s=… fragment or a whole page URL
    --steps N          Steps to simulate (1 step = 1/60 s), at most 1000000
    --planner NAME     Give every group this planner with its default parameters
    --seed S           Replace the scene's seed (0…4294967295)
    --metrics FILE|-   Write the metrics JSON to FILE, or to stdout with `-`;
                       without it a one-line summary is printed
    --metrics-history FILE
                       Write the metrics over time as CSV: step,time_s,group,<series…>,
                       a row per sample (every 5 steps, halved beyond 4096 samples) for
                       the whole run (group `all`) and per group
    --paths FILE       Write every agent's path as CSV: agent,group,step,time,x,y,vx,vy
                       (one row per agent per recorded step, step 0 included)
    --paths-json FILE  Write the paths as JSON
    --maya FILE        Write a Maya MEL script: one keyframed locator per agent (x-z plane)
    --blender FILE     Write a Blender Python script: one keyframed empty per agent
    --svg FILE         Write the trails as SVG
    --fps F            Keyframes per second of the MEL/Python exports (1…240, default 24)
    --scale S          Scene px → 3-D units in the MEL/Python exports (default 0.01)
    -h, --help         Show this help

Every step is recorded up to 1 GiB (agents × steps × 16 bytes); beyond that every other
step is dropped and a note says so on stderr.
";

const BENCH_HELP: &str = "\
flockpath bench — ns per agent-step of World::step and render time per frame

USAGE:
    taskset -c 0 flockpath bench [--quick] [--only step|grid|planners|render|packed|metrics] [--json FILE]

OPTIONS:
    --quick            Fewer and shorter repetitions (CI smoke run; figures are rougher)
    --only step|grid|planners|render|packed|metrics
                       Run only the step benchmarks (grid, brute force, per planner), only
                       the Boids grid step benchmark, only the per-planner table, only
                       the render benchmark, only the packed-vs-spread table, or only the
                       cost of one metrics summary against N
    --json FILE        Also write the figures as JSON
    -h, --help         Show this help

Scenes are presets::constant_density(N, 9.0): about 9 neighbours per agent at every N.
Pin to one core (taskset -c 0) so the figures are comparable between runs.
";

/// A command-line failure: what went wrong, and whether it was a usage mistake.
#[derive(Debug)]
enum CliError {
    /// Bad command line (unknown flag, missing value, bad number): exit code 2.
    Usage(String),
    /// The command line was fine but the work failed (missing file, invalid scene): exit code 1.
    Failed(String),
}

fn usage(msg: impl Into<String>) -> CliError {
    CliError::Usage(msg.into())
}

fn failed(msg: impl Into<String>) -> CliError {
    CliError::Failed(msg.into())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match dispatch(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::Usage(msg)) => {
            eprintln!("flockpath: {msg}");
            eprintln!("Run `flockpath --help` for usage.");
            ExitCode::from(2)
        }
        Err(CliError::Failed(msg)) => {
            eprintln!("flockpath: {msg}");
            ExitCode::from(1)
        }
    }
}

fn dispatch(args: &[String]) -> Result<(), CliError> {
    let Some((command, rest)) = args.split_first() else {
        eprint!("{HELP}");
        return Err(usage("no command given"));
    };
    let wants_help = rest.iter().any(|a| a == "-h" || a == "--help");
    match command.as_str() {
        "-h" | "--help" => out(HELP),
        "help" => match rest.first().map(String::as_str) {
            None => out(HELP),
            Some("run") => out(RUN_HELP),
            Some("bench") => out(BENCH_HELP),
            Some(other) => out(&command_help(other)?),
        },
        "-V" | "--version" => out(&format!("flockpath {}\n", env!("CARGO_PKG_VERSION"))),
        "run" if wants_help => out(RUN_HELP),
        "bench" if wants_help => out(BENCH_HELP),
        // `tune` parses its own flags (and its own --help); the bin only supplies the clock.
        "tune" => {
            let start = std::time::Instant::now();
            std::process::exit(i32::from(flockpath::tune_cli::main(rest, &|| start.elapsed().as_secs_f64())))
        }
        c if wants_help => out(&command_help(c)?),
        "presets" => {
            no_more_args("presets", rest)?;
            let width = presets::ALL.iter().map(|p| p.name.len()).max().unwrap_or(0);
            let mut text = String::new();
            for p in presets::ALL {
                text.push_str(&format!("{:width$}  {}\n", p.name, p.description));
            }
            out(&text)
        }
        "preset" => {
            let name = one_arg("preset", "NAME", rest)?;
            let preset = presets::find(name).ok_or_else(|| {
                usage(format!("unknown preset {name:?}; `flockpath presets` lists them ({})", preset_names()))
            })?;
            out(&format!("{}\n", scene_to_json(&(preset.build)())))
        }
        "url" => {
            let file = one_arg("url", "FILE", rest)?;
            let scene = load_scene(file)?;
            out(&format!("{}\n", scene_to_fragment(&scene)))
        }
        "scene" => {
            let text = one_arg("scene", "STRING", rest)?;
            let scene = scene_from_any(text).map_err(|e| failed(format!("bad scene string: {e}")))?;
            out(&format!("{}\n", scene_to_json(&scene)))
        }
        "run" => run(rest),
        "optimize" => optimize(rest),
        "bench" => bench::main(&parse_bench(rest)?).map_err(failed),
        // Hidden: the scene the benchmarks use, for the browser bench page.
        "density-scene" => {
            // `density-scene --planners` lists the per-planner rows; `density-scene N [--planner
            // NAME]` prints the scene (the per-planner one heads for a central goal).
            if rest.first().map(String::as_str) == Some("--planners") {
                let names: Vec<&str> = bench::planner_configs().into_iter().map(|(name, _)| name).collect();
                return out(&format!("{}\n", names.join("\n")));
            }
            let (n, planner) = match rest {
                [n] => (n, None),
                [n, flag, name] if flag == "--planner" => (n, Some(name.as_str())),
                _ => return Err(usage("usage: flockpath density-scene N [--planner NAME] | --planners")),
            };
            let n: u32 = parse_number("N", n)?;
            if n == 0 || n > flockpath::scene::MAX_AGENTS {
                return Err(usage(format!("N = {n} is outside 1…{}", flockpath::scene::MAX_AGENTS)));
            }
            let scene = match planner {
                None => bench::bench_scene(n),
                Some(name) => {
                    let config = bench::planner_configs()
                        .into_iter()
                        .find(|(row, _)| *row == name)
                        .map(|(_, config)| config)
                        .ok_or_else(|| usage(format!("no bench row {name:?}; see --planners")))?;
                    bench::planner_scene(n, &config)
                }
            };
            out(&format!("{}\n", scene_to_json(&scene)))
        }
        c if LATER_COMMANDS.contains(&c) => {
            Err(usage(format!("`flockpath {c}` is not available yet in this build")))
        }
        other => Err(usage(format!("unknown command {other:?}"))),
    }
}

fn command_help(command: &str) -> Result<String, CliError> {
    Ok(match command {
        "run" => RUN_HELP.to_string(),
        "bench" => BENCH_HELP.to_string(),
        "optimize" => flockpath::optim::report::HELP.to_string(),
        "presets" => {
            "flockpath presets — list the preset scenes, one per line: name, then description\n".into()
        }
        "preset" => "flockpath preset NAME — print the preset scene NAME as JSON\n".into(),
        "url" => {
            "flockpath url FILE — print the URL fragment value for the scene JSON in FILE (`-` = stdin)\n"
                .into()
        }
        "scene" => {
            "flockpath scene STRING — print the scene JSON for a fragment value, #s= fragment or URL\n".into()
        }
        c if LATER_COMMANDS.contains(&c) => {
            return Err(usage(format!("`flockpath {c}` is not available yet in this build")))
        }
        other => return Err(usage(format!("unknown command {other:?}"))),
    })
}

/// `flockpath optimize`: the logic lives in `flockpath::optim::report`; this adds the clock
/// and the progress line on stderr.
fn optimize(rest: &[String]) -> Result<(), CliError> {
    let start = std::time::Instant::now();
    let clock = move || start.elapsed().as_secs_f64();
    let mut progress = |done: usize, total: usize| {
        eprint!("{}", flockpath::optim::report::progress_line(done, total));
        if done == total {
            eprintln!();
        }
    };
    let args = flockpath::optim::report::OptimizeArgs::parse(rest).map_err(usage)?;
    let text = flockpath::optim::report::execute(&args, &clock, &mut progress).map_err(failed)?;
    out(&text)
}

/// Writes to stdout; a closed pipe (`flockpath presets | head -1`) is not an error worth a panic.
fn out(text: &str) -> Result<(), CliError> {
    let mut stdout = std::io::stdout().lock();
    match stdout.write_all(text.as_bytes()).and_then(|()| stdout.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(failed(format!("cannot write to stdout: {e}"))),
    }
}

fn preset_names() -> String {
    presets::ALL.iter().map(|p| p.name).collect::<Vec<_>>().join(", ")
}

fn no_more_args(command: &str, rest: &[String]) -> Result<(), CliError> {
    match rest.first() {
        None => Ok(()),
        Some(extra) => Err(usage(format!("`flockpath {command}` takes no arguments, got {extra:?}"))),
    }
}

fn one_arg<'a>(command: &str, what: &str, rest: &'a [String]) -> Result<&'a str, CliError> {
    match rest {
        [one] if !(one.starts_with("--") && one.len() > 2) => Ok(one),
        [one] => Err(usage(format!("unknown option {one:?} for `flockpath {command}`"))),
        [] => Err(usage(format!("`flockpath {command}` needs {what}"))),
        [_, extra, ..] => Err(usage(format!("`flockpath {command}` takes one {what}, got also {extra:?}"))),
    }
}

fn parse_number<T: std::str::FromStr>(what: &str, text: &str) -> Result<T, CliError> {
    text.trim().parse().map_err(|_| usage(format!("{what} must be a whole number, got {text:?}")))
}

/// Splits `--flag value` / `--flag=value` pairs; every flag takes a value unless listed in
/// `switches`. Returns `(flag, value)` in order; `value` is empty for switches.
fn flag_pairs(
    command: &str,
    args: &[String],
    with_value: &[&str],
    switches: &[&str],
    later: &[&str],
) -> Result<Vec<(String, String)>, CliError> {
    let mut pairs = Vec::new();
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let (flag, inline) = match arg.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f, Some(v.to_string())),
            _ => (arg.as_str(), None),
        };
        if later.contains(&flag) {
            return Err(usage(format!("{flag} is not available yet in this build")));
        }
        if switches.contains(&flag) {
            if inline.is_some() {
                return Err(usage(format!("{flag} takes no value")));
            }
            pairs.push((flag.to_string(), String::new()));
        } else if with_value.contains(&flag) {
            let value = match inline {
                Some(v) => v,
                None => it.next().cloned().ok_or_else(|| usage(format!("{flag} needs a value")))?,
            };
            if pairs.iter().any(|(f, _)| f == flag) {
                return Err(usage(format!("{flag} is given twice")));
            }
            pairs.push((flag.to_string(), value));
        } else if flag.starts_with('-') && flag.len() > 1 {
            return Err(usage(format!("unknown option {flag:?} for `flockpath {command}`")));
        } else {
            return Err(usage(format!("unexpected argument {arg:?} for `flockpath {command}`")));
        }
    }
    Ok(pairs)
}

/// Loads a scene from a file, stdin (`-`), inline JSON, a fragment value or a URL.
fn load_scene(source: &str) -> Result<Scene, CliError> {
    let path = Path::new(source);
    let text = if source == "-" {
        let mut text = String::new();
        std::io::stdin().read_to_string(&mut text).map_err(|e| failed(format!("cannot read stdin: {e}")))?;
        text
    } else if path.is_file() {
        std::fs::read_to_string(path)
            .map_err(|e| failed(format!("cannot read scene file {source:?}: {e}")))?
    } else if looks_like_path(source) {
        return Err(failed(format!("cannot read scene file {source:?}: no such file")));
    } else {
        source.to_string()
    };
    let what = if source == "-" { "stdin".to_string() } else { format!("{source:?}") };
    let what =
        if what.len() > 60 { format!("{}…", what.chars().take(57).collect::<String>()) } else { what };
    scene_from_any(&text).map_err(|e| failed(format!("bad scene in {what}: {e}")))
}

/// A string that cannot be a scene string or JSON but reads like a file name.
fn looks_like_path(s: &str) -> bool {
    let t = s.trim_start();
    if t.starts_with('{') || t.contains("#s=") || t.contains("://") {
        return false;
    }
    // Fragment values are base64url (no `/`) after a version prefix such as `1.`.
    t.contains('/') || t.contains('\\') || t.ends_with(".json") || !t.contains('.')
}

fn run(args: &[String]) -> Result<(), CliError> {
    let pairs = flag_pairs(
        "run",
        args,
        &[
            "--scene",
            "--planner",
            "--seed",
            "--steps",
            "--metrics",
            "--metrics-history",
            "--paths",
            "--paths-json",
            "--maya",
            "--blender",
            "--svg",
            "--fps",
            "--scale",
        ],
        &[],
        LATER_RUN_FLAGS,
    )?;
    let get = |flag: &str| pairs.iter().find(|(f, _)| f == flag).map(|(_, v)| v.as_str());
    let source = get("--scene").ok_or_else(|| usage("`flockpath run` needs --scene"))?;
    let steps_text = get("--steps").ok_or_else(|| usage("`flockpath run` needs --steps N"))?;
    let steps: u32 = parse_number("--steps", steps_text)?;
    if steps > MAX_STEPS {
        return Err(usage(format!("--steps {steps} is over the limit of {MAX_STEPS}")));
    }
    let planner = match get("--planner") {
        Some(name) => Some(PlannerKind::from_name(name).ok_or_else(|| {
            let known: Vec<&str> = PlannerKind::ALL.iter().map(|k| k.name()).collect();
            usage(format!("unknown planner {name:?}; available: {}", known.join(", ")))
        })?),
        None => None,
    };
    let seed = get("--seed").map(|s| parse_number::<u32>("--seed", s)).transpose()?;
    let real = |flag: &str, default: f32| -> Result<f32, CliError> {
        get(flag).map_or(Ok(default), |text| {
            text.trim().parse().map_err(|_| usage(format!("{flag} must be a number, got {text:?}")))
        })
    };
    let defaults = ExportOptions::default();
    let export_options =
        ExportOptions::checked(real("--fps", defaults.fps)?, real("--scale", defaults.scale)?)
            .map_err(|m| usage(format!("--fps/--scale: {m}")))?;
    let recording_wanted = EXPORT_FLAGS.iter().any(|f| get(f).is_some());

    let mut scene = load_scene(source)?;
    if let Some(kind) = planner {
        for g in &mut scene.groups {
            g.planner = kind.default_config();
        }
    }
    if let Some(seed) = seed {
        scene.seed = seed;
    }
    let mut world = World::new(scene).map_err(|e| failed(format!("cannot run the scene: {e}")))?;
    let mut recording = recording_wanted.then(|| Recording::of_world(&world, RECORDING_BUDGET_BYTES));
    let history_file = get("--metrics-history");
    let mut history = history_file.map(|_| MetricsHistory::new(history::DEFAULT_EVERY, HISTORY_CAP));
    if recording.is_none() && history.is_none() {
        world.step_n(steps);
    } else {
        for _ in 0..steps {
            world.step();
            if let Some(r) = recording.as_mut() {
                r.capture_world(&world);
            }
            if let Some(h) = history.as_mut() {
                h.sample(&world);
            }
        }
    }
    if let Some(recording) = &recording {
        write_exports(&world, recording, export_options, &get)?;
    }
    if let (Some(h), Some(file)) = (&history, history_file) {
        let names: Vec<String> = world.scene().groups.iter().map(|g| g.name.clone()).collect();
        std::fs::write(file, h.to_csv(&names))
            .map_err(|e| failed(format!("cannot write metrics history file {file:?}: {e}")))?;
    }
    let metrics = world.metrics();
    let json = serde_json::to_string_pretty(&metrics)
        .map_err(|e| failed(format!("cannot write the metrics: {e}")))?;
    match get("--metrics") {
        Some("-") => out(&format!("{json}\n")),
        Some(file) => {
            std::fs::write(file, format!("{json}\n"))
                .map_err(|e| failed(format!("cannot write metrics file {file:?}: {e}")))?;
            out(&summary(&world))
        }
        None => out(&summary(&world)),
    }
}

/// Writes each export file asked for; a thinned recording is reported on stderr.
fn write_exports<'a>(
    world: &World,
    recording: &Recording,
    options: ExportOptions,
    get: &dyn Fn(&str) -> Option<&'a str>,
) -> Result<(), CliError> {
    let scene = world.scene();
    if recording.thinned() > 0 {
        eprintln!(
            "flockpath: note: the recording outgrew its 1 GiB budget and keeps every {}th step",
            recording.every()
        );
    }
    let exports: [(&str, &dyn Fn() -> String); 5] = [
        ("--paths", &|| export::paths_csv(scene, recording)),
        ("--paths-json", &|| export::paths_json(scene, recording)),
        ("--maya", &|| export::maya_mel(scene, recording, options)),
        ("--blender", &|| export::blender_py(scene, recording, options)),
        ("--svg", &|| export::trails_svg(scene, recording)),
    ];
    for (flag, make) in exports {
        if let Some(file) = get(flag) {
            std::fs::write(file, make())
                .map_err(|e| failed(format!("cannot write {flag} file {file:?}: {e}")))?;
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

fn parse_bench(args: &[String]) -> Result<bench::Options, CliError> {
    let pairs = flag_pairs("bench", args, &["--only", "--json"], &["--quick"], &[])?;
    let mut options = bench::Options::default();
    let mut only = None;
    for (flag, value) in pairs {
        match flag.as_str() {
            "--quick" => options.quick = true,
            "--json" => options.json = Some(value),
            "--only" => only = Some(value),
            _ => return Err(usage(format!("unknown option {flag:?} for `flockpath bench`"))),
        }
    }
    if let Some(only) = only {
        let o = &mut options;
        (o.step, o.brute, o.planners, o.render, o.packed, o.metrics) = match only.as_str() {
            "step" => (true, true, true, false, false, false),
            "grid" => (true, false, false, false, false, false),
            "planners" => (false, false, true, false, false, false),
            "render" => (false, false, false, true, false, false),
            "packed" => (false, false, false, false, true, false),
            "metrics" => (false, false, false, false, false, true),
            other => {
                return Err(usage(format!(
                "--only must be `step`, `grid`, `planners`, `render`, `packed` or `metrics`, got {other:?}"
            )))
            }
        };
    }
    Ok(options)
}
