//! Regression of the suite's exits (issue 25 §1). T6, T12 and T15 counted walkers standing in
//! an area near a goal, and their exits lay on the world's border, which the planners that keep
//! off the border (Boids' containment) treat as a wall: no Boids walker got out of T6 or T12.
//! Now each exit is a door with room beyond it, a walker leaves the scene on reaching it, and
//! the tests count crossings of the exit line from positions alone: that count must equal the
//! world's own count of walkers that left.

use flockpath::experiments::validation::record::record;
use flockpath::experiments::validation::scenes::{bottleneck, bottleneck_lines, Corner, BEYOND_EXIT};
use flockpath::experiments::validation::suite::{find_test, T6_AGENTS};
use flockpath::experiments::validation::units::{config_at_speed, FREE_SPEED, PX_PER_METRE};
use flockpath::model::params::PlannerKind;
use flockpath::sim::world::World;

/// All 20 of T6 leave the scene, and the walkers out across the exit line, recounted from the
/// trajectories, are exactly the ones the world removed at the exit.
#[test]
fn every_t6_walker_leaves_and_the_line_count_equals_the_worlds() {
    for kind in [PlannerKind::Orca, PlannerKind::SocialForce, PlannerKind::Boids] {
        let corner = Corner { leg: 12.0, width: 2.0 };
        let cfg = config_at_speed(kind, FREE_SPEED).expect("a speed");
        let scene = corner.scene("t6", &cfg, T6_AGENTS as u32, 6.0);
        let world = World::new_beyond_cost_limit(scene).expect("the scene is valid");
        let rec = record(world, 40 * 60, 3, |_| false);
        let crossed = rec.traj.crossing_times(corner.exit_line()).iter().flatten().count();
        assert_eq!(
            rec.metrics.as_ref().expect("a world's run").overall.exited_agents as usize,
            T6_AGENTS,
            "{kind:?}: all left the scene"
        );
        assert_eq!(crossed, T6_AGENTS, "{kind:?}: every one that left crossed the exit line once");
        // The suite's own row and curve say the same.
        let outcome = find_test("t6-corner").expect("T6").run(kind);
        assert!(outcome.rows[0].pass, "{kind:?}: {}", outcome.rows[0].measured);
        let curve = outcome.curves.iter().find(|c| c.name.contains("exits")).expect("an exits curve");
        let last = curve.rows.last().expect("frames")[1];
        assert_eq!(last as usize, T6_AGENTS, "{kind:?}: persons out over time ends at 20");
        assert!(curve.rows.windows(2).all(|w| w[1][1] >= w[0][1]), "{kind:?}: the count never falls");
    }
}

/// T12's last exit is a door in the second room's wall with room beyond it (not on the world's
/// border), and every walker the world removed there crossed the last exit's line, after the
/// corridor's end.
#[test]
fn t12s_walkers_cross_the_corridor_then_the_last_exit() {
    let cfg = config_at_speed(PlannerKind::Orca, FREE_SPEED).expect("a speed");
    let scene = bottleneck(&cfg, 150);
    let exit = &scene.goals[0];
    assert!(scene.width - exit.position[0] >= BEYOND_EXIT * PX_PER_METRE, "the exit has room beyond it");
    let world = World::new_beyond_cost_limit(scene).expect("the scene is valid");
    let rec = record(world, 90 * 60, 6, |_| false);
    let (corridor_end, last_exit) = bottleneck_lines();
    let through = rec.traj.crossing_times(corridor_end);
    let out = rec.traj.crossing_times(last_exit);
    assert_eq!(
        out.iter().flatten().count(),
        rec.metrics.as_ref().expect("a world's run").overall.exited_agents as usize
    );
    assert_eq!(out.iter().flatten().count(), 150, "all out in 90 s");
    for (a, (t, o)) in through.iter().zip(&out).enumerate() {
        let (t, o) = (t.expect("through the corridor"), o.expect("out"));
        assert!(t < o, "walker {a} crossed the corridor's end at {t} s, the last exit at {o} s");
    }
}
