//! Prints how long one planning slice holds its thread (issue 24: the page's worker used to plan
//! one optimizer iteration per call, which among 5,000 obstacles at the largest planning held it
//! for seconds; now a call computes at most its budget of objective evaluations). The scene is
//! `tests/e2e/heavy-pause.test.mjs`'s: two IGSA groups at population 200, 3,000 iterations and 8
//! waypoints among 5,000 circles of radius 3 px. For each budget: the longest and median call
//! over the first `seconds` of planning, natively (the page runs wasm, about 1.3× slower).
//! `cargo run --release --example planning_slices -- [seconds]`.

use flockpath::model::geometry::Obstacle;
use flockpath::model::params::{IgsaParams, PlannerConfig};
use flockpath::{presets, Goal, Region, Scene, World};
use std::time::Instant;

/// The heavy-pause IGSA scene: 1,000 × 700 px, 5,000 seeded circles in x 160–640, y 10–490.
fn scene() -> Scene {
    let mut s = Scene::empty(1_000.0, 700.0);
    let mut state = 12_345u32;
    let mut unit = || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32
    };
    for _ in 0..5_000 {
        let c = [160.0 + unit() * 480.0, 10.0 + unit() * 480.0];
        s.obstacles.push(Obstacle::Circle { center: c, radius: 3.0 });
    }
    s.goals.push(Goal::fixed([745.0, 250.0], 40.0));
    let template = presets::open_field().groups.remove(0);
    for k in 0..2 {
        let mut g = template.clone();
        g.count = 40;
        g.spawn = Region { min: [20.0, 40.0 + 220.0 * k as f32], max: [110.0, 200.0 + 220.0 * k as f32] };
        g.goal = Some(0);
        let params =
            IgsaParams { population: 200, iterations: 3_000, waypoint_count: 8, ..IgsaParams::default() };
        g.planner = PlannerConfig::Igsa(params);
        s.groups.push(g);
    }
    s
}

fn main() {
    let seconds: f64 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(3.0);
    for budget in [1u32, 4, 16, 64] {
        let mut world = World::new_sliced(scene()).expect("valid scene");
        let mut calls: Vec<f64> = Vec::new();
        let start = Instant::now();
        while start.elapsed().as_secs_f64() < seconds {
            let t = Instant::now();
            world.advance_planning(budget);
            calls.push(t.elapsed().as_secs_f64() * 1e3);
        }
        let progress = world.planning_progress();
        calls.sort_by(f64::total_cmp);
        println!(
            "budget {budget:3} evaluations: {:6} calls in {seconds} s, median {:7.3} ms, longest {:7.3} ms, \
             planned {:.2} %",
            calls.len(),
            calls[calls.len() / 2],
            calls[calls.len() - 1],
            100.0 * progress,
        );
    }
}
