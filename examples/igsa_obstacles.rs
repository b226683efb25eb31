//! Prints IGSA path-planning time against the number of small circular obstacles (release build:
//! `cargo run --release --example igsa_obstacles -- [iterations] [reps]`). Timing lives here,
//! never in the core; the planned fitness is printed so before/after runs can be compared.

use flockpath::model::geometry::Obstacle;
use flockpath::model::params::{IgsaParams, PlannerConfig};
use flockpath::model::presets;
use flockpath::planners::igsa::plan_group_path;
use std::time::Instant;

fn main() {
    let args: Vec<u32> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let iterations = args.first().copied().unwrap_or(30);
    let reps = args.get(1).copied().unwrap_or(3).max(1);
    let params = IgsaParams { iterations, ..IgsaParams::default() };
    for n in [0usize, 100, 500, 1_000, 2_000, 5_000] {
        let mut scene = (presets::find("igsa-path-1").expect("preset").build)();
        scene.obstacles.clear();
        // Small circles (radius 3 px) on a jittered lattice, clear of the start and the goal.
        let mut state = 12_345u32;
        let mut unit = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1u32 << 24) as f32
        };
        while scene.obstacles.len() < n {
            let c = [150.0 + unit() * 500.0, 10.0 + unit() * 480.0];
            scene.obstacles.push(Obstacle::Circle { center: c, radius: 3.0 });
        }
        scene.groups[0].planner = PlannerConfig::Igsa(params.clone());
        let mut times = Vec::new();
        let mut fitness = None;
        for _ in 0..reps {
            let start = Instant::now();
            let path = plan_group_path(&scene, 0, &params).expect("group 0");
            times.push(start.elapsed().as_secs_f64());
            fitness = path.fitness;
        }
        times.sort_by(f64::total_cmp);
        println!(
            "{n:5} obstacles: {:8.3} s median of {reps} (T = {iterations}), fitness {:?}",
            times[times.len() / 2],
            fitness
        );
    }
}
