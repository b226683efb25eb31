//! Named scenes: one name→builder table shared by the page, the CLI, the tests and the benches.

use crate::geometry::Obstacle;
use crate::planners::PlannerConfig;
use crate::scene::{Goal, Group, Region, Scene};

/// A named scene builder.
#[derive(Clone, Copy, Debug)]
pub struct Preset {
    /// Stable name (URL, CLI, tests).
    pub name: &'static str,
    /// One-line description shown in the UI.
    pub description: &'static str,
    /// Builds the scene.
    pub build: fn() -> Scene,
}

/// Every preset, in menu order. The first is the page's default scene.
pub const ALL: &[Preset] = &[
    Preset {
        name: "pillars",
        description: "A flock crosses a field of circular pillars to the goal on the right.",
        build: pillars,
    },
    Preset {
        name: "open-field",
        description: "One group crosses an empty field to its goal.",
        build: open_field,
    },
    Preset {
        name: "two-groups-swap",
        description: "Two groups swap sides and pass through each other.",
        build: two_groups_swap,
    },
    Preset {
        name: "corridor",
        description: "A group squeezes through a rectangle-walled passage.",
        build: corridor,
    },
];

/// Looks a preset up by name.
pub fn find(name: &str) -> Option<&'static Preset> {
    ALL.iter().find(|p| p.name == name)
}

fn group(name: &str, color: &str, count: u32, spawn: ([f32; 2], [f32; 2]), goal: u32) -> Group {
    Group {
        name: name.into(),
        color: color.into(),
        count,
        spawn: Region { min: spawn.0, max: spawn.1 },
        goal: Some(goal),
        agent_radius: 4.0,
        planner: PlannerConfig::default(),
    }
}

fn base(name: &str, width: f32, height: f32) -> Scene {
    Scene { name: name.into(), ..Scene::empty(width, height) }
}

/// One group crosses an empty field.
pub fn open_field() -> Scene {
    let mut s = base("open-field", 800.0, 500.0);
    s.goals.push(Goal { position: [700.0, 250.0], radius: 40.0 });
    s.groups.push(group("flock", "#2f6fdf", 60, ([40.0, 150.0], [160.0, 350.0]), 0));
    s
}

/// A flock crossing a staggered field of pillars.
pub fn pillars() -> Scene {
    let mut s = base("pillars", 900.0, 560.0);
    for col in 0..4 {
        for row in 0..4 {
            let x = 300.0 + col as f32 * 100.0;
            let y = 110.0 + row as f32 * 110.0 + if col % 2 == 1 { 55.0 } else { 0.0 };
            s.obstacles.push(Obstacle::Circle { center: [x, y], radius: 22.0 });
        }
    }
    s.goals.push(Goal { position: [830.0, 280.0], radius: 40.0 });
    s.groups.push(group("flock", "#2f6fdf", 80, ([30.0, 170.0], [170.0, 390.0]), 0));
    s
}

/// Two groups swap sides.
pub fn two_groups_swap() -> Scene {
    let mut s = base("two-groups-swap", 900.0, 500.0);
    s.goals.push(Goal { position: [820.0, 250.0], radius: 40.0 });
    s.goals.push(Goal { position: [80.0, 250.0], radius: 40.0 });
    s.groups.push(group("left", "#2f6fdf", 50, ([30.0, 150.0], [150.0, 350.0]), 0));
    s.groups.push(group("right", "#df4f2f", 50, ([750.0, 150.0], [870.0, 350.0]), 1));
    s
}

/// A group squeezes through a passage between two rectangular walls.
pub fn corridor() -> Scene {
    let mut s = base("corridor", 900.0, 500.0);
    s.obstacles.push(Obstacle::Rect { min: [350.0, 0.0], max: [550.0, 205.0] });
    s.obstacles.push(Obstacle::Rect { min: [350.0, 295.0], max: [550.0, 500.0] });
    s.goals.push(Goal { position: [820.0, 250.0], radius: 40.0 });
    s.groups.push(group("flock", "#2f9f5f", 60, ([30.0, 100.0], [200.0, 400.0]), 0));
    s
}

/// A square world of `n` wandering agents at constant density, about `neighbours` agents inside
/// each agent's perception radius (benchmarks: per-agent cost should not grow with `n`).
pub fn constant_density(n: u32, neighbours: f32) -> Scene {
    let perception = crate::planners::BoidsParams::default().perception_radius;
    let density = neighbours / (std::f32::consts::PI * perception * perception);
    let side = (n as f32 / density).sqrt().max(100.0);
    let mut s = base(&format!("density-{n}"), side, side);
    let mut g = group("crowd", "#2f6fdf", n, ([0.0, 0.0], [side, side]), 0);
    g.goal = None;
    s.groups.push(g);
    s
}

/// Path 1 of the IGSA experiments: pillars block the straight line from start to goal.
/// (Not in [`ALL`] until the `igsa` crowd planner lands: Boids, the groups' default planner,
/// is not meant to find these detours, and every listed preset must be reachable by Boids.)
pub fn igsa_path_1() -> Scene {
    let mut s = base("igsa-path-1", 800.0, 500.0);
    for (c, r) in
        [([260.0, 260.0], 70.0), ([430.0, 165.0], 65.0), ([450.0, 365.0], 60.0), ([610.0, 255.0], 55.0)]
    {
        s.obstacles.push(Obstacle::Circle { center: c, radius: r });
    }
    s.goals.push(Goal { position: [745.0, 250.0], radius: 30.0 });
    s.groups.push(group("group", "#2f6fdf", 40, ([30.0, 215.0], [100.0, 285.0]), 0));
    s
}

/// Path 2 of the IGSA experiments: a wall from the bottom edge forces a detour over its top
/// end; a triangle and a disc add clutter on both sides.
pub fn igsa_path_2() -> Scene {
    let mut s = base("igsa-path-2", 800.0, 500.0);
    s.obstacles.push(Obstacle::Rect { min: [380.0, 150.0], max: [425.0, 500.0] });
    s.obstacles.push(Obstacle::Polygon { points: vec![[170.0, 250.0], [255.0, 160.0], [265.0, 330.0]] });
    s.obstacles.push(Obstacle::Circle { center: [590.0, 250.0], radius: 60.0 });
    s.goals.push(Goal { position: [745.0, 330.0], radius: 30.0 });
    s.groups.push(group("group", "#df4f2f", 40, ([30.0, 380.0], [110.0, 460.0]), 0));
    s
}
