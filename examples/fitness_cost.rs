//! Prints what the fitness measures in the metrics cost a Boids step: on-CPU ns per agent-step
//! (Linux `schedstat`, so other processes' turns on the core do not count; wall clock elsewhere)
//! with them never sampled, sampled every `FITNESS_SAMPLE_EVERY` steps (the default) and every
//! step (`taskset -c 0 cargo run --release --example fitness_cost`). Timing lives here, never in
//! the core.

use flockpath::sim::metrics::FITNESS_SAMPLE_EVERY;
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
                let (start, cpu_start) = (Instant::now(), cpu_ns());
                world.step_n(STEPS);
                let spent = match (cpu_start, cpu_ns()) {
                    (Some(a), Some(b)) => (b - a) as f64,
                    _ => start.elapsed().as_nanos() as f64,
                };
                let ns = spent / (f64::from(STEPS) * f64::from(n));
                best[slot] = best[slot].min(ns);
            }
        }
        for ((label, every), ns) in settings.iter().zip(best) {
            let overhead = 100.0 * (ns / best[0] - 1.0);
            println!("{n:6} agents, fitness {label:10} (every {every:2}): {ns:7.1} ns/agent-step ({overhead:+5.1} %)");
        }
    }
}

/// Nanoseconds this thread has spent on a CPU (Linux `schedstat`), if the OS reports it.
fn cpu_ns() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}
