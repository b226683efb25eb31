//! A bounded recording of agent positions and velocities per step, for exports and replay.
//!
//! When the recording would exceed its memory budget it keeps every other recorded step and
//! records half as often from then on (thinning, [`crate::sim::series`]), and says so in
//! [`Recording::thinned`], so nothing is dropped silently. The budgets per front-end are in
//! [`crate::sim::limits`].

use crate::sim::series::BoundedSeries;
use crate::sim::world::World;
use glam::Vec2;

/// Bytes one agent takes in one recorded step (x, y, vx, vy as `f32`).
const BYTES_PER_SAMPLE: usize = 16;

/// Recorded frames of a run.
#[derive(Clone, Debug)]
pub struct Recording {
    agents: usize,
    budget_bytes: usize,
    /// Row `f` holds `[x, y, vx, vy]` of every agent at recorded step `f`.
    frames: BoundedSeries<[f32; 4]>,
}

impl Recording {
    /// An empty recording of `agents` agents, capturing every step, within `budget_bytes`.
    pub fn new(agents: usize, budget_bytes: usize) -> Self {
        let cap = BoundedSeries::<[f32; 4]>::cap_for_bytes(budget_bytes, agents, BYTES_PER_SAMPLE);
        Self { agents, budget_bytes, frames: BoundedSeries::new(agents, cap, 1) }
    }

    /// An empty recording sized for `world`'s agents, holding its current state as the first frame.
    pub fn of_world(world: &World, budget_bytes: usize) -> Self {
        let mut recording = Self::new(world.agent_count(), budget_bytes);
        recording.capture_world(world);
        recording
    }

    /// Records `world`'s current state at its current step (see [`Recording::capture`]).
    pub fn capture_world(&mut self, world: &World) {
        self.capture(world.step_count(), world.positions(), world.velocities());
    }

    /// Records the state after `step` if it falls on the current sampling interval.
    pub fn capture(&mut self, step: u32, positions: &[Vec2], velocities: &[Vec2]) {
        if positions.len() != self.agents || velocities.len() != self.agents {
            return;
        }
        let row = positions.iter().zip(velocities).map(|(p, v)| [p.x, p.y, v.x, v.y]);
        self.frames.push(step, row);
    }

    /// Drops the frames after `step` (the run went back in time and took another course).
    pub fn truncate_after(&mut self, step: u32) {
        self.frames.truncate_after(step);
    }

    /// Number of agents per frame.
    pub fn agents(&self) -> usize {
        self.agents
    }

    /// The recorded step numbers, increasing.
    pub fn steps(&self) -> &[u32] {
        self.frames.steps()
    }

    /// Steps between recorded frames now.
    pub fn every(&self) -> u32 {
        self.frames.every()
    }

    /// How many times the recording was thinned to stay within its budget.
    pub fn thinned(&self) -> u32 {
        self.frames.thinned()
    }

    /// `[x, y, vx, vy]` of every agent at recorded frame `f`.
    pub fn frame(&self, f: usize) -> &[[f32; 4]] {
        self.frames.row(f)
    }

    /// Index of the recorded frame nearest to `step`.
    pub fn nearest_frame(&self, step: u32) -> Option<usize> {
        let steps = self.frames.steps();
        if steps.is_empty() {
            return None;
        }
        let i = steps.partition_point(|&s| s < step);
        if i == 0 {
            return Some(0);
        }
        if i >= steps.len() {
            return Some(steps.len() - 1);
        }
        let (before, after) = (steps[i - 1], steps[i]);
        Some(if step - before <= after - step { i - 1 } else { i })
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.frames.values().len() * BYTES_PER_SAMPLE
    }

    /// The memory budget in bytes.
    pub fn budget_bytes(&self) -> usize {
        self.budget_bytes
    }

    /// Most steps this recording could hold at one frame per step (for stating the budget).
    pub fn capacity_steps(&self) -> usize {
        self.frames.cap()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thinning_keeps_within_budget_and_says_so() {
        let agents = 10;
        let budget = 100 * agents * BYTES_PER_SAMPLE;
        let mut r = Recording::new(agents, budget);
        let pos = vec![Vec2::ONE; agents];
        for step in 0..1000 {
            r.capture(step, &pos, &pos);
            assert!(r.bytes() <= budget);
        }
        assert!(r.thinned() >= 3);
        assert!(r.steps().windows(2).all(|w| w[1] - w[0] == r.every()));
        assert_eq!(r.steps()[0], 0);
        assert!(*r.steps().last().expect("frames") > 900);
    }

    #[test]
    fn nearest_frame_rounds_to_the_closest_step() {
        let mut r = Recording::new(1, 1 << 20);
        for step in [0, 10, 20] {
            r.capture(step, &[Vec2::splat(step as f32)], &[Vec2::ZERO]);
        }
        assert_eq!(r.nearest_frame(4), Some(0));
        assert_eq!(r.nearest_frame(6), Some(1));
        assert_eq!(r.nearest_frame(99), Some(2));
        assert_eq!(r.frame(2)[0][0], 20.0);
    }
}
