//! Groups whose flow fields would be identical share one (issue 24: each group used to build and
//! keep its own, up to 262,144 cells; 500 one-agent groups of a 20,000 px world kept 903 MB),
//! and a scene whose distinct fields would pass the memory limit is refused on load.
//!
//! Sharing must change no result: `PINNED` is the digest of the scene below computed by the
//! code before sharing (main at f7180b6, where every group built its own field).

#[path = "support/flow_groups.rs"]
mod flow_groups;

use flockpath::model::geometry::Obstacle;
use flockpath::model::refusal::Refusal;
use flockpath::model::scene::{Goal, Region, Scene, SceneError};
use flockpath::sim::cost::{self, MAX_FLOW_FIELD_BYTES};
use flockpath::spatial::flow_field::{cells_of, BYTES_PER_CELL};
use flockpath::{presets, PlannerKind, World};

/// `flow_groups::scene()` after `flow_groups::STEPS` steps, each group with its own field.
const PINNED: u64 = 0x64cd_73d2_bf93_dfd9;

#[test]
fn groups_sharing_a_field_step_exactly_as_with_a_field_each() {
    let scene = flow_groups::scene();
    let estimate = cost::flow_field_memory(&scene);
    let mut world = World::new(scene).expect("valid scene");
    world.step_n(flow_groups::STEPS);
    assert_eq!(world.digest(), PINNED, "digest {:016x}", world.digest());
    // Nine groups, three fields: goal 0 at 4 px (six groups) and at 6 px, goal 1 (two groups,
    // the field rebuilt as the goal circles), and the load's estimate counts the same.
    assert_eq!(world.flow_field_count(), 3, "goal 0 × 4 px, goal 0 × 6 px, goal 1 × 4 px");
    assert_eq!(estimate.fields, 3);
    // A clone (a timeline checkpoint) shares the fields and steps the same.
    let mut copy = world.clone();
    copy.step_n(20);
    world.step_n(20);
    assert_eq!(copy.digest(), world.digest());
}

/// `groups` one-agent ORCA groups (flow-field guidance) among a few circles in a 20,000 px world,
/// heading for `goals` goals (group k for goal k mod `goals`).
fn many_groups(groups: usize, goals: usize) -> Scene {
    let side = 20_000.0;
    let mut s = Scene::empty(side, side);
    for k in 0..goals {
        s.goals.push(Goal::fixed([side - 300.0, 100.0 + 19.0 * k as f32], 8.0));
    }
    s.obstacles.push(Obstacle::Circle { center: [10_000.0, 10_000.0], radius: 300.0 });
    let template = presets::open_field().groups.remove(0);
    for k in 0..groups {
        let mut g = template.clone();
        g.count = 1;
        let y = 100.0 + 19.0 * k as f32;
        g.spawn = Region { min: [100.0, y], max: [110.0, y + 10.0] };
        g.goal = Some((k % goals) as u32);
        g.planner = PlannerKind::Orca.default_config();
        s.groups.push(g);
    }
    s
}

#[test]
fn distinct_fields_over_the_memory_limit_are_refused_naming_the_group_and_the_limit() {
    let field_bytes = cells_of(glam::Vec2::new(20_000.0, 20_000.0)) * BYTES_PER_CELL;
    let fit = (MAX_FLOW_FIELD_BYTES / field_bytes) as usize;
    assert!((400..800).contains(&fit), "{fit} fields of {field_bytes} bytes fit");
    // Exactly the limit's worth of distinct fields loads; one more is refused.
    assert_eq!(cost::check(&many_groups(fit, fit)), Ok(()));
    let e = cost::check(&many_groups(fit + 1, fit + 1)).expect_err("one field more");
    assert!(matches!(e, SceneError::FlowFieldMemory { .. }), "{e:?}");
    assert_eq!(e.code(), "scene.flow_field_memory");
    let arg = |name: &str| e.message().arg_text(name);
    assert_eq!(arg("path").as_deref(), Some(format!("groups[{fit}]").as_str()));
    assert_eq!(arg("limit_mb").as_deref(), Some("1024"));
    assert_eq!(arg("fields"), Some((fit + 1).to_string()));
    let text = e.to_string();
    assert!(
        text.starts_with(&format!("groups[{fit}]: the groups' {} distinct flow fields", fit + 1)),
        "{text}"
    );
    assert!(text.contains("over the 1024 MB limit"), "{text}");
    // World::new refuses it too (before spawning anything).
    assert!(matches!(World::new(many_groups(fit + 1, fit + 1)), Err(SceneError::FlowFieldMemory { .. })));
    // As many groups sharing ten goals keep ten fields: accepted, and far more of them too.
    assert_eq!(cost::check(&many_groups(fit + 1, 10)), Ok(()));
    assert_eq!(cost::flow_field_memory(&many_groups(5_000, 10)).fields, 10);
    // Straight guidance keeps no field at all.
    let mut straight = many_groups(fit + 1, fit + 1);
    for g in &mut straight.groups {
        g.planner.set_param("guidance", serde_json::json!("goal")).expect("a guidance choice");
    }
    assert_eq!(cost::flow_field_memory(&straight).fields, 0);
    assert_eq!(cost::check(&straight), Ok(()));
}

#[test]
fn switching_groups_to_flow_field_guidance_is_refused_at_the_limit_and_the_run_keeps_its_planner() {
    let field_bytes = cells_of(glam::Vec2::new(20_000.0, 20_000.0)) * BYTES_PER_CELL;
    let fit = (MAX_FLOW_FIELD_BYTES / field_bytes) as usize;
    let mut scene = many_groups(fit + 1, fit + 1);
    let straight = |config: &mut flockpath::PlannerConfig| {
        config.set_param("guidance", serde_json::json!("goal")).expect("a guidance choice");
    };
    scene.groups.iter_mut().for_each(|g| straight(&mut g.planner));
    let mut world = World::new(scene).expect("straight guidance keeps no field");
    let guided = PlannerKind::Orca.default_config();
    for g in 0..fit {
        world.set_group_planner(g, guided.clone()).expect("within the limit");
    }
    let e = world.set_group_planner(fit, guided).expect_err("one field over the limit");
    assert!(matches!(e, SceneError::FlowFieldMemory { .. }), "{e:?}");
    let mut kept = PlannerKind::Orca.default_config();
    straight(&mut kept);
    assert_eq!(world.scene().groups[fit].planner, kept, "the run keeps its planner");
}
