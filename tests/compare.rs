//! Side-by-side comparison: lockstep panes, independent generators, the URL spec round trip and
//! readable messages for bad specs, the summary CSV.

use flockpath::model::params::PlannerKind;
use flockpath::sim::compare::{Comparison, ComparisonSpec, PaneSpec, SERIES_KEYS};
use flockpath::{presets, PlannerConfig, Scene, World};

fn scene(name: &str) -> Scene {
    (presets::find(name).expect("preset").build)()
}

fn spec(text: &str) -> ComparisonSpec {
    ComparisonSpec::parse(text).unwrap_or_else(|e| panic!("{text}: {e}"))
}

#[test]
fn panes_step_in_lockstep() {
    let mut c = Comparison::new(scene("pillars"), spec("1.scene~pso~firefly")).expect("valid");
    c.step_n(37);
    c.step_n(3);
    let steps: Vec<u32> = c.panes().iter().map(|p| p.world().step_count()).collect();
    assert_eq!(steps, vec![40, 40, 40]);
    assert_eq!(c.step_count(), 40);
    for m in c.metrics() {
        assert_eq!(m.steps, 40);
    }
    c.reset().expect("reset");
    assert!(c.panes().iter().all(|p| p.world().step_count() == 0));
}

#[test]
fn a_scene_pane_runs_exactly_as_the_playground() {
    let s = scene("pillars");
    let mut c = Comparison::new(s.clone(), spec("1.scene~pso")).expect("valid");
    let mut alone = World::new(s).expect("valid");
    c.step_n(120);
    alone.step_n(120);
    assert_eq!(c.digests()[0], alone.digest());
}

#[test]
fn panes_have_independent_generators() {
    // PSO draws random numbers every step: if panes shared a generator, adding a pane before
    // it would change its run.
    let s = scene("pso-crowd");
    let mut pso_alone = Comparison::new(s.clone(), spec("1.pso")).expect("valid");
    let mut with_others = Comparison::new(s.clone(), spec("1.firefly~pso~pso")).expect("valid");
    pso_alone.step_n(150);
    with_others.step_n(150);
    let d = with_others.digests();
    assert_eq!(d[1], pso_alone.digests()[0], "a pane's run does not depend on the panes beside it");
    assert_eq!(d[1], d[2], "identical panes give identical runs (same seed, own generators)");
    assert_ne!(d[0], d[1], "different planners differ");
    // All panes start from the same spawn positions.
    let fresh = Comparison::new(s, spec("1.firefly~pso~boids")).expect("valid");
    let starts: Vec<_> = fresh.panes().iter().map(|p| p.world().positions().to_vec()).collect();
    assert!(starts.windows(2).all(|w| w[0] == w[1]));
}

#[test]
fn the_spec_string_round_trips() {
    let mut tuned = PlannerKind::Pso.default_config();
    tuned.set_param("acceptance", serde_json::json!("off")).expect("choice");
    let mut boids = PlannerKind::Boids.default_config();
    boids.set_param("separation_weight", serde_json::json!(2.3)).expect("in range");
    boids.set_param("arbitration", serde_json::json!("priority")).expect("choice");
    let original = ComparisonSpec {
        panes: vec![
            PaneSpec::scene(),
            PaneSpec { all: Some(tuned), groups: Vec::new() },
            PaneSpec { all: Some(boids.clone()), groups: vec![(1, PlannerKind::Firefly.default_config())] },
            PaneSpec { all: None, groups: vec![(0, boids), (2, PlannerKind::Forces.default_config())] },
        ],
    };
    let text = original.to_spec_string();
    assert!(text.starts_with("1."), "{text}");
    assert!(text.len() < 600, "compact: {} chars: {text}", text.len());
    assert!(!text.contains(['&', '#', ' ', '%']), "safe in a URL fragment: {text}");
    assert_eq!(ComparisonSpec::parse(&text).expect("reads back"), original);
    // Through a whole URL too.
    let url = format!("https://example.org/compare.html#s=2.abc&c={text}");
    assert_eq!(ComparisonSpec::parse(&url).expect("reads back"), original);
}

#[test]
fn short_hand_specs_take_defaults() {
    let s = spec("1.boids~pso(0.8)~2=firefly");
    assert_eq!(s.panes[0].all, Some(PlannerKind::Boids.default_config()));
    let PlannerConfig::Pso(p) = s.panes[1].all.clone().expect("pso") else { panic!("pso") };
    assert!((p.inertia - 0.8).abs() < 1e-6);
    assert_eq!(s.panes[2].groups, vec![(1, PlannerKind::Firefly.default_config())]);
}

#[test]
fn bad_specs_give_messages() {
    let cases = [
        ("", "empty"),
        ("boids~pso", "version"),
        ("9.boids", "version"),
        ("1.boids~teleport", "unknown planner"),
        ("1.boids~pso(1,2", "closing"),
        ("1.pso(abc)", "number"),
        ("1.pso(1e99)", "outside"),
        ("1.boids(50,14,2,0.15,1.5,1,1,1,3,50,60,sideways)", "one of"),
        // More values than any planner's table has (tables grow at the end).
        (
            "1.pso(1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1)",
            "parameters",
        ),
        ("1.scene~scene~scene~scene~scene", "at most"),
        ("1.0=pso", "from 1"),
        ("1.x=pso", "group number"),
        ("1.boids;pso", "twice"),
        ("1.1=pso;1=boids", "twice"),
        ("1.scene~", "empty"),
    ];
    for (text, needle) in cases {
        let e = ComparisonSpec::parse(text).expect_err(text).to_string();
        assert!(e.to_lowercase().contains(needle), "{text:?} → {e}");
    }
    // A group the scene does not have is refused when the comparison is built.
    let e = Comparison::new(scene("open-field"), spec("1.3=pso")).err().expect("no group 3").to_string();
    assert!(e.contains("group 3"), "{e}");
}

#[test]
fn the_default_comparison_sets_the_scene_against_another_planner() {
    let d = ComparisonSpec::default_for(&scene("pillars"));
    assert_eq!(d.panes.len(), 2);
    assert_eq!(d.panes[1].all.as_ref().map(PlannerConfig::kind), Some(PlannerKind::Pso));
    let d = ComparisonSpec::default_for(&scene("pso-crowd"));
    assert_eq!(d.panes[1].all.as_ref().map(PlannerConfig::kind), Some(PlannerKind::Boids));
}

#[test]
fn series_and_summary_come_from_every_pane() {
    let mut c = Comparison::new(scene("pso-four-corners"), spec("1.scene~boids")).expect("valid");
    c.step_n(200);
    for p in c.panes() {
        let s = p.series();
        assert_eq!(s.steps.first(), Some(&0));
        assert_eq!(s.steps.last(), Some(&200));
        assert_eq!(s.steps.len(), 21);
        assert_eq!(s.speed.len(), s.steps.len());
        assert!(s.collisions_agent_agent.windows(2).all(|w| w[1] >= w[0]), "cumulative");
    }
    assert_eq!(SERIES_KEYS.len(), 5);
    let csv = c.summary_csv();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 3, "{csv}");
    assert!(lines[0].starts_with("pane,planners,steps,agents,arrived_share"));
    let columns = lines[0].split(',').count();
    for (row, name) in lines[1..].iter().zip(["A", "B"]) {
        assert!(row.starts_with(name), "{row}");
        assert!(row.contains(",200,"), "{row}");
        assert_eq!(row.split(',').count(), columns, "{row}");
    }
    let summary = c.summary();
    assert_eq!(summary[0].penetrations_agent_obstacle, c.metrics()[0].overall.penetrations_agent_obstacle);
}

#[test]
fn long_runs_thin_the_series_within_bounds() {
    let mut s = scene("open-field");
    s.groups[0].count = 5;
    let mut c = Comparison::new(s, spec("1.scene")).expect("valid");
    c.step_n(12_000);
    let series = c.panes()[0].series();
    assert!(series.steps.len() <= flockpath::sim::compare::MAX_SERIES_SAMPLES);
    assert!(series.every > 10);
    assert!(series.steps.windows(2).all(|w| w[1] - w[0] == series.every));
}

#[test]
fn panes_are_added_changed_and_removed_natively_and_a_refusal_changes_nothing() {
    let mut c = Comparison::new(scene("open-field"), spec("1.scene")).expect("valid");
    c.add_pane(Some(PlannerKind::Pso)).expect("room for a second pane");
    c.add_pane(None).expect("and a third");
    assert_eq!(c.spec().to_spec_string(), spec("1.scene~pso~scene").to_spec_string());
    c.set_pane_planner(2, Some(PlannerKind::Firefly)).expect("pane 3 exists");
    c.set_pane_param(1, "max_speed", serde_json::json!(2.5)).expect("in range");
    let PlannerConfig::Pso(p) = c.spec().panes[1].all.clone().expect("every-group planner") else {
        panic!("pane 2 runs PSO")
    };
    assert_eq!(p.max_speed, 2.5);
    c.step_n(30);
    let before = c.spec();
    let e = c.set_pane_param(0, "max_speed", serde_json::json!(2.0)).expect_err("a scene pane");
    assert!(e.to_string().contains("pick a planner"), "{e}");
    assert!(c.set_pane_param(1, "max_speed", serde_json::json!(1e9)).is_err(), "out of range");
    assert!(c.set_pane_planner(7, None).expect_err("no pane 8").to_string().contains("no pane 8"));
    c.add_pane(None).expect("a fourth");
    assert!(c.add_pane(None).is_err(), "at most four panes");
    c.remove_pane(3).expect("the fourth goes");
    assert_eq!(c.spec(), before, "refusals changed nothing");
    assert_eq!(c.step_count(), 0, "every accepted change restarts the panes");
    c.remove_pane(0).expect("pane 1 goes");
    c.remove_pane(0).expect("pane 2 goes");
    assert!(c.remove_pane(0).is_err(), "the last pane stays");
    assert_eq!(c.panes().len(), 1);
}
