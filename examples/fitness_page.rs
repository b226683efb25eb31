//! The fitness sample's cost at the page benchmark's 100,000-agent Boids scene (as
//! `examples/page_cost.rs`): the world step with the fitness measures sampled every step less
//! the step with them never sampled, wall-clock medians, alternating the two settings on clones
//! of one world (so both step the same crowd).
//!
//! `taskset -c 1 cargo run --release --example fitness_page [planner] [agents] [spread|packed] [skip] [steps]`

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
    let planner = args.first().map_or("boids", String::as_str);
    let n: u32 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let layout = args.get(2).map_or("packed", String::as_str);
    let skip: u32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(20);
    let steps: u32 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(10);
    let mut world = World::new(scene(planner, n, layout)).expect("valid scene");
    world.step_n(skip);
    let (mut with, mut without) = (Vec::new(), Vec::new());
    for _ in 0..steps {
        for (every, out) in [(1, &mut with), (0, &mut without)] {
            let mut w = world.clone();
            w.set_fitness_sample_every(every);
            let t = Instant::now();
            w.step();
            out.push(t.elapsed().as_secs_f64() * 1e3);
        }
        world.step();
    }
    let (a, b) = (median(with), median(without));
    println!(
        "{planner} {n} {layout}: step with the fitness sample {a:.2} ms, without {b:.2} ms, sample {:.2} ms",
        a - b
    );
}
