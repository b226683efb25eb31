//! Teacher-locked links: the classroom options (`controls=`, `lock=`, `hide=`) beside `s=` decode
//! from whole links, old links (every fixture of every released fragment version) decode to
//! "everything allowed", the released names keep parsing, written options read back the same
//! with the same scene, and a refused option names the field and the allowed names.
//!
//! Fixtures: `tests/data/classroom/<name>.txt` holds a link and `<name>.json` the scene fixture it
//! carries and the options it must decode to; `names-v1.json` every name released so far (names
//! are added, never renamed or removed: a link's meaning must not change).

use flockpath::model::classroom::{Classroom, ClassroomError, Control, Field, Named, Panel, Part};
use flockpath::model::codec::{classroom_from_link, classroom_from_link_lenient, link_fragment};
use flockpath::rng::Rng;
use flockpath::{presets, scene_from_any, scene_from_fragment, scene_from_json, scene_to_fragment};
use std::path::Path;

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&read(path)).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Names of a JSON array of strings.
fn names(value: &serde_json::Value) -> Vec<String> {
    value
        .as_array()
        .expect("a list of names")
        .iter()
        .map(|v| v.as_str().expect("a name").to_string())
        .collect()
}

/// The names a classroom shows, locks and hides, as the fixtures list them.
fn listed(c: &Classroom) -> [Vec<String>; 3] {
    let view = c.view();
    let own = |list: Vec<&str>| list.into_iter().map(str::to_string).collect();
    [own(view.controls), own(view.lock), own(view.hide)]
}

#[test]
fn old_links_decode_to_everything_allowed() {
    let root = Path::new("tests/data/fragments");
    let mut checked = 0;
    for dir in std::fs::read_dir(root).expect("fixture folder").flatten() {
        for entry in std::fs::read_dir(dir.path()).expect("version folder").flatten() {
            let path = entry.path();
            if path.extension().is_none_or(|e| e != "txt") {
                continue;
            }
            let fragment = read(&path);
            for link in [
                fragment.trim().to_string(),
                format!("https://example.org/f/index.html#s={}", fragment.trim()),
            ] {
                let classroom =
                    classroom_from_link(&link).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                assert!(classroom.is_open(), "{}: an old link must allow everything", path.display());
                assert_eq!(classroom.fragment(), "");
            }
            checked += 1;
        }
    }
    assert!(checked >= 10, "only {checked} old links checked");
}

#[test]
fn locked_link_fixtures_decode_to_their_scene_and_options() {
    let dir = Path::new("tests/data/classroom");
    let mut checked = 0;
    for entry in std::fs::read_dir(dir).expect("classroom fixtures").flatten() {
        let path = entry.path();
        if path.extension().is_none_or(|e| e != "txt") {
            continue;
        }
        let link = read(&path);
        let expected = json(&path.with_extension("json"));
        let scene_file = dir.join(expected["scene"].as_str().expect("the scene fixture's path"));
        let scene = scene_from_json(&read(&scene_file)).expect("valid scene fixture");
        assert_eq!(scene_from_any(link.trim()).as_ref(), Ok(&scene), "{}: the scene", path.display());
        let classroom = classroom_from_link(&link).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let want = [names(&expected["controls"]), names(&expected["lock"]), names(&expected["hide"])];
        assert_eq!(listed(&classroom), want, "{}", path.display());
        checked += 1;
    }
    assert!(checked >= 2, "only {checked} locked links checked");
}

#[test]
fn every_released_name_still_parses_in_its_field() {
    let released = json(Path::new("tests/data/classroom/names-v1.json"));
    for field in Field::ALL {
        let names = names(&released[field.key()]);
        assert!(!names.is_empty(), "{field:?}");
        let current = field.names();
        for name in &names {
            assert!(
                current.contains(&name.as_str()),
                "{}: the released name {name:?} was removed",
                field.key()
            );
            let link = format!("#s=2.x&{}={name}", field.key());
            let classroom = classroom_from_link(&link).unwrap_or_else(|e| panic!("{link}: {e}"));
            let listed = listed(&classroom);
            let index = Field::ALL.iter().position(|f| *f == field).expect("a field");
            assert_eq!(listed[index], std::slice::from_ref(name), "{link}");
        }
    }
}

/// A random subset of `T`'s values.
fn subset<T: Named>(rng: &mut Rng) -> Vec<T> {
    T::ALL.iter().copied().filter(|_| rng.below(2) == 0).collect()
}

#[test]
fn written_links_read_back_the_same_scene_and_options() {
    let mut rng = Rng::new(15, 3);
    for preset in presets::ALL {
        let scene = (preset.build)();
        // Everything allowed: exactly the link written before the options existed.
        assert_eq!(link_fragment(&scene, &Classroom::default()), format!("s={}", scene_to_fragment(&scene)));
        for _ in 0..8 {
            let classroom = Classroom::new(
                subset::<Control>(&mut rng),
                subset::<Part>(&mut rng),
                subset::<Panel>(&mut rng),
            );
            let link = format!("https://example.org/x/index.html#{}", link_fragment(&scene, &classroom));
            assert_eq!(classroom_from_link(&link).as_ref(), Ok(&classroom), "{link}");
            assert_eq!(scene_from_fragment(&link).as_ref(), Ok(&scene), "{}", preset.name);
        }
    }
}

#[test]
fn a_refused_option_names_the_field_and_the_allowed_names() {
    let e = classroom_from_link("index.html#s=2.x&controls=play,jump").expect_err("jump");
    assert_eq!(e, ClassroomError::UnknownName { field: Field::Controls, name: "jump".into() });
    let message = e.to_string();
    assert!(
        message.starts_with("controls: unknown name \"jump\"; allowed: play, step, reset, speed, planner"),
        "{message}"
    );
    assert!(message.ends_with("views, fullscreen (or all, none)"), "{message}");
    // The page reads leniently: the other options still apply.
    let (classroom, errors) = classroom_from_link_lenient("#s=2.x&lock=goals&hide=metrics,charts");
    assert_eq!(errors.len(), 1);
    assert_eq!(errors[0].to_string(), "hide: unknown name \"charts\"; allowed: metrics, plots, diagnose, timeline, groups, keys (or all, none)");
    assert!(classroom.is_locked(Part::Goals));
    assert!(!classroom.hides(Panel::Metrics), "the refused option stays at everything allowed");
    // Percent-encoding is read; a broken escape is named as written.
    assert!(classroom_from_link("#lock=obstacles%2cgoals").expect("escaped comma").is_locked(Part::Goals));
    let e = classroom_from_link("#lock=obstacles%2").expect_err("broken escape");
    assert_eq!(e, ClassroomError::UnknownName { field: Field::Lock, name: "obstacles%2".into() });
}

#[test]
fn options_do_not_change_what_the_scene_string_decodes_to() {
    let plain = std::fs::read_to_string("tests/data/fragments/v2/pillars.txt").expect("fixture");
    let locked = std::fs::read_to_string("tests/data/classroom/pillars-locked.txt").expect("fixture");
    assert_eq!(scene_from_any(locked.trim()), scene_from_any(plain.trim()));
    assert_eq!(scene_from_fragment(locked.trim()), scene_from_fragment(plain.trim()));
}
