//! Exports of a recorded run: paths as CSV and JSON, a Maya MEL script, a Blender Python script
//! and SVG trails. 3-D tools get the ground plane as x–z with y up (Maya) or x–y with z up and
//! y flipped (Blender), as the papers did when they imported their paths into Maya.
//!
//! Layer: export. Uses `model` and `sim` (the recording).

use crate::model::scene::DT;
use crate::model::scene::{parse_color, Scene};
use crate::sim::recording::Recording;
use serde::Serialize;
use std::fmt::Write as _;

/// Options of the 3-D exports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExportOptions {
    /// Frames per second of the animation (one key per frame). Default 24.
    pub fps: f32,
    /// Scene px → 3-D units. Default 0.01 (1 px = 1 cm in Maya, 0.01 m in Blender).
    pub scale: f32,
}

impl ExportOptions {
    /// Options from user input: `fps` in 1…240 and `scale` finite and > 0, else an error
    /// naming the value.
    pub fn checked(fps: f32, scale: f32) -> Result<Self, ExportError> {
        if !(fps.is_finite() && (1.0..=240.0).contains(&fps)) {
            return Err(ExportError::FrameRate(fps));
        }
        if !(scale.is_finite() && scale > 0.0) {
            return Err(ExportError::Scale(scale));
        }
        Ok(Self { fps, scale })
    }
}

/// Why an export's options were refused.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// Keyframes per second outside 1…240 (or not a number).
    #[error("the frame rate must be 1…240 fps, not {0}")]
    FrameRate(f32),
    /// A scene-to-3-D scale that is not a finite number above 0.
    #[error("the scale must be a number > 0, not {0}")]
    Scale(f32),
}

impl crate::model::refusal::Refusal for ExportError {
    fn message(&self) -> crate::model::refusal::Message {
        use crate::model::refusal::{Code, Message};
        match self {
            ExportError::FrameRate(x) => Message::new(Code::ExportFrameRate).with("value", x.to_string()),
            ExportError::Scale(x) => Message::new(Code::ExportScale).with("value", x.to_string()),
        }
    }
}

impl Default for ExportOptions {
    fn default() -> Self {
        Self { fps: 24.0, scale: 0.01 }
    }
}

/// Group index of each agent, from the scene's group sizes.
fn group_of_agents(scene: &Scene) -> Vec<usize> {
    scene
        .groups
        .iter()
        .enumerate()
        .flat_map(|(g, group)| std::iter::repeat_n(g, group.count as usize))
        .collect()
}

/// The time of `step` in seconds as text: `steps × DT` to the microsecond, trailing zeros dropped
/// (`0`, `0.016667`, `5`), not the f32 product's noise (`5.0000005`).
fn seconds_at(step: u32) -> String {
    // DT is 1/60 s rounded to f32; dividing by the whole steps per second keeps long runs exact.
    let steps_per_second = (1.0 / f64::from(DT)).round();
    let text = format!("{:.6}", f64::from(step) / steps_per_second);
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `agent,group,step,time,x,y,vx,vy`: one row per agent per recorded step.
pub fn paths_csv(scene: &Scene, rec: &Recording) -> String {
    let groups = group_of_agents(scene);
    let mut out = String::with_capacity(rec.steps().len() * rec.agents() * 48 + 64);
    out.push_str("agent,group,step,time,x,y,vx,vy\n");
    for (f, &step) in rec.steps().iter().enumerate() {
        let time = seconds_at(step);
        for (i, s) in rec.frame(f).iter().enumerate() {
            let g = groups.get(i).copied().unwrap_or(0);
            let _ = writeln!(out, "{i},{g},{step},{time},{},{},{},{}", s[0], s[1], s[2], s[3]);
        }
    }
    out
}

#[derive(Serialize)]
struct JsonAgent<'a> {
    id: usize,
    group: usize,
    group_name: &'a str,
    color: &'a str,
    /// Flat `[x0, y0, x1, y1, …]` at the recording's steps.
    xy: Vec<f32>,
}

#[derive(Serialize)]
struct JsonPaths<'a> {
    scene: &'a str,
    dt: f32,
    width: f32,
    height: f32,
    steps: &'a [u32],
    agents: Vec<JsonAgent<'a>>,
}

/// Paths as JSON: per agent its group, colour and flat `xy` samples at the listed `steps`.
pub fn paths_json(scene: &Scene, rec: &Recording) -> String {
    let groups = group_of_agents(scene);
    let mut agents: Vec<JsonAgent> = (0..rec.agents())
        .map(|i| {
            let g = groups.get(i).copied().unwrap_or(0);
            let group = scene.groups.get(g);
            JsonAgent {
                id: i,
                group: g,
                group_name: group.map_or("", |gr| gr.name.as_str()),
                color: group.map_or("#808080", |gr| gr.color.as_str()),
                xy: Vec::with_capacity(rec.steps().len() * 2),
            }
        })
        .collect();
    for f in 0..rec.steps().len() {
        for (a, s) in agents.iter_mut().zip(rec.frame(f)) {
            a.xy.extend_from_slice(&[s[0], s[1]]);
        }
    }
    let doc = JsonPaths {
        scene: &scene.name,
        dt: DT,
        width: scene.width,
        height: scene.height,
        steps: rec.steps(),
        agents,
    };
    // Plain derived records with string keys: writing them cannot fail (a non-finite number is
    // written as null), so a failure is a bug and panics loudly rather than exporting "".
    serde_json::to_string(&doc).expect("the paths document always serialises")
}

/// For each animation frame 1, 2, …: the recorded frame index nearest its time.
fn keyframes(rec: &Recording, fps: f32) -> Vec<(u32, usize)> {
    let Some(&last) = rec.steps().last() else { return Vec::new() };
    let fps = if fps.is_finite() && fps > 0.0 { fps } else { 24.0 };
    let duration = last as f32 * DT;
    let frames = (duration * fps).floor() as u32 + 1;
    let mut keys: Vec<(u32, usize)> = Vec::with_capacity(frames as usize);
    for k in 0..frames {
        let step = ((k as f32 / fps) / DT).round() as u32;
        if let Some(f) = rec.nearest_frame(step) {
            // Skip repeats when the recording is coarser than the frame rate.
            if keys.last().is_none_or(|&(_, prev)| prev != f) {
                keys.push((k + 1, f));
            }
        }
    }
    keys
}

fn safe_name(s: &str) -> String {
    let cleaned: String = s.chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect();
    if cleaned.is_empty() {
        "group".into()
    } else {
        cleaned
    }
}

/// Maya's name for a frame rate, for `currentUnit -time`.
fn maya_time_unit(fps: f32) -> &'static str {
    match fps.round() as u32 {
        15 => "game",
        25 => "pal",
        30 => "ntsc",
        48 => "show",
        50 => "palf",
        60 => "ntscf",
        _ => "film",
    }
}

/// A MEL script creating one keyframed locator per agent (x–z ground plane, y up), grouped per
/// group, with the playback range set. Source it in Maya's script editor.
pub fn maya_mel(scene: &Scene, rec: &Recording, opts: ExportOptions) -> String {
    let groups = group_of_agents(scene);
    let keys = keyframes(rec, opts.fps);
    let last_frame = keys.last().map_or(1, |k| k.0);
    let mut out = String::new();
    let _ =
        writeln!(out, "// flockpath export: scene \"{}\", {} agents", safe_name(&scene.name), rec.agents());
    let _ = writeln!(out, "// ground plane x-z, y up; 1 px = {} units; {} fps", opts.scale, opts.fps);
    let _ = writeln!(out, "currentUnit -time {};", maya_time_unit(opts.fps));
    let _ = writeln!(out, "playbackOptions -min 1 -max {last_frame};");
    for (g, group) in scene.groups.iter().enumerate() {
        let _ = writeln!(out, "group -empty -name \"{}_{g}\";", safe_name(&group.name));
    }
    for i in 0..rec.agents() {
        let g = groups.get(i).copied().unwrap_or(0);
        let name = format!("agent_{i}");
        let _ = writeln!(out, "spaceLocator -name \"{name}\";");
        if let Some(group) = scene.groups.get(g) {
            let _ = writeln!(out, "parent \"{name}\" \"{}_{g}\";", safe_name(&group.name));
        }
        for &(frame, f) in &keys {
            let s = rec.frame(f)[i];
            let (x, z) = (s[0] * opts.scale, s[1] * opts.scale);
            let _ =
                writeln!(out, "setKeyframe -time {frame} -attribute \"translateX\" -value {x} \"{name}\";");
            let _ =
                writeln!(out, "setKeyframe -time {frame} -attribute \"translateZ\" -value {z} \"{name}\";");
        }
    }
    out
}

/// A Blender Python script creating one keyframed empty per agent (x–y ground plane, z up, canvas
/// y flipped), coloured per group, with the scene frame range and fps set. Run it in Blender.
pub fn blender_py(scene: &Scene, rec: &Recording, opts: ExportOptions) -> String {
    let groups = group_of_agents(scene);
    let keys = keyframes(rec, opts.fps);
    let last_frame = keys.last().map_or(1, |k| k.0);
    let mut out = String::new();
    out.push_str("# flockpath export: run inside Blender (Scripting workspace)\n");
    out.push_str("import bpy\n\n");
    let _ = writeln!(out, "scene = bpy.context.scene");
    let _ = writeln!(out, "scene.render.fps = {}", opts.fps.round().max(1.0) as u32);
    let _ = writeln!(out, "scene.frame_start = 1");
    let _ = writeln!(out, "scene.frame_end = {last_frame}");
    out.push_str("\nGROUPS = [\n");
    for group in &scene.groups {
        let [r, g, b] = parse_color(&group.color);
        let _ = writeln!(
            out,
            "    ({:?}, ({:.4}, {:.4}, {:.4}, 1.0)),",
            safe_name(&group.name),
            f32::from(r) / 255.0,
            f32::from(g) / 255.0,
            f32::from(b) / 255.0
        );
    }
    out.push_str("]\n\n# Per agent: (group index, [(frame, x, y), ...])\nAGENTS = [\n");
    for i in 0..rec.agents() {
        let g = groups.get(i).copied().unwrap_or(0);
        let _ = write!(out, "    ({g}, [");
        for &(frame, f) in &keys {
            let s = rec.frame(f)[i];
            let _ = write!(out, "({frame}, {}, {}), ", s[0] * opts.scale, -s[1] * opts.scale);
        }
        out.push_str("]),\n");
    }
    out.push_str(
        r#"]

collections = []
for name, color in GROUPS:
    coll = bpy.data.collections.new("flockpath_" + name)
    scene.collection.children.link(coll)
    collections.append((coll, color))

for index, (group, keys) in enumerate(AGENTS):
    empty = bpy.data.objects.new("agent_%d" % index, None)
    empty.empty_display_type = "CONE"
    empty.empty_display_size = 0.05
    if collections:
        coll, color = collections[group]
        empty.color = color
        coll.objects.link(empty)
    else:
        scene.collection.objects.link(empty)
    for frame, x, y in keys:
        empty.location = (x, y, 0.0)
        empty.keyframe_insert(data_path="location", frame=frame)
"#,
    );
    out
}

/// The recorded trails as SVG polylines, one per agent, coloured by group, over the obstacles
/// and the goals where they are when the trails end.
pub fn trails_svg(scene: &Scene, rec: &Recording) -> String {
    let groups = group_of_agents(scene);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w} {h}" width="{w}" height="{h}">"#,
        w = scene.width,
        h = scene.height
    );
    let _ = writeln!(out, r##"<rect width="100%" height="100%" fill="#f7f7f4"/>"##);
    for o in &scene.obstacles {
        match o {
            crate::model::geometry::Obstacle::Circle { center, radius } => {
                let _ = writeln!(
                    out,
                    r##"<circle cx="{}" cy="{}" r="{radius}" fill="#4a5568"/>"##,
                    center[0], center[1]
                );
            }
            crate::model::geometry::Obstacle::Rect { min, max } => {
                let _ = writeln!(
                    out,
                    r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#4a5568"/>"##,
                    min[0],
                    min[1],
                    max[0] - min[0],
                    max[1] - min[1]
                );
            }
            crate::model::geometry::Obstacle::Polygon { points } => {
                let pts: Vec<String> = points.iter().map(|p| format!("{},{}", p[0], p[1])).collect();
                let _ = writeln!(out, r##"<polygon points="{}" fill="#4a5568"/>"##, pts.join(" "));
            }
        }
    }
    write_goals_svg(&mut out, scene, rec);
    for i in 0..rec.agents() {
        let color =
            scene.groups.get(groups.get(i).copied().unwrap_or(0)).map_or("#808080", |g| g.color.as_str());
        let mut pts = String::new();
        for f in 0..rec.steps().len() {
            let s = rec.frame(f)[i];
            let _ = write!(pts, "{:.2},{:.2} ", s[0], s[1]);
        }
        let _ = writeln!(
            out,
            r#"<polyline points="{}" fill="none" stroke="{color}" stroke-width="1" stroke-opacity="0.6"/>"#,
            pts.trim_end()
        );
    }
    out.push_str("</svg>\n");
    out
}

/// Colour of a goal no group heads for (the renderer's `GOAL_COLOR`).
const UNUSED_GOAL_COLOR: &str = "#3a8a4f";

/// Each goal as a ring and centre dot where it is at the recording's last step, where the trails
/// end (a moving goal's scene `position` is only where it started, and the trails would chase an
/// empty spot); a moving goal also gets its route over the recorded steps as a dashed line.
fn write_goals_svg(out: &mut String, scene: &Scene, rec: &Recording) {
    let last = rec.steps().last().copied().unwrap_or(0);
    for (i, goal) in scene.goals.iter().enumerate() {
        let user = scene.groups.iter().find(|g| g.goal == Some(i as u32));
        let color = user.map_or(UNUSED_GOAL_COLOR, |g| g.color.as_str());
        if goal.motion.is_some() && rec.steps().len() > 1 {
            let mut d = String::new();
            for (k, &step) in rec.steps().iter().enumerate() {
                let p = goal.position_at(step);
                let _ = write!(d, "{}{:.2},{:.2} ", if k == 0 { 'M' } else { 'L' }, p.x, p.y);
            }
            let _ = writeln!(
                out,
                r#"<path d="{}" fill="none" stroke="{color}" stroke-width="1" stroke-dasharray="6 4" stroke-opacity="0.5"/>"#,
                d.trim_end()
            );
        }
        let at = goal.position_at(last);
        let _ = writeln!(
            out,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{}" fill="none" stroke="{color}" stroke-width="2"/>"#,
            at.x, at.y, goal.radius
        );
        let _ = writeln!(out, r#"<circle cx="{:.2}" cy="{:.2}" r="3" fill="{color}"/>"#, at.x, at.y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{presets, World};

    #[test]
    fn times_are_the_step_count_in_seconds_without_float_noise() {
        let shown: Vec<String> = [0, 1, 7, 300, 301, 10_000_000].into_iter().map(seconds_at).collect();
        assert_eq!(shown, ["0", "0.016667", "0.116667", "5", "5.016667", "166666.666667"]);
    }

    fn recorded(steps: u32) -> (Scene, Recording) {
        let scene = presets::open_field();
        let mut world = World::new(scene.clone()).expect("valid");
        let mut rec = Recording::new(world.agent_count(), 1 << 26);
        rec.capture(0, world.positions(), world.velocities());
        for _ in 0..steps {
            world.step();
            rec.capture(world.step_count(), world.positions(), world.velocities());
        }
        (scene, rec)
    }

    #[test]
    fn csv_has_one_row_per_agent_per_step_and_parses_back() {
        let (scene, rec) = recorded(30);
        let csv = paths_csv(&scene, &rec);
        let rows: Vec<&str> = csv.lines().collect();
        assert_eq!(rows[0], "agent,group,step,time,x,y,vx,vy");
        assert_eq!(rows.len() - 1, 31 * 60);
        let last: Vec<f32> = rows[rows.len() - 1].split(',').map(|x| x.parse().expect("number")).collect();
        let s = rec.frame(30)[59];
        assert_eq!(last[0], 59.0);
        assert_eq!(last[2], 30.0);
        assert_eq!((last[4], last[5], last[6], last[7]), (s[0], s[1], s[2], s[3]));
    }

    #[test]
    fn json_paths_parse_and_hold_every_sample() {
        let (scene, rec) = recorded(10);
        let v: serde_json::Value = serde_json::from_str(&paths_json(&scene, &rec)).expect("json");
        assert_eq!(v["agents"].as_array().map(Vec::len), Some(60));
        assert_eq!(v["agents"][0]["xy"].as_array().map(Vec::len), Some(22));
    }

    #[test]
    fn mel_keys_every_agent_on_every_frame() {
        let (scene, rec) = recorded(60);
        let mel = maya_mel(&scene, &rec, ExportOptions::default());
        assert_eq!(mel.matches("spaceLocator").count(), 60);
        // One second at 24 fps: frames 1..=25, two attributes each.
        assert_eq!(mel.matches("setKeyframe").count(), 60 * 25 * 2);
        assert!(mel.lines().all(|l| l.is_empty() || l.starts_with("//") || l.ends_with(';')));
    }

    #[test]
    fn blender_script_compiles_as_python() {
        let (scene, rec) = recorded(30);
        let py = blender_py(&scene, &rec, ExportOptions::default());
        assert_eq!(py.matches("    (0, [(1, ").count(), 60);
        let path = std::env::temp_dir().join(format!("flockpath-export-{}.py", std::process::id()));
        std::fs::write(&path, py).expect("writes");
        let status = std::process::Command::new("python3").arg("-m").arg("py_compile").arg(&path).status();
        let _ = std::fs::remove_file(&path);
        assert!(status.expect("python3 runs").success(), "py_compile rejected the Blender script");
    }

    #[test]
    fn svg_has_a_polyline_per_agent() {
        let (scene, rec) = recorded(5);
        let svg = trails_svg(&scene, &rec);
        assert_eq!(svg.matches("<polyline").count(), 60);
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    }

    #[test]
    fn svg_draws_a_moving_goal_where_it_is_when_the_trails_end() {
        let scene = presets::pso_circle_target();
        let mut world = World::new(scene.clone()).expect("valid");
        let mut rec = Recording::new(world.agent_count(), 1 << 26);
        for _ in 0..600 {
            world.step();
            rec.capture(world.step_count(), world.positions(), world.velocities());
        }
        let svg = trails_svg(&scene, &rec);
        let now = scene.goals[0].position_at(600);
        let ring = format!(r#"<circle cx="{:.2}" cy="{:.2}" r="#, now.x, now.y);
        assert!(svg.contains(&ring), "no ring at the goal's step-600 position {now}");
        assert!(!svg.contains(r#"cx="750.00" cy="350.00""#), "a ring where the goal started");
        assert_eq!(svg.matches("stroke-dasharray").count(), 1, "one route for the one moving goal");
    }
}
