//! The collision-free speed model (Tordeux, Chraibi & Seyfried 2016) as a planner: its
//! fundamental diagram by construction in single file, no overlap in a bottleneck, a golden
//! digest of its preset (checked in wasm by `tests/web_baselines.rs`), and its selection by link
//! and CLI.

use flockpath::experiments::validation::record::record;
use flockpath::experiments::validation::scenes::periodic_corridor;
use flockpath::experiments::validation::suite::{periodic_point, HZ, MEASURE_S, PERIODIC_EVERY, WARM_UP_S};
use flockpath::experiments::validation::units::px;
use flockpath::model::codec::{scene_from_fragment, scene_to_fragment};
use flockpath::model::params::{CollisionFreeSpeedParams, PlannerConfig};
use flockpath::model::presets;
use flockpath::{Scene, World};
use std::process::Command;

/// Body radius of the single-file test (m): a body length ℓ = 0.3 m, so that 3 persons/m
/// (spacing 0.33 m) still fits in file.
const RADIUS_M: f32 = 0.15;
/// The single-file ring: 20 m long, 0.5 m wide.
const RING: (f32, f32) = (20.0, 0.5);

/// The measured point (density persons/m, speed m/s) of `per_metre` persons/m in the ring.
fn single_file_point(params: &CollisionFreeSpeedParams, per_metre: f32) -> (f64, f64) {
    let (length, width) = RING;
    let count = (per_metre * length).round() as u32;
    let cfg = PlannerConfig::CollisionFreeSpeed(params.clone());
    let (mut scene, band) = periodic_corridor("csm-single-file", &cfg, count, length, width);
    for g in &mut scene.groups {
        g.agent_radius = px(RADIUS_M);
    }
    let mut world = World::new_beyond_cost_limit(scene).expect("the ring is valid");
    world.set_periodic_x(Some(band));
    let rec = record(world, (WARM_UP_S + MEASURE_S) * HZ, PERIODIC_EVERY, |_| false);
    let point = periodic_point(&rec.traj, width).expect("walkers in the measurement area");
    (point.density * f64::from(width), point.speed)
}

/// A first-order model with the optimal-velocity function `V(s) = min(v⁰, max(0, (s − ℓ)/T))`
/// has its fundamental diagram by construction: in a homogeneous single file at ρ persons/m the
/// spacing is 1/ρ, so every walker walks at `min(v⁰, (1/ρ − ℓ)/T)`. Measured in the periodic ring
/// at 1, 2 and 3 persons/m (at the density measured, not the nominal one), the speed matches
/// within 0.05 m/s and falls with the density.
#[test]
fn single_file_speed_follows_the_optimal_velocity_function() {
    let params = CollisionFreeSpeedParams::default();
    let l = f64::from(2.0 * RADIUS_M);
    let (v0, t) = (f64::from(params.desired_speed), f64::from(params.time_gap));
    let mut last = f64::INFINITY;
    for rho in [1.0f32, 2.0, 3.0] {
        let (density, speed) = single_file_point(&params, rho);
        let expected = ((1.0 / density - l) / t).clamp(0.0, v0);
        println!(
            "{rho} persons/m: measured {density:.3} persons/m, {speed:.3} m/s; min(v0, (1/ρ − ℓ)/T) = {expected:.3}"
        );
        assert!((density - f64::from(rho)).abs() < 0.15 * f64::from(rho), "density {density} at {rho}");
        assert!((speed - expected).abs() < 0.05, "{rho} persons/m: {speed} m/s vs {expected}");
        assert!(speed < last, "speed falls with density: {speed} after {last}");
        last = speed;
    }
}

fn run(scene: Scene, steps: u32) -> World {
    let mut world = World::new(scene).expect("valid");
    world.step_n(steps);
    world
}

/// 60 pedestrians through a 1.6 m door: no two bodies ever overlap, nobody enters a wall, and
/// the room empties.
#[test]
fn the_bottleneck_has_no_overlap_and_empties() {
    let mut world = World::new(presets::csm_bottleneck()).expect("valid");
    let mut worst_pairs = 0;
    for _ in 0..40 {
        world.step_n(100);
        worst_pairs = worst_pairs.max(world.metrics().overall.collisions_agent_agent);
    }
    let m = world.metrics();
    println!(
        "collision-free bottleneck after 4000 steps: arrived {:.2}, overlapping pairs {}, wall penetrations {}",
        m.overall.arrived_share, m.overall.collisions_agent_agent, m.overall.penetrations_agent_obstacle
    );
    assert_eq!(worst_pairs, 0, "overlapping pairs");
    assert_eq!(m.overall.penetrations_agent_obstacle, 0);
    assert!(m.overall.arrived_share >= 0.95, "arrived {}", m.overall.arrived_share);
}

#[test]
fn the_preset_replays_exactly_and_matches_its_golden_digest() {
    let digest = |scene: Scene| run(scene, 300).digest();
    assert_eq!(digest(presets::csm_bottleneck()), digest(presets::csm_bottleneck()));
    let other = Scene { seed: 2, ..presets::csm_bottleneck() };
    assert_ne!(digest(other), digest(presets::csm_bottleneck()));
    let expected = include_str!("data/golden-baselines.txt")
        .lines()
        .find_map(|l| l.strip_prefix("csm-bottleneck").map(|d| d.trim().to_string()))
        .expect("a golden digest for csm-bottleneck");
    assert_eq!(format!("{:016x}", digest(presets::csm_bottleneck())), expected);
}

#[test]
fn the_model_is_selectable_by_link_and_by_the_cli() {
    let mut scene = presets::open_field();
    scene.groups[0].planner =
        PlannerConfig::CollisionFreeSpeed(CollisionFreeSpeedParams { time_gap: 0.8, ..Default::default() });
    let back = scene_from_fragment(&scene_to_fragment(&scene)).expect("the link decodes");
    assert_eq!(back, scene, "the planner and its parameters travel in the link");

    let out = Command::new(env!("CARGO_BIN_EXE_flockpath"))
        .args([
            "run",
            "--scene",
            "open-field",
            "--planner",
            "collision_free_speed",
            "--steps",
            "60",
            "--metrics",
            "-",
        ])
        .output()
        .expect("the binary runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let metrics: serde_json::Value = serde_json::from_slice(&out.stdout).expect("metrics JSON");
    assert_eq!(metrics["groups"][0]["planner"], "collision_free_speed");
}
