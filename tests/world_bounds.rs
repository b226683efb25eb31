//! Agents stay in the world (issue 12 item 3) and spawn without overlap (item 2).
//!
//! A seeded property test over random small worlds, every planner: obstacles touching the
//! border, bodies wider than the world, several groups. After every step every centre lies in
//! the world rectangle. The spawn tests check the lattice placement: no two bodies overlap, no
//! body touches an obstacle, centres stay in their region, the density limit is named.

use flockpath::model::params::IgsaParams;
use flockpath::rng::Rng;
use flockpath::{
    presets, Goal, Group, Obstacle, PlannerConfig, PlannerKind, Region, Scene, SceneError, World,
};

const CASES: u32 = 200;

fn steps() -> u32 {
    if cfg!(debug_assertions) {
        150
    } else {
        400
    }
}

/// A planner of `kind`; IGSA with its smallest optimizer so planning stays quick.
fn planner(kind: PlannerKind) -> PlannerConfig {
    match kind {
        PlannerKind::Igsa => {
            PlannerConfig::Igsa(IgsaParams { population: 5, iterations: 10, ..IgsaParams::default() })
        }
        other => other.default_config(),
    }
}

/// An obstacle whose centre mostly lies near a border, so it leaves a narrow gap along it or
/// crosses it: the places where a push out of an obstacle can end beyond the border.
fn random_obstacle(rng: &mut Rng, w: f32, h: f32) -> Obstacle {
    let near = |rng: &mut Rng, side: f32| match rng.below(3) {
        0 => rng.range(-3.0, 6.0),
        1 => side - rng.range(-3.0, 6.0),
        _ => rng.range(0.0, side),
    };
    let c = [near(rng, w), near(rng, h)];
    if rng.below(2) == 0 {
        Obstacle::Circle { center: c, radius: rng.range(1.0, 0.6 * w.min(h)) }
    } else {
        let half = [rng.range(1.0, 0.5 * w), rng.range(1.0, 0.5 * h)];
        Obstacle::Rect { min: [c[0] - half[0], c[1] - half[1]], max: [c[0] + half[0], c[1] + half[1]] }
    }
}

/// A random small world: 10…60 px a side, up to three obstacles (see [`random_obstacle`]), up to three groups of 1…6 agents of radius 0.5…12 px (so some are wider than
/// the world), each with its own planner and, mostly, a goal.
fn random_scene(rng: &mut Rng, case: u32) -> Scene {
    let (w, h) = (rng.range(10.0, 60.0), rng.range(10.0, 60.0));
    let mut s = Scene::empty(w, h);
    s.seed = case;
    for _ in 0..rng.below(4) {
        s.obstacles.push(random_obstacle(rng, w, h));
    }
    let mut goal = [rng.range(0.0, w), rng.range(0.0, h)];
    for _ in 0..20 {
        if !s.obstacles.iter().any(|o| o.contains(goal.into())) {
            break;
        }
        goal = [rng.range(0.0, w), rng.range(0.0, h)];
    }
    s.goals.push(Goal::fixed(goal, rng.range(1.0, 10.0)));
    for g in 0..1 + rng.below(3) {
        let (x0, y0) = (rng.range(0.0, 0.5 * w), rng.range(0.0, 0.5 * h));
        let kind = PlannerKind::ALL[((case + g) % PlannerKind::ALL.len() as u32) as usize];
        s.groups.push(Group {
            name: format!("g{g}"),
            color: "#336699".into(),
            count: 1 + rng.below(8),
            spawn: Region { min: [x0, y0], max: [rng.range(0.5 * w, w), rng.range(0.5 * h, h)] },
            goal: (rng.below(4) != 0).then_some(0),
            agent_radius: if rng.below(5) == 0 { rng.range(0.5, 12.0) } else { rng.range(0.5, 2.5) },
            planner: planner(kind),
        });
    }
    s
}

fn assert_inside(world: &World, what: &str) {
    let (w, h) = (world.scene().width, world.scene().height);
    for (i, p) in world.positions().iter().enumerate() {
        assert!(
            p.x >= 0.0 && p.x <= w && p.y >= 0.0 && p.y <= h,
            "{what}: agent {i} at ({}, {}) left the {w}×{h} world",
            p.x,
            p.y
        );
    }
}

#[test]
fn no_agent_leaves_a_random_small_world() {
    let mut rng = Rng::new(12, 3);
    let mut ran = [0u32; PlannerKind::ALL.len()];
    let mut refused = 0;
    for case in 0..CASES {
        let scene = random_scene(&mut rng, case);
        let kinds: Vec<PlannerKind> = scene.groups.iter().map(|g| g.planner.kind()).collect();
        let mut world = match World::new(scene) {
            Ok(world) => world,
            Err(SceneError::Blocked(_)) => {
                // A goal inside an obstacle or a region too small for its count.
                refused += 1;
                continue;
            }
            Err(e) => panic!("case {case}: unexpected refusal {e}"),
        };
        assert_inside(&world, &format!("case {case} at spawn"));
        // A third of the way, an obstacle is dropped onto the running crowd (an edit keeps
        // the agents where they are): those under it are pushed out, never out of the world.
        let mut edited = world.scene().clone();
        edited.obstacles.push(random_obstacle(&mut rng, edited.width, edited.height));
        for step in 1..=steps() {
            if step == steps() / 3 {
                // Refused when it covers the goal; the run then goes on unchanged.
                let _ = world.edit_scene(edited.clone());
            }
            world.step();
            assert_inside(&world, &format!("case {case} ({kinds:?}) step {step}"));
        }
        for k in kinds {
            ran[PlannerKind::ALL.iter().position(|&x| x == k).expect("a planner")] += 1;
        }
    }
    println!(
        "{refused} of {CASES} random worlds refused (too dense, or the goal in an obstacle); ran {ran:?}"
    );
    assert!(refused < CASES / 2, "{refused} of {CASES} random scenes were refused");
    assert!(ran.iter().all(|&n| n >= 20), "every planner ran in enough worlds: {ran:?}");
}

/// The case: a 10×10 world with a radius-2 circle in the middle and bodies of radius 4.
fn ten_by_ten(kind: PlannerKind, count: u32) -> Scene {
    let mut s = Scene::empty(10.0, 10.0);
    s.obstacles.push(Obstacle::Circle { center: [5.0, 5.0], radius: 2.0 });
    s.goals.push(Goal::fixed([9.0, 9.0], 1.0));
    s.groups.push(Group {
        name: "crowd".into(),
        color: "#336699".into(),
        count,
        spawn: Region { min: [0.0, 0.0], max: [10.0, 10.0] },
        goal: Some(0),
        agent_radius: 4.0,
        planner: planner(kind),
    });
    s
}

#[test]
fn the_ten_by_ten_world_holds_its_agents_or_refuses_them_by_the_density_limit() {
    for &kind in PlannerKind::ALL {
        let e =
            World::new(ten_by_ten(kind, 1000)).err().expect("1000 bodies of radius 4 cannot fit in 10×10");
        let text = e.to_string();
        assert!(matches!(e, SceneError::Blocked(_)), "{text}");
        for part in ["group 1 (crowd)", "1000 agents", "density limit", "at most 0"] {
            assert!(text.contains(part), "{part:?} missing from {text:?}");
        }
        // Without the pillar the world holds one body wider than the world, centred.
        let mut scene = ten_by_ten(kind, 1);
        scene.obstacles.clear();
        scene.groups[0].agent_radius = 6.0;
        let mut world = World::new(scene).expect("one body fits");
        for step in 0..600 {
            world.step();
            assert_inside(&world, &format!("{kind:?} step {step}"));
        }
        assert_eq!(
            world.positions()[0],
            glam::Vec2::splat(5.0),
            "{kind:?}: a body wider than the world stays centred"
        );
        // The pillar dropped onto a running crowd (an edit keeps the agents where they are):
        // pushed out of it, nobody may be pushed out of the world.
        let mut scene = ten_by_ten(kind, 9);
        scene.obstacles.clear();
        scene.groups[0].agent_radius = 1.5;
        let mut world = World::new(scene.clone()).expect("nine small bodies fit");
        world.step_n(5);
        scene.obstacles.push(Obstacle::Circle { center: [5.0, 5.0], radius: 4.0 });
        world.edit_scene(scene).expect("the pillar is a valid edit");
        assert_eq!(world.step_count(), 5, "the edit kept the run");
        for step in 0..600 {
            world.step();
            assert_inside(&world, &format!("{kind:?} with the pillar, step {step}"));
        }
    }
}

/// Every pair of bodies is at least the sum of their radii apart (up to rounding).
fn assert_apart(world: &World, what: &str) {
    let (p, r) = (world.positions(), world.radii());
    let grid = world.grid();
    let reach = r.iter().copied().fold(0.0f32, f32::max) * 2.0;
    for i in 0..p.len() {
        grid.for_each_within(p[i], reach, |n| {
            let j = n.id as usize;
            if j != i {
                assert!(n.d2.sqrt() >= r[i] + r[j] - 1e-3, "{what}: agents {i} and {j} overlap at spawn");
            }
        });
    }
}

#[test]
fn spawned_bodies_never_overlap_each_other_or_obstacles_and_stay_in_their_region() {
    let mut scenes: Vec<Scene> = presets::ALL.iter().map(|p| (p.build)()).collect();
    // Two groups of different sizes sharing one region among pillars, packed near the limit.
    let mut mixed = presets::pillars();
    mixed.groups[0].spawn = Region { min: [250.0, 50.0], max: [500.0, 300.0] };
    mixed.groups[0].count = 450;
    let mut big = mixed.groups[0].clone();
    big.count = 30;
    big.agent_radius = 9.0;
    mixed.groups.push(big);
    scenes.push(mixed);
    for scene in scenes {
        let name = scene.name.clone();
        let world = World::new(scene.clone()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_apart(&world, &name);
        for (i, p) in world.positions().iter().enumerate() {
            let g = &scene.groups[world.group_of()[i] as usize];
            let r = world.radii()[i];
            for o in &scene.obstacles {
                assert!(o.surface(*p).signed_distance >= r - 1e-3, "{name}: agent {i} touches an obstacle");
            }
            let (lo, hi) = (g.spawn.min, g.spawn.max);
            let inside = |x: f32, a: f32, b: f32, side: f32| {
                let r = r.min(0.5 * side);
                x >= a.clamp(r, side - r) - 1e-3 && x <= b.clamp(r, side - r) + 1e-3
            };
            assert!(
                inside(p.x, lo[0], hi[0], scene.width) && inside(p.y, lo[1], hi[1], scene.height),
                "{name}: agent {i} at {p} outside its spawn region"
            );
        }
    }
}

#[test]
fn spawning_is_seeded_and_spreads_over_the_region() {
    let mut scene = presets::open_field();
    let a = World::new(scene.clone()).expect("valid");
    assert_eq!(a.positions(), World::new(scene.clone()).expect("valid").positions());
    scene.seed += 1;
    assert_ne!(a.positions(), World::new(scene.clone()).expect("valid").positions());
    // 60 agents in a 120×200 region: every quarter of the region gets some.
    let region = scene.groups[0].spawn;
    let mid = [0.5 * (region.min[0] + region.max[0]), 0.5 * (region.min[1] + region.max[1])];
    let mut quarters = [0; 4];
    for p in a.positions() {
        quarters[usize::from(p.x > mid[0]) + 2 * usize::from(p.y > mid[1])] += 1;
    }
    assert!(quarters.iter().all(|&q| q >= 8), "quarters {quarters:?}");
}

#[test]
fn the_crash_link_is_refused_by_the_density_limit_at_once() {
    // 200,000 agents (the maximum) in a 120×200 px region: it holds 416 bodies of radius 4.
    let mut scene = presets::open_field();
    scene.groups[0].count = 200_000;
    let e = World::new(scene).err().expect("too dense");
    let text = e.to_string();
    for part in ["group 1 (flock)", "200000 agents", "at most 416", "density limit"] {
        assert!(text.contains(part), "{part:?} missing from {text:?}");
    }
}

#[test]
fn a_region_that_just_holds_its_count_is_filled() {
    let mut scene = presets::open_field();
    scene.groups[0].count = 416;
    let world = World::new(scene).expect("exactly the capacity fits");
    assert_apart(&world, "full region");
}

/// Issue 24: switching a big crowd to a costlier planner was refused by the step-time estimate
/// while the page stepped on its main thread; the simulation runs in a worker now and the
/// estimate is gone (`src/sim/cost.rs`), so the switch is accepted and the run goes on.
#[test]
fn switching_a_big_crowd_to_a_costlier_planner_is_accepted() {
    // 20,000 Boids wander in a 4000×4000 world; as social-force pedestrians they once were over
    // the 180 ms step estimate.
    let mut scene = presets::open_field();
    (scene.width, scene.height) = (4000.0, 4000.0);
    scene.groups[0].count = 20_000;
    scene.groups[0].goal = None;
    scene.groups[0].spawn = Region { min: [0.0, 0.0], max: [4000.0, 4000.0] };
    let mut world = World::new(scene).expect("20,000 Boids load");
    world.step();
    world.set_group_planner(0, PlannerKind::SocialForce.default_config()).expect("accepted");
    assert_eq!(world.scene().groups[0].planner.kind(), PlannerKind::SocialForce);
    assert_eq!(world.step_count(), 1, "switching keeps the run");
}
