//! The run's history for the timeline: compact positions per step and whole-world checkpoints,
//! so the page can jump to any step and play on from there.
//!
//! Memory and time are bounded and the bounds are stated:
//! - positions are quantised to `u16` per axis relative to the scene bounds (4 bytes per agent
//!   per step; 0.31 px resolution on a 20,000 px scene). The default budget,
//!   [`REPLAY_FRAME_BUDGET_BYTES`] (all budgets are in [`crate::sim::limits`]), holds 10,000 agents × 2,000 steps at every step. Over budget,
//!   every other recorded step is dropped and recording goes on at half the rate (thinning);
//!   [`ReplayInfo::frames_thinned`] says so, so the page can put a note on screen.
//! - every `checkpoint_every` steps the whole [`World`] is cloned (positions, velocities,
//!   planner state, generator state, metric accumulators). A jump to step k restores the nearest
//!   checkpoint at or before k and re-simulates at most `checkpoint_every − 1` steps: the result
//!   is bit-identical to the original run at k. The interval is chosen so a jump re-simulates
//!   about [`REPLAY_JUMP_AGENT_STEPS`] agent-steps (20 steps of 1,000 agents or more, 200 of 100
//!   or fewer), and over [`REPLAY_CHECKPOINT_BUDGET_BYTES`] every other checkpoint is dropped and
//!   the interval doubles (stated in the info). Both halvings are a
//!   [`crate::sim::series::BoundedSeries`].
//! - the digest of each checkpoint is the check that a re-simulated run is the recorded one: a
//!   replayed step that reaches a checkpoint with another digest counts as a divergence.
//!
//! Edits during a run (a planner parameter changed at step s) are part of the history: the world
//! after the edit is checkpointed at s, so jumping to any step replays the edit where it happened.
//! Stepping on from a step before an edit starts a new future: the recorded steps after it go.

use crate::sim::limits::{
    REPLAY_CHECKPOINT_BUDGET_BYTES, REPLAY_CHECKPOINT_EVERY_RANGE, REPLAY_FRAME_BUDGET_BYTES,
    REPLAY_JUMP_AGENT_STEPS,
};
use crate::sim::series::BoundedSeries;
use crate::sim::world::World;
use glam::Vec2;
use serde::Serialize;

/// Bytes one agent takes in one recorded step (x and y as `u16`).
const BYTES_PER_AGENT_STEP: usize = 4;
/// Estimated bytes per agent of a cloned world: state arrays (pos, vel, next_vel, group, radius:
/// 32 B), metric accumulators (40 B), grid entries (~24 B) and planner state (≤ 40 B), rounded up.
const CHECKPOINT_BYTES_PER_AGENT: usize = 160;
/// Estimated fixed part of a cloned world (scene, obstacle index, grid cells).
const CHECKPOINT_BYTES_FIXED: usize = 16 << 10;
const QUANT_MAX: f32 = 65_535.0;

/// Memory limits of a [`Replay`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReplayBudget {
    /// Bytes the quantised positions may take before thinning.
    pub frame_bytes: usize,
    /// Estimated bytes the checkpoints may take before thinning.
    pub checkpoint_bytes: usize,
    /// Steps between checkpoints at the start (doubles when thinned); 0 chooses it from the
    /// agent count (see [`auto_checkpoint_every`]).
    pub checkpoint_every: u32,
}

impl Default for ReplayBudget {
    fn default() -> Self {
        Self {
            frame_bytes: REPLAY_FRAME_BUDGET_BYTES,
            checkpoint_bytes: REPLAY_CHECKPOINT_BUDGET_BYTES,
            checkpoint_every: 0,
        }
    }
}

/// What the timeline shows about the recording (serialised for the page).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReplayInfo {
    /// First recorded step (0 for a run recorded from its start).
    pub first_step: u32,
    /// Last step of the recorded history: the timeline's end.
    pub end_step: u32,
    /// Steps between recorded position frames now (1 until thinned).
    pub frame_every: u32,
    /// Recorded position frames.
    pub frames: usize,
    /// Bytes the positions take.
    pub frame_bytes: usize,
    /// The position budget in bytes.
    pub frame_budget_bytes: usize,
    /// Steps of this run the position budget holds at one frame per step.
    pub capacity_steps: usize,
    /// Times older frames were thinned to stay within the budget.
    pub frames_thinned: u32,
    /// Steps between checkpoints now: the most a jump re-simulates, plus one.
    pub checkpoint_every: u32,
    /// Checkpoints held.
    pub checkpoints: usize,
    /// Estimated bytes the checkpoints take.
    pub checkpoint_bytes: usize,
    /// The checkpoint budget in bytes.
    pub checkpoint_budget_bytes: usize,
    /// Times checkpoints were thinned.
    pub checkpoints_thinned: u32,
    /// Times a re-simulated step did not match the recorded digest (a determinism bug; the
    /// recorded future after it was replaced). Always 0 unless something is broken.
    pub diverged: u32,
    /// Steps where the run was edited (planner parameters, obstacles) while it ran.
    pub edits: Vec<u32>,
    /// A sentence for the page when anything was thinned or diverged, else `None`.
    pub note: Option<String>,
}

/// The recorded history of one run (see the module docs).
#[derive(Clone)]
pub struct Replay {
    width: f32,
    height: f32,
    agents: usize,
    budget: ReplayBudget,
    first_step: u32,
    end_step: u32,
    /// Row `f` holds the quantised (x, y) of every agent at recorded step `f`; the first step
    /// is kept through thinning.
    frames: BoundedSeries<[u16; 2]>,
    /// Snapshots in increasing step order (rows of one world); always holds the first step's
    /// and every edit's.
    checkpoints: BoundedSeries<World>,
    edits: Vec<u32>,
    diverged: u32,
}

/// The automatic checkpoint interval for `agents` agents: about [`REPLAY_JUMP_AGENT_STEPS`]
/// agent-steps.
pub fn auto_checkpoint_every(agents: usize) -> u32 {
    let agents = u32::try_from(agents.max(1)).unwrap_or(u32::MAX);
    (REPLAY_JUMP_AGENT_STEPS / agents).clamp(REPLAY_CHECKPOINT_EVERY_RANGE.0, REPLAY_CHECKPOINT_EVERY_RANGE.1)
}

/// Estimated bytes of one checkpoint of `world`.
pub fn checkpoint_bytes_estimate(world: &World) -> usize {
    CHECKPOINT_BYTES_FIXED + world.agent_count() * CHECKPOINT_BYTES_PER_AGENT
}

impl Replay {
    /// Starts recording `world` at its current step, with the default budget.
    pub fn new(world: &World) -> Self {
        Self::with_budget(world, ReplayBudget::default())
    }

    /// Starts recording `world` at its current step within `budget`.
    pub fn with_budget(world: &World, budget: ReplayBudget) -> Self {
        let scene = world.scene();
        let step = world.step_count();
        let checkpoint_every = match budget.checkpoint_every {
            0 => auto_checkpoint_every(world.agent_count()),
            n => n,
        };
        let agents = world.agent_count();
        let frame_cap =
            BoundedSeries::<[u16; 2]>::cap_for_bytes(budget.frame_bytes, agents, BYTES_PER_AGENT_STEP);
        let checkpoint_cap = budget.checkpoint_bytes / checkpoint_bytes_estimate(world);
        let mut replay = Self {
            width: scene.width.max(f32::MIN_POSITIVE),
            height: scene.height.max(f32::MIN_POSITIVE),
            agents,
            budget: ReplayBudget { checkpoint_every, ..budget },
            first_step: step,
            end_step: step,
            frames: BoundedSeries::new(agents, frame_cap, 1).with_anchor(step),
            checkpoints: BoundedSeries::new(1, checkpoint_cap, checkpoint_every).with_anchor(step),
            edits: Vec::new(),
            diverged: 0,
        };
        replay.checkpoints.push_always(step, [world.clone()]);
        replay.push_frame(world);
        replay
    }

    /// Number of agents recorded.
    pub fn agents(&self) -> usize {
        self.agents
    }

    /// The last step of the recorded history.
    pub fn end_step(&self) -> u32 {
        self.end_step
    }

    /// The first recorded step.
    pub fn first_step(&self) -> u32 {
        self.first_step
    }

    /// Records `world` after it stepped. Returns `true` when the step extended the history (the
    /// caller's other recordings should capture it too) and `false` when it re-played a recorded
    /// step (the recorded frame is kept; at a checkpoint the digest is checked).
    pub fn record(&mut self, world: &World) -> bool {
        let step = world.step_count();
        if world.agent_count() != self.agents || step <= self.first_step {
            return false;
        }
        if step <= self.end_step {
            // Stepping on before an edit would leave the edit out: that future is gone.
            if self.edits.iter().any(|&e| e >= step) {
                self.truncate_after(step - 1);
            } else {
                match self.digest_at(step) {
                    Some(recorded) if recorded != world.digest() => {
                        self.diverged += 1;
                        self.truncate_after(step - 1);
                    }
                    _ => return false,
                }
            }
        }
        self.end_step = step;
        if self.frames.due(step) {
            self.push_frame(world);
        }
        if self.checkpoints.due(step) {
            self.checkpoints.push_always(step, [world.clone()]);
            self.thin_checkpoints_if_over_budget();
        }
        true
    }

    /// Notes that `world` was edited at its current step (parameters, obstacles): the future
    /// after this step is dropped and the edited world becomes the checkpoint for this step.
    pub fn note_edit(&mut self, world: &World) {
        let step = world.step_count();
        if world.agent_count() != self.agents || step < self.first_step {
            return;
        }
        self.truncate_after(step);
        self.checkpoints.truncate_before(step);
        self.checkpoints.push_always(step, [world.clone()]);
        if step > self.first_step && !self.edits.contains(&step) {
            self.edits.push(step);
        }
        if step == self.first_step {
            // An edit before the first step replaces the start: nothing earlier to keep.
            self.edits.clear();
        }
        self.thin_checkpoints_if_over_budget();
    }

    /// Drops every recorded step after `step`.
    pub fn truncate_after(&mut self, step: u32) {
        self.frames.truncate_after(step);
        self.checkpoints.truncate_after(step);
        self.edits.retain(|&e| e <= step);
        self.end_step = self.end_step.min(step).max(self.first_step);
    }

    /// Moves `world` to `step` (clamped to the recorded history): from the current world when it
    /// is on the way, else from the nearest checkpoint at or before `step`. Returns the number of
    /// steps re-simulated (less than the checkpoint interval, except after a failed edit).
    pub fn seek(&self, step: u32, world: &mut World) -> u32 {
        self.seek_toward(step, u32::MAX, world)
    }

    /// [`Replay::seek`] in slices: moves `world` toward `step` re-simulating at most
    /// `max_steps` (restoring the checkpoint when the current world is not on the way). Called
    /// again with the same `step`, it goes on from the world it left (now on the way), so a jump
    /// that re-simulates for seconds can be cut into pieces that each answer in time; the world
    /// reached is bit-identical to one [`Replay::seek`]. Returns the steps re-simulated.
    pub fn seek_toward(&self, step: u32, max_steps: u32, world: &mut World) -> u32 {
        let target = step.clamp(self.first_step, self.end_step);
        let at = self.checkpoints.steps().partition_point(|&s| s <= target);
        let Some(checkpoint) = at.checked_sub(1).and_then(|i| self.checkpoints.row(i).first()) else {
            return 0;
        };
        let current = world.step_count();
        if !(checkpoint.step_count() <= current && current <= target) {
            *world = checkpoint.clone();
        }
        let steps = (target - world.step_count()).min(max_steps);
        world.step_n(steps);
        steps
    }

    /// The step a jump to `step` ends on (clamped to the recorded history).
    pub fn seek_target(&self, step: u32) -> u32 {
        step.clamp(self.first_step, self.end_step)
    }

    /// The recorded digest at `step`, if that step has a checkpoint.
    pub fn digest_at(&self, step: u32) -> Option<u64> {
        let i = self.checkpoints.steps().binary_search(&step).ok()?;
        self.checkpoints.row(i).first().map(World::digest)
    }

    /// The recorded positions at `step` (within the quantisation step), if that step has a frame.
    pub fn positions_at(&self, step: u32) -> Option<Vec<Vec2>> {
        let f = self.frames.steps().binary_search(&step).ok()?;
        let frame = self.frames.row(f);
        let (sx, sy) = (self.width / QUANT_MAX, self.height / QUANT_MAX);
        Some(frame.iter().map(|q| Vec2::new(f32::from(q[0]) * sx, f32::from(q[1]) * sy)).collect())
    }

    /// The recorded steps that have a position frame, increasing.
    pub fn frame_steps(&self) -> &[u32] {
        self.frames.steps()
    }

    /// The steps that have a checkpoint, increasing.
    pub fn checkpoint_steps(&self) -> Vec<u32> {
        self.checkpoints.steps().to_vec()
    }

    /// Largest position error of the quantisation (px): half a quantisation step.
    pub fn resolution(&self) -> f32 {
        0.5 * self.width.max(self.height) / QUANT_MAX
    }

    /// Bytes the position frames take.
    pub fn frame_bytes(&self) -> usize {
        self.frames.values().len() * BYTES_PER_AGENT_STEP
    }

    /// Estimated bytes the checkpoints take.
    pub fn checkpoint_bytes(&self) -> usize {
        self.checkpoints.values().iter().map(checkpoint_bytes_estimate).sum()
    }

    /// The state of the recording for the timeline.
    pub fn info(&self) -> ReplayInfo {
        let capacity_steps = self.frames.cap();
        let mut notes = Vec::new();
        if self.frames.thinned() > 0 {
            notes.push(format!(
                "positions are kept every {} steps (the {} MB budget holds {} steps of {} agents)",
                self.frames.every(),
                self.budget.frame_bytes / 1_000_000,
                capacity_steps,
                self.agents
            ));
        }
        if self.checkpoints.thinned() > 0 {
            notes.push(format!(
                "checkpoints are kept every {} steps, so a jump re-simulates up to {} steps",
                self.checkpoints.every(),
                self.checkpoints.every() - 1
            ));
        }
        if self.diverged > 0 {
            notes.push(format!(
                "{} replayed step(s) differed from the recording (a determinism bug; please report it)",
                self.diverged
            ));
        }
        ReplayInfo {
            first_step: self.first_step,
            end_step: self.end_step,
            frame_every: self.frames.every(),
            frames: self.frames.len(),
            frame_bytes: self.frame_bytes(),
            frame_budget_bytes: self.budget.frame_bytes,
            capacity_steps,
            frames_thinned: self.frames.thinned(),
            checkpoint_every: self.checkpoints.every(),
            checkpoints: self.checkpoints.len(),
            checkpoint_bytes: self.checkpoint_bytes(),
            checkpoint_budget_bytes: self.budget.checkpoint_bytes,
            checkpoints_thinned: self.checkpoints.thinned(),
            diverged: self.diverged,
            edits: self.edits.clone(),
            note: (!notes.is_empty()).then(|| {
                let mut text = notes.join("; ");
                if let Some(first) = text.get(..1) {
                    text = first.to_uppercase() + text.get(1..).unwrap_or_default();
                }
                text + "."
            }),
        }
    }

    fn push_frame(&mut self, world: &World) {
        let (sx, sy) = (QUANT_MAX / self.width, QUANT_MAX / self.height);
        self.frames.push(
            world.step_count(),
            world.positions().iter().map(|p| {
                // Agents are kept inside the bounds; the clamp only guards the conversion.
                let qx = (p.x * sx + 0.5).clamp(0.0, QUANT_MAX) as u16;
                let qy = (p.y * sy + 0.5).clamp(0.0, QUANT_MAX) as u16;
                [qx, qy]
            }),
        );
    }

    /// Thins the checkpoints while they are over budget. The first step and every edit keep
    /// theirs: without them a jump could not reproduce the run.
    fn thin_checkpoints_if_over_budget(&mut self) {
        let edits = &self.edits;
        self.checkpoints.shrink_to_cap(|s| edits.contains(&s));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::presets;

    fn world(name: &str) -> World {
        World::new((presets::find(name).expect("preset").build)()).expect("valid")
    }

    #[test]
    fn quantised_positions_stay_within_the_resolution() {
        let mut w = world("pillars");
        let mut r = Replay::new(&w);
        w.step_n(30);
        r.record(&w);
        let exact = w.positions().to_vec();
        let stored = r.positions_at(30).expect("frame at 30");
        let err = exact.iter().zip(&stored).map(|(a, b)| a.distance(*b)).fold(0.0f32, f32::max);
        assert!(err <= r.resolution() * 1.5, "error {err} vs resolution {}", r.resolution());
        assert!(r.positions_at(29).is_none(), "29 was not recorded (record was called at 30 only)");
    }

    #[test]
    fn frames_thin_within_budget_and_keep_the_first_step() {
        let mut w = world("open-field");
        let agents = w.agent_count();
        let budget = ReplayBudget { frame_bytes: 50 * agents * 4, ..ReplayBudget::default() };
        let mut r = Replay::with_budget(&w, budget);
        for _ in 0..400 {
            w.step();
            assert!(r.record(&w));
            assert!(r.frame_bytes() <= budget.frame_bytes);
        }
        let info = r.info();
        assert!(info.frames_thinned >= 3, "{info:?}");
        assert_eq!(r.frame_steps()[0], 0);
        assert!(r.frame_steps().windows(2).all(|p| p[1] - p[0] == info.frame_every));
        assert!(info.note.as_deref().is_some_and(|n| n.contains("every")), "{:?}", info.note);
        assert_eq!(info.end_step, 400);
    }

    #[test]
    fn an_edit_is_replayed_where_it_happened_and_stepping_before_it_drops_the_future() {
        let mut w = world("open-field");
        let mut r = Replay::new(&w);
        for _ in 0..150 {
            w.step();
            r.record(&w);
        }
        let mut config = w.scene().groups[0].planner.clone();
        config.set_param("max_speed", serde_json::json!(1.0)).expect("in range");
        w.set_group_planner(0, config).expect("group 0");
        r.note_edit(&w);
        for _ in 0..100 {
            w.step();
            r.record(&w);
        }
        let at_220 = {
            let mut probe = w.clone();
            r.seek(220, &mut probe);
            probe.digest()
        };
        r.seek(220, &mut w);
        assert_eq!(w.digest(), at_220);
        assert_eq!(r.info().edits, vec![150]);
        // Back before the edit, then step on: the future after the edit is gone.
        r.seek(120, &mut w);
        w.step();
        assert!(r.record(&w), "stepping on before an edit starts a new future");
        assert_eq!(r.end_step(), 121);
        assert!(r.info().edits.is_empty());
    }
}
