//! Packed crowds: every neighbour rule is bounded per agent, so a pile of overlapping agents
//! costs a bounded amount of memory and work per agent.
//!
//! The memory bound of one step is measured on the process's resident memory (Linux: the peak
//! is reset through `/proc/self/clear_refs`, then read from `/proc/self/status`); the crate
//! forbids `unsafe`, so no counting allocator. Before the caps, the overlap counting alone kept
//! a list of every overlapping pair of the 200,000-agent pile (some 10^10), natively 1.3 GB and
//! not done after 500 s, and the wasm build panicked with `capacity overflow`.

use flockpath::spatial::{QueryCap, SpatialGrid, NEIGHBOUR_CAP};
use flockpath::{Goal, Group, PlannerKind, Region, Scene, World};
use glam::Vec2;

/// A `/proc/self/status` field in bytes (`VmRSS`, `VmHWM`).
fn status_bytes(field: &str) -> usize {
    let status = std::fs::read_to_string("/proc/self/status").expect("Linux /proc/self/status");
    let line = status.lines().find(|l| l.starts_with(field)).unwrap_or_else(|| panic!("no {field}"));
    let kib: usize = line.split_whitespace().nth(1).and_then(|v| v.parse().ok()).expect("a number of kB");
    kib * 1024
}

/// `count` agents of `planner` piled in a `w × h` px square at (100, 100) of a 1000 × 800 world,
/// heading for a goal on the right: a state a converging crowd can reach, though no scene spawns
/// it (the spawn keeps bodies apart), so the world starts from given positions.
fn pile(count: u32, planner: PlannerKind, size: (f32, f32)) -> World {
    let scene = pile_scene(count, planner, size);
    World::new_at(scene, pile_positions(count, size)).expect("valid scene")
}

/// `count` points spread over the `w × h` square at (100, 100) (a fixed low-discrepancy
/// sequence: the same pile everywhere).
fn pile_positions(count: u32, (w, h): (f32, f32)) -> Vec<Vec2> {
    const GOLDEN: f64 = 0.618_033_988_749_894_9;
    (0..count)
        .map(|i| {
            let u = (f64::from(i) + 0.5) / f64::from(count.max(1));
            let v = (f64::from(i) * GOLDEN).fract();
            Vec2::new(100.0 + w * u as f32, 100.0 + h * v as f32)
        })
        .collect()
}

fn pile_scene(count: u32, planner: PlannerKind, (w, h): (f32, f32)) -> Scene {
    let mut scene = Scene::empty(1000.0, 800.0);
    scene.goals.push(Goal::fixed([900.0, 400.0], 40.0));
    scene.groups.push(Group {
        name: "pile".into(),
        color: "#336699".into(),
        count,
        spawn: Region { min: [100.0, 100.0], max: [100.0 + w, 100.0 + h] },
        goal: Some(0),
        agent_radius: 4.0,
        planner: planner.default_config(),
    });
    scene
}

#[test]
fn a_step_of_200_000_packed_boids_needs_a_bounded_amount_of_memory_per_agent() {
    let n = 200_000usize;
    let mut world = pile(n as u32, PlannerKind::Boids, (120.0, 200.0));
    // Every test of this binary runs a small scene next to this one; a step of this one should
    // touch a few hundred bytes per agent (its grids, sums and metrics buffers, first filled here).
    std::fs::write("/proc/self/clear_refs", "5").expect("the peak resident memory can be reset");
    let before = status_bytes("VmRSS");
    // Step 1 also takes the fitness measures and counts the overlaps of the whole pile.
    world.step();
    let peak = status_bytes("VmHWM").saturating_sub(before);
    let per_agent = peak / n;
    assert!(per_agent <= 600, "a step needed {peak} more bytes at its peak, {per_agent} per agent");
    let m = world.metrics();
    assert!(m.collisions_last_step > 0, "the pile overlaps");
    assert_eq!(m.collisions_capped_steps, 1, "the overlap count of a pile is capped");
    assert!(world.positions().iter().all(|p| p.is_finite()));
}

#[test]
fn an_agent_in_a_pile_of_5000_considers_at_most_the_cap() {
    // 5,000 agents within 10 px of one point.
    let points: Vec<Vec2> =
        (0..5000).map(|i| Vec2::new(50.0 + (i % 100) as f32 * 0.1, 50.0 + (i / 100) as f32 * 0.2)).collect();
    let mut grid = SpatialGrid::new(200.0, 200.0, 50.0, points.len());
    grid.rebuild(&points, &[]);
    let p = Vec2::new(55.0, 55.0);
    let cap = QueryCap { neighbours: 64, candidates: 4096 };
    let mut seen = Vec::new();
    assert!(grid.for_each_within_capped(p, 50.0, cap, |n| seen.push(n.id)));
    assert_eq!(seen.len(), 64);
    // The first 64 in the uncapped query's order: the cap is deterministic.
    let mut all = Vec::new();
    grid.for_each_within(p, 50.0, |n| all.push(n.id));
    assert_eq!(all.len(), 5000);
    assert_eq!(seen, all[..64]);
    let mut slots = Vec::new();
    assert!(grid.gather_within(p, 50.0, cap, &mut slots));
    let ids = grid.columns().ids;
    assert_eq!(slots.iter().map(|&k| ids[k as usize]).collect::<Vec<_>>(), seen);
    // The candidate cap stops a scan of the pile even when few candidates are within reach.
    let tiny = QueryCap { neighbours: 5000, candidates: 300 };
    let mut counted = 0;
    assert!(grid.for_each_within_capped(p, 0.5, tiny, |_| counted += 1));
    assert!(grid.gather_within(p, 50.0, tiny, &mut slots));
    assert_eq!(slots.len(), 300);
    // The planners' shared cap holds in the pile: the first 2,048 of the 5,000 within reach.
    let mut count = 0;
    assert!(grid.for_each_within_capped(p, 50.0, NEIGHBOUR_CAP, |_| count += 1));
    assert_eq!(count, NEIGHBOUR_CAP.neighbours);
}

#[test]
fn every_capped_planner_steps_a_pile_of_5000_and_stays_finite() {
    for &kind in PlannerKind::ALL {
        let mut world = pile(5000, kind, (10.0, 10.0));
        world.step_n(2);
        assert!(
            world.positions().iter().zip(world.velocities()).all(|(p, v)| p.is_finite() && v.is_finite()),
            "{kind:?}"
        );
    }
}
