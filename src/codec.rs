//! Scene ↔ JSON and scene ↔ URL fragment. Versioned, compact, and never panics on bad input.
//!
//! Fragment formats (`<version>.<payload>`, the payload URL-safe base64 without padding of a raw
//! deflate stream, miniz_oxide at level 9):
//! - `2.` (written today): the deflated JSON of a compact form of the scene. Obstacles, goals and
//!   groups are positional arrays, not keyed objects, so a scene with 20 obstacles and 4 groups
//!   needs about 750 characters instead of about 1,100. Every planner parameter is written, even
//!   when it equals today's default: a link must replay the same run after a default changes.
//!   The one exception: parameters appended later for a feature that is off by default (marked
//!   `omitted_at_default` in their table) are left out at the end while they hold their
//!   defaults, so links written before they existed keep their exact text. When a scene holds something the compact form cannot express, the
//!   payload is the keyed scene JSON instead (the decoder tells them apart by `[` or `{`), so the
//!   round trip is always exact.
//! - `1.` (read only): the deflated keyed scene JSON.
//!
//! Every released version keeps decoding: fixtures of each live in `tests/data/fragments/`.

use crate::geometry::Obstacle;
use crate::planners::{PlannerConfig, PlannerKind};
use crate::scene::{Goal, GoalMotion, Group, Hill, PathSpec, Region, Scene, SceneError, ViewOptions};
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use base64::Engine as _;
use serde::{Deserialize, Serialize};

/// The fragment version written today.
pub const FRAGMENT_VERSION: &str = "2";
/// Every version this build reads, oldest first.
pub const READABLE_VERSIONS: &[&str] = &["1", "2"];
/// Largest decompressed scene accepted from a URL (bytes): a guard against deflate bombs.
const MAX_SCENE_BYTES: usize = 4 << 20;
/// Largest text accepted from a URL or file (bytes).
const MAX_INPUT_BYTES: usize = 8 << 20;

/// Parses and validates a scene from JSON text.
pub fn scene_from_json(text: &str) -> Result<Scene, SceneError> {
    check_input_size(text)?;
    let scene: Scene = serde_json::from_str(text).map_err(|e| SceneError::Parse(e.to_string()))?;
    scene.validate()?;
    Ok(scene)
}

fn check_input_size(text: &str) -> Result<(), SceneError> {
    if text.len() > MAX_INPUT_BYTES {
        return Err(SceneError::Parse(format!(
            "the scene text is {} bytes, over the 8 MiB limit",
            text.len()
        )));
    }
    Ok(())
}

/// The scene as pretty JSON.
pub fn scene_to_json(scene: &Scene) -> String {
    serde_json::to_string_pretty(scene).unwrap_or_default()
}

/// The URL fragment value (`s=` part) for a scene, in the current version.
pub fn scene_to_fragment(scene: &Scene) -> String {
    let compact = CompactScene::from_scene(scene);
    // The compact form must give back this very scene; otherwise (a field it does not know)
    // fall back to the keyed JSON, which the same version decodes.
    let json = match compact.to_scene() {
        Ok(back) if &back == scene => serde_json::to_vec(&compact),
        _ => serde_json::to_vec(scene),
    }
    .unwrap_or_default();
    format!("{FRAGMENT_VERSION}.{}", pack(&json))
}

fn pack(bytes: &[u8]) -> String {
    URL_SAFE_NO_PAD.encode(miniz_oxide::deflate::compress_to_vec(bytes, 9))
}

/// Base64url-decodes and inflates a payload into text.
fn unpack(payload: &str) -> Result<String, SceneError> {
    let packed = URL_SAFE_NO_PAD.decode(payload.trim_end_matches('=')).map_err(|e| {
        SceneError::Parse(format!("the scene string is not valid base64 ({e}); was it cut short?"))
    })?;
    let bytes =
        miniz_oxide::inflate::decompress_to_vec_with_limit(&packed, MAX_SCENE_BYTES).map_err(|e| {
            SceneError::Parse(format!("the scene string is damaged or truncated ({:?})", e.status))
        })?;
    String::from_utf8(bytes).map_err(|_| SceneError::Parse("the scene string does not hold text".into()))
}

/// Decodes a fragment value of any readable version; also accepts a whole URL or a `#s=…`
/// fragment.
pub fn scene_from_fragment(input: &str) -> Result<Scene, SceneError> {
    let value = fragment_value(input.trim());
    check_input_size(value)?;
    let (version, payload) = value.split_once('.').ok_or_else(|| {
        SceneError::Parse(format!(
            "the scene string has no version prefix (expected \"{FRAGMENT_VERSION}.…\")"
        ))
    })?;
    match version {
        "1" => scene_from_json(&unpack(payload)?),
        "2" => {
            let text = unpack(payload)?;
            if text.trim_start().starts_with('[') {
                let compact: CompactScene = serde_json::from_str(&text).map_err(|e| {
                    SceneError::Parse(format!("the scene string does not hold a version 2 scene ({e})"))
                })?;
                let scene = compact.to_scene()?;
                scene.validate()?;
                Ok(scene)
            } else {
                scene_from_json(&text)
            }
        }
        other => Err(SceneError::Parse(format!(
            "unknown scene format version {:?}; this flockpath reads versions {}",
            other.chars().take(12).collect::<String>(),
            READABLE_VERSIONS.join(" and ")
        ))),
    }
}

/// Loads a scene from whatever a user pasted: JSON, a fragment value, a `#s=` fragment or a URL.
pub fn scene_from_any(input: &str) -> Result<Scene, SceneError> {
    let trimmed = input.trim_start();
    if trimmed.starts_with('{') {
        scene_from_json(trimmed)
    } else if trimmed.is_empty() {
        Err(SceneError::Parse("the scene text is empty".into()))
    } else {
        scene_from_fragment(trimmed)
    }
}

/// Extracts the `s=` value from a URL or fragment, or returns the input unchanged.
fn fragment_value(input: &str) -> &str {
    let after_hash = input.rsplit_once('#').map_or(input, |(_, f)| f);
    for part in after_hash.split('&') {
        if let Some(v) = part.strip_prefix("s=") {
            return v;
        }
    }
    after_hash
}

/// Version 2's compact scene: `[name, width, height, seed, obstacles, goals, groups, view]`, and
/// a ninth element `terrain` only when the scene has paths or hills: links made before those
/// existed have eight elements and still decode, to a scene without them.
#[derive(Debug, Serialize, Deserialize)]
struct CompactScene(
    String,
    f32,
    f32,
    u32,
    Vec<CompactObstacle>,
    Vec<CompactGoal>,
    Vec<CompactGroup>,
    CompactView,
    #[serde(default, skip_serializing_if = "CompactTerrain::is_empty")] CompactTerrain,
);

/// `[paths, hills]`: a path is `[radius, [[x, y], …]]`, a hill `[x, y, radius, height]`.
#[derive(Debug, Default, Serialize, Deserialize)]
struct CompactTerrain(Vec<(f32, Vec<[f32; 2]>)>, Vec<[f32; 4]>);

impl CompactTerrain {
    fn is_empty(&self) -> bool {
        self.0.is_empty() && self.1.is_empty()
    }
}

/// An obstacle by arity: circle `[x, y, r]`, rectangle `[x0, y0, x1, y1]`, polygon `[[x, y], …]`.
#[derive(Debug, Serialize, Deserialize)]
#[serde(untagged)]
enum CompactObstacle {
    Circle([f32; 3]),
    Rect([f32; 4]),
    Polygon(Vec<[f32; 2]>),
}

/// A goal: `[x, y, radius]`, or `[x, y, radius, motion]` for a moving one.
#[derive(Debug, Serialize, Deserialize)]
#[serde(untagged)]
enum CompactGoal {
    Fixed([f32; 3]),
    Moving(f32, f32, f32, GoalMotion),
}

/// `[name, colour, count, [x0, y0, x1, y1], goal, agent radius, planner, [params]]`, the
/// parameters in the order of the planner's parameter table. Tables only ever grow at the end
/// (with a default that keeps the old behaviour), so older links missing trailing values load.
#[derive(Debug, Serialize, Deserialize)]
struct CompactGroup(String, String, u32, [f32; 4], Option<u32>, f32, String, Vec<serde_json::Value>);

/// `[trails, trail fade]`.
#[derive(Debug, Serialize, Deserialize)]
struct CompactView(bool, f32);

impl CompactScene {
    fn from_scene(s: &Scene) -> Self {
        let obstacles = s
            .obstacles
            .iter()
            .map(|o| match o {
                Obstacle::Circle { center, radius } => {
                    CompactObstacle::Circle([center[0], center[1], *radius])
                }
                Obstacle::Rect { min, max } => CompactObstacle::Rect([min[0], min[1], max[0], max[1]]),
                Obstacle::Polygon { points } => CompactObstacle::Polygon(points.clone()),
            })
            .collect();
        let goals = s
            .goals
            .iter()
            .map(|g| match &g.motion {
                None => CompactGoal::Fixed([g.position[0], g.position[1], g.radius]),
                Some(m) => CompactGoal::Moving(g.position[0], g.position[1], g.radius, m.clone()),
            })
            .collect();
        let groups = s
            .groups
            .iter()
            .map(|g| {
                let (min, max) = (g.spawn.min, g.spawn.max);
                CompactGroup(
                    g.name.clone(),
                    g.color.clone(),
                    g.count,
                    [min[0], min[1], max[0], max[1]],
                    g.goal,
                    g.agent_radius,
                    g.planner.kind().name().to_string(),
                    planner_params(&g.planner),
                )
            })
            .collect();
        CompactScene(
            s.name.clone(),
            s.width,
            s.height,
            s.seed,
            obstacles,
            goals,
            groups,
            CompactView(s.view.trails, s.view.trail_fade),
            CompactTerrain(
                s.paths.iter().map(|p| (p.radius, p.points.clone())).collect(),
                s.hills.iter().map(|h| [h.center[0], h.center[1], h.radius, h.height]).collect(),
            ),
        )
    }

    fn to_scene(&self) -> Result<Scene, SceneError> {
        let CompactScene(name, width, height, seed, obstacles, goals, groups, view, terrain) = self;
        let obstacles = obstacles
            .iter()
            .map(|o| match o {
                CompactObstacle::Circle([x, y, r]) => Obstacle::Circle { center: [*x, *y], radius: *r },
                CompactObstacle::Rect([x0, y0, x1, y1]) => {
                    Obstacle::Rect { min: [*x0, *y0], max: [*x1, *y1] }
                }
                CompactObstacle::Polygon(points) => Obstacle::Polygon { points: points.clone() },
            })
            .collect();
        let goals = goals
            .iter()
            .map(|g| match g {
                CompactGoal::Fixed([x, y, radius]) => Goal::fixed([*x, *y], *radius),
                CompactGoal::Moving(x, y, radius, motion) => {
                    Goal { position: [*x, *y], radius: *radius, motion: Some(motion.clone()) }
                }
            })
            .collect();
        let groups = groups
            .iter()
            .enumerate()
            .map(|(i, CompactGroup(name, color, count, [x0, y0, x1, y1], goal, radius, planner, params))| {
                Ok(Group {
                    name: name.clone(),
                    color: color.clone(),
                    count: *count,
                    spawn: Region { min: [*x0, *y0], max: [*x1, *y1] },
                    goal: *goal,
                    agent_radius: *radius,
                    planner: planner_with(planner, params)
                        .map_err(|m| SceneError::OutOfRange(format!("group {} ({name}): {m}", i + 1)))?,
                })
            })
            .collect::<Result<_, SceneError>>()?;
        Ok(Scene {
            name: name.clone(),
            width: *width,
            height: *height,
            seed: *seed,
            obstacles,
            goals,
            groups,
            view: ViewOptions { trails: view.0, trail_fade: view.1 },
            paths: terrain
                .0
                .iter()
                .map(|(radius, points)| PathSpec { points: points.clone(), radius: *radius })
                .collect(),
            hills: terrain
                .1
                .iter()
                .map(|&[x, y, radius, height]| Hill { center: [x, y], radius, height })
                .collect(),
        })
    }
}

/// A planner's parameter values in the order of its parameter table (trailing extension values
/// at their defaults left out), then, only when the planner holds any, one object with the
/// values that are not sliders (an IGSA group's edited waypoints). Links without that object
/// decode as before.
fn planner_params(config: &PlannerConfig) -> Vec<serde_json::Value> {
    let params = serde_json::to_value(config).ok().and_then(|mut v| v.get_mut("params").map(std::mem::take));
    let params = params.unwrap_or_default();
    let specs = config.kind().param_specs();
    let mut values: Vec<serde_json::Value> =
        specs.iter().map(|spec| params.get(spec.key).cloned().unwrap_or_default()).collect();
    // Extension parameters at their defaults at the end are left out (ParamSpec::omitted_at_default).
    while let (Some(value), Some(spec)) = (values.last(), specs.get(values.len().wrapping_sub(1))) {
        if !(spec.omit_default && spec.is_default(value)) {
            break;
        }
        values.pop();
    }
    if let Some(object) = params.as_object() {
        let extras: serde_json::Map<String, serde_json::Value> = object
            .iter()
            .filter(|(key, _)| !specs.iter().any(|s| s.key == key.as_str()))
            .map(|(key, value)| (key.clone(), value.clone()))
            .collect();
        if !extras.is_empty() {
            values.push(serde_json::Value::Object(extras));
        }
    }
    values
}

/// The planner `name` with the table's first `values.len()` parameters set (range-checked) and
/// the rest at their defaults.
fn planner_with(name: &str, values: &[serde_json::Value]) -> Result<PlannerConfig, String> {
    let kind = PlannerKind::from_name(name).ok_or_else(|| {
        let known: Vec<&str> = PlannerKind::ALL.iter().map(|k| k.name()).collect();
        format!(
            "unknown planner {:?}; known: {}",
            name.chars().take(40).collect::<String>(),
            known.join(", ")
        )
    })?;
    let specs = kind.param_specs();
    let (values, extras) = match values.split_last() {
        // No table parameter is an object: a trailing object holds the non-slider values.
        Some((serde_json::Value::Object(extras), table)) => (table, Some(extras)),
        _ => (values, None),
    };
    if values.len() > specs.len() {
        return Err(format!(
            "{} takes {} parameters, the link has {}",
            kind.label(),
            specs.len(),
            values.len()
        ));
    }
    let mut params = serde_json::to_value(kind.default_config())
        .ok()
        .and_then(|mut v| v.get_mut("params").map(std::mem::take))
        .unwrap_or_default();
    for (spec, value) in specs.iter().zip(values) {
        if let Some(object) = params.as_object_mut() {
            object.insert(spec.key.to_string(), value.clone());
        }
    }
    for (key, value) in extras.into_iter().flatten() {
        if let Some(object) = params.as_object_mut() {
            object.insert(key.clone(), value.clone());
        }
    }
    let config: PlannerConfig =
        serde_json::from_value(serde_json::json!({ "kind": kind.name(), "params": params }))
            .map_err(|e| format!("{}: {e}", kind.label()))?;
    config.validate()?;
    Ok(config)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets;

    #[test]
    fn every_planner_serialises_exactly_its_table_keys() {
        // The compact form writes parameters by table position: a field outside the table would
        // be lost from links.
        for &kind in PlannerKind::ALL {
            let json = serde_json::to_value(kind.default_config()).expect("serialises");
            let mut keys: Vec<&str> =
                json["params"].as_object().expect("object").keys().map(String::as_str).collect();
            let mut specs: Vec<&str> = kind.param_specs().iter().map(|s| s.key).collect();
            keys.sort_unstable();
            specs.sort_unstable();
            assert_eq!(keys, specs, "{}", kind.name());
        }
    }

    #[test]
    fn every_preset_round_trips_through_json_and_fragment() {
        for p in presets::ALL {
            let scene = (p.build)();
            assert_eq!(scene_from_json(&scene_to_json(&scene)).as_ref(), Ok(&scene), "{}", p.name);
            let frag = scene_to_fragment(&scene);
            assert_eq!(scene_from_fragment(&frag).as_ref(), Ok(&scene), "{}", p.name);
            let url = format!("http://localhost/index.html#s={frag}");
            assert_eq!(scene_from_any(&url).as_ref(), Ok(&scene), "{}", p.name);
        }
    }

    #[test]
    fn edited_igsa_waypoints_travel_in_the_compact_link() {
        let mut scene = presets::igsa_path_2();
        let before = scene_to_fragment(&scene);
        if let PlannerConfig::Igsa(p) = &mut scene.groups[0].planner {
            p.waypoints = vec![[200.0, 100.0], [400.0, 90.0], [520.0, 160.5]];
        } else {
            panic!("igsa-path-2 runs the igsa planner");
        }
        let fragment = scene_to_fragment(&scene);
        assert_eq!(scene_from_fragment(&fragment).as_ref(), Ok(&scene));
        // Compact (positional) form, not the keyed fallback: the waypoints ride after the table.
        let text = unpack(fragment.split_once('.').expect("version").1).expect("unpacks");
        assert!(text.starts_with('['), "{text}");
        assert!(text.contains(r#"{"waypoints":[[200.0,100.0],[400.0,90.0],[520.0,160.5]]}"#), "{text}");
        // Scenes without edited waypoints encode exactly as before (no trailing object).
        assert!(!unpack(before.split_once('.').expect("version").1).expect("unpacks").contains("waypoints"));
        // A link from before the waypoints existed (table values only) still decodes.
        let old = CompactScene::from_scene(&presets::igsa_path_2());
        let json = serde_json::to_vec(&old).expect("json");
        let decoded = scene_from_fragment(&format!("2.{}", pack(&json))).expect("decodes");
        assert_eq!(decoded, presets::igsa_path_2());
        // Bad waypoints are refused with a message.
        let bad = text.replace("[200.0,100.0]", "[200.0]");
        assert!(scene_from_fragment(&format!("2.{}", pack(bad.as_bytes()))).is_err());
    }

    #[test]
    fn paths_and_hills_ride_in_the_compact_form_and_old_links_lack_them() {
        let mut scene = presets::open_field();
        scene
            .paths
            .push(PathSpec { points: vec![[50.0, 60.0], [300.0, 80.5], [500.0, 400.0]], radius: 25.0 });
        scene.hills.push(Hill { center: [400.0, 250.0], radius: 80.0, height: 120.0 });
        let frag = scene_to_fragment(&scene);
        let text = unpack(frag.split_once('.').expect("version").1).expect("inflates");
        assert!(text.starts_with('['), "compact form expected: {text}");
        assert_eq!(scene_from_fragment(&frag), Ok(scene.clone()));
        // Only hills: the path list is written empty so the hills keep their position.
        scene.paths.clear();
        assert_eq!(scene_from_fragment(&scene_to_fragment(&scene)), Ok(scene.clone()));
        // A scene without either writes the eight elements of every older link.
        scene.hills.clear();
        let frag = scene_to_fragment(&scene);
        let text = unpack(frag.split_once('.').expect("version").1).expect("inflates");
        let elements = serde_json::from_str::<Vec<serde_json::Value>>(&text).expect("array").len();
        assert_eq!(elements, 8, "{text}");
        assert_eq!(scene_from_fragment(&frag), Ok(scene));
    }

    #[test]
    fn garbage_gives_messages_not_panics() {
        for bad in ["", "1.", "1.!!!", "2.abc", "nonsense", "1.AAAA", "{", "{\"width\": 1}", "#s=1.x"] {
            let e = scene_from_any(bad).expect_err(bad);
            assert!(!e.to_string().is_empty());
        }
    }

    #[test]
    fn truncated_fragments_fail_cleanly() {
        let frag = scene_to_fragment(&(presets::ALL[0].build)());
        for cut in 2..frag.len() {
            assert!(scene_from_fragment(&frag[..cut]).is_err(), "cut at {cut}");
        }
    }
}
