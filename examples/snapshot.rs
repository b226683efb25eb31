//! Renders a preset (or a scene JSON file) after N steps to a PPM image, as the page draws it with
//! trails: for looking at what a change does (`cargo run --release --example snapshot --
//! pillars 1200 out.ppm [projector]`).

use flockpath::render::{Renderer, Theme};
use flockpath::{presets, Scene, World};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (name, steps, out) = match args.as_slice() {
        [name, steps, out, ..] => (name.as_str(), steps.parse::<u32>()?, out.as_str()),
        _ => return Err("usage: snapshot PRESET|scene.json STEPS out.ppm [projector]".into()),
    };
    let scene: Scene = match presets::find(name) {
        Some(p) => (p.build)(),
        None => serde_json::from_str(&std::fs::read_to_string(name)?)?,
    };
    let (w, h) = (scene.width.ceil() as u32, scene.height.ceil() as u32);
    let mut world = World::new(scene)?;
    let mut renderer = Renderer::new(w, h);
    if args.get(3).is_some_and(|t| t == "projector") {
        renderer.set_theme(Theme::Projector);
    }
    for _ in 0..steps {
        world.step();
        renderer.trace_step(&world);
    }
    renderer.render(&world);
    // A binary PPM (the background is opaque, so premultiplied RGB is the colour): `convert`
    // or any viewer turns it into a PNG.
    let mut ppm = format!("P6\n{w} {h}\n255\n").into_bytes();
    for px in renderer.pixels().chunks_exact(4) {
        ppm.extend_from_slice(&px[..3]);
    }
    std::fs::write(out, ppm)?;
    let m = world.metrics();
    let mut states = std::collections::BTreeMap::new();
    for a in world.arrivals() {
        let state = format!("{a:?}");
        *states.entry(state.split('(').next().unwrap_or_default().to_string()).or_insert(0) += 1;
    }
    println!(
        "{name} step {steps}: arrived {:.3}, waiting {}, {states:?}",
        m.overall.arrived_share, m.overall.waiting_agents
    );
    Ok(())
}
