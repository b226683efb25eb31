//! `flockpath bench`: ns per agent-step of `World::step` on constant-density scenes, an O(N²)
//! brute-force baseline, and render time per frame. Prints figures; it is not a test.
//!
//! Wall-clock timing lives here, in `src/bin/`, and nowhere in the core.

use crate::{failed, CliError};
use flockpath::model::params::boids::{FlowGuide, Leader, Role};
use flockpath::model::params::BoidsParams;
use flockpath::render::Renderer;
use flockpath::spatial::SpatialGrid;
use flockpath::{presets, PlannerConfig, PlannerKind, Scene, World};
use serde_json::{json, Map, Value};
use std::time::Instant;

/// Agents within the perception radius of an agent in the benchmark scenes.
pub const NEIGHBOURS: f32 = 9.0;
/// Sizes of the grid-based step benchmark.
const STEP_SIZES: &[u32] = &[1_000, 10_000, 100_000];
/// Sizes of the brute-force baseline (O(N²): 100k would take minutes per step).
const BRUTE_SIZES: &[u32] = &[1_000, 10_000];

/// What to run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Fewer, shorter repetitions (rough figures).
    pub quick: bool,
    /// One short repetition at a hundredth of every size: checks the benchmark runs (the test
    /// command's smoke run), its figures mean nothing.
    pub smoke: bool,
    /// Run the step benchmarks.
    pub step: bool,
    /// Include the brute-force baseline in the step benchmarks.
    pub brute: bool,
    /// Run the per-planner table.
    pub planners: bool,
    /// Run the render benchmarks.
    pub render: bool,
    /// Run the packed-versus-spread table (every planner at equal N).
    pub packed: bool,
    /// Time one metrics summary (`World::metrics` as JSON, what the page polls) against N.
    pub metrics: bool,
    /// Where to write the figures as JSON.
    pub json: Option<String>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            quick: false,
            smoke: false,
            step: true,
            brute: true,
            planners: true,
            render: true,
            packed: true,
            metrics: true,
            json: None,
        }
    }
}

impl Options {
    /// `n` agents, or a hundredth of them (at least 10) in a smoke run.
    fn size(&self, n: u32) -> u32 {
        if self.smoke {
            (n / 100).max(10)
        } else {
            n
        }
    }

    /// `quick` or `full`, or one repetition of one step in a smoke run.
    fn plan(&self, quick: Plan, full: Plan) -> Plan {
        if self.smoke {
            Plan { warmup_steps: 1, steps: 1, agents_per_rep: 1, reps: 1 }
        } else if self.quick {
            quick
        } else {
            full
        }
    }
}

/// The benchmark scene with `n` agents: constant density, about nine neighbours each.
pub fn bench_scene(n: u32) -> Scene {
    presets::constant_density(n, NEIGHBOURS)
}

/// How one configuration is timed. Every repetition starts from freshly spawned worlds, so each
/// N is measured at the same simulated moment: boids clump over time (a 1k world has ~50
/// neighbours per agent after 300 steps), and timing later steps of small worlds than of large
/// ones would compare different densities.
struct Plan {
    /// Untimed steps after spawning (caches, allocations, first velocities).
    warmup_steps: u32,
    /// Timed steps per world.
    steps: u32,
    /// Agents stepped per repetition: small N runs several worlds so each timing is long enough.
    agents_per_rep: u32,
    reps: usize,
}

/// Runs the benchmarks and prints the figures.
pub fn main(options: &Options) -> Result<(), CliError> {
    println!("flockpath bench — {} build", if cfg!(debug_assertions) { "DEBUG (slow!)" } else { "release" });
    println!("Pin to one core for stable figures: taskset -c 0 flockpath bench");
    println!(
        "Scenes: presets::constant_density(N, {NEIGHBOURS}); figures are medians of {} repetitions.",
        if options.smoke {
            "1 (smoke run: a hundredth of every size, figures mean nothing)"
        } else if options.quick {
            "3 (quick)"
        } else {
            "7"
        }
    );
    let mut report = Map::new();
    report.insert("quick".into(), json!(options.quick));
    report.insert("smoke".into(), json!(options.smoke));
    report.insert("neighbours_target".into(), json!(NEIGHBOURS));
    if options.step {
        step_benchmarks(options, &mut report)?;
    }
    if options.planners {
        planner_benchmarks(options, &mut report)?;
    }
    if options.packed {
        packed_benchmarks(options, &mut report)?;
    }
    if options.metrics {
        metrics_benchmarks(options, &mut report)?;
    }
    if options.render {
        render_benchmarks(options, &mut report)?;
    }
    if let Some(file) = &options.json {
        let text = serde_json::to_string_pretty(&Value::Object(report)).map_err(failed)?;
        std::fs::write(file, format!("{text}\n"))
            .map_err(|e| failed(format!("cannot write {file:?}: {e}")))?;
        println!("figures written to {file}");
    }
    Ok(())
}

fn step_benchmarks(options: &Options, report: &mut Map<String, Value>) -> Result<(), CliError> {
    let grid_plan = options.plan(
        Plan { warmup_steps: 2, steps: 5, agents_per_rep: 20_000, reps: 3 },
        Plan { warmup_steps: 3, steps: 10, agents_per_rep: 100_000, reps: 7 },
    );
    let brute_plan = options.plan(
        Plan { warmup_steps: 1, steps: 2, agents_per_rep: 1_000, reps: 3 },
        Plan { warmup_steps: 3, steps: 10, agents_per_rep: 10_000, reps: 5 },
    );

    println!();
    println!("World::step, ns per agent-step (median; min…max over repetitions)");
    println!(
        "{:>9}  {:>14}  {:>18}  {:>9}  {:>7}  {:>10}",
        "agents", "ns/agent-step", "range", "cpu ns", "steps", "neighbours"
    );
    let mut grid_ns = Map::new();
    let mut grid_cpu = Map::new();
    let mut by_n = Vec::new();
    let mut by_n_cpu = Vec::new();
    for n in STEP_SIZES.iter().map(|&n| options.size(n)) {
        let r = time_steps(n, &grid_plan, false)?;
        print_row(n, &r);
        grid_ns.insert(n.to_string(), json!(r.median));
        grid_cpu.insert(n.to_string(), json!(r.cpu_median));
        by_n.push((n, r.median));
        by_n_cpu.push((n, r.cpu_median));
    }
    report.insert("step_ns_per_agent_step".into(), Value::Object(grid_ns));
    report.insert("step_cpu_ns_per_agent_step".into(), Value::Object(grid_cpu));
    let ends = |v: &[(u32, f64)]| Some((v.first()?.1, v.last()?.1));
    let cpu: Vec<(u32, f64)> = by_n_cpu.iter().filter_map(|&(n, c)| Some((n, c?))).collect();
    for (label, figures) in [("wall-clock", &by_n), ("on-CPU", &cpu)] {
        let Some((first, last)) =
            ends(figures).filter(|_| figures.len() == STEP_SIZES.len() && !options.smoke)
        else {
            continue;
        };
        let growth = last / first;
        println!();
        println!("{label}: growth of the per-agent cost 100k / 1k: {growth:.2}× (target < 1.5×)");
        println!("{label}: per-agent cost at 100k: {last:.0} ns (target ≤ 120 ns)");
        let key = if label == "on-CPU" { "growth_100k_over_1k_cpu" } else { "growth_100k_over_1k" };
        report.insert(key.into(), json!(growth));
    }

    if !options.brute {
        return Ok(());
    }
    println!();
    println!("Brute-force baseline (one grid cell: every agent scans every agent), ns per agent-step");
    let mut brute_ns = Map::new();
    for n in BRUTE_SIZES.iter().map(|&n| options.size(n)) {
        let r = time_steps(n, &brute_plan, true)?;
        print_row(n, &r);
        brute_ns.insert(n.to_string(), json!(r.median));
        if let Some(&(_, grid)) = by_n.iter().find(|(m, _)| *m == n) {
            println!("{:>9}  grid is {:.1}× faster than brute force", "", r.median / grid);
        }
    }
    report.insert("brute_ns_per_agent_step".into(), Value::Object(brute_ns));

    Ok(())
}

/// Sizes of the per-planner table.
pub const PLANNER_SIZES: &[u32] = &[1_000, 10_000];

/// The planners and Boids extensions of the per-planner table, by name.
pub fn planner_configs() -> Vec<(&'static str, PlannerConfig)> {
    let boids = |edit: fn(&mut BoidsParams)| {
        let mut p = BoidsParams::default();
        edit(&mut p);
        PlannerConfig::Boids(p)
    };
    let mut rows: Vec<(&'static str, PlannerConfig)> =
        PlannerKind::ALL.iter().map(|&k| (k.name(), k.default_config())).collect();
    rows.push(("boids+leader", boids(|p| p.leader = Leader::First)));
    rows.push(("boids+flow-field", boids(|p| p.flow_field = FlowGuide::Goal)));
    rows.push(("boids+prey", boids(|p| p.role = Role::Prey)));
    rows
}

/// The constant-density scene with a goal at its centre, every agent steered by `config` (also
/// written for the browser bench by the hidden `flockpath density-scene N --planner NAME`).
pub fn planner_scene(n: u32, config: &PlannerConfig) -> Scene {
    let mut scene = bench_scene(n);
    let c = [0.5 * scene.width, 0.5 * scene.height];
    scene.goals.push(flockpath::Goal::fixed(c, 0.05 * scene.width));
    for g in &mut scene.groups {
        g.goal = Some(0);
        g.planner = config.clone();
    }
    scene
}

/// ns per agent-step of every planner (and the Boids extensions) at 1k and 10k agents, on the
/// constant-density scene heading for a central goal (from spawn, so the figures compare the
/// same moment of every run).
fn planner_benchmarks(options: &Options, report: &mut Map<String, Value>) -> Result<(), CliError> {
    let plan = options.plan(
        Plan { warmup_steps: 2, steps: 3, agents_per_rep: 10_000, reps: 3 },
        Plan { warmup_steps: 3, steps: 10, agents_per_rep: 20_000, reps: 5 },
    );
    println!();
    println!(
        "Per planner: World::step, ns per agent-step (median; min…max), constant density, goal at the centre"
    );
    println!("{:>18}  {:>9}  {:>14}  {:>18}  {:>9}", "planner", "agents", "ns/agent-step", "range", "cpu ns");
    let mut table = Map::new();
    for (name, config) in planner_configs() {
        let mut row = Map::new();
        for n in PLANNER_SIZES.iter().map(|&n| options.size(n)) {
            let r = time_scene(n, &plan, |seed| {
                let mut scene = planner_scene(n, &config);
                scene.seed = seed;
                scene
            })?;
            println!(
                "{:>18}  {:>9}  {:>14.1}  {:>18}  {:>9}",
                name,
                n,
                r.median,
                format!("{:.1}…{:.1}", r.min, r.max),
                r.cpu_median.map_or("–".to_string(), |c| format!("{c:.1}"))
            );
            row.insert(n.to_string(), json!(r.median));
        }
        table.insert(name.to_string(), Value::Object(row));
    }
    report.insert("planner_ns_per_agent_step".into(), Value::Object(table));
    Ok(())
}

/// Agents of the packed-versus-spread table.
const PACKED_SIZE: u32 = 1_000;
/// Side (px) of the square every agent of a packed scene spawns in, at the world's centre: at
/// 1,000 agents 2.5 per px², every body overlapping hundreds of others.
const PACKED_SIDE: f32 = 20.0;

/// [`planner_scene`] with every agent piled in a [`PACKED_SIDE`] square halfway between the
/// world's left border and the goal (outside the goal: the agents still have somewhere to go).
/// No scene spawns such a pile (the spawn keeps bodies apart), but a converging crowd can reach
/// one, so the world starts from given positions (a fixed low-discrepancy pattern).
pub fn packed_world(n: u32, config: &PlannerConfig, seed: u32) -> Result<World, CliError> {
    const GOLDEN: f64 = 0.618_033_988_749_894_9;
    let scene = Scene { seed, ..planner_scene(n, config) };
    let (cx, cy) = (0.25 * scene.width, 0.5 * scene.height);
    let h = 0.5 * PACKED_SIDE;
    let positions = (0..n)
        .map(|i| {
            let u = (f64::from(i) + 0.5) / f64::from(n.max(1));
            let v = (f64::from(i) * GOLDEN).fract();
            glam::Vec2::new(cx - h + PACKED_SIDE * u as f32, cy - h + PACKED_SIDE * v as f32)
        })
        .collect();
    World::new_at(scene, positions).map_err(|e| failed(format!("packed scene with {n} agents: {e}")))
}

/// ns per agent-step of every planner on the spread (constant-density) scene and on the packed
/// one at equal N, and their ratio: the per-agent neighbour caps keep a pile a small constant
/// times as dear as a spread crowd.
fn packed_benchmarks(options: &Options, report: &mut Map<String, Value>) -> Result<(), CliError> {
    // Ten worlds per repetition: the OS's on-CPU clock is too coarse for one small world.
    let plan = options.plan(
        Plan { warmup_steps: 1, steps: 2, agents_per_rep: 10 * PACKED_SIZE, reps: 3 },
        Plan { warmup_steps: 1, steps: 3, agents_per_rep: 10 * PACKED_SIZE, reps: 5 },
    );
    let n = options.size(PACKED_SIZE);
    println!();
    println!(
        "Packed vs spread: World::step, on-CPU ns per agent-step (median), {n} agents piled in a {PACKED_SIDE}×{PACKED_SIDE} px \
         square vs at constant density"
    );
    println!("{:>20}  {:>14}  {:>14}  {:>8}", "planner", "spread ns", "packed ns", "ratio");
    let mut table = Map::new();
    for &kind in PlannerKind::ALL {
        let config = kind.default_config();
        let spread = time_scene(n, &plan, |seed| Scene { seed, ..planner_scene(n, &config) })?;
        let packed = time_worlds(n, &plan, false, |seed| packed_world(n, &config, seed))?;
        // On-CPU time where the OS reports it: a loaded machine inflates wall-clock time.
        let (spread, packed) =
            (spread.cpu_median.unwrap_or(spread.median), packed.cpu_median.unwrap_or(packed.median));
        let ratio = packed / spread;
        println!("{:>20}  {:>14.1}  {:>14.1}  {:>7.2}×", kind.name(), spread, packed, ratio);
        table.insert(kind.name().to_string(), json!({ "spread": spread, "packed": packed, "ratio": ratio }));
    }
    report.insert("packed_vs_spread_ns_per_agent_step".into(), Value::Object(table));
    Ok(())
}

/// Sizes of the metrics-summary benchmark.
const METRICS_SIZES: &[u32] = &[1_000, 10_000, 100_000];

/// ms per call of `World::metrics` serialised to JSON (what the page's metrics panel polls every
/// 250 ms), against N, for Boids and firefly crowds at constant density and a packed Boids crowd.
fn metrics_benchmarks(options: &Options, report: &mut Map<String, Value>) -> Result<(), CliError> {
    let calls = if options.smoke {
        1
    } else if options.quick {
        3
    } else {
        9
    };
    println!();
    println!("One metrics summary (World::metrics → JSON), on-CPU ms per call (median of {calls})");
    println!("{:>18}  {:>9}  {:>10}", "scene", "agents", "ms");
    let mut table = Map::new();
    let boids = PlannerKind::Boids.default_config();
    let firefly = PlannerKind::Firefly.default_config();
    let mut rows: Vec<(&str, u32, World)> = Vec::new();
    for n in METRICS_SIZES.iter().map(|&n| options.size(n)) {
        rows.push(("boids", n, bench_world(planner_scene(n, &boids))?));
    }
    let n = options.size(10_000);
    rows.push(("firefly", n, bench_world(planner_scene(n, &firefly))?));
    rows.push(("boids packed", n, packed_world(n, &boids, 1)?));
    for (label, n, mut world) in rows {
        world.step_n(2);
        let mut samples = Vec::with_capacity(calls);
        for _ in 0..calls {
            // Enough calls per sample for the OS's coarse on-CPU clock.
            let repeat = if options.smoke { 1 } else { (100_000 / n).max(1) };
            let (cpu, start) = (thread_cpu_ns(), Instant::now());
            for _ in 0..repeat {
                let text = serde_json::to_string(&world.metrics()).map_err(failed)?;
                std::hint::black_box(text.len());
            }
            let wall = start.elapsed().as_nanos() as f64 / 1e6;
            // On-CPU time where the OS reports it: a loaded machine inflates wall-clock time.
            // (A clock that did not advance, too coarse for these calls, leaves wall-clock time.)
            let ms = match (cpu, thread_cpu_ns()) {
                (Some(a), Some(b)) if b > a => (b - a) as f64 / 1e6,
                _ => wall,
            };
            samples.push(ms / f64::from(repeat));
        }
        let ms = median(&mut samples);
        println!("{:>18}  {:>9}  {:>10.3}", label, n, ms);
        table.insert(format!("{label} {n}"), json!(ms));
    }
    report.insert("metrics_summary_ms".into(), Value::Object(table));
    Ok(())
}

/// Timing of one configuration.
struct Timing {
    median: f64,
    /// Median on-CPU time (ns per agent-step) when the OS reports it: unlike wall-clock time it
    /// leaves out the time other processes held the core.
    cpu_median: Option<f64>,
    min: f64,
    max: f64,
    steps: u32,
    neighbours: f64,
}

fn print_row(n: u32, r: &Timing) {
    println!(
        "{:>9}  {:>14.1}  {:>18}  {:>9}  {:>7}  {:>10.1}",
        n,
        r.median,
        format!("{:.1}…{:.1}", r.min, r.max),
        r.cpu_median.map_or("–".to_string(), |c| format!("{c:.1}")),
        r.steps,
        r.neighbours
    );
}

fn time_steps(n: u32, plan: &Plan, brute: bool) -> Result<Timing, CliError> {
    time_worlds(n, plan, brute, |seed| bench_world(Scene { seed, ..bench_scene(n) }))
}

fn time_scene(n: u32, plan: &Plan, scene: impl Fn(u32) -> Scene) -> Result<Timing, CliError> {
    time_worlds(n, plan, false, |seed| bench_world(scene(seed)))
}

/// A benchmark's world (beyond the page's cost limit on purpose: the bench times large scenes).
fn bench_world(scene: Scene) -> Result<World, CliError> {
    let n = scene.agent_count();
    World::new_beyond_cost_limit(scene).map_err(|e| failed(format!("benchmark scene with {n} agents: {e}")))
}

/// Times `plan` on worlds of `n` agents built by `world(seed)`.
fn time_worlds(
    n: u32,
    plan: &Plan,
    brute: bool,
    world: impl Fn(u32) -> Result<World, CliError>,
) -> Result<Timing, CliError> {
    let worlds_per_rep = plan.agents_per_rep.div_ceil(n).max(1);
    let mut samples = Vec::with_capacity(plan.reps);
    let mut cpu_samples = Vec::with_capacity(plan.reps);
    let mut neighbours = 0.0;
    for _ in 0..plan.reps {
        let mut worlds = Vec::with_capacity(worlds_per_rep as usize);
        for w in 0..worlds_per_rep {
            let mut world = world(w + 1)?;
            if brute {
                world.use_brute_force_neighbours();
            }
            world.step_n(plan.warmup_steps);
            worlds.push(world);
        }
        let agent_steps = f64::from(plan.steps) * f64::from(n) * f64::from(worlds_per_rep);
        let cpu_start = thread_cpu_ns();
        let start = Instant::now();
        for world in &mut worlds {
            world.step_n(plan.steps);
        }
        let ns = start.elapsed().as_nanos() as f64;
        samples.push(ns / agent_steps);
        if let (Some(a), Some(b)) = (cpu_start, thread_cpu_ns()) {
            cpu_samples.push(b.saturating_sub(a) as f64 / agent_steps);
        }
        // Keep the optimiser from discarding the work.
        std::hint::black_box(worlds.iter().map(World::digest).fold(0, u64::wrapping_add));
        neighbours = worlds.first().map_or(0.0, mean_neighbours);
    }
    let cpu_median = (cpu_samples.len() == samples.len()).then(|| median(&mut cpu_samples));
    Ok(Timing {
        cpu_median,
        median: median(&mut samples),
        min: samples.iter().copied().fold(f64::INFINITY, f64::min),
        max: samples.iter().copied().fold(0.0, f64::max),
        steps: plan.steps,
        neighbours,
    })
}

/// Mean number of other agents within the perception radius at the end of the run (the scene
/// promises about nine; flocking clumps agents, so this says what the step really did).
fn mean_neighbours(world: &World) -> f64 {
    let radius = flockpath::model::params::BoidsParams::default().perception_radius;
    let scene = world.scene();
    let mut grid = SpatialGrid::new(scene.width, scene.height, radius, world.agent_count());
    grid.rebuild(world.positions(), world.velocities());
    let mut total = 0u64;
    for &p in world.positions() {
        grid.for_each_within(p, radius, |_| total += 1);
    }
    let n = world.agent_count().max(1) as f64;
    (total as f64 - n) / n
}

/// Nanoseconds this thread has spent on a CPU (Linux `schedstat`), if the OS reports it.
fn thread_cpu_ns() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

fn median(samples: &mut [f64]) -> f64 {
    samples.sort_by(f64::total_cmp);
    match samples.len() {
        0 => f64::NAN,
        len if len % 2 == 1 => samples[len / 2],
        len => 0.5 * (samples[len / 2 - 1] + samples[len / 2]),
    }
}

/// Canvas size of the render benchmark (device px).
const CANVAS: (u32, u32) = (1280, 800);
/// Sizes of the render benchmark.
const RENDER_SIZES: &[u32] = &[1_000, 10_000];

fn render_benchmarks(options: &Options, report: &mut Map<String, Value>) -> Result<(), CliError> {
    let (frames, reps, warmup) = if options.smoke {
        (1, 1, 1)
    } else if options.quick {
        (10, 3, 5)
    } else {
        (60, 7, 30)
    };
    println!();
    println!(
        "Render::render at {}×{}, trails on, ms per frame (median of {reps} runs of {frames} frames)",
        CANVAS.0, CANVAS.1
    );
    println!("{:>9}  {:>10}  {:>18}  {:>16}", "agents", "render ms", "range", "step+render ms");
    let mut render_ms = Map::new();
    let mut frame_ms = Map::new();
    for n in RENDER_SIZES.iter().map(|&n| options.size(n)) {
        let mut world = World::new_beyond_cost_limit(bench_scene(n))
            .map_err(|e| failed(format!("benchmark scene with {n} agents: {e}")))?;
        let mut renderer = Renderer::new(CANVAS.0, CANVAS.1);
        for _ in 0..warmup {
            world.step();
            renderer.render(&world);
        }
        let (mut render_samples, mut frame_samples) = (Vec::new(), Vec::new());
        for _ in 0..reps {
            let (mut render_ns, mut frame_ns) = (0u128, 0u128);
            for _ in 0..frames {
                let start = Instant::now();
                world.step();
                let stepped = Instant::now();
                renderer.render(&world);
                let done = Instant::now();
                render_ns += (done - stepped).as_nanos();
                frame_ns += (done - start).as_nanos();
            }
            render_samples.push(render_ns as f64 / 1e6 / f64::from(frames));
            frame_samples.push(frame_ns as f64 / 1e6 / f64::from(frames));
        }
        std::hint::black_box(renderer.pixels().first());
        let render = median(&mut render_samples);
        let frame = median(&mut frame_samples);
        println!(
            "{:>9}  {:>10.2}  {:>18}  {:>16.2}",
            n,
            render,
            format!("{:.2}…{:.2}", render_samples[0], render_samples[render_samples.len() - 1]),
            frame
        );
        render_ms.insert(n.to_string(), json!(render));
        frame_ms.insert(n.to_string(), json!(frame));
    }
    report.insert("render_ms_per_frame".into(), Value::Object(render_ms));
    report.insert("step_and_render_ms_per_frame".into(), Value::Object(frame_ms));
    Ok(())
}
