//! Trajectories in PedPy's plain-text format (`pedpy.load_trajectory_from_txt`): comment
//! lines with the frame rate and the unit, then one line per agent and frame:
//! `id frame x y z` in metres (z = 0), separated by spaces.

use super::measure::{Frame, Trajectories};
use crate::model::scene::{Scene, DT};
use crate::sim::recording::Recording;
use glam::Vec2;
use std::fmt::Write as _;

/// `traj` as PedPy text. With `period` (m, a periodic corridor) an agent that wraps round
/// gets a new id from then on: PedPy sees each pass as its own pedestrian, so no speed is
/// taken across the jump. `title` goes in the first comment line.
pub fn trajectory_text(traj: &Trajectories, period: Option<f32>, title: &str) -> String {
    let n = traj.agents();
    let mut ids: Vec<u32> = (1..=n as u32).collect();
    let mut next_id = n as u32 + 1;
    let fps = if traj.frame_s > 0.0 { 1.0 / traj.frame_s } else { 0.0 };
    let mut out = String::with_capacity(traj.frames.len() * n * 32 + 256);
    let title: String = title.chars().filter(|c| !c.is_control()).collect();
    let _ = writeln!(out, "# flockpath trajectories: {title}");
    let _ = writeln!(out, "# framerate: {fps:.4}");
    out.push_str("# unit: metre; y grows downwards as on the canvas\n");
    out.push_str("# id frame x/m y/m z/m\n");
    let mut previous: Option<&Frame> = None;
    for (k, f) in traj.frames.iter().enumerate() {
        for (a, p) in f.pos.iter().enumerate() {
            if let (Some(l), Some(q)) = (period, previous.and_then(|f| f.pos.get(a))) {
                if (p.x - q.x).abs() > 0.5 * l {
                    ids[a] = next_id;
                    next_id += 1;
                }
            }
            let _ = writeln!(out, "{} {k} {:.4} {:.4} 0", ids[a], p.x, p.y);
        }
        previous = Some(f);
    }
    out
}

/// A recording (px, every `rec.every()` steps) of `scene` as trajectories in metres.
pub fn from_recording(scene: &Scene, rec: &Recording, px_per_metre: f32) -> Trajectories {
    let group =
        scene.groups.iter().enumerate().flat_map(|(g, gr)| std::iter::repeat_n(g as u32, gr.count as usize));
    let to_mps = 1.0 / (px_per_metre * DT);
    Trajectories {
        frame_s: rec.every() as f32 * DT,
        group: group.collect(),
        frames: (0..rec.steps().len())
            .map(|f| {
                let s = rec.frame(f);
                Frame {
                    pos: s.iter().map(|a| Vec2::new(a[0], a[1]) / px_per_metre).collect(),
                    vel: s.iter().map(|a| Vec2::new(a[2], a[3]) * to_mps).collect(),
                }
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_has_frame_rate_unit_and_one_line_per_agent_and_frame() {
        let traj = Trajectories {
            frame_s: 0.1,
            group: vec![0, 0],
            frames: (0..3)
                .map(|k| Frame {
                    pos: vec![Vec2::new(k as f32, 1.0), Vec2::new(19.5 + 0.4 * k as f32, 2.0)],
                    vel: vec![Vec2::ZERO; 2],
                })
                .map(|mut f| {
                    f.pos[1].x = f.pos[1].x.rem_euclid(20.0);
                    f
                })
                .collect(),
        };
        let text = trajectory_text(&traj, Some(20.0), "test");
        assert!(text.contains("# framerate: 10.0000"), "{text}");
        assert!(text.contains("x/m") && !text.contains("cm"), "{text}");
        let data: Vec<Vec<&str>> =
            text.lines().filter(|l| !l.starts_with('#')).map(|l| l.split(' ').collect()).collect();
        assert_eq!(data.len(), 6);
        assert_eq!(data[2], ["1", "1", "1.0000", "1.0000", "0"]);
        // Agent 2 wraps between frames 0 (19.5) and 1 (19.9 → no) and 2 (20.3 → 0.3): new id.
        assert_eq!(data[1][0], "2");
        assert_eq!(data[3][0], "2");
        assert_eq!(data[5][..3], ["3", "2", "0.3000"]);
        // Without a period the id stays.
        assert!(trajectory_text(&traj, None, "t").lines().filter(|l| l.starts_with("2 ")).count() == 3);
    }
}
