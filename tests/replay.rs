//! Replay and scrub: jumping to step k (back or forward, across checkpoints and thinning) gives
//! the same digest as the original run at k, and playing on from there stays identical.

use flockpath::model::presets;
use flockpath::sim::replay::{Replay, ReplayBudget};
use flockpath::World;

fn world(name: &str) -> World {
    World::new((presets::find(name).expect("preset").build)()).expect("valid preset")
}

/// The digest after every step of an independent, unrecorded run (index = step).
fn truth(name: &str, steps: u32) -> Vec<u64> {
    let mut w = world(name);
    let mut out = vec![w.digest()];
    for _ in 0..steps {
        w.step();
        out.push(w.digest());
    }
    out
}

/// Records a run of `steps` with `budget`; returns the world at the end and its replay.
fn recorded(name: &str, steps: u32, budget: ReplayBudget) -> (World, Replay) {
    let mut w = world(name);
    let mut r = Replay::with_budget(&w, budget);
    for _ in 0..steps {
        w.step();
        assert!(r.record(&w), "every new step extends the history");
    }
    (w, r)
}

fn scrub_matches_the_original(name: &str) {
    const STEPS: u32 = 420;
    let truth = truth(name, STEPS);
    let agents = world(name).agent_count();
    // Tight budgets so both thinnings happen during the run.
    let budget = ReplayBudget {
        frame_bytes: 120 * agents * 4,
        checkpoint_bytes: 3 * flockpath::sim::replay::checkpoint_bytes_estimate(&world(name)),
        checkpoint_every: 50,
    };
    let (mut w, r) = recorded(name, STEPS, budget);
    let info = r.info();
    assert!(info.frames_thinned > 0 && info.checkpoints_thinned > 0, "{name}: {info:?}");
    assert!(info.note.is_some(), "thinning is stated");
    assert_eq!(w.digest(), truth[STEPS as usize]);

    // Back and forth, including checkpoint steps, steps between them and the ends.
    for k in [0u32, 1, 49, 50, 51, 199, 200, 333, 419, 420, 7, 250, 100] {
        let resimulated = r.seek(k, &mut w);
        assert_eq!(w.step_count(), k, "{name}: seek to {k}");
        assert!(resimulated < r.info().checkpoint_every, "{name}: {resimulated} steps for {k}");
        assert_eq!(w.digest(), truth[k as usize], "{name}: digest at {k} after scrubbing");
        if let Some(d) = r.digest_at(k) {
            assert_eq!(d, truth[k as usize], "{name}: recorded digest at {k}");
        }
    }
    // Play on from a scrubbed step: the same run.
    r.seek(137, &mut w);
    let mut r = r;
    for k in 138..=260u32 {
        w.step();
        assert!(!r.record(&w), "re-played steps are not new");
        assert_eq!(w.digest(), truth[k as usize], "{name}: digest at {k} after playing on");
    }
    assert_eq!(r.info().diverged, 0);
    assert_eq!(r.end_step(), STEPS, "the recorded future is kept: nothing changed");
}

#[test]
fn scrubbing_boids_gives_the_original_digests() {
    scrub_matches_the_original("pillars");
}

#[test]
fn scrubbing_pso_gives_the_original_digests() {
    scrub_matches_the_original("pso-four-corners");
}

#[test]
fn scrubbing_firefly_gives_the_original_digests() {
    scrub_matches_the_original("firefly-migration");
}

#[test]
fn scrubbing_forces_gives_the_original_digests() {
    scrub_matches_the_original("forces-e2-narrow");
}

#[test]
fn metrics_after_a_jump_equal_the_original_metrics() {
    let mut original = world("pillars");
    original.step_n(230);
    let (mut w, r) = recorded("pillars", 400, ReplayBudget::default());
    r.seek(230, &mut w);
    assert_eq!(w.metrics(), original.metrics());
}

#[test]
fn a_jump_in_slices_ends_on_the_world_of_one_jump() {
    // The page's worker cuts a long jump into slices (`seek_toward`): each slice re-simulates
    // at most `max_steps`, the next goes on from there, and the world reached is the original's.
    const STEPS: u32 = 300;
    let truth = truth("pillars", STEPS);
    let budget = ReplayBudget { checkpoint_every: 100, ..ReplayBudget::default() };
    let (mut w, r) = recorded("pillars", STEPS, budget);
    for (target, slice) in [(99u32, 7u32), (250, 1), (120, 30), (299, 200), (5, 2)] {
        let mut slices = 0;
        let mut resimulated = 0;
        loop {
            let steps = r.seek_toward(target, slice, &mut w);
            assert!(steps <= slice, "a slice re-simulates at most {slice}: {steps}");
            resimulated += steps;
            slices += 1;
            if w.step_count() == r.seek_target(target) {
                break;
            }
            assert!(slices < 1_000, "the jump to {target} ends");
        }
        assert_eq!(w.digest(), truth[target as usize], "digest at {target} after {slices} slices of {slice}");
        assert!(resimulated < 100, "no more than one jump re-simulates: {resimulated}");
        assert!(slices >= (target % 100).div_ceil(slice) as usize, "the slices were used: {slices}");
    }
    assert_eq!(r.seek_target(10_000), STEPS, "a jump past the end ends on the last step");
}

#[test]
fn the_recording_stays_within_its_budgets() {
    let w = world("pso-crowd");
    let agents = w.agent_count();
    let budget = ReplayBudget {
        frame_bytes: 64 * agents * 4,
        checkpoint_bytes: 4 * flockpath::sim::replay::checkpoint_bytes_estimate(&w),
        checkpoint_every: 20,
    };
    let mut w = w;
    let mut r = Replay::with_budget(&w, budget);
    for _ in 0..1000 {
        w.step();
        r.record(&w);
        assert!(r.frame_bytes() <= budget.frame_bytes);
        assert!(r.checkpoint_bytes() <= budget.checkpoint_bytes);
    }
    let info = r.info();
    assert_eq!(info.end_step, 1000);
    assert!(info.frames >= 32, "thinning keeps at least half the budget: {info:?}");
    assert!(info.frame_every >= 16 && info.checkpoint_every >= 160, "{info:?}");
    assert_eq!(r.frame_steps()[0], 0, "the start is never thinned away");
    assert_eq!(r.checkpoint_steps()[0], 0);
}

#[test]
fn the_default_budget_holds_ten_thousand_agents_for_two_thousand_steps() {
    let r = ReplayBudget::default();
    assert!(r.frame_bytes >= 10_000 * 2_000 * 4);
}
