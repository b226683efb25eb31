//! Prints what one page frame's render costs for the page benchmark's scenes
//! (`scripts/bench-page.mjs`: the `open-field` preset scaled to the kernel bench's density, one
//! group, spread or packed), natively, on the page's 1280×800-ish canvas, after some steps.
//!
//! `taskset -c 0 cargo run --release --example render_cost [planner] [agents] [spread|packed] [steps]`

use flockpath::render::{Overlays, Renderer};
use flockpath::World;
use std::time::Instant;

#[path = "support/median.rs"]
mod median;
use median::median;

#[path = "support/page_scene.rs"]
mod page_scene;
use page_scene::scene;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let planner = args.first().map_or("igsa", String::as_str);
    let n: u32 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10_000);
    let layout = args.get(2).map_or("packed", String::as_str);
    let steps: u32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(200);
    let mut world = World::new(scene(planner, n, layout)).expect("valid scene");
    let t = Instant::now();
    world.step_n(steps);
    println!("{planner} {n} {layout}: {steps} steps in {:.0} ms", 1e3 * t.elapsed().as_secs_f64());
    let mut ms = Vec::new();
    let mut stuck = 0;
    for _ in 0..9 {
        let t = Instant::now();
        stuck = flockpath::sim::diagnose::stuck_agents(&world).len();
        ms.push(1e3 * t.elapsed().as_secs_f64());
    }
    println!("  stuck_agents: {stuck} agents in {:.2} ms", median(ms));
    for (label, overlays, trails) in [
        ("default overlays", Overlays::default(), true),
        ("no stuck rings", Overlays { stuck: false, ..Overlays::default() }, true),
        ("no stuck rings, trails off", Overlays { stuck: false, ..Overlays::default() }, false),
    ] {
        let mut w = world.clone();
        let mut r = Renderer::new(1239, 640);
        r.set_overlays(overlays);
        r.set_trails(trails);
        r.render(&w);
        // A frame as the page draws it: 2 steps (each traced), then the render; only the render
        // and the tracing are timed.
        let mut ms = Vec::new();
        for _ in 0..9 {
            let mut traced = 0.0;
            for _ in 0..2 {
                w.step();
                let t = Instant::now();
                r.trace_step(&w);
                traced += 1e3 * t.elapsed().as_secs_f64();
            }
            let t = Instant::now();
            r.render(&w);
            ms.push(traced + 1e3 * t.elapsed().as_secs_f64());
        }
        println!("  trace + render per frame, {label}: {:.2} ms", median(ms));
    }
}
