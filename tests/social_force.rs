//! The social force model (Helbing & Molnár 1995; body forces of Helbing, Farkas & Vicsek 2000)
//! as a planner: the driving term relaxes the speed to the desired one with time constant τ; the
//! wall repulsion has the papers' value at known distances; pedestrians at low density never
//! touch; the bottleneck preset replays bit for bit (natively here, in the browser in
//! `tests/web_baselines.rs`); the planner is selectable by link and by the CLI.

use flockpath::model::params::{Ellipse, Guidance, SocialForceParams};
use flockpath::planners::social_force::{agent_forces, driving, wall_contact, wall_repulsion, Body};
use flockpath::{
    presets, scene_from_fragment, scene_to_fragment, Goal, Group, PlannerConfig, Region, Scene, World, DT,
};
use glam::Vec2;
use std::process::Command;

/// px per metre of the scenes (20) and px/step per m/s.
const SCALE: f32 = 20.0;
const PX_STEP_PER_MS: f32 = SCALE * DT;

fn walker(count: u32, spawn: ([f32; 2], [f32; 2]), goal: u32, params: SocialForceParams) -> Group {
    Group {
        name: "walkers".into(),
        color: "#336699".into(),
        count,
        spawn: Region { min: spawn.0, max: spawn.1 },
        goal: Some(goal),
        agent_radius: 5.0,
        planner: PlannerConfig::SocialForce(params),
    }
}

#[test]
fn the_driving_term_relaxes_to_the_desired_speed_with_time_constant_tau() {
    // One pedestrian in the middle of a 100 m square, far from every wall, heading for a goal far
    // to the right: only the driving term acts. It starts at a quarter of the top speed.
    for tau in [0.5f32, 1.0] {
        let params = SocialForceParams {
            relaxation_time: tau,
            guidance: Guidance::Goal,
            ..SocialForceParams::default()
        };
        let v0 = params.desired_speed;
        let mut s = Scene::empty(2000.0, 2000.0);
        s.goals.push(Goal::fixed([1990.0, 1000.0], 5.0));
        s.groups.push(walker(1, ([990.0, 990.0], [1010.0, 1010.0]), 0, params));
        let mut world = World::new_at(s, vec![Vec2::new(1000.0, 1000.0)]).expect("valid");
        let start = world.velocities()[0].x / PX_STEP_PER_MS;
        assert!(start < 0.5 * v0, "starts slower than v⁰: {start}");
        let steps = (tau / DT).round() as u32;
        world.step_n(steps);
        let v = world.velocities()[0] / PX_STEP_PER_MS;
        assert!(v.y.abs() < 1e-4, "straight on: {v}");
        // v(t) = v⁰ − (v⁰ − v(0)) e^{−t/τ}: after one τ the gap is e⁻¹ of the start's.
        let left = (v0 - v.x) / (v0 - start);
        let expected = libm::expf(-1.0);
        assert!((left - expected).abs() < 0.02 * expected, "τ = {tau}: gap share {left}, e⁻¹ = {expected}");
        // Exactly the explicit Euler steps of dv/dt = (v⁰ − v)/τ.
        let euler = (1.0 - DT / tau).powi(steps as i32);
        assert!((left - euler).abs() < 1e-3, "τ = {tau}: {left} vs {euler}");
        // Then it walks at v⁰.
        world.step_n(10 * steps);
        let v = world.velocities()[0].x / PX_STEP_PER_MS;
        assert!((v - v0).abs() < 1e-3 * v0, "settles at v⁰ = {v0}: {v}");
    }
    // The function itself.
    let p = SocialForceParams::default();
    assert_eq!(driving(&p, Vec2::X, Vec2::ZERO), Vec2::new(1.34 / 0.5, 0.0));
}

#[test]
fn the_wall_repulsion_matches_the_formula_at_known_distances() {
    // U⁰ = 10 m²/s², R = 0.2 m: (U⁰/R) e^{−d/R}.
    let p = SocialForceParams::default();
    for (d, expected) in
        [(0.2f32, 50.0 * 0.367_879_4), (0.4, 50.0 * 0.135_335_3), (1.0, 50.0 * 0.006_737_947)]
    {
        let f = wall_repulsion(&p, d, Vec2::Y);
        assert!(f.x == 0.0 && (f.y - expected).abs() < 1e-4 * expected, "at {d} m: {f} vs {expected}");
    }
    // Touching (HFV eq. 3): k (r − d) / m along the normal; no contact force at a distance.
    let f = wall_contact(&p, 0.25, 0.2, Vec2::Y, Vec2::ZERO);
    assert!((f.y - 1.2e5 * 0.05 / 80.0).abs() < 1e-2 && f.x == 0.0, "{f}");
    assert_eq!(wall_contact(&p, 0.25, 0.3, Vec2::Y, Vec2::X), Vec2::ZERO);
    // Sliding along the wall brakes (friction against the motion).
    assert!(wall_contact(&p, 0.25, 0.2, Vec2::Y, Vec2::X).x < 0.0);

    // And in a run: a pedestrian standing 0.5 m from a wall on its left, desired speed tiny,
    // is pushed away from it by the formula's amount in its first step.
    let params =
        SocialForceParams { desired_speed: 0.1, guidance: Guidance::Goal, ..SocialForceParams::default() };
    let mut s = Scene::empty(2000.0, 2000.0);
    s.obstacles.push(flockpath::Obstacle::Rect { min: [900.0, 0.0], max: [990.0, 2000.0] });
    s.goals.push(Goal::fixed([1000.0, 1990.0], 5.0));
    s.groups.push(walker(1, ([995.0, 995.0], [1005.0, 1005.0]), 0, params.clone()));
    let mut world = World::new_at(s, vec![Vec2::new(1000.0, 1000.0)]).expect("valid");
    let v_before = world.velocities()[0] / PX_STEP_PER_MS;
    world.step();
    let v_after = world.velocities()[0] / PX_STEP_PER_MS;
    let e = Vec2::Y;
    let expected_x =
        v_before.x + DT * (driving(&params, e, v_before).x + wall_repulsion(&params, 0.5, Vec2::X).x);
    assert!((v_after.x - expected_x).abs() < 1e-5, "{} vs {expected_x}", v_after.x);
}

#[test]
fn pedestrians_at_low_density_never_touch() {
    // Two groups of 8 pass each other in a 40 m × 20 m hall, eastbound in the upper half and
    // westbound in the lower, spawned 1–3 m apart: the social forces alone keep every walking
    // pair apart. (Parked in a goal, a late arrival may brush an early one by a few hundredths of
    // a pixel: parking is not the model's, so pairs with an arrived agent are left out.)
    let mut s = Scene::empty(800.0, 400.0);
    let goals = [([740.0, 130.0], 50.0), ([60.0, 270.0], 50.0)];
    for (c, r) in goals {
        s.goals.push(Goal::fixed(c, r));
    }
    s.groups.push(walker(8, ([20.0, 40.0], [160.0, 220.0]), 0, SocialForceParams::default()));
    s.groups.push(walker(8, ([640.0, 180.0], [780.0, 360.0]), 1, SocialForceParams::default()));
    let mut world = World::new(s).expect("valid");
    let walking = |world: &World, i: usize| {
        let (c, r) = goals[world.group_of()[i] as usize];
        world.positions()[i].distance(Vec2::from(c)) > r
    };
    let (mut closest, mut pairs) = (f32::INFINITY, 0u32);
    for _ in 0..2400 {
        world.step();
        let p = world.positions();
        for i in 0..p.len() {
            for j in i + 1..p.len() {
                if walking(&world, i) && walking(&world, j) {
                    closest = closest.min(p[i].distance(p[j]));
                    pairs += 1;
                }
            }
        }
    }
    assert!(pairs > 10_000, "the groups walked together for a while: {pairs} pair-steps");
    assert!(closest >= 10.0, "two walking bodies (radius 0.25 m) touched: closest centres {closest} px");
    // Inside their goal now: a walker nudged back out of the disc by the others is not there.
    assert!(world.metrics().overall.arrived_share >= 0.9, "{}", world.metrics().overall.arrived_share);
}

/// A body of radius 0.25 m.
fn body(position: Vec2, velocity: Vec2) -> Body {
    Body { position, velocity, radius: 0.25 }
}

#[test]
fn the_agent_force_is_the_gradient_of_the_elliptical_potential() {
    // −∇V(b(r)) computed analytically equals central differences of V(b) = V⁰ e^{−b/σ}.
    let p = SocialForceParams { view_angle_deg: 360.0, ..SocialForceParams::default() };
    let v_b = Vec2::new(-1.2, 0.3);
    let potential = |r: Vec2| {
        let y = v_b * p.step_time;
        let b = 0.5 * ((r.length() + (r - y).length()).powi(2) - y.length_squared()).sqrt();
        p.agent_strength * (-(b / p.agent_range)).exp()
    };
    for r in [Vec2::new(1.0, 0.4), Vec2::new(-0.8, 1.1), Vec2::new(2.5, -0.5)] {
        let (f, contact) = agent_forces(&p, body(r, Vec2::ZERO), Vec2::ZERO, body(Vec2::ZERO, v_b));
        let h = 1e-3;
        let grad = Vec2::new(
            (potential(r + Vec2::X * h) - potential(r - Vec2::X * h)) / (2.0 * h),
            (potential(r + Vec2::Y * h) - potential(r - Vec2::Y * h)) / (2.0 * h),
        );
        assert!((f + grad).length() < 2e-3 * grad.length().max(1e-3), "at {r}: {f} vs {}", -grad);
        assert_eq!(contact, Vec2::ZERO, "not touching");
    }
    // Behind the pedestrian (outside its 200° view) the force is weighted by c = 0.5.
    let d = SocialForceParams::default();
    let ahead = agent_forces(&d, body(Vec2::ZERO, Vec2::ZERO), Vec2::X, body(Vec2::X, Vec2::ZERO)).0;
    let behind = agent_forces(&d, body(Vec2::ZERO, Vec2::ZERO), Vec2::X, body(Vec2::NEG_X, Vec2::ZERO)).0;
    assert!((behind.length() - 0.5 * ahead.length()).abs() < 1e-6, "{ahead} {behind}");
}

/// Spec II (Johansson, Helbing & Shukla 2007) stretches the ellipse along the relative step
/// `(v_β − v_α) Δt`: its force is the gradient of `V(b)` with that step; two pedestrians walking
/// side by side at one velocity are circles to each other (the force of two standing ones),
/// where spec I stretches the ellipse along β's own step; head-on, the closing speed stretches
/// it further than spec I does, so the push is stronger.
#[test]
fn spec_ii_stretches_the_ellipse_along_the_relative_step() {
    let p =
        SocialForceParams { view_angle_deg: 360.0, ellipse: Ellipse::SpecIi, ..SocialForceParams::default() };
    let (v_a, v_b) = (Vec2::new(0.9, 0.1), Vec2::new(-1.2, 0.3));
    let potential = |r: Vec2| {
        let y = (v_b - v_a) * p.step_time;
        let b = 0.5 * ((r.length() + (r - y).length()).powi(2) - y.length_squared()).sqrt();
        p.agent_strength * (-(b / p.agent_range)).exp()
    };
    for r in [Vec2::new(1.0, 0.4), Vec2::new(-0.8, 1.1), Vec2::new(2.5, -0.5)] {
        let (f, _) = agent_forces(&p, body(r, v_a), Vec2::ZERO, body(Vec2::ZERO, v_b));
        let h = 1e-3;
        let grad = Vec2::new(
            (potential(r + Vec2::X * h) - potential(r - Vec2::X * h)) / (2.0 * h),
            (potential(r + Vec2::Y * h) - potential(r - Vec2::Y * h)) / (2.0 * h),
        );
        assert!((f + grad).length() < 2e-3 * grad.length().max(1e-3), "at {r}: {f} vs {}", -grad);
    }
    let spec_i = SocialForceParams { ellipse: Ellipse::SpecI, ..p.clone() };
    let side = Vec2::new(0.0, 0.8);
    let walking = Vec2::new(1.3, 0.0);
    let together =
        |q: &SocialForceParams| agent_forces(q, body(side, walking), Vec2::ZERO, body(Vec2::ZERO, walking)).0;
    let standing = agent_forces(&spec_i, body(side, Vec2::ZERO), Vec2::ZERO, body(Vec2::ZERO, Vec2::ZERO)).0;
    assert!((together(&p) - standing).length() < 1e-6, "{} vs {standing}", together(&p));
    assert!((together(&spec_i) - standing).length() > 1e-3, "spec I sees β's own step");
    let ahead = Vec2::new(-6.0, 0.5);
    let head_on = |q: &SocialForceParams| {
        agent_forces(q, body(ahead, walking), Vec2::ZERO, body(Vec2::ZERO, -walking)).0
    };
    assert!(head_on(&p).length() > head_on(&spec_i).length(), "{} vs {}", head_on(&p), head_on(&spec_i));
}

fn run(scene: Scene, steps: u32) -> World {
    let mut world = World::new(scene).expect("valid");
    world.step_n(steps);
    world
}

#[test]
fn the_bottleneck_preset_empties_the_room_and_replays_exactly() {
    let world = run(presets::social_force_bottleneck(), 4000);
    let m = world.metrics();
    assert_eq!(m.overall.penetrations_agent_obstacle, 0);
    assert!(m.overall.arrived_share >= 0.8, "arrived {}", m.overall.arrived_share);
    assert_eq!(
        run(presets::social_force_bottleneck(), 300).digest(),
        run(presets::social_force_bottleneck(), 300).digest()
    );
    let other = Scene { seed: 2, ..presets::social_force_bottleneck() };
    assert_ne!(run(other, 300).digest(), run(presets::social_force_bottleneck(), 300).digest());
    let expected = include_str!("data/golden-baselines.txt")
        .lines()
        .find_map(|l| l.strip_prefix("social-force-bottleneck").map(|d| d.trim().to_string()))
        .expect("a golden digest for social-force-bottleneck");
    assert_eq!(format!("{:016x}", run(presets::social_force_bottleneck(), 300).digest()), expected);
}

#[test]
fn social_force_is_selectable_by_link_and_by_the_cli() {
    let mut scene = presets::open_field();
    scene.groups[0].planner = PlannerConfig::SocialForce(SocialForceParams {
        relaxation_time: 0.8,
        ..SocialForceParams::default()
    });
    let back = scene_from_fragment(&scene_to_fragment(&scene)).expect("the link decodes");
    assert_eq!(back, scene, "the planner and its parameters travel in the link");

    let out = Command::new(env!("CARGO_BIN_EXE_flockpath"))
        .args([
            "run",
            "--scene",
            "open-field",
            "--planner",
            "social_force",
            "--steps",
            "60",
            "--metrics",
            "-",
        ])
        .output()
        .expect("the binary runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let metrics: serde_json::Value = serde_json::from_slice(&out.stdout).expect("metrics JSON");
    assert_eq!(metrics["groups"][0]["planner"], "social_force");
}
