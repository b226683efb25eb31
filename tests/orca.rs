//! ORCA (van den Berg et al. 2011) as a planner: two agents walking straight at each other pass
//! without touching; the chosen velocity keeps every half-plane in crafted cases and is the
//! nearest to the preferred one; the crossing preset runs without a collision, arrives, and
//! replays bit for bit (natively here, in the browser in `tests/web_baselines.rs`); the planner is
//! selectable by link and by the CLI.

use flockpath::model::params::{Guidance, OrcaParams};
use flockpath::planners::orca::{agent_half_plane, solve, surface_half_plane, HalfPlane};
use flockpath::{
    presets, scene_from_fragment, scene_to_fragment, Goal, Group, PlannerConfig, Region, Scene, World,
};
use glam::Vec2;
use std::process::Command;

fn group(name: &str, goal: u32) -> Group {
    Group {
        name: name.into(),
        color: "#336699".into(),
        count: 1,
        spawn: Region { min: [0.0, 0.0], max: [10.0, 10.0] },
        goal: Some(goal),
        agent_radius: 5.0,
        planner: PlannerConfig::Orca(OrcaParams { guidance: Guidance::Goal, ..OrcaParams::default() }),
    }
}

#[test]
fn two_agents_head_on_pass_without_overlap_and_both_arrive() {
    // 40 m apart on one line, each heading for the other's start: exactly symmetric.
    let mut s = Scene::empty(1000.0, 300.0);
    s.goals.push(Goal::fixed([900.0, 150.0], 10.0));
    s.goals.push(Goal::fixed([100.0, 150.0], 10.0));
    s.groups.push(group("east-bound", 0));
    s.groups.push(group("west-bound", 1));
    let mut world = World::new_at(s, vec![Vec2::new(100.0, 150.0), Vec2::new(900.0, 150.0)]).expect("valid");
    let mut closest = f32::INFINITY;
    let mut sidestep = 0.0f32;
    for _ in 0..3000 {
        world.step();
        let p = world.positions();
        closest = closest.min(p[0].distance(p[1]));
        sidestep = sidestep.max((p[0].y - 150.0).abs());
    }
    assert!(closest >= 10.0, "the bodies (radius 5 px) overlapped: closest centres {closest} px");
    assert!(sidestep > 2.0, "they passed by stepping aside ({sidestep} px)");
    let m = world.metrics();
    assert_eq!(m.overall.collisions_agent_agent, 0);
    assert_eq!(m.overall.arrived_share, 1.0, "both reached the other side");
}

/// The velocity ORCA picks keeps every half-plane, lies in the speed disc, and no allowed
/// velocity on a fine grid is nearer the preferred one.
fn assert_optimal(lines: &[HalfPlane], v_pref: Vec2, max_speed: f32) -> Vec2 {
    let v = solve(lines, 0, v_pref, max_speed, &mut Vec::new());
    assert!(v.length() <= max_speed + 1e-5, "|v| = {} > {max_speed}", v.length());
    for (k, h) in lines.iter().enumerate() {
        assert!(h.violation(v) <= 1e-5, "half-plane {k} violated by {}: v = {v}", h.violation(v));
    }
    let best = v.distance(v_pref);
    let steps = 200;
    for a in 0..=steps {
        for b in 0..=steps {
            let s = Vec2::new(a as f32, b as f32) / steps as f32 * (2.0 * max_speed) - Vec2::splat(max_speed);
            if s.length() <= max_speed && lines.iter().all(|h| h.violation(s) <= 0.0) {
                assert!(s.distance(v_pref) >= best - 1e-4, "{s} is allowed and nearer v_pref than {v}");
            }
        }
    }
    v
}

#[test]
fn the_orca_velocity_satisfies_every_half_plane_in_a_crafted_case() {
    // Agent A at the origin walking right at 1 px/step among four neighbours: one ahead coming
    // towards it, one ahead-left walking the same way more slowly, one to the right crossing,
    // one behind; a wall 12 px below. τ = 60 steps, radii 5 px.
    let v_a = Vec2::new(1.0, 0.0);
    let neighbours = [
        (Vec2::new(60.0, 3.0), Vec2::new(-1.0, 0.0)),
        (Vec2::new(45.0, -22.0), Vec2::new(0.4, 0.0)),
        (Vec2::new(15.0, 25.0), Vec2::new(0.0, -0.8)),
        (Vec2::new(-25.0, 0.0), Vec2::new(1.2, 0.0)),
    ];
    let mut lines = vec![surface_half_plane(Vec2::NEG_Y, 12.0 - 5.0, 60.0)];
    for (q, w) in neighbours {
        lines.push(agent_half_plane(q, v_a - w, v_a, 10.0, 60.0, Vec2::X));
    }
    let v_pref = Vec2::new(1.0, 0.0);
    assert!(lines.iter().any(|h| h.violation(v_pref) > 0.0), "the crafted case must exclude v_pref");
    let v = assert_optimal(&lines, v_pref, 1.5);
    assert!(v.distance(v_pref) > 0.01, "{v}");
    // And each pair constraint is the paper's: A's new velocity avoids a collision within τ with
    // B keeping its velocity plus its half of the avoidance, so at least with B standing still
    // at its own velocity when A takes the whole: the relative velocity v − w is outside the
    // truncated velocity obstacle shifted by half of u, checked by sampling the next τ steps.
    for (q, w) in neighbours {
        let h = agent_half_plane(q, v_a - w, v_a, 10.0, 60.0, Vec2::X);
        let u2 = h.point - v_a;
        // B mirrors A's half: it changes its velocity by −u/2.
        let (rel_new, mut min_d) = ((v - (w - u2)), f32::INFINITY);
        for t in 0..=60 {
            min_d = min_d.min((q - rel_new * t as f32).length());
        }
        assert!(min_d >= 10.0 - 1e-3, "with {q} the pair would come within {min_d} px");
    }
}

#[test]
fn random_cases_keep_every_half_plane_and_the_speed_limit() {
    // 200 crafted crowds (a deterministic pattern): whenever the half-planes leave room, the
    // velocity keeps all of them and is the nearest allowed one.
    let mut solved_feasible = 0;
    for case in 0..200u32 {
        let f = |k: u32| ((case * 7919 + k * 104_729) % 1000) as f32 / 1000.0;
        let v_a = Vec2::new(f(1) - 0.5, f(2) - 0.5) * 2.0;
        let mut lines = Vec::new();
        for k in 0..(2 + case % 6) {
            let q = Vec2::new(f(10 + k) - 0.5, f(20 + k) - 0.5) * 80.0;
            let w = Vec2::new(f(30 + k) - 0.5, f(40 + k) - 0.5) * 2.0;
            if q.length() > 10.5 {
                lines.push(agent_half_plane(q, v_a - w, v_a, 10.0, 40.0, Vec2::X));
            }
        }
        let v_pref = Vec2::new(f(3) - 0.5, f(4) - 0.5) * 3.0;
        let v = solve(&lines, 0, v_pref, 1.5, &mut Vec::new());
        assert!(v.is_finite() && v.length() <= 1.5 + 1e-5, "case {case}: {v}");
        if lines.iter().all(|h| h.violation(v) <= 1e-5) {
            solved_feasible += 1;
            if case % 20 == 0 {
                assert_optimal(&lines, v_pref, 1.5);
            }
        }
    }
    assert!(solved_feasible > 150, "only {solved_feasible} of 200 cases were feasible");
}

#[test]
fn a_boxed_in_agent_keeps_the_walls_and_gives_up_the_agents_least() {
    // Walls 1 px away on both sides (hard), agents pressing from ahead and behind: no velocity
    // keeps everything, the wall half-planes are still kept.
    let walls = [surface_half_plane(Vec2::Y, 1.0, 60.0), surface_half_plane(Vec2::NEG_Y, 1.0, 60.0)];
    let v_a = Vec2::ZERO;
    let agents = [
        agent_half_plane(Vec2::new(9.0, 0.0), v_a - Vec2::new(-1.0, 0.0), v_a, 10.0, 60.0, Vec2::X),
        agent_half_plane(Vec2::new(-9.0, 0.0), v_a - Vec2::new(1.0, 0.0), v_a, 10.0, 60.0, Vec2::NEG_X),
    ];
    let lines: Vec<HalfPlane> = walls.iter().chain(agents.iter()).copied().collect();
    let v = solve(&lines, walls.len(), Vec2::new(1.0, 0.0), 1.5, &mut Vec::new());
    assert!(v.is_finite() && v.length() <= 1.5 + 1e-5, "{v}");
    for w in &walls {
        assert!(w.violation(v) <= 1e-5, "a wall was given up: {v}");
    }
    // Symmetric squeeze: the least-violating velocity stays between the two pushes.
    assert!(v.x.abs() < 1e-4, "{v}");
}

fn run(scene: Scene, steps: u32) -> World {
    let mut world = World::new(scene).expect("valid");
    world.step_n(steps);
    world
}

#[test]
fn the_crossing_preset_arrives_without_collisions_and_replays_exactly() {
    let world = run(presets::orca_crossing(), 2400);
    let m = world.metrics();
    assert_eq!(m.overall.collisions_agent_agent, 0, "ORCA kept every pair apart");
    assert_eq!(m.overall.penetrations_agent_obstacle, 0);
    assert!(m.overall.arrived_share >= 0.95, "arrived {}", m.overall.arrived_share);
    // Same scene and seed: the same run; another seed: another run.
    assert_eq!(run(presets::orca_crossing(), 300).digest(), run(presets::orca_crossing(), 300).digest());
    let other = Scene { seed: 2, ..presets::orca_crossing() };
    assert_ne!(run(other, 300).digest(), run(presets::orca_crossing(), 300).digest());
}

#[test]
fn the_crossing_preset_matches_its_golden_digest() {
    let expected = golden("orca-crossing");
    assert_eq!(format!("{:016x}", run(presets::orca_crossing(), 300).digest()), expected);
}

/// The golden digest of a baseline preset after 300 steps (`tests/data/golden-baselines.txt`,
/// also read by the browser test `tests/web_baselines.rs`).
fn golden(name: &str) -> String {
    include_str!("data/golden-baselines.txt")
        .lines()
        .find_map(|l| l.strip_prefix(name).map(|d| d.trim().to_string()))
        .unwrap_or_else(|| panic!("no golden digest for {name}"))
}

#[test]
fn a_wall_between_agent_and_goal_is_walked_round_by_the_flow_field() {
    let mut s = Scene::empty(600.0, 300.0);
    s.obstacles.push(flockpath::Obstacle::Rect { min: [280.0, 40.0], max: [320.0, 300.0] });
    s.goals.push(Goal::fixed([520.0, 200.0], 20.0));
    let mut g = group("walkers", 0);
    g.count = 6;
    g.spawn = Region { min: [40.0, 150.0], max: [120.0, 250.0] };
    g.planner = PlannerConfig::Orca(OrcaParams::default());
    s.groups.push(g.clone());
    let m = run(s.clone(), 3000).metrics();
    assert_eq!(m.overall.arrived_share, 1.0, "the flow field leads over the wall's top end");
    assert_eq!(m.overall.penetrations_agent_obstacle, 0);
    // Heading straight for the goal, they stay behind the wall.
    s.groups[0].planner =
        PlannerConfig::Orca(OrcaParams { guidance: Guidance::Goal, ..OrcaParams::default() });
    assert_eq!(run(s, 3000).metrics().overall.arrived_share, 0.0);
}

#[test]
fn orca_is_selectable_by_link_and_by_the_cli() {
    let mut scene = presets::open_field();
    scene.groups[0].planner =
        PlannerConfig::Orca(OrcaParams { time_horizon: 3.5, max_neighbours: 7, ..OrcaParams::default() });
    let back = scene_from_fragment(&scene_to_fragment(&scene)).expect("the link decodes");
    assert_eq!(back, scene, "the planner and its parameters travel in the link");
    // A link of an older kind (boids) still decodes to boids.
    assert!(matches!(
        scene_from_fragment(&scene_to_fragment(&presets::open_field())).expect("decodes").groups[0].planner,
        PlannerConfig::Boids(_)
    ));

    let out = Command::new(env!("CARGO_BIN_EXE_flockpath"))
        .args(["run", "--scene", "open-field", "--planner", "orca", "--steps", "60", "--metrics", "-"])
        .output()
        .expect("the binary runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let metrics: serde_json::Value = serde_json::from_slice(&out.stdout).expect("metrics JSON");
    assert_eq!(metrics["groups"][0]["planner"], "orca");
    assert_eq!(metrics["steps"], 60);
}
