//! The scene of `tests/flow_field_sharing.rs`: groups of three planners guided by flow fields,
//! several heading for the same goal with the same body radius (they share one field), one with
//! other bodies and one heading for a moving goal (fields of their own).

use flockpath::model::geometry::Obstacle;
use flockpath::model::params::social_force::Ellipse;
use flockpath::model::params::{FlowGuide, PlannerConfig, PlannerKind};
use flockpath::model::scene::{Goal, GoalMotion, Region, Scene};
use flockpath::presets;

/// Steps the digest is taken after.
pub const STEPS: u32 = 200;

/// Nine groups of four agents among a wall and two pillars: ORCA ×3, social force ×2 and Boids
/// (flow field on) ×2 for goal 0 (one ORCA group with bodies of 6 px), Boids ×1 and ORCA ×1 for
/// the circling goal 1.
pub fn scene() -> Scene {
    let mut s = Scene::empty(1_000.0, 700.0);
    s.seed = 11;
    s.obstacles.push(Obstacle::Rect { min: [480.0, 0.0], max: [520.0, 420.0] });
    s.obstacles.push(Obstacle::Circle { center: [300.0, 550.0], radius: 40.0 });
    s.obstacles.push(Obstacle::Circle { center: [700.0, 250.0], radius: 50.0 });
    s.goals.push(Goal::fixed([880.0, 120.0], 30.0));
    let mut circling = Goal::fixed([800.0, 500.0], 25.0);
    circling.motion = Some(GoalMotion::Circle { center: [800.0, 450.0], radius: 60.0, period_steps: 240.0 });
    s.goals.push(circling);
    let template = presets::open_field().groups.remove(0);
    let boids_on_field = || {
        let mut config = PlannerKind::Boids.default_config();
        if let PlannerConfig::Boids(p) = &mut config {
            p.flow_field = FlowGuide::Goal;
        }
        config
    };
    // Spec I, as when `PINNED` was computed (spec II became social force's default later).
    let social_force_spec_i = || {
        let mut config = PlannerKind::SocialForce.default_config();
        if let PlannerConfig::SocialForce(p) = &mut config {
            p.ellipse = Ellipse::SpecI;
        }
        config
    };
    let plan: [(PlannerConfig, u32, f32); 9] = [
        (PlannerKind::Orca.default_config(), 0, 4.0),
        (PlannerKind::Orca.default_config(), 0, 4.0),
        (PlannerKind::Orca.default_config(), 0, 6.0),
        (social_force_spec_i(), 0, 4.0),
        (social_force_spec_i(), 0, 4.0),
        (boids_on_field(), 0, 4.0),
        (boids_on_field(), 0, 4.0),
        (boids_on_field(), 1, 4.0),
        (PlannerKind::Orca.default_config(), 1, 4.0),
    ];
    for (k, (planner, goal, radius)) in plan.into_iter().enumerate() {
        let mut g = template.clone();
        g.name = format!("g{k}");
        g.count = 4;
        let y = 40.0 + 70.0 * k as f32;
        g.spawn = Region { min: [40.0, y], max: [140.0, y + 40.0] };
        g.goal = Some(goal);
        g.agent_radius = radius;
        g.planner = planner;
        s.groups.push(g);
    }
    s
}
