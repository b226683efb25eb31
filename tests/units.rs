//! Units: a scene's scale (`px_per_metre`), its conversions, its place in JSON and links, its
//! refusal, and the metre keys of the metrics.

use flockpath::model::scene::{Scale, DEFAULT_PX_PER_METRE, DT};
use flockpath::{
    presets, scene_from_any, scene_from_fragment, scene_from_json, scene_to_fragment, scene_to_json,
};
use flockpath::{SceneError, World};

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

#[test]
fn the_scale_converts_lengths_areas_and_speeds() {
    let s = Scale::default();
    assert_eq!(s.px_per_metre(), 20.0);
    assert_eq!(s.metres(40.0), 2.0);
    assert_eq!(s.px(0.2), 4.0);
    assert_eq!(s.square_metres(400.0), 1.0);
    // 1 px/step at 60 steps/s and 20 px/m is 3 m/s (DT is the f32 nearest 1/60 s).
    assert!((s.m_s(1.0) - 3.0).abs() < 1e-6, "{}", s.m_s(1.0));
    assert!(close(s.m_s(1.0), 1.0 / 20.0 / f64::from(DT)));
    assert!(close(s.px_per_step(1.34), 1.34 * 20.0 * f64::from(DT)));
    for x in [0.0, 0.37, 1.0, 12.5, 900.0] {
        assert!(close(s.m_s(s.px_per_step(x)), x), "{x}");
        assert!(close(s.metres(s.px(x)), x), "{x}");
    }
    let fine = Scale::new(50.0);
    assert_eq!(fine.metres(100.0), 2.0);
    assert!((fine.m_s(1.0) - 60.0 / 50.0).abs() < 1e-6);
    assert_eq!(fine.square_metres(2500.0), 1.0);
    assert_eq!(presets::open_field().scale(), Scale::default());
}

#[test]
fn the_default_scale_is_left_out_of_json_and_links() {
    for p in presets::ALL {
        let scene = (p.build)();
        assert_eq!(scene.px_per_metre, DEFAULT_PX_PER_METRE, "{}", p.name);
        assert!(!scene_to_json(&scene).contains("px_per_metre"), "{}", p.name);
    }
    // A stated scale changes the link and the JSON, and both give it back.
    let plain = presets::open_field();
    let mut scaled = plain.clone();
    scaled.px_per_metre = 32.5;
    let json = scene_to_json(&scaled);
    assert!(json.contains("\"px_per_metre\": 32.5"), "{json}");
    assert_eq!(scene_from_json(&json), Ok(scaled.clone()));
    let (plain_link, scaled_link) = (scene_to_fragment(&plain), scene_to_fragment(&scaled));
    assert_ne!(plain_link, scaled_link);
    assert_eq!(scene_from_fragment(&scaled_link), Ok(scaled.clone()));
    assert_eq!(scene_from_fragment(&plain_link), Ok(plain.clone()));
    // Setting the default back gives the very link of before.
    scaled.px_per_metre = DEFAULT_PX_PER_METRE;
    assert_eq!(scene_to_fragment(&scaled), plain_link);
    // With paths (the element before the scale) and a scale, both survive.
    let mut both = presets::boids_path();
    both.px_per_metre = 10.0;
    assert_eq!(scene_from_fragment(&scene_to_fragment(&both)), Ok(both));
    // A scene text written before the scale existed loads at the default.
    let old = r#"{"width": 300, "height": 200}"#;
    assert_eq!(scene_from_json(old).map(|s| s.px_per_metre), Ok(DEFAULT_PX_PER_METRE));
}

fn refused_field(result: Result<flockpath::Scene, SceneError>) -> (String, String) {
    match result {
        Err(SceneError::Field(f)) => (f.path, f.value.to_string()),
        other => panic!("expected a field refusal, got {other:?}"),
    }
}

#[test]
fn a_bad_scale_is_refused_naming_the_field() {
    for bad in ["0", "-20", "0.5", "1e6", "1e39"] {
        let text = format!(r#"{{"width": 300, "height": 200, "px_per_metre": {bad}}}"#);
        let (path, value) = refused_field(scene_from_json(&text));
        assert_eq!(path, "px_per_metre", "{bad}");
        assert_eq!(value, bad.replace("1e6", "1000000"), "{bad}");
        let message = scene_from_json(&text).expect_err("refused").to_string();
        assert!(message.contains("1…1000 px per metre"), "{message}");
    }
    let (path, value) =
        refused_field(scene_from_any(r#"{"width": 300, "height": 200, "px_per_metre": NaN}"#));
    assert_eq!((path.as_str(), value.as_str()), ("px_per_metre", "NaN"));
    let mut scene = presets::open_field();
    scene.px_per_metre = f32::NAN;
    let (path, value) = refused_field(scene.validate().map(|()| scene.clone()));
    assert_eq!((path.as_str(), value.as_str()), ("px_per_metre", "NaN"));
    // In a link too (the compact form's tenth element), by the same name.
    scene.px_per_metre = 0.0;
    let (path, _) = refused_field(scene_from_fragment(&scene_to_fragment(&scene)));
    assert_eq!(path, "px_per_metre");
    // And by the world.
    assert!(matches!(World::new(scene), Err(SceneError::Field(f)) if f.path == "px_per_metre"));
}

#[test]
fn metrics_gain_metre_keys_at_the_scene_scale_and_the_run_does_not_change() {
    let run = |px_per_metre: f32| {
        let mut scene = presets::pillars();
        scene.px_per_metre = px_per_metre;
        let mut world = World::new(scene).expect("pillars");
        world.step_n(120);
        (world.digest(), world.metrics())
    };
    let (d20, m20) = run(20.0);
    let (d40, m40) = run(40.0);
    assert_eq!(d20, d40, "the scale does not touch the simulation");
    assert_eq!((m20.px_per_metre, m40.px_per_metre), (20.0, 40.0));
    for (m, ppm) in [(&m20, 20.0), (&m40, 40.0)] {
        let o = &m.overall;
        assert!(o.mean_speed > 0.0 && o.mean_path_length > 0.0);
        assert!(close(o.mean_speed_m_s, o.mean_speed / ppm / f64::from(DT)));
        assert!(close(o.mean_path_length_m, o.mean_path_length / ppm));
        let near = o.mean_speed_near_obstacles.expect("pillars has obstacles near the crowd");
        assert!(close(o.mean_speed_near_obstacles_m_s.expect("m/s too"), near / ppm / f64::from(DT)));
        for g in &m.groups {
            assert!(close(g.mean_speed_m_s, g.mean_speed / ppm / f64::from(DT)));
            assert!(close(g.mean_path_length_m, g.mean_path_length / ppm));
        }
    }
    assert!(close(m20.overall.mean_speed_m_s, 2.0 * m40.overall.mean_speed_m_s));
    let json = serde_json::to_value(&m20).expect("json");
    for key in ["px_per_metre", "mean_speed_m_s", "mean_speed_near_obstacles_m_s", "mean_path_length_m"] {
        assert!(json.get(key).is_some(), "{key}");
        assert!(json["groups"][0].get(key).is_some() || key == "px_per_metre", "{key}");
    }
    for key in ["mean_speed", "mean_speed_near_obstacles", "mean_path_length"] {
        assert!(json.get(key).is_some(), "px key {key} kept");
    }
}
