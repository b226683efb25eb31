//! One size limit for names and links (issue 24, part 3).
//!
//! Regression: a group name of 7 MiB was accepted from a scene's JSON, but the scene's link was
//! longer than anything could open: `flockpath url` wrote a link `flockpath run` refused (it
//! unpacked past the reader's 4 MiB), and the page could not keep it in the address bar (a
//! reload silently showed the default scene). Names now have a limit ([`MAX_NAME_CHARS`]), and
//! every load (JSON, link, the page's API, an edit) refuses a scene whose own link would not
//! open it again ([`MAX_LINK_CHARS`], [`MAX_SCENE_BYTES`]), naming the field or the link and the
//! limit. The largest scene that loads round-trips through its link.

#[path = "support/largest_scene.rs"]
mod largest_scene;

use flockpath::model::codec::{check_link_fits, MAX_LINK_CHARS, MAX_SCENE_BYTES};
use flockpath::model::edit::{apply, Edit};
use flockpath::model::refusal::Refusal as _;
use flockpath::model::scene::{SceneError, MAX_NAME_CHARS};
use flockpath::sim::run::{Run, RunOptions};
use flockpath::{
    presets, scene_from_any, scene_from_fragment, scene_from_json, scene_to_fragment, scene_to_json,
};

fn pillars_with_group_name(name: &str) -> String {
    let mut scene = (presets::lookup("pillars").expect("preset").build)();
    scene.groups[0].name = name.to_string();
    scene_to_json(&scene)
}

fn arg(e: &SceneError, name: &str) -> String {
    e.message().arg_text(name).unwrap_or_default()
}

#[test]
fn a_name_of_7_mib_is_refused_naming_the_field_and_the_limit() {
    let text = pillars_with_group_name(&"x".repeat(7 << 20));
    for e in [scene_from_json(&text).expect_err("JSON"), scene_from_any(&text).expect_err("the page's load")]
    {
        assert_eq!(e.code(), "scene.field");
        assert_eq!(arg(&e, "path"), "groups[0].name");
        assert!(arg(&e, "value").starts_with("text of 7340032 character(s) (\"xxxx"), "{e}");
        assert_eq!(arg(&e, "allowed"), format!("text of at most {MAX_NAME_CHARS} characters on one line"));
        assert!(e.to_string().len() < 200, "the message does not repeat the name: {e}");
    }
    // The same name in a link: the reader refuses what unpacks past its limit…
    let mut scene = (presets::lookup("pillars").expect("preset").build)();
    scene.groups[0].name = "x".repeat(7 << 20);
    let e = scene_from_fragment(&scene_to_fragment(&scene)).expect_err("a 7 MiB link payload");
    assert_eq!((e.code(), arg(&e, "limit")), ("scene.too_large", MAX_SCENE_BYTES.to_string()));
    // …and a name just over the limit, which unpacks, is refused by name.
    scene.groups[0].name = "名".repeat(MAX_NAME_CHARS + 1);
    let e = scene_from_fragment(&scene_to_fragment(&scene)).expect_err("101 characters");
    assert_eq!(arg(&e, "path"), "groups[0].name", "{e}");
    scene.groups[0].name = "名".repeat(MAX_NAME_CHARS);
    assert_eq!(scene_from_fragment(&scene_to_fragment(&scene)).as_ref(), Ok(&scene));
    // The scene's own name, and a line break, are refused the same way.
    let mut named = (presets::lookup("pillars").expect("preset").build)();
    named.name = "a\nb".into();
    let e = scene_from_json(&scene_to_json(&named)).expect_err("a line break");
    assert_eq!(
        (arg(&e, "path"), arg(&e, "value")),
        ("name".into(), "text holding the control character U+000A".into())
    );
}

#[test]
fn an_edit_may_not_give_a_group_a_name_over_the_limit_nor_grow_the_link_past_its_limit() {
    let scene = (presets::lookup("pillars").expect("preset").build)();
    let mut group = scene.groups[0].clone();
    group.name = "g".repeat(MAX_NAME_CHARS + 1);
    let e = apply(&scene, &Edit::SetGroup { index: 0, group }).expect_err("too long");
    assert_eq!(arg(&e, "path"), "groups[0].name");
    // The page's edits go through `Run::edit_scene`, which checks the link as a load does.
    let mut run = Run::new(scene, RunOptions::page()).expect("pillars runs");
    let e = run.edit_scene(scene_with_too_long_a_link()).expect_err("past the link limit");
    assert_eq!(arg(&e, "what"), "the scene's link");
}

#[test]
fn the_largest_scene_that_loads_round_trips_through_its_link_and_a_larger_one_is_refused() {
    let (largest, more) = largest_scene::largest_scene();
    let link = scene_to_fragment(&largest);
    assert!(link.len() <= MAX_LINK_CHARS, "{} characters", link.len());
    assert!(largest_scene::fullness(&largest) > 0.995, "the scene fills its link: {} characters", link.len());
    assert_eq!(
        scene_from_any(&format!("https://example.org/index.html#s={link}")).as_ref(),
        Ok(&largest),
        "url → run"
    );
    // Its JSON (compact: 4 MB) loads too.
    assert_eq!(scene_from_json(&serde_json::to_string(&largest).expect("JSON")).as_ref(), Ok(&largest));

    // A few groups more and its link would not open: refused on load, by the limit's name.
    let e = scene_from_json(&serde_json::to_string(&more).expect("JSON")).expect_err("too long a link");
    assert_eq!(e.code(), "scene.too_large_bytes");
    assert_eq!((arg(&e, "what"), arg(&e, "limit")), ("the scene's link".into(), MAX_LINK_CHARS.to_string()));
    assert!(e.to_string().starts_with("the scene's link is too large ("), "{e}");
}

/// Pillars with empty groups named in random CJK text added until its link is 2 % longer than
/// [`MAX_LINK_CHARS`].
fn scene_with_too_long_a_link() -> flockpath::Scene {
    let mut rng = flockpath::rng::Rng::new(7, 0);
    let mut scene = (presets::lookup("pillars").expect("preset").build)();
    let template = scene.groups[0].clone();
    let mut add_groups = |scene: &mut flockpath::Scene, n: usize| {
        for _ in 0..n {
            let mut g = template.clone();
            g.count = 0;
            g.name = largest_scene::longest_name(&mut rng);
            scene.groups.push(g);
        }
    };
    // What 500 groups add to the link sets how many take it 2 % past its limit.
    let base = scene_to_fragment(&scene).len();
    add_groups(&mut scene, 500);
    let per_group = (scene_to_fragment(&scene).len() - base) / 500;
    add_groups(&mut scene, (MAX_LINK_CHARS * 102 / 100 - base) / per_group - 500);
    assert!(scene_to_fragment(&scene).len() > MAX_LINK_CHARS);
    scene
}

#[test]
fn a_link_longer_than_a_browser_keeps_is_refused_by_the_link_limit() {
    let scene = scene_with_too_long_a_link();
    let e = scene_from_json(&serde_json::to_string(&scene).expect("JSON")).expect_err("too long a link");
    assert_eq!(e.code(), "scene.too_large_bytes");
    assert_eq!((arg(&e, "what"), arg(&e, "limit")), ("the scene's link".into(), MAX_LINK_CHARS.to_string()));
    assert!(e.to_string().starts_with("the scene's link is too large ("), "{e}");
    assert!(e.to_string().ends_with(&format!("; limit {MAX_LINK_CHARS} bytes)")), "{e}");
    assert!(check_link_fits(&scene).is_err());
}
