//! Prints what one page frame costs at the page benchmark's scenes (`scripts/bench-page.mjs`:
//! the `open-field` preset scaled to the kernel bench's density, one group, spread or packed),
//! natively, split as the page spends it: `World::step`, the trail tracing (`trace_step`), the
//! run's bookkeeping (recording, replay checkpoints, metric series: `Run::step_each` less the
//! other two), one `World::metrics()` and the render, wall-clock, medians over the timed steps.
//!
//! `taskset -c 0 cargo run --release --example page_cost [planner] [agents] [spread|packed] [skip] [steps]`

use flockpath::render::Renderer;
use flockpath::sim::run::{Run, RunOptions};
use std::time::Instant;

#[path = "support/median.rs"]
mod median;
use median::median;

/// Nanoseconds since `start`, wall-clock: `schedstat`'s on-CPU time only moves at scheduler
/// ticks (4 ms), too coarse for the parts of a frame; run pinned and take the medians.
fn now_ns(start: Instant) -> f64 {
    start.elapsed().as_nanos() as f64
}

#[path = "support/page_scene.rs"]
mod page_scene;
use page_scene::scene;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let planner = args.first().map_or("boids", String::as_str);
    let n: u32 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let layout = args.get(2).map_or("packed", String::as_str);
    let skip: u32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(20);
    let steps: u32 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(20);
    let sc = scene(planner, n, layout);
    let view = sc.view;
    let mut run = Run::new(sc, RunOptions::page()).expect("valid scene");
    let mut renderer = Renderer::new(1239, 640);
    renderer.set_trails(view.trails);
    renderer.set_trail_fade(view.trail_fade);
    run.step_each(skip, |w| renderer.trace_step(w));
    let clock = Instant::now();
    let (mut world_ms, mut trace_ms, mut run_ms, mut render_ms, mut metrics_ms) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for _ in 0..steps {
        // The world step alone, timed on a clone (so the run's own step stays the one recorded).
        let mut alone = run.world().clone();
        let t = now_ns(clock);
        alone.step();
        world_ms.push((now_ns(clock) - t) / 1e6);
        drop(alone);
        let mut traced = 0.0;
        let t = now_ns(clock);
        run.step_each(1, |w| {
            let t = now_ns(clock);
            renderer.trace_step(w);
            traced += now_ns(clock) - t;
        });
        let all = now_ns(clock) - t;
        trace_ms.push(traced / 1e6);
        run_ms.push(all / 1e6);
        let t = now_ns(clock);
        renderer.render(run.world());
        render_ms.push((now_ns(clock) - t) / 1e6);
        let t = now_ns(clock);
        std::hint::black_box(run.world().metrics());
        metrics_ms.push((now_ns(clock) - t) / 1e6);
    }
    let (w, r) = (median(world_ms), median(run_ms));
    println!(
        "{planner} {n} {layout}, steps {skip}..{}: world step {w:.2} ms, Run::step_each {r:.2} ms \
         (trace {:.2}, bookkeeping ≈ {:.2}), render {:.2} ms, metrics() {:.2} ms",
        skip + steps,
        median(trace_ms.clone()),
        r - w - median(trace_ms),
        median(render_ms),
        median(metrics_ms)
    );
}
