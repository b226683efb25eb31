//! A scene at the largest sizes a scene may have, shared by `tests/link_limit.rs` and
//! `tests/cli.rs`: every list at its limit (5,000 obstacles of which 50 polygons of 1,000 points,
//! 64 paths of 1,000 points, 256 hills, goals moving along 1,000-point routes), every name at
//! [`MAX_NAME_CHARS`] characters of random CJK text (three bytes each, hard to compress), and
//! then as many (empty) groups as the link limit lets in. Coordinates are full-precision random
//! `f32`s, so the link is about as long per item as a real scene's can be.

use flockpath::model::codec::{check_link_fits, MAX_LINK_CHARS};
use flockpath::model::geometry::Obstacle;
use flockpath::model::scene::{
    GoalMotion, Hill, PathSpec, MAX_HILLS, MAX_NAME_CHARS, MAX_OBSTACLES, MAX_PATHS,
};
use flockpath::rng::Rng;
use flockpath::{scene_to_fragment, Goal, Group, Region, Scene};

/// The world's side (the largest allowed): obstacles fill its right half, goals and spawn
/// regions its left half, so no goal lies inside an obstacle.
const SIDE: f32 = 20_000.0;
/// Polygons, and the points of each (50 × 1,000 = the 50,000 polygon points a scene may hold).
const POLYGONS: usize = 50;
const POLYGON_POINTS: usize = 1_000;
/// Points of each path and each goal route (the most a path or route may have).
const ROUTE_POINTS: usize = 1_000;
/// Goals, each moving along its own route.
const GOALS: usize = 8;

/// `MAX_NAME_CHARS` random CJK characters.
pub fn longest_name(rng: &mut Rng) -> String {
    (0..MAX_NAME_CHARS).map(|_| char::from_u32(0x4E00 + rng.below(20_000)).unwrap_or('名')).collect()
}

fn point_in(rng: &mut Rng, x: (f32, f32), y: (f32, f32)) -> [f32; 2] {
    [rng.range(x.0, x.1), rng.range(y.0, y.1)]
}

/// Every list at its limit, no groups yet.
fn full_scene_without_groups(rng: &mut Rng) -> Scene {
    let mut s = Scene::empty(SIDE, SIDE);
    s.name = longest_name(rng);
    s.seed = rng.next_u32();
    let right = (SIDE * 0.55, SIDE * 0.95);
    for _ in 0..POLYGONS {
        // A star around its centre: points in order of angle at random radii never cross.
        let c = point_in(rng, right, (1_000.0, SIDE - 1_000.0));
        let points = (0..POLYGON_POINTS)
            .map(|k| {
                let angle = std::f32::consts::TAU * k as f32 / POLYGON_POINTS as f32;
                let r = rng.range(100.0, 300.0);
                [c[0] + r * angle.cos(), c[1] + r * angle.sin()]
            })
            .collect();
        s.obstacles.push(Obstacle::Polygon { points });
    }
    while s.obstacles.len() < MAX_OBSTACLES {
        let center = point_in(rng, right, (0.0, SIDE));
        s.obstacles.push(Obstacle::Circle { center, radius: rng.range(1.0, 40.0) });
    }
    let left = (0.0, SIDE * 0.45);
    for _ in 0..GOALS {
        let mut goal = Goal::fixed(point_in(rng, left, (0.0, SIDE)), rng.range(5.0, 100.0));
        let points = (0..ROUTE_POINTS).map(|_| point_in(rng, left, (0.0, SIDE))).collect();
        goal.motion = Some(GoalMotion::Polyline { points, speed: rng.range(0.0, 5.0) });
        s.goals.push(goal);
    }
    for _ in 0..MAX_PATHS {
        let points = (0..ROUTE_POINTS).map(|_| point_in(rng, (0.0, SIDE), (0.0, SIDE))).collect();
        s.paths.push(PathSpec { points, radius: rng.range(5.0, 60.0) });
    }
    for _ in 0..MAX_HILLS {
        let center = point_in(rng, (0.0, SIDE), (0.0, SIDE));
        s.hills.push(Hill { center, radius: rng.range(10.0, 2_000.0), height: rng.range(0.0, 500.0) });
    }
    s
}

/// An empty group (count 0: it keeps its settings and spawns nothing, so running the scene
/// costs nothing) with the longest name.
fn group(rng: &mut Rng, goals: usize) -> Group {
    let min = point_in(rng, (0.0, SIDE * 0.2), (0.0, SIDE * 0.9));
    Group {
        name: longest_name(rng),
        color: format!("#{:06x}", rng.next_u32() & 0xFF_FFFF),
        count: 0,
        spawn: Region { min, max: [min[0] + 500.0, min[1] + 500.0] },
        goal: Some(rng.below(goals as u32)),
        agent_radius: rng.range(0.5, 100.0),
        planner: Default::default(),
    }
}

/// The scene's link's share of [`MAX_LINK_CHARS`] (1 = at the limit).
pub fn fullness(scene: &Scene) -> f64 {
    scene_to_fragment(scene).len() as f64 / MAX_LINK_CHARS as f64
}

/// The largest scene that loads, and `more`: the same scene with groups added until it no
/// longer loads.
pub fn largest_scene() -> (Scene, Scene) {
    let mut rng = Rng::new(24, 0);
    let mut scene = full_scene_without_groups(&mut rng);
    // Fill with groups in shrinking steps, measuring after each how much one group adds.
    const BATCH: usize = 200;
    let mut full = fullness(&scene);
    let mut add = BATCH;
    loop {
        for _ in 0..add {
            scene.groups.push(group(&mut rng, GOALS));
        }
        let fuller = fullness(&scene);
        let per_group = ((fuller - full) / add as f64).max(1e-9);
        full = fuller;
        let fit = (1.0 - full) / per_group;
        if fit < 4.0 {
            break;
        }
        add = ((fit * 0.8) as usize).max(1);
    }
    while check_link_fits(&scene).is_err() {
        assert!(scene.groups.pop().is_some(), "the scene without groups fits its link");
    }
    let mut more = scene.clone();
    while check_link_fits(&more).is_ok() {
        for _ in 0..8 {
            more.groups.push(group(&mut rng, GOALS));
        }
    }
    (scene, more)
}
