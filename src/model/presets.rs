//! Named scenes: one name→builder table shared by the page, the CLI, the tests and the benches.

use crate::model::forces_cases::{Behaviour, Environment};
use crate::model::geometry::Obstacle;
use crate::model::palette::{BLUE, BLUISH_GREEN, ORANGE, REDDISH_PURPLE, VERMILLION};
use crate::model::params::boids::{Arbitration, FlowGuide, Leader, Role};
use crate::model::params::{
    BoidsParams, CollisionFreeSpeedParams, FireflyParams, IgsaParams, OrcaParams, PlannerConfig, PsoParams,
    SocialForceParams,
};
use crate::model::scene::{Goal, GoalMotion, Group, Hill, OnArrival, PathSpec, Region, Scene};
use crate::rng::Rng;

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
        description: "Boids, priority arbitration: watch the flock split round the 16 pillars without touching them, close up again and gather inside the goal ring on the right.",
        build: pillars,
    },
    Preset {
        name: "open-field",
        description: "Boids with nothing in the way: watch 60 agents keep their spacing as they cross the field and gather inside the goal ring on the right.",
        build: open_field,
    },
    Preset {
        name: "two-groups-swap",
        description: "Two Boids groups swap sides: watch blue and red meet in the middle, pass through each other and each gather inside the ring the other one left.",
        build: two_groups_swap,
    },
    Preset {
        name: "corridor",
        description: "Boids through a 90 px gap between two walls: watch the flock narrow into a queue at the entrance, then spread out again into the goal ring on the right.",
        build: corridor,
    },
    Preset {
        name: "pso-influx",
        description: "PSO (Chen & Lin Fig. 3): watch 20 people scattered over the whole field converge from every side on the target ring in the centre.",
        build: pso_influx,
    },
    Preset {
        name: "pso-stream",
        description: "PSO (Fig. 4): watch 20 people on the left first draw together into one group, then walk as a group to the target ring on the right.",
        build: pso_stream,
    },
    Preset {
        name: "pso-static-obstacle",
        description: "PSO (Fig. 5): watch 20 people along the top edge bend round the obstacle at (500, 15) on their way to the target on the right; turn acceptance off and they walk through it.",
        build: pso_static_obstacle,
    },
    Preset {
        name: "pso-dodge",
        description: "PSO (Fig. 6): watch two people walking head-on step aside just before they meet, pass each other and reach each other's start.",
        build: pso_dodge,
    },
    Preset {
        name: "pso-crowd",
        description: "PSO (Fig. 7): watch two crowds of 20 meet in the middle, thread through each other, and each reach the target ring on the opposite side.",
        build: pso_crowd,
    },
    Preset {
        name: "pso-circle-target",
        description: "PSO (Figs. 8–9): the target ring circles the field (radius 250 px, one turn a minute); watch 20 people leave the centre, catch up with it and follow it round.",
        build: pso_circle_target,
    },
    Preset {
        name: "pso-four-corners",
        description: "PSO (Fig. 10): watch four groups of 10 cross to the opposite corners at once, giving way to each other round the central pillar.",
        build: pso_four_corners,
    },
    Preset {
        name: "firefly-migration",
        description: "Firefly (Zhang et al.): watch 80 fireflies follow brighter neighbours, form single files between the trees and reach the target ring on the right.",
        build: firefly_migration,
    },
    Preset {
        name: "u-trap",
        description: "A U-shaped cup opens towards the groups: watch the PSO, firefly and Boids agents walk into it and get stuck (flagged), while the purple Boids on a path go round it to the goal.",
        build: u_trap,
    },
    Preset {
        name: "forces-e1-open",
        description: "Virtual forces (E1): the goal ring moves right along the middle at 1.2 px/step; watch the group of 30 follow it across open space and keep up with it.",
        build: forces_e1_open,
    },
    Preset {
        name: "forces-e2-narrow",
        description: "Virtual forces (E2): the goal ring moves right through a 50 px gap in a wall; watch the group of 30 funnel through the gap after it.",
        build: forces_e2_narrow,
    },
    Preset {
        name: "forces-e3-cluttered",
        description: "Virtual forces (E3): the goal ring moves right through a grove of small pillars; watch the group of 30 weave between them to follow it.",
        build: forces_e3_cluttered,
    },
    Preset {
        name: "boids-leader",
        description: "Boids leader following: watch the first agent lead and the flock trail behind it without overtaking, all the way into the goal ring on the right.",
        build: boids_leader,
    },
    Preset {
        name: "boids-path",
        description: "Boids path following: watch the flock stay inside the winding path's 30 px corridor and gather inside the goal ring at its end.",
        build: boids_path,
    },
    Preset {
        name: "boids-flow-field",
        description: "Boids flow field: the straight way through the maze ends in a U-shaped trap; watch the flock follow the flow field round it and into the goal ring.",
        build: boids_flow_field,
    },
    Preset {
        name: "boids-predator",
        description: "Boids predator/prey: watch the green flock graze in its ring, then scatter and close ranks again whenever one of the two red predators comes near.",
        build: boids_predator,
    },
    Preset {
        name: "pso-hills",
        description: "PSO (§5.6): watch 300 people cross to the wide target on the right, walking over the lowest hill and going round the highest one, never climbing it; a few are held up at the hills (some flagged stuck).",
        build: pso_hills,
    },
    Preset {
        name: "igsa-path-1",
        description: "IGSA group path (Liu & Liu, Figs. 8–9): watch the dashed planned path thread between four pillars and 40 agents follow it to the goal; drag a waypoint to change it.",
        build: igsa_path_1,
    },
    Preset {
        name: "igsa-path-2",
        description: "IGSA group path (Figs. 10–11): a wall, a triangle and a disc; watch the planned path climb over the top of the wall and the group follow it to the goal.",
        build: igsa_path_2,
    },
    Preset {
        name: "igsa-crowd-1000",
        description: "IGSA group path (Table 4): watch 1000 agents follow one planned path round the large disc, avoiding each other, and fill the goal on the right.",
        build: igsa_crowd_1000,
    },
    Preset {
        name: "orca-crossing",
        description: "ORCA (van den Berg et al. 2011): four groups of 20 cross a 40 m × 30 m square; watch them meet in the centre and slip past each other, each taking the velocity nearest its wish that avoids the others.",
        build: orca_crossing,
    },
    Preset {
        name: "social-force-bottleneck",
        description: "Social force (Helbing & Molnár 1995, body forces of Helbing et al. 2000): watch 60 pedestrians press towards a 1.6 m door, an arch form in front of it, and the room empty through it.",
        build: social_force_bottleneck,
    },
    Preset {
        name: "csm-bottleneck",
        description: "Collision-free speed model (Tordeux et al. 2016): 60 pedestrians leave the room through the same 1.6 m door; watch them queue without touching, each slowing with the gap ahead.",
        build: csm_bottleneck,
    },
];

/// Looks a preset up by name.
pub fn find(name: &str) -> Option<&'static Preset> {
    ALL.iter().find(|p| p.name == name)
}

/// Looks a preset up by name; an unknown name is refused with the list of known ones.
pub fn lookup(name: &str) -> Result<&'static Preset, crate::model::scene::SceneError> {
    find(name).ok_or_else(|| crate::model::scene::SceneError::UnknownPreset {
        name: name.chars().take(40).collect(),
        known: ALL.iter().map(|p| p.name).collect(),
    })
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
    s.goals.push(Goal::fixed([700.0, 250.0], 60.0));
    s.groups.push(group("flock", BLUE, 60, ([40.0, 150.0], [160.0, 350.0]), 0));
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
    s.goals.push(Goal::fixed([820.0, 280.0], 70.0));
    // Priority arbitration: squeezing between pillars, the weighted sum lets 80 agents overlap
    // (about 25,000 overlapping pair-steps in 600 steps, against about 770 with priority).
    s.groups.push(with_boids(group("flock", BLUE, 80, ([30.0, 170.0], [170.0, 390.0]), 0), |_| {}));
    s
}

/// Two groups swap sides.
pub fn two_groups_swap() -> Scene {
    let mut s = base("two-groups-swap", 900.0, 500.0);
    s.goals.push(Goal::fixed([820.0, 250.0], 60.0));
    s.goals.push(Goal::fixed([80.0, 250.0], 60.0));
    s.groups.push(group("left", BLUE, 50, ([30.0, 150.0], [150.0, 350.0]), 0));
    s.groups.push(group("right", VERMILLION, 50, ([750.0, 150.0], [870.0, 350.0]), 1));
    s
}

/// A group squeezes through a passage between two rectangular walls.
pub fn corridor() -> Scene {
    let mut s = base("corridor", 900.0, 500.0);
    s.obstacles.push(Obstacle::Rect { min: [350.0, 0.0], max: [550.0, 205.0] });
    s.obstacles.push(Obstacle::Rect { min: [350.0, 295.0], max: [550.0, 500.0] });
    s.goals.push(Goal::fixed([820.0, 250.0], 60.0));
    s.groups.push(group("flock", BLUISH_GREEN, 60, ([30.0, 100.0], [200.0, 400.0]), 0));
    s
}

/// A U-shaped wall between three groups and their goal, opening towards them: the straight way
/// leads into the cup, a local minimum of every cost that only looks at the distance to the goal.
/// PSO (blue), firefly (orange) and Boids (green) groups start side by side on the left; a
/// fourth Boids group (purple) follows a path round the cup.
pub fn u_trap() -> Scene {
    let mut s = base("u-trap", 900.0, 600.0);
    s.obstacles.push(Obstacle::Rect { min: [520.0, 160.0], max: [550.0, 440.0] });
    s.obstacles.push(Obstacle::Rect { min: [360.0, 160.0], max: [550.0, 190.0] });
    s.obstacles.push(Obstacle::Rect { min: [360.0, 410.0], max: [550.0, 440.0] });
    s.goals.push(Goal::fixed([800.0, 300.0], 50.0));
    s.groups.push(pso_group("pso", BLUE, 15, ([60.0, 230.0], [160.0, 290.0]), 0));
    let firefly = PlannerConfig::Firefly(FireflyParams::default());
    s.groups
        .push(Group { planner: firefly, ..group("firefly", ORANGE, 15, ([60.0, 310.0], [160.0, 370.0]), 0) });
    s.groups.push(group("boids", BLUISH_GREEN, 15, ([60.0, 390.0], [160.0, 450.0]), 0));
    // Path following goes round the cup: guidance from above the local rules.
    let around = vec![[110.0, 520.0], [400.0, 520.0], [620.0, 490.0], [720.0, 390.0], [790.0, 310.0]];
    s.paths.push(PathSpec { points: around, radius: 30.0 });
    let walkers =
        boids_group("boids on a path", REDDISH_PURPLE, 15, ([60.0, 490.0], [160.0, 550.0]), Some(0));
    s.groups.push(with_boids(walkers, |p| p.path = 1));
    s
}

/// E1 with the following behaviour (B2), named as the preset (the page finds a preset's
/// description by its scene's name; [`forces_scene`] names it after the paper's case, `forces-b2-e1`).
pub fn forces_e1_open() -> Scene {
    following_preset("forces-e1-open", forces_scene(Behaviour::Following, Environment::Open))
}

/// E2 with the following behaviour (B2).
pub fn forces_e2_narrow() -> Scene {
    following_preset("forces-e2-narrow", forces_scene(Behaviour::Following, Environment::Narrow))
}

/// E3 with the following behaviour (B2).
pub fn forces_e3_cluttered() -> Scene {
    following_preset("forces-e3-cluttered", forces_scene(Behaviour::Following, Environment::Cluttered))
}

/// A following scene of the virtual-force experiment as the preset `name`: the goal the group
/// follows is wide enough to hold all 30 agents once it stops (radius 40 px holds about 65
/// bodies of radius 4), so the run ends with the group gathered inside it. The experiment's
/// own scenes keep the paper's small goal.
fn following_preset(name: &str, mut s: Scene) -> Scene {
    s.name = name.into();
    for goal in &mut s.goals {
        goal.radius = goal.radius.max(40.0);
    }
    s
}

/// Agents in every scene of the virtual-force experiment.
pub const FORCES_AGENTS: u32 = 30;

/// A scene of the virtual-force experiment (DESIGN §3.5): an 800×400 world, 30 agents with the
/// `forces` planner on the left, heading right. B1 heads for a fixed goal on the right; B2 and
/// B3 go with a goal that moves along the middle line (1.2 and 0.8 px/step).
pub fn forces_scene(behaviour: Behaviour, environment: Environment) -> Scene {
    let name = format!("forces-{}-{}", behaviour.code(), environment.code());
    let mut s = base(&name, 800.0, 400.0);
    match environment {
        Environment::Open => {}
        Environment::Narrow => {
            // A wall across the world with one 50 px gap (about six bodies wide).
            s.obstacles.push(Obstacle::Rect { min: [370.0, 0.0], max: [430.0, 175.0] });
            s.obstacles.push(Obstacle::Rect { min: [370.0, 225.0], max: [430.0, 400.0] });
        }
        Environment::Cluttered => {
            // Small pillars (radius 8 px) on a staggered 50 px lattice.
            for col in 0..9 {
                let x = 230.0 + col as f32 * 50.0;
                let offset = if col % 2 == 1 { 25.0 } else { 0.0 };
                for row in 0..8 {
                    let y = 30.0 + offset + row as f32 * 50.0;
                    if y < 390.0 {
                        s.obstacles.push(Obstacle::Circle { center: [x, y], radius: 8.0 });
                    }
                }
            }
        }
    }
    let mut flock = group("flock", REDDISH_PURPLE, FORCES_AGENTS, ([40.0, 140.0], [160.0, 260.0]), 0);
    flock.planner = PlannerConfig::Forces(crate::model::params::ForcesParams::default());
    match behaviour {
        Behaviour::GroupMoving => s.goals.push(Goal::fixed([730.0, 200.0], 40.0)),
        Behaviour::Following | Behaviour::Guarding => {
            let speed = if behaviour == Behaviour::Following { 1.2 } else { 0.8 };
            s.goals.push(Goal {
                position: [180.0, 200.0],
                radius: 20.0,
                motion: Some(GoalMotion::Polyline { points: vec![[180.0, 200.0], [740.0, 200.0]], speed }),
                on_arrival: OnArrival::Gather,
            });
            flock.spawn = Region { min: [60.0, 140.0], max: [170.0, 260.0] };
        }
    }
    s.groups.push(flock);
    s
}

/// A square world of `n` wandering agents at constant density, about `neighbours` agents inside
/// each agent's perception radius (benchmarks: per-agent cost should not grow with `n`).
pub fn constant_density(n: u32, neighbours: f32) -> Scene {
    let perception = crate::model::params::BoidsParams::default().perception_radius;
    let density = neighbours / (std::f32::consts::PI * perception * perception);
    let side = (n as f32 / density).sqrt().max(100.0);
    let mut s = base(&format!("density-{n}"), side, side);
    let mut g = group("crowd", BLUE, n, ([0.0, 0.0], [side, side]), 0);
    g.goal = None;
    s.groups.push(g);
    s
}

/// [`constant_density`] with every group heading for one goal of `goal_radius` px at the
/// world's centre (the per-planner benchmarks and cost examples).
pub fn constant_density_to_centre(n: u32, neighbours: f32, goal_radius: f32) -> Scene {
    let mut s = constant_density(n, neighbours);
    s.goals.push(Goal::fixed([0.5 * s.width, 0.5 * s.height], goal_radius));
    for g in &mut s.groups {
        g.goal = Some(0);
    }
    s
}

fn pso_group(name: &str, color: &str, count: u32, spawn: ([f32; 2], [f32; 2]), goal: u32) -> Group {
    Group { planner: PlannerConfig::Pso(PsoParams::default()), ..group(name, color, count, spawn, goal) }
}

/// PSO influx: 20 people scattered over the whole field converge on a central target.
pub fn pso_influx() -> Scene {
    let mut s = base("pso-influx", 1000.0, 600.0);
    // The ring holds the crowd the paper's objective gathers round the target (agents stay
    // an agent σ apart: 20 of them reach about 75 px out, measured at step 3000).
    s.goals.push(Goal::fixed([500.0, 300.0], 90.0));
    s.groups.push(pso_group("people", BLUE, 20, ([20.0, 20.0], [980.0, 580.0]), 0));
    s
}

/// PSO stream: 20 people on the left walk to a target on the right.
pub fn pso_stream() -> Scene {
    let mut s = base("pso-stream", 1000.0, 600.0);
    // Holds the gathered crowd (it reaches about 85 px from the target).
    s.goals.push(Goal::fixed([920.0, 300.0], 90.0));
    s.groups.push(pso_group("people", BLUE, 20, ([20.0, 100.0], [140.0, 500.0]), 0));
    s
}

/// The paper's static obstacle, at (500, 15) with σ = 30 (a circle of radius 30), lying across
/// the straight way of 20 people walking along the top edge.
pub fn pso_static_obstacle() -> Scene {
    let mut s = base("pso-static-obstacle", 1000.0, 300.0);
    s.obstacles.push(Obstacle::Circle { center: [500.0, 15.0], radius: 30.0 });
    // Holds the gathered crowd (it reaches about 80 px from the target).
    s.goals.push(Goal::fixed([950.0, 25.0], 110.0));
    s.groups.push(pso_group("people", BLUE, 20, ([10.0, 5.0], [110.0, 60.0]), 0));
    s
}

/// Two persons walking head-on, each towards the other's start.
pub fn pso_dodge() -> Scene {
    let mut s = base("pso-dodge", 800.0, 300.0);
    s.goals.push(Goal::fixed([700.0, 150.0], 15.0));
    s.goals.push(Goal::fixed([100.0, 150.0], 15.0));
    s.groups.push(pso_group("A", BLUE, 1, ([98.0, 149.0], [102.0, 151.0]), 0));
    s.groups.push(pso_group("B", VERMILLION, 1, ([698.0, 149.0], [702.0, 151.0]), 1));
    s
}

/// Two crowds of 20 walking through each other.
pub fn pso_crowd() -> Scene {
    let mut s = base("pso-crowd", 1000.0, 600.0);
    // Each holds its gathered crowd of 20 (about 70 px out).
    s.goals.push(Goal::fixed([900.0, 300.0], 85.0));
    s.goals.push(Goal::fixed([100.0, 300.0], 85.0));
    s.groups.push(pso_group("east", BLUE, 20, ([20.0, 180.0], [160.0, 420.0]), 0));
    s.groups.push(pso_group("west", VERMILLION, 20, ([840.0, 180.0], [980.0, 420.0]), 1));
    s
}

/// A target moving on a circle of radius 250 (one turn per 60 s), chased by 20 people.
pub fn pso_circle_target() -> Scene {
    let mut s = base("pso-circle-target", 1000.0, 700.0);
    // Wide enough for the 20 chasers to keep up inside it as it turns.
    let mut goal = Goal::fixed([750.0, 350.0], 70.0);
    goal.motion = Some(GoalMotion::Circle { center: [500.0, 350.0], radius: 250.0, period_steps: 3600.0 });
    s.goals.push(goal);
    s.groups.push(pso_group("chasers", BLUE, 20, ([440.0, 290.0], [560.0, 410.0]), 0));
    s
}

/// Four groups of 10 in the corners cross to the opposite corners past a central pillar.
pub fn pso_four_corners() -> Scene {
    let mut s = base("pso-four-corners", 800.0, 800.0);
    s.obstacles.push(Obstacle::Circle { center: [400.0, 400.0], radius: 40.0 });
    let corners = [([20.0, 20.0], [120.0, 120.0]), ([680.0, 20.0], [780.0, 120.0])];
    let corners = [corners[0], corners[1], ([680.0, 680.0], [780.0, 780.0]), ([20.0, 680.0], [120.0, 780.0])];
    let names = [
        ("north-west", BLUE),
        ("north-east", VERMILLION),
        ("south-east", BLUISH_GREEN),
        ("south-west", ORANGE),
    ];
    for (k, &(lo, hi)) in corners.iter().enumerate() {
        let (opposite_lo, opposite_hi) = corners[(k + 2) % 4];
        let centre = [0.5 * (opposite_lo[0] + opposite_hi[0]), 0.5 * (opposite_lo[1] + opposite_hi[1])];
        // Holds its gathered group of 10 (about 60 px out).
        s.goals.push(Goal::fixed(centre, 70.0));
        s.groups.push(pso_group(names[k].0, names[k].1, 10, (lo, hi), k as u32));
    }
    s
}

/// The firefly migration of the paper with seed 1; see [`firefly_migration_with_seed`].
pub fn firefly_migration() -> Scene {
    firefly_migration_with_seed(1)
}

/// 80 fireflies scattered over an 800×600 stage head for a gathering point on the right, among
/// circular obstacles (trees) placed at random from `seed` (the paper's §4.1 setting).
pub fn firefly_migration_with_seed(seed: u32) -> Scene {
    let mut s = base("firefly-migration", 800.0, 600.0);
    s.seed = seed;
    let target = glam::Vec2::new(740.0, 300.0);
    // Obstacle placement has its own random stream, so the agents' spawn stream is unchanged.
    let mut rng = Rng::new(seed, 7);
    let mut placed = 0;
    for _ in 0..200 {
        if placed == 6 {
            break;
        }
        let c = glam::Vec2::new(rng.range(150.0, 650.0), rng.range(60.0, 540.0));
        let r = rng.range(18.0, 40.0);
        let clear_of_target = c.distance(target) > r + 80.0;
        let clear_of_others = s.obstacles.iter().all(|o| match o {
            Obstacle::Circle { center, radius } => c.distance(glam::Vec2::from(*center)) > r + radius + 60.0,
            _ => true,
        });
        if clear_of_target && clear_of_others {
            s.obstacles.push(Obstacle::Circle { center: [c.x, c.y], radius: r });
            placed += 1;
        }
    }
    // Radius 55 px holds about 130 bodies of radius 4: the 80 gather inside it.
    s.goals.push(Goal::fixed([target.x, target.y], 55.0));
    s.groups.push(Group {
        planner: PlannerConfig::Firefly(FireflyParams::default()),
        ..group("fireflies", ORANGE, 80, ([20.0, 20.0], [560.0, 580.0]), 0)
    });
    s
}

fn igsa_group(name: &str, color: &str, count: u32, spawn: ([f32; 2], [f32; 2]), goal: u32) -> Group {
    Group { planner: PlannerConfig::Igsa(IgsaParams::default()), ..group(name, color, count, spawn, goal) }
}

/// Path 1 of the IGSA experiments: pillars block the straight line from start to goal.
pub fn igsa_path_1() -> Scene {
    let mut s = base("igsa-path-1", 800.0, 500.0);
    for (c, r) in
        [([260.0, 260.0], 70.0), ([430.0, 165.0], 65.0), ([450.0, 365.0], 60.0), ([610.0, 255.0], 55.0)]
    {
        s.obstacles.push(Obstacle::Circle { center: c, radius: r });
    }
    s.goals.push(Goal::fixed([735.0, 250.0], 55.0));
    s.groups.push(igsa_group("group", BLUE, 40, ([20.0, 190.0], [110.0, 310.0]), 0));
    s
}

/// Path 2 of the IGSA experiments: a wall from the bottom edge forces a detour over its top
/// end; a triangle and a disc add clutter on both sides.
pub fn igsa_path_2() -> Scene {
    let mut s = base("igsa-path-2", 800.0, 500.0);
    s.obstacles.push(Obstacle::Rect { min: [380.0, 150.0], max: [425.0, 500.0] });
    s.obstacles.push(Obstacle::Polygon { points: vec![[170.0, 250.0], [255.0, 160.0], [265.0, 330.0]] });
    s.obstacles.push(Obstacle::Circle { center: [590.0, 250.0], radius: 60.0 });
    s.goals.push(Goal::fixed([745.0, 330.0], 50.0));
    s.groups.push(igsa_group("group", VERMILLION, 40, ([20.0, 370.0], [120.0, 470.0]), 0));
    s
}

/// The crowd of the IGSA experiment III with 1000 agents; see [`igsa_crowd`].
pub fn igsa_crowd_1000() -> Scene {
    igsa_crowd(1000)
}

/// IGSA experiment III (Table 4): `count` agents follow one planned path from the left, around a
/// large disc (the "obstacle point"), to a goal on the right big enough to park 1000 of them
/// (their parking lattice fills a disc of about 180 px; the goal counts arrivals within 230 px).
/// The spawn region, the obstacle and the goal do not depend on `count`, so the planned path
/// does not either.
pub fn igsa_crowd(count: u32) -> Scene {
    let mut s = base(if count == 1000 { "igsa-crowd-1000" } else { "igsa-crowd" }, 1300.0, 700.0);
    s.obstacles.push(Obstacle::Circle { center: [640.0, 350.0], radius: 100.0 });
    s.goals.push(Goal::fixed([1060.0, 350.0], 230.0));
    s.groups.push(igsa_group("crowd", BLUE, count, ([40.0, 100.0], [440.0, 600.0]), 0));
    s
}

fn boids_group(name: &str, color: &str, count: u32, spawn: ([f32; 2], [f32; 2]), goal: Option<u32>) -> Group {
    Group { goal, ..group(name, color, count, spawn, 0) }
}

/// A group with Boids under priority arbitration (the lecture's "more robust method"): with
/// guidance that funnels agents onto one line (a point behind a leader, a path, the shortest way
/// round a corner) the weighted sum lets them overlap (measured on these presets: 10–600 times
/// the overlapping pairs of priority allocation, which gives separation the force first).
fn with_boids(mut g: Group, edit: impl FnOnce(&mut BoidsParams)) -> Group {
    let mut params = BoidsParams { arbitration: Arbitration::Priority, ..BoidsParams::default() };
    edit(&mut params);
    g.planner = PlannerConfig::Boids(params);
    g
}

/// Leader following: the group's first agent leads 25 agents across an open field to the goal.
pub fn boids_leader() -> Scene {
    let mut s = base("boids-leader", 900.0, 500.0);
    s.goals.push(Goal::fixed([800.0, 250.0], 60.0));
    let flock = boids_group("flock", BLUE, 25, ([40.0, 170.0], [180.0, 330.0]), Some(0));
    s.groups.push(with_boids(flock, |p| p.leader = Leader::First));
    s
}

/// Path following: 30 agents walk a winding path (radius 30 px) to the goal at its end.
pub fn boids_path() -> Scene {
    let mut s = base("boids-path", 900.0, 600.0);
    let points = [
        [90.0, 520.0],
        [300.0, 490.0],
        [420.0, 330.0],
        [300.0, 170.0],
        [480.0, 80.0],
        [760.0, 110.0],
        [820.0, 300.0],
        [790.0, 480.0],
    ];
    s.paths.push(PathSpec { points: points.to_vec(), radius: 30.0 });
    s.goals.push(Goal::fixed([790.0, 500.0], 50.0));
    let flock = boids_group("walkers", BLUISH_GREEN, 30, ([40.0, 480.0], [140.0, 570.0]), Some(0));
    s.groups.push(with_boids(flock, |p| p.path = 1));
    s
}

/// The flow-field maze: the straight way from the start to the goal runs into a U-shaped cup
/// that opens towards the start (plain seeking piles up inside it), and a second wall past the
/// cup leaves only a gap at the bottom.
pub fn boids_flow_field() -> Scene {
    let mut s = boids_flow_field_maze();
    let flock = boids_group("flock", REDDISH_PURPLE, 40, ([40.0, 230.0], [170.0, 370.0]), Some(0));
    s.groups.push(with_boids(flock, |p| p.flow_field = FlowGuide::Goal));
    s
}

/// The walls and goal of [`boids_flow_field`], without a group.
pub fn boids_flow_field_maze() -> Scene {
    let mut s = base("boids-flow-field", 900.0, 600.0);
    s.obstacles.push(Obstacle::Rect { min: [480.0, 140.0], max: [510.0, 460.0] });
    s.obstacles.push(Obstacle::Rect { min: [300.0, 140.0], max: [510.0, 170.0] });
    s.obstacles.push(Obstacle::Rect { min: [300.0, 430.0], max: [510.0, 460.0] });
    s.obstacles.push(Obstacle::Rect { min: [650.0, 0.0], max: [680.0, 430.0] });
    s.goals.push(Goal::fixed([810.0, 250.0], 50.0));
    s
}

/// Predator/prey: 40 prey graze on a pasture (their goal); two faster predators start in the
/// corners and chase the nearest prey.
pub fn boids_predator() -> Scene {
    let mut s = base("boids-predator", 900.0, 600.0);
    s.goals.push(Goal::fixed([450.0, 300.0], 80.0));
    let prey = boids_group("prey", BLUISH_GREEN, 40, ([380.0, 230.0], [520.0, 370.0]), Some(0));
    s.groups.push(with_boids(prey, |p| p.role = Role::Prey));
    let predators = boids_group("predators", VERMILLION, 2, ([20.0, 20.0], [80.0, 80.0]), None);
    s.groups.push(with_boids(predators, |p| {
        p.role = Role::Predator;
        p.max_speed = 2.4;
        p.chase_radius = 1000.0;
        p.alignment_weight = 0.0;
        p.cohesion_weight = 0.0;
    }));
    s
}

/// The paper's hills (§5.6): 300 people on the left cross to a wide target on the right over
/// three Gaussian hills of heights 120, 45 and 20 px, with the PSO climb limit at 60 px (half the highest).
pub fn pso_hills() -> Scene {
    let mut s = base("pso-hills", 1000.0, 700.0);
    s.hills.push(Hill { center: [450.0, 350.0], radius: 90.0, height: 120.0 });
    s.hills.push(Hill { center: [650.0, 220.0], radius: 80.0, height: 45.0 });
    s.hills.push(Hill { center: [650.0, 480.0], radius: 80.0, height: 20.0 });
    s.goals.push(Goal::fixed([920.0, 350.0], 150.0));
    s.groups.push(pso_group("crowd", BLUE, 300, ([20.0, 60.0], [200.0, 640.0]), 0));
    s
}

/// Body radius of the baselines' presets: 5 px, 0.25 m at 20 px per metre (the 2000 paper's
/// radii are 0.25–0.35 m).
const PEDESTRIAN_RADIUS: f32 = 5.0;

/// Four groups of 20 cross an 800 × 600 px square (40 m × 30 m at 20 px/m) to the opposite
/// sides, steered by ORCA with its default parameters: they meet in the middle.
pub fn orca_crossing() -> Scene {
    let mut s = base("orca-crossing", 800.0, 600.0);
    let sides = [
        ("west", "#2f6fdf", ([20.0, 220.0], [120.0, 380.0]), [740.0, 300.0]),
        ("east", "#df4f2f", ([680.0, 220.0], [780.0, 380.0]), [60.0, 300.0]),
        ("north", "#2f9f5f", ([320.0, 20.0], [480.0, 120.0]), [400.0, 540.0]),
        ("south", "#8f3fbf", ([320.0, 480.0], [480.0, 580.0]), [400.0, 60.0]),
    ];
    for (k, (name, color, spawn, goal)) in sides.into_iter().enumerate() {
        s.goals.push(Goal::fixed(goal, 60.0));
        s.groups.push(Group {
            agent_radius: PEDESTRIAN_RADIUS,
            planner: PlannerConfig::Orca(OrcaParams::default()),
            ..group(name, color, 20, spawn, k as u32)
        });
    }
    s
}

/// 60 pedestrians in a room (left) leave through a door 1.6 m (32 px) wide in a wall across the
/// scene for a goal beyond it, steered by the social force model with its papers' parameters.
pub fn social_force_bottleneck() -> Scene {
    let mut s = base("social-force-bottleneck", 800.0, 400.0);
    s.obstacles.push(Obstacle::Rect { min: [420.0, 0.0], max: [440.0, 184.0] });
    s.obstacles.push(Obstacle::Rect { min: [420.0, 216.0], max: [440.0, 400.0] });
    // An exit: pedestrians leave the scene through it, as in an evacuation.
    s.goals.push(Goal::fixed([700.0, 200.0], 60.0).exit());
    s.groups.push(Group {
        agent_radius: PEDESTRIAN_RADIUS,
        planner: PlannerConfig::SocialForce(SocialForceParams::default()),
        ..group("room", "#2f6fdf", 60, ([40.0, 60.0], [300.0, 340.0]), 0)
    });
    s
}

/// The room and door of [`social_force_bottleneck`] with the collision-free speed model (its
/// JuPedSim defaults): the two models side by side on one geometry.
pub fn csm_bottleneck() -> Scene {
    let mut s = social_force_bottleneck();
    s.name = "csm-bottleneck".into();
    for g in &mut s.groups {
        g.planner = PlannerConfig::CollisionFreeSpeed(CollisionFreeSpeedParams::default());
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The page shows a preset's description for the scene whose name is the preset's: a
    /// scene named otherwise (the forces presets were `forces-b2-e1`…) showed only its name.
    #[test]
    fn every_preset_builds_a_scene_named_after_it_with_a_description_of_what_to_watch() {
        for p in ALL {
            assert_eq!((p.build)().name, p.name, "preset {}", p.name);
            let d = p.description;
            assert!(d.contains("watch") && d.ends_with('.') && d.len() <= 240, "{}: {d:?}", p.name);
        }
        let mut descriptions: Vec<_> = ALL.iter().map(|p| p.description).collect();
        descriptions.sort_unstable();
        descriptions.dedup();
        assert_eq!(descriptions.len(), ALL.len(), "two presets share a description");
    }
}
