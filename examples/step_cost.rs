//! Measures what the cost limits in `src/cost.rs` are set from: ns per agent-step of every
//! planner in its worst valid scene (a square crowd packed at the spawn density limit, heading
//! for a goal in its middle) against the constant-density scene of the benchmarks, natively.
//! `taskset -c 0 cargo run --release --example step_cost [N] [PLANNER|all] [SCENES] [RADIUS]`,
//! SCENES a comma list of `spread`, `packed`, `late` (packed after 300 steps), `free` (packed
//! without a goal: a crowd that cannot park, so it cannot jam), the first three by default; a scene not run prints `-`; RADIUS the packed bodies' radius in px (default 4: the
//! smallest allowed, 0.5, packs the most bodies into a planner's reach). Timing lives here, never
//! in the core. Figures are on-CPU time where the OS reports it (Linux `schedstat`): on a machine
//! shared with other work, wall-clock time also counts the time other processes held the core.

use flockpath::{presets, Goal, PlannerKind, Region, Scene, World};
use std::time::Instant;

/// A square of `n` bodies packed at the density limit (one per 2r × 2r place) in a world with
/// room around it, all heading for a goal at the square's centre.
fn packed(n: u32, kind: PlannerKind, radius: f32) -> Scene {
    let side = (f64::from(n).sqrt().ceil() as f32) * 2.0 * radius;
    let world = side + 200.0;
    let mut s = Scene::empty(world, world);
    let (lo, hi) = (100.0 + radius, 100.0 + side - radius);
    s.goals.push(Goal::fixed([0.5 * world, 0.5 * world], 20.0));
    let mut g = presets::constant_density(1, 1.0).groups.remove(0);
    g.count = n;
    g.spawn = Region { min: [lo, lo], max: [hi, hi] };
    g.goal = Some(0);
    g.agent_radius = radius;
    g.planner = kind.default_config();
    s.groups.push(g);
    s
}

/// [`packed`] without a goal: nothing parks (a Boids crowd that cannot jam), but the bodies stay
/// as crowded as the planner lets them.
fn free(n: u32, kind: PlannerKind, radius: f32) -> Scene {
    let mut s = packed(n, kind, radius);
    s.groups[0].goal = None;
    s.goals.clear();
    s
}

fn spread(n: u32, kind: PlannerKind) -> Scene {
    let mut s = presets::constant_density_to_centre(n, 9.0, 20.0);
    s.groups[0].planner = kind.default_config();
    s
}

/// Nanoseconds this thread has spent on a CPU (Linux `schedstat`), if the OS reports it.
fn cpu_ns() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

/// Median and worst ns per agent-step over `windows` windows of `steps` steps after `skip`, and
/// the worst single step (the one that also takes the fitness measures, every
/// `FITNESS_SAMPLE_EVERY` steps, or the first), on-CPU where the OS reports it, else wall-clock.
fn time(scene: Scene, skip: u32, windows: u32, steps: u32) -> (f64, f64, f64) {
    let n = scene.agent_count() as f64;
    let mut world = match World::new_beyond_cost_limit(scene) {
        Ok(w) => w,
        Err(e) => {
            println!("  refused: {e}");
            return (f64::NAN, f64::NAN, f64::NAN);
        }
    };
    world.step_n(skip);
    let mut worst_step = 0.0f64;
    let mut samples: Vec<f64> = (0..windows)
        .map(|_| {
            let mut window = 0.0;
            for _ in 0..steps {
                let (start, cpu_start) = (Instant::now(), cpu_ns());
                world.step();
                let spent = match (cpu_start, cpu_ns()) {
                    (Some(a), Some(b)) => b.saturating_sub(a) as f64,
                    _ => start.elapsed().as_nanos() as f64,
                };
                worst_step = worst_step.max(spent / n);
                window += spent;
            }
            window / (n * f64::from(steps))
        })
        .collect();
    samples.sort_by(f64::total_cmp);
    (samples[samples.len() / 2], samples[samples.len() - 1], worst_step)
}

fn main() {
    let n: u32 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(2_000);
    let clock = if cpu_ns().is_some() { "on-CPU" } else { "wall-clock" };
    println!(
        "{n} agents, {clock} ns per agent-step (median / worst of 10-step windows; worst single step), \
         native release"
    );
    println!(
        "{:>8}  {:>26}  {:>26}  {:>26}  {:>26}",
        "planner", "spread (steps 0-100)", "packed (0-100)", "packed (300-400)", "free (0-100)"
    );
    let only = std::env::args().nth(2).and_then(|name| PlannerKind::from_name(&name));
    let scenes = std::env::args().nth(3).unwrap_or_else(|| "spread,packed,late".into());
    let radius: f32 = std::env::args().nth(4).and_then(|a| a.parse().ok()).unwrap_or(4.0);
    let wanted = |name: &str| scenes.split(',').any(|s| s.trim() == name);
    let cell = |run: bool, timed: &dyn Fn() -> (f64, f64, f64)| {
        if run {
            let (m, w, s) = timed();
            format!("{m:.0} / {w:.0}; {s:.0}")
        } else {
            "-".to_string()
        }
    };
    for &kind in PlannerKind::ALL.iter().filter(|&&k| only.is_none_or(|o| o == k)) {
        println!(
            "{:>8}  {:>26}  {:>26}  {:>26}  {:>26}",
            kind.name(),
            cell(wanted("spread"), &|| time(spread(n, kind), 0, 10, 10)),
            cell(wanted("packed"), &|| time(packed(n, kind, radius), 0, 10, 10)),
            cell(wanted("late"), &|| time(packed(n, kind, radius), 300, 10, 10)),
            cell(wanted("free"), &|| time(free(n, kind, radius), 0, 10, 10)),
        );
    }
}
