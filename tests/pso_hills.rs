//! The PSO hills scene (Chen & Lin 2009, §5.6): a crowd crosses hills of three heights; ground
//! at or above the climb limit is never walked on, lower hills are crossed, the crowd arrives.

use flockpath::model::scene::Hill;
use flockpath::{presets, PlannerConfig, World};

#[test]
fn nobody_climbs_the_highest_hill_and_the_crowd_arrives() {
    let mut scene = presets::pso_hills();
    // 100 of the preset's 300 people keep a debug build quick; `flockpath run` on the preset
    // itself gives the 300-person figures.
    scene.groups[0].count = 100;
    let climb_limit = match &scene.groups[0].planner {
        PlannerConfig::Pso(p) => p.climb_limit,
        other => panic!("not PSO: {other:?}"),
    };
    let hills = scene.hills.clone();
    let highest = hills.iter().max_by(|a, b| a.height.total_cmp(&b.height)).expect("hills").clone();
    assert!(highest.height > climb_limit && hills.iter().filter(|h| h.height < climb_limit).count() == 2);
    let mut world = World::new(scene).expect("valid");
    let on_top = |h: &Hill, p: glam::Vec2| h.height_at(p) >= 0.5 * h.height;
    let mut topped = vec![vec![false; world.agent_count()]; hills.len()];
    let mut highest_ground = 0.0f32;
    for _ in 0..1800 {
        world.step();
        for (i, &p) in world.positions().iter().enumerate() {
            highest_ground = highest_ground.max(highest.height_at(p));
            for (k, h) in hills.iter().enumerate() {
                topped[k][i] |= on_top(h, p);
            }
        }
    }
    let counts: Vec<usize> = topped.iter().map(|t| t.iter().filter(|&&x| x).count()).collect();
    let m = world.metrics();
    println!(
        "pso-hills (100 people, 1800 steps): highest ground reached on the {:.0} px hill {highest_ground:.1} px \
         (climb limit {climb_limit}); people who stood on the upper half of each hill (heights {:?}): {counts:?}; \
         arrived {:.2}, penetrations {}",
        highest.height,
        hills.iter().map(|h| h.height).collect::<Vec<_>>(),
        m.overall.arrived_share,
        m.overall.penetrations_agent_obstacle
    );
    assert!(highest_ground < climb_limit, "someone stood {highest_ground} px up the highest hill");
    let highest_index = hills.iter().position(|h| h.height == highest.height).expect("found");
    assert_eq!(counts[highest_index], 0);
    assert!(counts.iter().sum::<usize>() > 0, "nobody crossed a lower hill's top");
    assert!(m.overall.arrived_share > 0.9, "arrived {:.2}", m.overall.arrived_share);
}
