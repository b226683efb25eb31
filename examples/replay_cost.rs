//! Prints what recording a run for the timeline costs: the share of the step time spent in
//! `Replay::record` at 1,000 and 10,000 agents (Boids, constant density, medians of blocks), and the export recording's for comparison.
//! Release build,
//! pinned to one core: `taskset -c 0 cargo run --release --example replay_cost`.

use flockpath::sim::limits::PAGE_RECORDING_BUDGET_BYTES;
use flockpath::sim::recording::Recording;
use flockpath::sim::replay::{checkpoint_bytes_estimate, Replay};
use flockpath::{presets, World};
use std::time::Instant;

#[path = "support/median.rs"]
mod median;
use median::median;

fn main() {
    for n in [1_000u32, 10_000] {
        let scene = presets::constant_density_to_centre(n, 8.0, 40.0);
        let mut world = World::new(scene).expect("valid scene");
        world.step_n(20);

        let mut replay = Replay::new(&world);
        let mut export = Recording::of_world(&world, PAGE_RECORDING_BUDGET_BYTES);
        let block = if n > 5_000 { 10 } else { 50 };
        let (mut step_ms, mut record_ms, mut export_ms) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..9 {
            let (mut s, mut r, mut e) = (0.0, 0.0, 0.0);
            for _ in 0..block {
                let t = Instant::now();
                world.step();
                s += t.elapsed().as_secs_f64();
                let t = Instant::now();
                replay.record(&world);
                r += t.elapsed().as_secs_f64();
                let t = Instant::now();
                export.capture_world(&world);
                e += t.elapsed().as_secs_f64();
            }
            step_ms.push(1e3 * s / f64::from(block));
            record_ms.push(1e3 * r / f64::from(block));
            export_ms.push(1e3 * e / f64::from(block));
        }
        let (s, r, e) = (median(step_ms), median(record_ms), median(export_ms));
        let info = replay.info();
        println!(
            "{n:6} agents: step {s:7.3} ms, record {r:6.3} ms per step = {:4.1} % of the step \
             (checkpoint every {} steps, {:.0} KB each, estimated); the export recording \
             (f32 x, y, vx, vy) adds {e:.3} ms = {:.1} %",
            100.0 * r / s,
            info.checkpoint_every,
            checkpoint_bytes_estimate(&world) as f64 / 1e3,
            100.0 * e / s,
        );
    }
}
