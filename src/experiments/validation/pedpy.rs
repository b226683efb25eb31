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

/// Trajectories another simulator wrote in the same text format (`id frame x y z`, metres,
/// `# framerate: F` in a comment), for measuring them with the suite's own code. Ids are the
/// walkers' order in the run's set-up, 1-based (no new id on a periodic wrap); a walker missing
/// from a frame (removed at an exit) holds its last place, standing still. Velocities are
/// central differences of the positions, taken across a periodic wrap of `period` metres.
/// A `# stopped by …` comment (a run the simulator aborted) is an error naming why.
pub fn parse_trajectory_text(text: &str, period: Option<f32>) -> Result<Trajectories, String> {
    let mut fps = None;
    let mut rows: Vec<(usize, usize, Vec2)> = vec![];
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if let Some(comment) = line.strip_prefix('#') {
            // A run the other simulator aborted (scripts/jupedsim_runs.py writes why): its
            // walkers after the abort are not walking, so nothing in it is measured.
            if let Some(why) = comment.trim().strip_prefix("stopped by") {
                return Err(format!("stopped by{why}"));
            }
            if let Some(v) = comment.trim().strip_prefix("framerate:") {
                fps = v.trim().parse::<f32>().ok().filter(|f| *f > 0.0);
            }
            continue;
        }
        if line.is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        let bad = || format!("line {}: expected `id frame x y z`, got {line:?}", n + 1);
        if fields.len() < 4 {
            return Err(bad());
        }
        let id: usize = fields[0].parse().map_err(|_| bad())?;
        let frame: usize = fields[1].parse().map_err(|_| bad())?;
        let x: f32 = fields[2].parse().map_err(|_| bad())?;
        let y: f32 = fields[3].parse().map_err(|_| bad())?;
        if id == 0 {
            return Err(format!("line {}: ids start at 1", n + 1));
        }
        rows.push((id - 1, frame, Vec2::new(x, y)));
    }
    let fps = fps.ok_or("no `# framerate: F` line")?;
    let agents = rows.iter().map(|r| r.0 + 1).max().unwrap_or(0);
    let frames = rows.iter().map(|r| r.1 + 1).max().unwrap_or(0);
    let mut pos: Vec<Vec<Option<Vec2>>> = vec![vec![None; agents]; frames];
    for (a, k, p) in rows {
        pos[k][a] = Some(p);
    }
    // A walker missing from a frame stays where it was last (or first) seen.
    for a in 0..agents {
        let first = (0..frames).find_map(|k| pos[k][a]).ok_or(format!("walker {} never appears", a + 1))?;
        let mut last = first;
        for frame in pos.iter_mut() {
            last = frame[a].unwrap_or(last);
            frame[a] = Some(last);
        }
    }
    let pos: Vec<Vec<Vec2>> = pos.into_iter().map(|f| f.into_iter().flatten().collect()).collect();
    let dt = 1.0 / fps;
    let unwrap = |d: Vec2| match period {
        Some(l) if d.x.abs() > 0.5 * l => Vec2::new(d.x - l * d.x.signum(), d.y),
        _ => d,
    };
    let vel_at = |k: usize, a: usize| {
        let (lo, hi) = (k.saturating_sub(1), (k + 1).min(frames - 1));
        if hi == lo {
            return Vec2::ZERO;
        }
        unwrap(pos[hi][a] - pos[lo][a]) / ((hi - lo) as f32 * dt)
    };
    let frames_out = (0..frames)
        .map(|k| Frame { pos: pos[k].clone(), vel: (0..agents).map(|a| vel_at(k, a)).collect() })
        .collect();
    Ok(Trajectories { frame_s: dt, group: vec![0; agents], frames: frames_out })
}

/// A recorded run as PedPy text (Export → PedPy on the page, `flockpath run --pedpy`): metres at
/// the scene's px_per_metre, titled with the scene's name.
pub fn recording_text(scene: &Scene, rec: &Recording) -> String {
    trajectory_text(&from_recording(scene, rec, scene.px_per_metre), None, &scene.name)
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

    /// Our own text read back: the same positions (to the 4 decimals written), the frame rate,
    /// velocities from the positions, and a walker that left standing where it left.
    #[test]
    fn trajectory_text_reads_back() {
        let traj = Trajectories {
            frame_s: 0.1,
            group: vec![0, 0],
            frames: (0..4)
                .map(|k| Frame {
                    pos: vec![Vec2::new(k as f32 * 0.1, 1.0), Vec2::new(5.0, 2.0 - k as f32 * 0.05)],
                    vel: vec![Vec2::new(1.0, 0.0), Vec2::new(0.0, -0.5)],
                })
                .collect(),
        };
        let read = parse_trajectory_text(&trajectory_text(&traj, None, "t"), None).expect("reads");
        assert!((read.frame_s - 0.1).abs() < 1e-5);
        assert_eq!(read.agents(), 2);
        assert_eq!(read.frames.len(), 4);
        for (f, g) in read.frames.iter().zip(&traj.frames) {
            for a in 0..2 {
                assert!(f.pos[a].distance(g.pos[a]) < 1e-4);
                assert!(f.vel[a].distance(g.vel[a]) < 1e-3, "{:?} vs {:?}", f.vel[a], g.vel[a]);
            }
        }
        // Walker 2 removed after frame 0: it stays at its last place, still.
        let gone = "# framerate: 10\n1 0 0 0 0\n2 0 3 3 0\n1 1 0.1 0 0\n";
        let read = parse_trajectory_text(gone, None).expect("reads");
        assert_eq!(read.frames[1].pos[1], Vec2::new(3.0, 3.0));
        assert_eq!(read.frames[1].vel[1], Vec2::ZERO);
        // Across a periodic wrap of 20 m the speed is the walk's, not the jump's.
        let wrap = "# framerate: 10\n1 0 29.95 1 0\n1 1 10.05 1 0\n";
        let read = parse_trajectory_text(wrap, Some(20.0)).expect("reads");
        assert!((read.frames[0].vel[0].x - 1.0).abs() < 1e-3, "{:?}", read.frames[0].vel[0]);
        assert!(parse_trajectory_text("1 0 0 0 0\n", None).is_err(), "no frame rate");
        let aborted = "# framerate: 10\n# stopped by JuPedSim at 0.74 s: outside\n1 0 0 0 0\n";
        assert!(parse_trajectory_text(aborted, None).is_err_and(|e| e.contains("0.74 s")));
        assert!(parse_trajectory_text("# framerate: 10\n1 zero 0 0 0\n", None).is_err());
    }

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
