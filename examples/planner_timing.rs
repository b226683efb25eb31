//! Prints ns per agent-step of the PSO and firefly planners at 1k and 10k agents (release build:
//! `cargo run --release --example planner_timing`). Timing lives here, never in the core.

use flockpath::model::params::{FireflyParams, PsoParams};
use flockpath::{presets, PlannerConfig, World};
use std::time::Instant;

fn main() {
    for (label, config) in [
        ("pso", PlannerConfig::Pso(PsoParams::default())),
        ("firefly", PlannerConfig::Firefly(FireflyParams::default())),
    ] {
        for n in [1_000u32, 10_000] {
            // Constant density (about 8 neighbours per 50 px), one goal in the middle.
            let mut scene = presets::constant_density_to_centre(n, 8.0, 20.0);
            scene.groups[0].planner = config.clone();
            let mut world = World::new(scene).expect("valid scene");
            world.step_n(20);
            let steps = if n > 5_000 { 60 } else { 300 };
            let start = Instant::now();
            world.step_n(steps);
            let ns = start.elapsed().as_nanos() as f64 / (f64::from(steps) * f64::from(n));
            println!("{label:8} {n:6} agents: {ns:8.0} ns per agent-step (world step incl. metrics)");
        }
    }
}
