//! Running a world and sampling it into [`Trajectories`] in metres and seconds.

use super::measure::{Frame, Trajectories};
use super::units::{mps, PX_PER_METRE};
use crate::model::scene::DT;
use crate::sim::metrics::Metrics;
use crate::sim::world::World;

/// A finished run: its trajectories and the world's own metrics.
pub struct Recorded {
    /// Frames every `sample_every` steps, from the start.
    pub traj: Trajectories,
    /// The world's metrics at the end (`None` for trajectories another simulator wrote).
    pub metrics: Option<Metrics>,
}

/// The world's agents now, in metres and m/s.
pub fn frame_of(world: &World) -> Frame {
    Frame {
        pos: world.positions().iter().map(|p| *p / PX_PER_METRE).collect(),
        vel: world.velocities().iter().map(|v| *v * (mps(1.0))).collect(),
    }
}

/// Steps `world` up to `steps` times, sampling a frame every `every` steps (and at the start);
/// stops early at a sample where `done` holds. Whole intervals only (`steps` rounds down).
pub fn record(mut world: World, steps: u32, every: u32, done: impl Fn(&Frame) -> bool) -> Recorded {
    world.set_fitness_sample_every(0);
    let every = every.max(1);
    let mut traj = Trajectories {
        frame_s: every as f32 * DT,
        group: world.group_of().to_vec(),
        frames: vec![frame_of(&world)],
    };
    for _ in 0..steps / every {
        world.step_n(every);
        let frame = frame_of(&world);
        let stop = done(&frame);
        traj.frames.push(frame);
        if stop {
            break;
        }
    }
    Recorded { traj, metrics: Some(world.metrics()) }
}
