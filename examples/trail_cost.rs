//! Prints what truthful trails cost at 1,000 and 10,000 agents (Boids, constant density, heading
//! for a goal in the middle, 1280×800 canvas), as ratios measured in one run:
//! - `step(n)` with trails on (`Renderer::trace_step` after every step, as `Sim::step` does) vs
//!   off, from the same world, plus the frame that draws what was traced;
//! - one step per frame: the render after a plain step (as before) vs after a traced one (now),
//!   and the share of the frame `trace_step` takes;
//! - a timeline jump's `Renderer::rebuild_trails` over its agent-step budget.
//!
//! Medians of 7. Release build, pinned to one core:
//! `taskset -c 0 cargo run --release --example trail_cost`.

use flockpath::render::Renderer;
use flockpath::{presets, World};
use std::time::Instant;

const CANVAS: (u32, u32) = (1280, 800);
const REPS: usize = 7;

#[path = "support/median.rs"]
mod median;
use median::median;

fn ms_since(t: Instant) -> f64 {
    1e3 * t.elapsed().as_secs_f64()
}

fn main() {
    for n in [1_000u32, 10_000] {
        let scene = presets::constant_density_to_centre(n, 8.0, 40.0);
        let mut start = World::new(scene).expect("valid scene");
        start.step_n(20);
        let steps = if n > 5_000 { 100 } else { 500 };

        // step(n) with trails on: the steps and the tracing timed apart in the same run (robust
        // on a loaded machine), then the frame that draws what was traced.
        let (mut stepping, mut tracing, mut flush) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..REPS {
            let mut world = start.clone();
            let mut r = Renderer::new(CANVAS.0, CANVAS.1);
            r.render(&world);
            let (mut s, mut t) = (0.0, 0.0);
            for _ in 0..steps {
                let t0 = Instant::now();
                world.step();
                let t1 = Instant::now();
                r.trace_step(&world);
                s += (t1 - t0).as_secs_f64() * 1e3;
                t += ms_since(t1);
            }
            stepping.push(s);
            tracing.push(t);
            let t = Instant::now();
            r.render(&world);
            flush.push(ms_since(t));
            std::hint::black_box(r.pixels().first());
        }
        let (off, trace, flush) = (median(stepping), median(tracing), median(flush));
        println!(
            "{n:6} agents, step({steps}): steps {off:8.2} ms, tracing {trace:6.2} ms: trails on/off \
             {:.3} ({:.1} ns per agent-step); the next frame {flush:.2} ms",
            (off + trace) / off,
            1e6 * trace / f64::from(steps * n),
        );

        // One step per frame: render after a plain step (as before) and after a traced step
        // (now), two copies of the world in lockstep, frames interleaved so load hits both alike.
        let frames = 60;
        let (mut before, mut now, mut traces, mut frame_now) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for _ in 0..REPS {
            let (mut a, mut b) = (start.clone(), start.clone());
            let (mut ra, mut rb) = (Renderer::new(CANVAS.0, CANVAS.1), Renderer::new(CANVAS.0, CANVAS.1));
            ra.render(&a);
            rb.render(&b);
            let (mut render_a, mut render_b, mut trace, mut frame) = (0.0, 0.0, 0.0, 0.0);
            for _ in 0..frames {
                a.step();
                let t = Instant::now();
                ra.render(&a);
                render_a += ms_since(t);
                let t0 = Instant::now();
                b.step();
                let t1 = Instant::now();
                rb.trace_step(&b);
                let t2 = Instant::now();
                rb.render(&b);
                render_b += ms_since(t2);
                trace += (t2 - t1).as_secs_f64() * 1e3;
                frame += ms_since(t0);
            }
            assert!(ra.pixels() == rb.pixels(), "a traced single step draws the same frame");
            let per_frame = |ms: f64| ms / f64::from(frames);
            before.push(per_frame(render_a));
            now.push(per_frame(render_b));
            traces.push(per_frame(trace));
            frame_now.push(per_frame(frame));
        }
        let (before, now, trace, frame) = (median(before), median(now), median(traces), median(frame_now));
        println!(
            "{:6} one step per frame (same pixels): render {before:.3} ms before, {now:.3} ms now \
             (ratio {:.3}); trace_step {trace:.3} ms = {:.1} % of the step+trace+render frame",
            "",
            now / before,
            100.0 * trace / frame,
        );

        // A timeline jump: rebuild from recorded positions over the rebuild budget.
        let mut world = start.clone();
        let mut history = vec![(world.step_count(), world.positions().to_vec())];
        for _ in 0..600 {
            world.step();
            history.push((world.step_count(), world.positions().to_vec()));
        }
        let mut r = Renderer::new(CANVAS.0, CANVAS.1);
        r.render(&world);
        let from = r.trail_rebuild_start(&world);
        let mut rebuild = Vec::new();
        for _ in 0..REPS {
            let t = Instant::now();
            r.rebuild_trails(&world, history.iter().filter(|h| h.0 >= from).cloned());
            rebuild.push(ms_since(t));
        }
        println!(
            "{:6} timeline jump at step {}: rebuilds steps {from}… ({} frames) in {:.1} ms \
             (default fade 0.01)",
            "",
            world.step_count(),
            world.step_count() - from,
            median(rebuild),
        );
    }
}
