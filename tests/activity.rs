//! Scene activities (issue #15 item 4): validation names the field and its limit, the activity
//! rides in links and JSON exactly (markup included, as plain text), scenes without one keep
//! their exact text, and the check on the metrics decides at the step an independent run finds.

use flockpath::model::activity::{Activity, MAX_CHOICES, MAX_PROMPT_CHARS};
use flockpath::sim::activity_check::{ActivityWatch, Page, Status};
use flockpath::sim::compare::{Comparison, ComparisonSpec};
use flockpath::sim::run::{Run, RunOptions};
use flockpath::{
    presets, scene_from_any, scene_from_fragment, scene_from_json, scene_to_fragment, scene_to_json,
};
use flockpath::{Scene, SceneError, World};

fn preset(name: &str) -> Scene {
    (presets::find(name).expect("preset").build)()
}

fn activity(json: &str) -> Activity {
    serde_json::from_str(json).expect("an activity")
}

/// Markup in every text field: it must come back as the same characters, never interpreted.
const MARKUP: &str = r#"{
  "prompt": "<img src=x onerror=alert(1)> & <script>alert(2)</script>\nline two \"quoted\" 路径",
  "prediction": {"question": "<b onmouseover=alert(3)>Which?</b>",
                 "choices": ["<script>alert(4)</script>", "<img src=x onerror=alert(5)>", "plain"],
                 "expected": 2},
  "check": {"steps": 1500, "conditions": [
    {"metric": "arrived_share", "op": ">=", "value": 0.9},
    {"metric": "penetrations_agent_obstacle", "op": "=", "value": 0}]}
}"#;

fn with_activity(name: &str, json: &str) -> Scene {
    let mut scene = preset(name);
    scene.activity = Some(activity(json));
    scene
}

/// The refused field's path and the allowed text of a scene's JSON.
fn refusal(scene: &Scene) -> (String, String) {
    match scene_from_json(&scene_to_json(scene)) {
        Err(SceneError::Field(f)) => (f.path, f.allowed),
        other => panic!("expected a field refusal, got {other:?}"),
    }
}

#[test]
fn an_activity_round_trips_through_json_and_the_link_as_plain_text() {
    let scene = with_activity("pillars", MARKUP);
    assert_eq!(scene_from_json(&scene_to_json(&scene)).as_ref(), Ok(&scene));
    let fragment = scene_to_fragment(&scene);
    let back = scene_from_fragment(&fragment).expect("decodes");
    assert_eq!(back, scene);
    let a = back.activity.expect("kept");
    assert!(a.prompt.starts_with("<img src=x onerror=alert(1)>") && a.prompt.contains("\nline two"));
    assert_eq!(a.prediction.expect("prediction").choices[0], "<script>alert(4)</script>");
    // Through a whole URL too, as a student's browser receives it.
    let url = format!("https://course.example/flockpath/index.html#s={fragment}");
    assert_eq!(scene_from_any(&url).as_ref(), Ok(&scene));
}

#[test]
fn the_compact_link_carries_the_activity_and_scenes_without_one_are_unchanged() {
    // The compact (positional) form, not the keyed fallback: the activity is an eleventh element.
    let scene = with_activity("open-field", MARKUP);
    let fragment = scene_to_fragment(&scene);
    let plain = scene_to_fragment(&preset("open-field"));
    assert!(fragment.len() < plain.len() + 400, "{} vs {}", fragment.len(), plain.len());
    // A scale that is not the default and hills keep their positions before the activity.
    let mut scaled = with_activity("pso-hills", MARKUP);
    scaled.px_per_metre = 12.5;
    assert_eq!(scene_from_fragment(&scene_to_fragment(&scaled)), Ok(scaled));
    // Scenes without an activity write no `activity` key and the same link as before.
    for p in presets::ALL {
        let s = (p.build)();
        assert!(!scene_to_json(&s).contains("activity"), "{}", p.name);
    }
    let golden = include_str!("data/golden-url.txt").trim();
    let decoded = scene_from_any(golden).expect("golden link");
    assert_eq!(decoded.activity, None);
    assert_eq!(
        format!("2.{}", golden.rsplit_once("#s=2.").expect("fragment").1),
        scene_to_fragment(&decoded)
    );
}

#[test]
fn refusals_name_the_field_and_its_limit() {
    let mut scene = with_activity("pillars", MARKUP);
    let a = scene.activity.as_mut().expect("activity");
    a.prompt = "x".repeat(MAX_PROMPT_CHARS + 1);
    let (path, allowed) = refusal(&scene);
    assert_eq!(path, "activity.prompt");
    assert!(allowed.contains("1…1000 characters"), "{allowed}");

    let mut scene = with_activity("pillars", MARKUP);
    if let Some(p) = scene.activity.as_mut().and_then(|a| a.prediction.as_mut()) {
        p.choices = (0..=MAX_CHOICES).map(|k| format!("choice {k}")).collect();
    }
    let (path, allowed) = refusal(&scene);
    assert_eq!((path.as_str(), allowed.as_str()), ("activity.prediction.choices", "2…6 choices"));

    let mut scene = with_activity("pillars", MARKUP);
    if let Some(p) = scene.activity.as_mut().and_then(|a| a.prediction.as_mut()) {
        p.expected = Some(3);
    }
    assert_eq!(refusal(&scene).0, "activity.prediction.expected");

    // An unknown metric key, a group the scene lacks, a check without conditions.
    let bad = [
        (
            r#"{"prompt": "p", "check": {"steps": 10, "conditions": [{"metric": "arrived", "op": ">=", "value": 1}]}}"#,
            "activity.check.conditions[0].metric",
            "arrived_share",
        ),
        (
            r#"{"prompt": "p", "check": {"steps": 10, "conditions": [{"before": [{"group": 0}, {"group": 1}]}]}}"#,
            "activity.check.conditions[0].before[1].group",
            "the scene has 1 group",
        ),
        (
            r#"{"prompt": "p", "check": {"steps": 10, "conditions": []}}"#,
            "activity.check.conditions",
            "1…8 conditions",
        ),
        (
            r#"{"prompt": "p", "check": {"steps": 0, "conditions": [{"metric": "stuck_agents", "op": "=", "value": 0}]}}"#,
            "activity.check.steps",
            "1…1000000",
        ),
        (r#"{"prompt": "  ", "check": null}"#, "activity.prompt", "1…1000"),
    ];
    for (json, path, words) in bad {
        let scene = with_activity("pillars", json);
        let (p, allowed) = refusal(&scene);
        assert_eq!(p, path, "{json}");
        assert!(allowed.contains(words), "{json}: {allowed}");
    }

    // Refused while reading, with the path: an unknown key and an unknown comparison.
    let text = scene_to_json(&with_activity("pillars", MARKUP));
    let unknown = text.replacen("\"prompt\"", "\"hint\": \"x\",\n    \"prompt\"", 1);
    let e = scene_from_json(&unknown).expect_err("unknown key").to_string();
    assert!(e.starts_with("activity.hint is an unknown key"), "{e}");
    let e = scene_from_json(&text.replacen("\">=\"", "\"≥\"", 1)).expect_err("bad op").to_string();
    assert!(e.starts_with("activity.check.conditions[0]"), "{e}");
}

/// Steps `scene` to `limit`, returning the first step (from 1) where `holds(metrics)`.
fn first_step_where(scene: &Scene, limit: u32, holds: impl Fn(&flockpath::Metrics) -> bool) -> Option<u32> {
    let mut world = World::new(scene.clone()).expect("valid");
    (1..=limit).find(|_| {
        world.step();
        holds(&world.metrics())
    })
}

#[test]
fn the_check_is_met_at_the_first_step_every_condition_holds() {
    let scene = with_activity("pillars", MARKUP);
    let expected = first_step_where(&scene, 1500, |m| {
        m.overall.arrived_share >= 0.9 && m.overall.penetrations_agent_obstacle == 0
    })
    .expect("pillars arrive within 1500 steps");
    let mut world = World::new(scene.clone()).expect("valid");
    let mut watch = ActivityWatch::new(Page::Run);
    let before = watch.report(world.scene(), 0).expect("a check");
    assert_eq!((before.status, before.step, before.limit), (Status::Running, 0, 1500));
    for _ in 0..1500 {
        world.step();
        watch.observe_world(&world);
    }
    let report = watch.report(world.scene(), world.step_count()).expect("a check");
    assert_eq!((report.status, report.step, report.from_step), (Status::Met, expected, 1));
    // The values shown are those of the deciding step, not of step 1500.
    let mut at = World::new(scene).expect("valid");
    at.step_n(expected);
    let m = at.metrics();
    assert_eq!(report.conditions[0].measured[0].value, Some(m.overall.arrived_share));
    assert_eq!(report.conditions[1].measured[0].value, Some(0.0));
    assert!(report.conditions.iter().all(|c| c.holds && c.applies));
    // Fed in frames of any size (the page steps several per frame) the decision is the same.
    let mut again = World::new(at.scene().clone()).expect("valid");
    let mut watch2 = ActivityWatch::new(Page::Run);
    for _ in 0..expected + 37 {
        again.step();
        watch2.observe_world(&again);
    }
    assert_eq!(watch2.report(again.scene(), again.step_count()), Some(report));
}

#[test]
fn an_unreached_goal_is_missed_at_the_step_limit_and_a_reset_starts_over() {
    let scene = with_activity(
        "pso-static-obstacle",
        r#"{"prompt": "All 20 reach the target?", "check": {"steps": 600, "conditions": [
             {"metric": "arrived_share", "op": ">=", "value": 1},
             {"metric": "stuck_agents", "op": "<=", "value": 0, "group": 0}]}}"#,
    );
    let mut world = World::new(scene.clone()).expect("valid");
    let mut watch = ActivityWatch::new(Page::Run);
    for _ in 0..650 {
        world.step();
        watch.observe_world(&world);
    }
    let report = watch.report(world.scene(), world.step_count()).expect("check");
    assert_eq!((report.status, report.step), (Status::Missed, 600));
    let mut at = World::new(scene.clone()).expect("valid");
    at.step_n(600);
    assert_eq!(report.conditions[0].measured[0].value, Some(at.metrics().overall.arrived_share));
    assert!(!report.conditions[0].holds);
    // A new run (step 1 again) starts a new check.
    let mut fresh = World::new(scene).expect("valid");
    fresh.step();
    watch.observe_world(&fresh);
    let report = watch.report(fresh.scene(), 1).expect("check");
    assert_eq!((report.status, report.step, report.from_step), (Status::Running, 1, 1));
}

#[test]
fn group_b_arrives_before_group_a_as_an_independent_run_finds() {
    let scene = with_activity(
        "pso-four-corners",
        r#"{"prompt": "Which corner group is first?", "check": {"steps": 3000, "conditions": [
             {"before": [{"group": 1}, {"group": 0}], "share": 0.5}]}}"#,
    );
    let reach = |g: usize| first_step_where(&scene, 3000, |m| m.groups[g].arrived_share >= 0.5);
    let (a, b) = (reach(1), reach(0));
    let mut world = World::new(scene.clone()).expect("valid");
    let mut watch = ActivityWatch::new(Page::Run);
    for _ in 0..3000 {
        world.step();
        watch.observe_world(&world);
    }
    let report = watch.report(world.scene(), world.step_count()).expect("check");
    let expected_met = match (a, b) {
        (Some(a), Some(b)) => a < b,
        (Some(_), None) => true,
        _ => false,
    };
    // On this preset and seed group 2 is half home before group 1 (both within 1,000 steps).
    assert!(expected_met && b.is_some(), "{a:?} {b:?}");
    assert_eq!((report.status, report.step), (Status::Met, a.expect("reached")));
    assert_eq!(report.conditions[0].measured[0].reached_step, a.filter(|&s| s <= report.step));
}

#[test]
fn on_the_compare_page_pane_b_arrives_before_pane_a() {
    // PSO (pane B) against Boids (pane A) on pso-influx: the check names the panes.
    let scene = with_activity(
        "pso-influx",
        r#"{"prompt": "PSO or Boids first?", "check": {"steps": 2000, "conditions": [
             {"before": [{"pane": 1}, {"pane": 0}], "share": 0.9},
             {"metric": "penetrations_agent_obstacle", "op": "=", "value": 0}]}}"#,
    );
    let spec = ComparisonSpec::parse("1.boids~pso").expect("spec");
    let mut comparison = Comparison::new(scene.clone(), spec.clone()).expect("comparison");
    let mut watch = ActivityWatch::new(Page::Compare);
    let mut reached: [Option<u32>; 2] = [None, None];
    for _ in 0..2000 {
        comparison.step_n(1);
        let step = comparison.step_count();
        let metrics = comparison.metrics();
        for (k, m) in metrics.iter().enumerate() {
            if reached[k].is_none() && m.overall.arrived_share >= 0.9 {
                reached[k] = Some(step);
            }
        }
        watch.observe(comparison.scene(), step, || metrics.clone());
    }
    let report = watch.report(comparison.scene(), comparison.step_count()).expect("check");
    assert!(reached.iter().all(Option::is_some), "both panes arrive: {reached:?}");
    let pso_first = match reached {
        [boids, Some(pso)] => boids.is_none_or(|b| pso < b),
        _ => false,
    };
    assert_eq!(report.status == Status::Met, pso_first, "{reached:?} {report:?}");
    // Decided at the step the race was decided (the winner's), not at the limit.
    let decided = if pso_first { reached[1] } else { reached[0] };
    assert_eq!(Some(report.step), decided, "{reached:?}");
    let measured = &report.conditions[0].measured;
    assert_eq!((measured[0].pane, measured[1].pane), (Some(1), Some(0)));
    // Every pane is checked for penetrations (no pane named).
    assert_eq!(report.conditions[1].measured.len(), 2);
    // The same check on the playground: the pane condition does not apply there, so neither does the check.
    let mut world = World::new(scene).expect("valid");
    let mut run_watch = ActivityWatch::new(Page::Run);
    world.step();
    run_watch.observe_world(&world);
    let run_report = run_watch.report(world.scene(), 1).expect("check");
    assert!(!run_report.conditions[0].applies && run_report.conditions[1].applies);
    assert_eq!(run_report.status, Status::Unavailable);
}

#[test]
fn the_run_and_the_comparison_feed_the_check_themselves() {
    // A watch fed by hand after every step, as the page once did, against the core's own.
    let scene = with_activity("pillars", MARKUP);
    let mut world = World::new(scene.clone()).expect("valid");
    let mut watch = ActivityWatch::new(Page::Run);
    for _ in 0..500 {
        world.step();
        watch.observe_world(&world);
    }
    let expected = watch.report(world.scene(), world.step_count());
    assert!(expected.is_some());
    // The page's run and the command line's (which keeps nothing else), stepped in frames.
    for options in [RunOptions::page(), RunOptions::command_line(false, false)] {
        let mut run = Run::new(scene.clone(), options).expect("valid");
        assert_eq!(run.activity_report().map(|r| (r.status, r.step)), Some((Status::Running, 0)));
        for n in [1, 7, 92, 400] {
            run.step(n);
        }
        assert_eq!(run.activity_report(), expected, "{options:?}");
    }

    let spec = ComparisonSpec::parse("1.boids~pso").expect("spec");
    let mut by_hand = Comparison::new(scene.clone(), spec.clone()).expect("comparison");
    let mut watch = ActivityWatch::new(Page::Compare);
    for _ in 0..300 {
        by_hand.step_n(1);
        let metrics = by_hand.metrics();
        watch.observe(by_hand.scene(), by_hand.step_count(), || metrics);
    }
    let mut comparison = Comparison::new(scene, spec).expect("comparison");
    comparison.step_n(120);
    comparison.step_n(180);
    assert_eq!(comparison.activity_report(), watch.report(by_hand.scene(), 300));
    assert_eq!(comparison.digests(), by_hand.digests(), "stepped together or in frames, the same panes");
    comparison.reset().expect("restarts");
    assert_eq!(comparison.activity_report().map(|r| (r.status, r.step)), Some((Status::Running, 0)));
}
