//! A scene as a Python script that runs it in JuPedSim (`flockpath run --jupedsim FILE`): the
//! same translation `scripts/jupedsim-check.sh` uses for the validation suite
//! (`scripts/jupedsim_runs.py`, included word for word), followed by the run's set-up as JSON
//! and a main that runs it and writes the trajectories in the suite's text format.

use super::suite::RunSetup;
use crate::model::scene::{Scene, DT};
use crate::sim::recording::Recording;
use glam::Vec2;

/// The translation from a run's set-up to JuPedSim (the module `scripts/jupedsim-check.sh` runs).
const TRANSLATION: &str = include_str!("../../../scripts/jupedsim_runs.py");

/// A Python script that runs `scene` in JuPedSim's `model` (`cfsm` or `sfm`) for `seconds`,
/// its walkers starting at `starts` (px; the world's spawn), and writes their trajectories
/// (`id frame x y z` in metres, 10 frames per second) to the file named on its command line.
/// Every goal becomes an exit (JuPedSim's walkers leave at the end of their journey).
pub fn script(scene: &Scene, starts: &[Vec2], group_of: &[u32], seconds: f32, model: &str) -> String {
    let mut scene = scene.clone();
    for goal in &mut scene.goals {
        *goal = goal.clone().exit();
    }
    let setup = RunSetup::new(&scene, starts, group_of, None, seconds, 0.1);
    // Serialising a set-up cannot fail: derived Serialize over numbers and strings.
    let json = serde_json::to_string(&setup).unwrap_or_default();
    let main = TRANSLATION.rfind("if __name__ == \"__main__\":").map_or(TRANSLATION, |at| &TRANSLATION[..at]);
    format!(
        "{main}\n# Exported by `flockpath run --jupedsim` (scene {name:?}); needs `pip install jupedsim==1.4.2`.\n\
         # Usage: python3 THIS.py [TRAJECTORY_FILE]   (default: trajectories.txt)\n\
         SETUP = json.loads(r\"\"\"{json}\"\"\")\n\n\
         if __name__ == \"__main__\":\n    \
             target = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else \"trajectories.txt\")\n    \
             target.write_text(run(SETUP, {model:?}))\n    \
             print(f\"JuPedSim {{jps.__version__}} {model}: wrote {{target}}\")\n",
        name = scene.name,
    )
}

/// The JuPedSim script of a recorded run (Export → JuPedSim on the page, `flockpath run
/// --jupedsim`): the walkers start where the recording's first frame has them and JuPedSim's
/// collision-free speed model runs for as long as the recording (at least 1 s, so a scene
/// exported before it was played still runs).
pub fn recording_script(scene: &Scene, rec: &Recording) -> String {
    let starts: Vec<Vec2> = if rec.steps().is_empty() {
        vec![]
    } else {
        rec.frame(0).iter().map(|a| Vec2::new(a[0], a[1])).collect()
    };
    let group_of: Vec<u32> = scene
        .groups
        .iter()
        .enumerate()
        .flat_map(|(g, group)| std::iter::repeat_n(g as u32, group.count as usize))
        .collect();
    let seconds = rec.steps().last().map_or(0.0, |&s| s as f32 * DT);
    script(scene, &starts, &group_of, seconds.max(1.0), "cfsm")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::presets;

    /// The script holds the suite's translation, the scene's set-up (every goal an exit, the
    /// starts in metres) and a main naming the model.
    #[test]
    fn a_scene_becomes_a_jupedsim_script() {
        let scene = presets::pillars();
        let world = crate::sim::world::World::new(scene.clone()).expect("the preset runs");
        let text = script(&scene, world.positions(), world.group_of(), 30.0, "cfsm");
        assert!(text.contains("def walkable_area(") && text.contains("def run(setup, model)"));
        assert!(text.contains("SETUP = json.loads(") && text.contains("run(SETUP, \"cfsm\")"));
        assert_eq!(
            text.matches("if __name__ == \"__main__\":").count(),
            1,
            "the suite's entry point is left out"
        );
        let json = &text[text.find("r\"\"\"").expect("json") + 4..text.rfind("\"\"\")").expect("end")];
        let setup: serde_json::Value = serde_json::from_str(json).expect("valid JSON");
        assert_eq!(setup["starts_m"].as_array().map(Vec::len), Some(world.positions().len()));
        assert!(setup["scene"]["goals"].as_array().expect("goals").iter().all(|g| g["on_arrival"] == "exit"));
    }
}
