//! Prints what the fitness measures in the metrics cost a Boids step: ns per agent-step with
//! them never sampled, sampled every `FITNESS_SAMPLE_EVERY` steps (the default) and every step
//! (`taskset -c 0 cargo run --release --example fitness_cost`). Timing lives here, never in the core.

use flockpath::metrics::FITNESS_SAMPLE_EVERY;
use flockpath::{presets, World};
use std::time::Instant;

/// Steps timed per repetition, from a freshly spawned world (Boids clump over time).
const STEPS: u32 = 100;
/// Repetitions per setting; the fastest is kept (the machine is shared).
const REPS: usize = 5;

fn main() {
    for n in [1_000u32, 10_000] {
        let settings = [("never", 0), ("default", FITNESS_SAMPLE_EVERY), ("every step", 1)];
        let mut best = [f64::INFINITY; 3];
        // Interleaved, so a burst of load from other jobs hits every setting alike.
        for _ in 0..REPS {
            for (slot, &(_, every)) in settings.iter().enumerate() {
                let mut world = World::new(presets::constant_density(n, 9.0)).expect("valid scene");
                world.set_fitness_sample_every(every);
                let start = Instant::now();
                world.step_n(STEPS);
                let ns = start.elapsed().as_nanos() as f64 / (f64::from(STEPS) * f64::from(n));
                best[slot] = best[slot].min(ns);
            }
        }
        for ((label, every), ns) in settings.iter().zip(best) {
            let overhead = 100.0 * (ns / best[0] - 1.0);
            println!("{n:6} agents, fitness {label:10} (every {every:2}): {ns:7.1} ns/agent-step ({overhead:+5.1} %)");
        }
    }
}
