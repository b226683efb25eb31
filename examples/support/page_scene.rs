//! The page benchmark's scene (`scripts/bench-page.mjs`), shared by the native examples that
//! reproduce it: the `open-field` preset scaled to N agents at the kernel bench's density (about 9
//! neighbours within 50 px) at its 8:5 shape, one group of `planner` with its defaults, spawned
//! `spread` over the field or packed in a square with room for 1.5 bodies per agent.

use flockpath::{presets, PlannerKind};

/// The scene of one page-bench case.
pub fn scene(planner: &str, n: u32, layout: &str) -> flockpath::Scene {
    let mut scene = presets::open_field();
    let density = 9.0 / (std::f32::consts::PI * 50.0 * 50.0);
    let width = (n as f32 / density * 1.6).sqrt();
    let height = width / 1.6;
    let (sx, sy) = (width / scene.width, height / scene.height);
    scene.width = width;
    scene.height = height;
    for goal in &mut scene.goals {
        goal.position = [goal.position[0] * sx, goal.position[1] * sy];
        goal.radius *= (sx * sy).sqrt();
    }
    let group = &mut scene.groups[0];
    group.count = n;
    group.planner = PlannerKind::parse(planner).expect("a planner name").default_config();
    let side = (n as f32 * 1.5).sqrt() * 2.0 * group.agent_radius;
    if layout == "spread" {
        group.spawn.min = [10.0, 10.0];
        group.spawn.max = [width - 10.0, height - 10.0];
    } else {
        group.spawn.min = [40.0, height / 2.0 - side / 2.0];
        group.spawn.max = [40.0 + side, height / 2.0 + side / 2.0];
    }
    scene
}
