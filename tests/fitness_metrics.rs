//! The five fitness measures of DESIGN §3.5 in `World::metrics()` for any planner: present
//! overall and per group from the first step, sampled every `FITNESS_SAMPLE_EVERY` steps, in
//! range, Gsum weighted with B1's weights, and equal to a `FitnessRecorder` fed the same steps.

use flockpath::model::forces_cases::Behaviour;
use flockpath::sim::fitness::FitnessRecorder;
use flockpath::sim::metrics::FITNESS_SAMPLE_EVERY;
use flockpath::{presets, World};
use glam::Vec2;

fn in_unit_range(x: f64) -> bool {
    (0.0..=1.0).contains(&x)
}

#[test]
fn every_preset_reports_fitness_overall_and_per_group() {
    for preset in presets::ALL {
        let mut world = World::new((preset.build)()).expect("preset is valid");
        let before = serde_json::to_value(world.metrics()).expect("serialises");
        assert!(before["fitness"].is_null(), "{}: nothing sampled at step 0", preset.name);
        world.step_n(2 * FITNESS_SAMPLE_EVERY + 1);
        let m = world.metrics();
        let f = m.overall.fitness.expect("sampled");
        assert_eq!(f.sampled_steps, 3, "{}: steps 1, 1 + N, 1 + 2N", preset.name);
        for x in [f.gm, f.gg, f.gc, f.ga, f.gd] {
            assert!(in_unit_range(x), "{}: {f:?}", preset.name);
        }
        let s = Behaviour::GroupMoving.weights();
        let gsum =
            s.spacing * f.gm + s.goal * f.gg + s.collision * f.gc + s.orientation * f.ga + s.distance * f.gd;
        assert!((f.gsum - gsum).abs() < 1e-9, "{}", preset.name);
        for g in &m.groups {
            let gf = g.fitness.expect("every group with agents is sampled");
            assert!(in_unit_range(gf.gc) && in_unit_range(gf.gm) && (0.0..=100.0).contains(&gf.gsum));
        }
        // The JSON carries the keys the page and scripts read.
        let json = serde_json::to_value(&m).expect("serialises");
        for key in ["gm", "gg", "gc", "ga", "gd", "gsum", "sampled_steps"] {
            assert!(json["fitness"][key].is_number(), "{}: fitness.{key}", preset.name);
            assert!(
                json["groups"][0]["fitness"][key].is_number(),
                "{}: groups[0].fitness.{key}",
                preset.name
            );
        }
    }
}

#[test]
fn the_metrics_equal_a_recorder_fed_the_sampled_steps() {
    let scene = (presets::find("pillars").expect("preset").build)();
    let mut world = World::new(scene.clone()).expect("valid");
    let n = world.agent_count();
    let mut recorder =
        FitnessRecorder::new(Behaviour::GroupMoving.fitness_params(), scene.width, scene.height, n);
    let steps = 5 * FITNESS_SAMPLE_EVERY;
    for step in 1..=steps {
        world.step();
        if step % FITNESS_SAMPLE_EVERY == 1 % FITNESS_SAMPLE_EVERY {
            let goals: Vec<Option<Vec2>> =
                world.group_of().iter().map(|&g| world.goal_of_group(g as usize).map(|(p, _)| p)).collect();
            recorder.record(world.fitness_frame(&goals));
        }
    }
    let f = world.metrics().overall.fitness.expect("sampled");
    let expected = recorder.measures();
    assert_eq!(
        (f.gm, f.gg, f.gc, f.ga, f.gd),
        (expected.gm, expected.gg, expected.gc, expected.ga, expected.gd)
    );
    assert_eq!(f.sampled_steps, recorder.frames());
    assert!(f.gc < 1.0 || f.gm < 1.0, "a crowd among pillars is not perfect: {f:?}");
}

#[test]
fn sampling_can_be_turned_off_and_on() {
    let scene = (presets::find("pillars").expect("preset").build)();
    let mut world = World::new(scene).expect("valid");
    world.set_fitness_sample_every(0);
    world.step_n(30);
    assert!(world.metrics().overall.fitness.is_none());
    world.set_fitness_sample_every(1);
    world.step_n(4);
    assert_eq!(world.metrics().overall.fitness.map(|f| f.sampled_steps), Some(4));
}
