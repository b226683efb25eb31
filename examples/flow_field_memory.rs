//! Prints the memory a scene of many one-agent flow-field groups keeps (issue 24): 500 one-agent
//! ORCA groups among 20 circles in a 20,000 px world, heading for one shared goal or each for its
//! own, loaded and stepped twice, each in a process of its own: its resident memory after the
//! steps and its peak (Linux `/proc/self/status`). Not a test, a figure:
//! `cargo run --release --example flow_field_memory`.

use flockpath::model::geometry::Obstacle;
use flockpath::model::params::PlannerKind;
use flockpath::model::scene::{Goal, Region, Scene};
use flockpath::{presets, World};

/// A `/proc/self/status` line's value in kB (`VmRSS`: resident now, `VmHWM`: its peak; Linux).
fn status_kb(key: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

const SIDE: f32 = 20_000.0;
const GROUPS: usize = 500;

/// `GROUPS` one-agent ORCA groups (flow-field guidance, the default) on the left among 20
/// circles; `goals` goals on the right, group k heading for goal k mod `goals`.
fn scene(goals: usize) -> Scene {
    let mut s = Scene::empty(SIDE, SIDE);
    let template = presets::open_field().groups.remove(0);
    for k in 0..goals {
        let y = 100.0 + (SIDE - 200.0) * k as f32 / goals.max(2) as f32;
        s.goals.push(Goal::fixed([SIDE - 300.0, y], 20.0));
    }
    for k in 0..20 {
        let c = [5_000.0 + 500.0 * k as f32, 1_000.0 + 900.0 * k as f32];
        s.obstacles.push(Obstacle::Circle { center: c, radius: 150.0 });
    }
    for k in 0..GROUPS {
        let mut g = template.clone();
        g.name = format!("g{k}");
        g.count = 1;
        let y = 100.0 + (SIDE - 400.0) * k as f32 / GROUPS as f32;
        g.spawn = Region { min: [100.0, y], max: [200.0, y + 30.0] };
        g.goal = Some((k % goals) as u32);
        g.planner = PlannerKind::Orca.default_config();
        s.groups.push(g);
    }
    s
}

fn main() {
    // One process per scene, so each peak is its own.
    if let Some(goals) = std::env::args().nth(1).and_then(|a| a.parse::<usize>().ok()) {
        let base = status_kb("VmRSS:").unwrap_or(0);
        let mut world = World::new(scene(goals)).expect("valid scene");
        world.step_n(2);
        let (rss, peak) = (status_kb("VmRSS:").unwrap_or(0), status_kb("VmHWM:").unwrap_or(0));
        println!(
            "{GROUPS} one-agent ORCA groups, {goals:3} goal(s), 20,000 px world: {} distinct flow \
             fields; resident {:.0} MB after 2 steps (peak {:.0} MB, {:.0} MB before loading)",
            world.flow_field_count(),
            rss as f64 / 1024.0,
            peak as f64 / 1024.0,
            base as f64 / 1024.0,
        );
        return;
    }
    let me = std::env::current_exe().expect("own path");
    for goals in [1, 10, GROUPS] {
        let status = std::process::Command::new(&me).arg(goals.to_string()).status().expect("run");
        assert!(status.success(), "{goals} goals: {status}");
    }
}
