//! `Run`, natively: the session logic the page and `flockpath run` share. A run keeps its
//! recording, timeline and metric series in step through new steps, jumps, live edits and
//! restarts, within its budgets, and runs exactly the world a plain `World` runs.

use flockpath::model::presets;
use flockpath::sim::limits;
use flockpath::sim::replay::{checkpoint_bytes_estimate, ReplayBudget};
use flockpath::sim::run::{Run, RunOptions};
use flockpath::{PlannerConfig, Scene, World};

fn scene(name: &str) -> Scene {
    (presets::find(name).expect("preset").build)()
}

/// The digest after every step of a plain, unrecorded world (index = step).
fn truth(scene: &Scene, steps: u32) -> Vec<u64> {
    let mut w = World::new(scene.clone()).expect("valid");
    let mut out = vec![w.digest()];
    for _ in 0..steps {
        w.step();
        out.push(w.digest());
    }
    out
}

fn page_run(name: &str) -> Run {
    Run::new(scene(name), RunOptions::page()).expect("valid preset")
}

#[test]
fn every_new_step_is_recorded_by_the_recording_the_timeline_and_the_metric_series() {
    let truth = truth(&scene("two-groups-swap"), 300);
    let mut run = page_run("two-groups-swap");
    let mut seen = Vec::new();
    run.step_each(300, |w| seen.push(w.step_count()));
    assert_eq!(seen, (1..=300).collect::<Vec<_>>(), "the callback sees every step once");
    assert_eq!(run.world().digest(), truth[300], "a Run steps the same world a plain World does");
    let r = run.recording();
    assert_eq!(r.steps(), (0..=300).collect::<Vec<_>>().as_slice());
    assert_eq!(r.frame(300)[0][0], run.world().positions()[0].x);
    let replay = run.replay().expect("the page keeps a timeline");
    assert_eq!((replay.first_step(), replay.end_step()), (0, 300));
    let m = run.metric_series();
    let every = limits::METRIC_SERIES_EVERY;
    assert_eq!(m.steps(), (1..=300 / every).map(|k| k * every).collect::<Vec<_>>().as_slice());
    assert_eq!(m.groups(), 2);
    let arrived = m.series("arrived_share", None).expect("series");
    let last = *arrived.last().expect("samples");
    assert_eq!(f64::from(last), f64::from(run.world().metrics().overall.arrived_share as f32));
}

#[test]
fn a_jump_back_is_bit_identical_and_replayed_steps_are_not_recorded_again() {
    let truth = truth(&scene("pillars"), 240);
    let mut run = page_run("pillars");
    run.step(240);
    for k in [100u32, 0, 239, 37, 240] {
        let resimulated = run.seek(k).expect("seek");
        assert_eq!(run.world().step_count(), k);
        assert_eq!(run.world().digest(), truth[k as usize], "digest at {k} after the jump");
        let every = run.replay().expect("timeline").info().checkpoint_every;
        assert!(resimulated < every, "{resimulated} steps re-simulated for a jump to {k}");
    }
    run.seek(60).expect("seek");
    run.step(180);
    assert_eq!(run.world().digest(), truth[240], "playing on from a jump is the same run");
    let info = run.replay().expect("timeline").info();
    assert_eq!((info.end_step, info.diverged), (240, 0));
    assert_eq!(run.recording().steps().len(), 241, "replayed steps are not recorded twice");
    assert_eq!(run.metric_series().steps().last(), Some(&240));
}

#[test]
fn a_jump_keeps_the_view_shown_now() {
    let mut run = page_run("open-field");
    run.step(50);
    let mut view = run.world().scene().view;
    view.trails = !view.trails;
    run.set_view(view).expect("valid view");
    assert_eq!(run.world().step_count(), 50, "view options do not restart the run");
    assert!(run.replay().expect("timeline").info().edits.is_empty(), "nor are they an edit");
    run.seek(10).expect("seek");
    assert_eq!(run.world().scene().view, view, "the checkpoint's older view is not restored");
}

#[test]
fn a_live_edit_after_a_jump_back_drops_the_old_future_everywhere() {
    let truth = truth(&scene("open-field"), 200);
    let mut run = page_run("open-field");
    run.step(200);
    run.seek(100).expect("seek");
    let mut config = run.world().scene().groups[0].planner.clone();
    config.set_param("max_speed", serde_json::json!(1.0)).expect("in range");
    run.set_group_planner(0, config).expect("valid planner");
    assert_eq!(run.world().step_count(), 100, "a live edit does not restart");
    let replay = run.replay().expect("timeline");
    assert_eq!((replay.end_step(), replay.info().edits), (100, vec![100]));
    assert_eq!(run.recording().steps().last(), Some(&100), "the recording's old future is gone");
    run.step(20);
    assert_ne!(run.world().digest(), truth[120], "the edit changed the run");
    assert_eq!(run.recording().steps().last(), Some(&120));
    let samples = run.metric_series().steps();
    assert_eq!(samples.last(), Some(&120));
    assert!(samples.windows(2).all(|w| w[1] - w[0] == limits::METRIC_SERIES_EVERY), "{samples:?}");
    // The edit is part of the history: a jump across it replays it where it happened.
    let at_120 = run.world().digest();
    run.seek(30).expect("seek");
    assert_eq!(run.world().digest(), truth[30], "before the edit: the original run");
    run.seek(120).expect("seek");
    assert_eq!(run.world().digest(), at_120);
}

#[test]
fn moving_a_waypoint_while_running_is_a_live_edit_that_does_not_restart() {
    let mut run = page_run("igsa-path-2");
    while run.advance_planning(200) < 1.0 {}
    run.step(120);
    let path = run.world().planned_path(0).expect("a planned path").clone();
    let mut waypoints = path.points[1..path.points.len() - 1].to_vec();
    waypoints[0][0] += 25.0;
    let mut config = run.world().scene().groups[0].planner.clone();
    let PlannerConfig::Igsa(params) = &mut config else { panic!("an igsa preset") };
    params.waypoints = waypoints.clone();
    run.set_group_planner(0, config).expect("an edited path is accepted");
    assert_eq!(run.world().step_count(), 120, "the run goes on");
    assert_eq!(run.recording().steps().first(), Some(&0), "the recording was not restarted");
    assert_eq!(run.replay().expect("timeline").info().edits, vec![120]);
    assert_eq!(run.world().planned_path(0).expect("edited path").points[1], waypoints[0]);
    run.step(60);
    let at_180 = run.world().digest();
    run.seek(40).expect("seek");
    run.seek(180).expect("seek");
    assert_eq!(run.world().digest(), at_180, "a jump across the move replays it");
    assert_eq!(run.replay().expect("timeline").info().diverged, 0);
}

#[test]
fn a_new_run_starts_a_new_recording_and_timeline() {
    let mut run = page_run("open-field");
    run.step(100);
    run.reset().expect("reset");
    assert_eq!(run.world().step_count(), 0);
    assert_eq!(run.recording().steps(), &[0]);
    assert_eq!(run.replay().expect("timeline").end_step(), 0);
    assert!(run.metric_series().steps().is_empty(), "the old run's samples went with it");
    run.step(10);
    assert_eq!(run.metric_series().steps(), &[5, 10]);
    // An edit to the groups respawns: a new run too.
    let mut edited = run.world().scene().clone();
    edited.groups[0].count += 1;
    run.edit_scene(edited).expect("valid edit");
    assert_eq!(run.world().step_count(), 0);
    assert_eq!(run.recording().agents(), run.world().agent_count());
    assert_eq!(run.recording().steps(), &[0]);
    // Another seed: another run of the same scene.
    let before = run.world().digest();
    let seed = run.world().scene().seed;
    run.set_seed(seed.wrapping_add(1)).expect("valid seed");
    assert_ne!(run.world().digest(), before);
}

#[test]
fn loading_a_scene_forgets_the_metric_series_at_once() {
    let mut run = page_run("two-groups-swap");
    run.step(50);
    assert_eq!(run.metric_series().groups(), 2);
    run.load(scene("open-field")).expect("valid scene");
    assert!(run.metric_series().steps().is_empty(), "another scene's samples are not this run's");
    run.step(5);
    assert_eq!((run.metric_series().groups(), run.metric_series().steps()), (1, &[5][..]));
    assert!(run.load(Scene::empty(1.0, 1.0)).is_err(), "a refused scene…");
    assert_eq!(run.world().scene().name, scene("open-field").name, "…leaves the run as it was");
    run.load(scene("pillars")).expect("valid scene");
    assert!(run.metric_series().steps().is_empty(), "as many groups, still another run");
}

#[test]
fn cancelling_the_planning_goes_back_to_the_world_shown_before() {
    let mut run = page_run("open-field");
    run.step(30);
    let before = run.world().digest();
    run.load(scene("igsa-path-2")).expect("valid scene");
    assert!(run.world().planning_progress() < 1.0, "the page plans in slices");
    assert!(run.can_cancel_planning());
    assert!(run.cancel_planning());
    assert_eq!(run.world().digest(), before);
    assert_eq!(run.world().step_count(), 30);
    assert_eq!(run.recording().steps(), &[30], "a new recording from the world gone back to");
    assert!(!run.cancel_planning(), "nothing left to cancel");
    // Planned to the end, there is nothing to cancel either.
    run.load(scene("igsa-path-2")).expect("valid scene");
    while run.advance_planning(200) < 1.0 {}
    assert!(!run.can_cancel_planning());
    assert_eq!(run.replay().expect("timeline").first_step(), 0);
}

#[test]
fn full_budgets_halve_and_a_jump_stays_exact() {
    let s = scene("open-field");
    let world = World::new(s.clone()).expect("valid");
    let agents = world.agent_count();
    let checkpoint_bytes = 8 * checkpoint_bytes_estimate(&world);
    let options = RunOptions {
        sliced_planning: false,
        recording_budget_bytes: Some(40 * agents * 16),
        replay: Some(ReplayBudget { frame_bytes: 60 * agents * 4, checkpoint_bytes, checkpoint_every: 25 }),
        metric_series: Some((1, 16)),
    };
    let truth = truth(&s, 500);
    let mut run = Run::new(s, options).expect("valid");
    run.step(500);
    let r = run.recording();
    assert!(r.thinned() >= 3 && r.bytes() <= 40 * agents * 16, "thinned {} bytes {}", r.thinned(), r.bytes());
    assert!(r.steps().windows(2).all(|w| w[1] - w[0] == r.every()) && r.every() >= 8);
    assert_eq!(r.steps()[0], 0);
    assert!(*r.steps().last().expect("frames") + r.every() > 500, "the recording spans the run");
    let m = run.metric_series();
    assert!(m.steps().len() <= 16 && m.thinned() >= 4 && *m.steps().last().expect("samples") > 450);
    let info = run.replay().expect("timeline").info();
    assert!(info.frames_thinned > 0 && info.checkpoints_thinned > 0, "{info:?}");
    assert!(info.frame_bytes <= info.frame_budget_bytes && info.checkpoints <= 8, "{info:?}");
    assert!(info.note.is_some(), "thinning is stated");
    for k in [333u32, 7, 499] {
        run.seek(k).expect("seek");
        assert_eq!(run.world().digest(), truth[k as usize], "jump to {k} after thinning");
    }
}

#[test]
fn the_command_line_run_records_only_what_it_writes_and_runs_the_same_world() {
    let s = scene("two-groups-swap");
    let mut bare = Run::new(s.clone(), RunOptions::command_line(false, false)).expect("valid");
    bare.step(120);
    assert!(bare.recording().steps().is_empty(), "no export asked for: nothing recorded");
    assert!(bare.metric_series().steps().is_empty() && bare.replay().is_none());
    assert_eq!(bare.seek(10).expect("no timeline"), 0);
    assert_eq!(bare.world().step_count(), 120, "without a timeline a seek does not move");

    let mut full = Run::new(s.clone(), RunOptions::command_line(true, true)).expect("valid");
    full.step(120);
    let mut page = Run::new(s, RunOptions::page()).expect("valid");
    page.step(120);
    assert_eq!(full.world().digest(), bare.world().digest());
    assert_eq!(page.world().digest(), bare.world().digest(), "page and command line: the same run");
    assert_eq!(full.recording().steps().len(), 121);
    assert_eq!(full.metric_series().steps(), page.metric_series().steps());
    assert_eq!(full.recording().budget_bytes(), limits::CLI_RECORDING_BUDGET_BYTES);
    assert_eq!(page.recording().budget_bytes(), limits::PAGE_RECORDING_BUDGET_BYTES);
}

#[test]
fn the_command_line_help_states_the_limits_it_uses() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_flockpath"))
        .args(["run", "--help"])
        .output()
        .expect("the binary runs");
    // Words as clap wraps them: any run of white space is one space.
    let help = String::from_utf8_lossy(&out.stdout).split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(help.contains(&format!("at most {}", limits::CLI_MAX_STEPS)), "{help}");
    assert!(help.contains(&format!("every {} steps", limits::METRIC_SERIES_EVERY)), "{help}");
    assert!(help.contains(&format!("beyond {} samples", limits::CLI_METRIC_SERIES_CAP)), "{help}");
    assert!(help.contains(&format!("up to {} GiB", limits::CLI_RECORDING_BUDGET_BYTES >> 30)), "{help}");
}
