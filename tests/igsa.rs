//! IGSA group path control (DESIGN §3.4, issue 4 §3): planned paths stay clear of obstacles on
//! the igsa presets, the group reaches its goal, the collision metric agrees with a brute-force
//! count, planning never looks at the group, and the optimizer lab's reference run is pinned
//! (the same digest is checked in Chromium by `tests/web_lab.rs`).

use flockpath::model::geometry::Obstacle;
use flockpath::model::params::{IgsaParams, PlannerConfig};
use flockpath::planners::explain::PathSource;
use flockpath::planners::igsa::plan_group_path;
use flockpath::{presets, Scene, World};
use glam::Vec2;

/// Whether segment a→b meets an obstacle, by dense sampling (independent of `ray_cast`).
fn sampled_crossing(a: [f32; 2], b: [f32; 2], obstacles: &[Obstacle]) -> bool {
    let (a, b) = (Vec2::from(a), Vec2::from(b));
    let samples = (a.distance(b) / 0.5).ceil().max(1.0) as u32;
    (0..=samples).any(|k| {
        let p = a.lerp(b, k as f32 / samples as f32);
        obstacles.iter().any(|o| o.contains(p))
    })
}

fn igsa_presets() -> Vec<Scene> {
    ["igsa-path-1", "igsa-path-2", "igsa-crowd-1000"]
        .iter()
        .map(|name| (presets::find(name).expect("listed preset").build)())
        .collect()
}

#[test]
fn planned_paths_never_cross_obstacles_on_the_igsa_presets() {
    for scene in igsa_presets() {
        let world = World::new(scene.clone()).expect("valid preset");
        let path = world.planned_path(0).expect("the igsa planner plans a path");
        assert_eq!(path.source, PathSource::Igsa, "{}", scene.name);
        assert_eq!(path.points.len(), 3 + 2, "{}: start, K = 3 waypoints, goal", scene.name);
        // The straight line is blocked: the detour is the planner's doing.
        let (start, goal) = (path.points[0], path.points[path.points.len() - 1]);
        assert!(sampled_crossing(start, goal, &scene.obstacles), "{}", scene.name);
        for (k, w) in path.points.windows(2).enumerate() {
            assert!(
                !sampled_crossing(w[0], w[1], &scene.obstacles),
                "{} segment {k}: {:?}",
                scene.name,
                path.points
            );
            assert!(!path.crossing[k], "{} segment {k} flagged", scene.name);
        }
    }
}

#[test]
fn the_followers_reach_the_goal_without_entering_obstacles() {
    for name in ["igsa-path-1", "igsa-path-2"] {
        let mut world = World::new((presets::find(name).expect("preset").build)()).expect("valid");
        world.step_n(2500);
        let m = world.metrics();
        // Inside their goal now (igsa-path-1's goal is cut by the world's right edge: 39 of 40
        // have their places by step 2,500, the last still walking round the crowd).
        assert!(m.overall.arrived_share >= 0.95, "{name}: {m:?}");
        assert_eq!(m.overall.penetrations_agent_obstacle, 0, "{name}");
        // Once the random spawn overlaps are pushed apart, the bounding circles hold.
        assert_eq!(m.collisions_last_step, 0, "{name}");
    }
}

#[test]
fn collisions_counted_by_the_metric_equal_a_brute_force_count() {
    // An igsa group and a group of weighted-sum Boids crossing each other's way head-on: many
    // overlaps to count (spawns never overlap, so the crossing must make them).
    let mut scene = presets::igsa_path_1();
    let mut other = scene.groups[0].clone();
    other.name = "back".into();
    other.planner = flockpath::PlannerKind::Boids.default_config();
    other.spawn.min = [660.0, 200.0];
    other.spawn.max = [730.0, 300.0];
    other.count = 60;
    scene.goals.push(flockpath::Goal::fixed([60.0, 250.0], 50.0));
    other.goal = Some(1);
    scene.groups.push(other);
    scene.groups[0].count = 60;
    let mut world = World::new(scene).expect("valid");
    let mut brute: u64 = 0;
    let mut seen_any = false;
    for _ in 0..400 {
        world.step();
        let (pos, radius) = (world.positions(), world.radii());
        let mut this_step = 0u64;
        for a in 0..pos.len() {
            for b in a + 1..pos.len() {
                let r = radius[a] + radius[b];
                if pos[a].distance_squared(pos[b]) < r * r {
                    this_step += 1;
                }
            }
        }
        seen_any |= this_step > 0;
        brute += this_step;
        assert_eq!(u64::from(world.metrics().collisions_last_step), this_step);
    }
    assert!(seen_any, "the scene should produce some overlaps to count");
    assert_eq!(world.metrics().overall.collisions_agent_agent, brute);
}

#[test]
fn planning_does_not_look_at_the_group_size() {
    let small = World::new(presets::igsa_crowd(100)).expect("valid");
    let large = World::new(presets::igsa_crowd(1000)).expect("valid");
    let (a, b) = (small.planned_path(0).expect("path"), large.planned_path(0).expect("path"));
    assert_eq!(a, b);
    let bits = |p: &[[f32; 2]]| p.iter().flat_map(|q| [q[0].to_bits(), q[1].to_bits()]).collect::<Vec<_>>();
    assert_eq!(bits(&a.points), bits(&b.points));
    // And the seed does matter: another seed plans another path.
    let mut reseeded = presets::igsa_crowd(100);
    reseeded.seed = 2;
    let params = IgsaParams::default();
    let c = plan_group_path(&reseeded, 0, &params).expect("path");
    assert_ne!(bits(&a.points), bits(&c.points));
}

#[test]
fn gsa_can_be_chosen_and_edited_waypoints_replace_the_plan() {
    let mut scene = presets::igsa_path_2();
    let PlannerConfig::Igsa(params) = &mut scene.groups[0].planner else { panic!("igsa preset") };
    params.optimizer = flockpath::model::params::PathOptimizer::Gsa;
    let gsa = World::new(scene.clone()).expect("valid");
    assert_eq!(gsa.planned_path(0).expect("path").source, PathSource::Gsa);
    // A path straight through the wall: accepted, run, and its crossing segment flagged.
    let PlannerConfig::Igsa(params) = &mut scene.groups[0].planner else { panic!("igsa preset") };
    params.waypoints = vec![[400.0, 420.0]];
    let mut edited = World::new(scene).expect("an edited path that crosses is still a valid scene");
    let path = edited.planned_path(0).expect("path").clone();
    assert_eq!(path.source, PathSource::Edited);
    assert_eq!(path.points[1], [400.0, 420.0]);
    assert_eq!(path.crossing, vec![true, true]);
    edited.step_n(200);
    assert_eq!(edited.metrics().overall.penetrations_agent_obstacle, 0);
}

#[test]
fn the_lab_reference_run_matches_the_pinned_digest() {
    let pinned = include_str!("data/golden-optim.txt").trim();
    assert_eq!(flockpath::optim::lab::reference_digest(), pinned);
}

/// Issue 24: the page plans in slices bounded by objective evaluations (its worker calls
/// `advance_planning` until its time budget is spent); slices of 1, 7 or all evaluations must
/// plan the same paths and step to the same digest as planning at once.
#[test]
fn planning_in_slices_of_any_budget_gives_the_same_run() {
    let mut scene = presets::igsa_path_2();
    scene.groups.push(scene.groups[0].clone());
    for g in &mut scene.groups {
        let PlannerConfig::Igsa(params) = &mut g.planner else { panic!("igsa preset") };
        (params.population, params.iterations) = (16, 30);
    }
    let run = |budget: Option<u32>| {
        let mut world = match budget {
            None => World::new(scene.clone()).expect("valid"),
            Some(budget) => {
                let mut world = World::new_sliced(scene.clone()).expect("valid");
                let mut calls = 0u32;
                while world.advance_planning(budget) < 1.0 {
                    calls += 1;
                }
                assert!(calls > 0 || budget == u32::MAX, "slices of {budget} took {calls} calls");
                world
            }
        };
        let paths: Vec<_> = (0..2).map(|g| world.planned_path(g).expect("path").clone()).collect();
        world.step_n(100);
        (paths, world.digest())
    };
    let at_once = run(None);
    for budget in [1, 7, u32::MAX] {
        assert_eq!(run(Some(budget)), at_once, "slices of {budget} evaluations");
    }
}
