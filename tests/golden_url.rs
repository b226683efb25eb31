//! A shared link replays the golden run: the URL in `tests/data/golden-url.txt` (preset `pillars`,
//! seed 7, as a version-2 link under a course sub-path) gives the golden digest after 300 steps,
//! here and in headless Chromium (`tests/web.rs` reads the same two files).

use flockpath::{scene_from_any, World};

#[test]
fn the_golden_url_replays_the_golden_digest() {
    let url = include_str!("data/golden-url.txt").trim();
    assert!(url.contains("#s=2."), "the fixture is a version-2 link: {url}");
    let scene = scene_from_any(url).expect("the golden link decodes");
    assert_eq!((scene.name.as_str(), scene.seed), ("pillars", 7));
    let mut world = World::new(scene).expect("valid scene");
    world.step_n(300);
    assert_eq!(format!("{:016x}", world.digest()), include_str!("data/golden-digest.txt").trim());
}
