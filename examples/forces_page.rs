//! The page benchmark's scene (`scripts/bench-page.mjs`: the `open-field` preset scaled to N
//! agents, spawned spread or packed at 1.5 bodies per agent) with the virtual-forces planner,
//! natively: on-CPU ns per agent-step over the first steps (the page's few seconds) and a
//! digest of the positions (bit for bit: compare two builds).
//! `taskset -c 0 cargo run --release --example forces_page [N] [STEPS] [packed|spread]`
use flockpath::World;
use std::time::Instant;

#[path = "support/page_scene.rs"]
mod page_scene;
use page_scene::scene;

fn cpu_ns() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

fn main() {
    let n: u32 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10_000);
    let steps: u32 = std::env::args().nth(2).and_then(|a| a.parse().ok()).unwrap_or(40);
    let layout = std::env::args().nth(3).unwrap_or_else(|| "packed".into());
    let scene = scene("forces", n, &layout);
    let mut world = World::new_beyond_cost_limit(scene).expect("scene");
    let (t0, c0) = (Instant::now(), cpu_ns());
    world.step_n(steps);
    let spent = match (c0, cpu_ns()) {
        (Some(a), Some(b)) => (b - a) as f64,
        _ => t0.elapsed().as_nanos() as f64,
    };
    let digest = world.positions().iter().chain(world.velocities()).fold(0u64, |h, v| {
        (h ^ (u64::from(v.x.to_bits()) << 32 | u64::from(v.y.to_bits()))).wrapping_mul(0x100_0000_01b3)
    });
    println!(
        "{layout} {n}: {:.0} ns per agent-step over {steps} steps; digest {digest:016x}",
        spent / (f64::from(n) * f64::from(steps))
    );
}
