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
//!
//! Beside `s=`, a link may carry the classroom options `controls=`, `lock=` and `hide=`
//! (`model::classroom`): page options like `autoplay`, not part of the scene string, so the
//! scene's version and digest are untouched by them. A link without them (every link written
//! before they existed) allows everything; their names are only ever added, and the released
//! ones are pinned by `tests/data/classroom/`.
//!
//! A refusal names the field by its path in the keyed scene JSON (`groups[2].planner.params.
//! max_speed`), in both forms (the compact form's positions are translated), with the value as
//! written and what is allowed; the parser's own words and position ride along as details.
//! Scene text and fragments may start with a UTF-8 byte-order mark; a bare name is a preset.

use crate::model::activity::Activity;
use crate::model::classroom::{Classroom, ClassroomError, Field, Options};
use crate::model::geometry::Obstacle;
use crate::model::link;
use crate::model::params::{PlannerConfig, PlannerKind};
use crate::model::refusal::{Arg, Code, Message};
use crate::model::scene::{
    allowed_for, Goal, GoalMotion, Group, Hill, OnArrival, PathSpec, Region, Scene, SceneError, ViewOptions,
    DEFAULT_PX_PER_METRE,
};
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use base64::Engine as _;
use serde::{Deserialize, Serialize};

/// The fragment version written today.
pub const FRAGMENT_VERSION: &str = "2";
/// Every version this build reads, oldest first.
pub const READABLE_VERSIONS: &[&str] = &["1", "2"];
pub use crate::model::scene::{MAX_INPUT_BYTES, MAX_LINK_CHARS, MAX_SCENE_BYTES};
/// The byte-order mark some editors put at the start of a UTF-8 file.
const BYTE_ORDER_MARK: char = '\u{feff}';

/// Parses and validates a scene from JSON text.
pub fn scene_from_json(text: &str) -> Result<Scene, SceneError> {
    let text = text.strip_prefix(BYTE_ORDER_MARK).unwrap_or(text);
    check_input_size(text)?;
    let scene: Scene = deserialize(text, Layout::Keyed)?;
    scene.validate().map_err(|e| as_written(e, text))?;
    check_link_fits(&scene)?;
    Ok(scene)
}

/// A refusal showing the number as the text wrote it: `1e39` read into an `f32` is infinite,
/// and the message should show what the user typed.
fn as_written(error: SceneError, text: &str) -> SceneError {
    let SceneError::Field(mut field) = error else { return error };
    // An f32 field past its range holds `infinite …` as text; a planner parameter holds the
    // `value.not_finite` words.
    let not_finite = match &field.value {
        Arg::Text(v) => v.contains("infinite"),
        Arg::Message(m) => m.code == Code::ValueNotFinite,
        _ => false,
    };
    if !not_finite {
        return SceneError::Field(field);
    }
    // Only to show the number as typed: the text already parsed as a scene, and if this re-read
    // failed the refusal would keep its own words.
    let json: Option<serde_json::Value> = serde_json::from_str(text).ok();
    let mut node = json.as_ref();
    for part in field.path.split('.') {
        let (key, indices) = part.split_once('[').map_or((part, ""), |(k, i)| (k, i));
        node = node.and_then(|n| n.get(key));
        for index in indices.split('[') {
            if let Ok(i) = index.trim_end_matches(']').parse::<usize>() {
                node = node.and_then(|n| n.get(i));
            }
        }
    }
    if let Some(number) = node.filter(|n| n.is_number()) {
        field.value = render(number).into();
    }
    SceneError::Field(field)
}

fn check_input_size(text: &str) -> Result<(), SceneError> {
    if text.len() > MAX_INPUT_BYTES {
        return Err(SceneError::TooLarge {
            what: Code::WhatSceneText,
            bytes: Some(text.len()),
            limit: MAX_INPUT_BYTES,
        });
    }
    Ok(())
}

/// Why writing a scene as JSON cannot fail: its types derive `Serialize`, every map key is a
/// string, and serde_json writes a non-finite float as `null` (which reading refuses, by name).
/// A failure would be a bug in these types, so it panics loudly rather than writing `""`.
const SCENE_SERIALISES: &str = "a Scene always serialises to JSON (derived Serialize, string keys)";

/// The scene as pretty JSON.
pub fn scene_to_json(scene: &Scene) -> String {
    serde_json::to_string_pretty(scene).expect(SCENE_SERIALISES)
}

/// The URL fragment value (`s=` part) for a scene, in the current version.
pub fn scene_to_fragment(scene: &Scene) -> String {
    format!("{FRAGMENT_VERSION}.{}", pack(&link_payload(scene)))
}

/// The JSON a link packs: the compact form, which must give back this very scene; otherwise
/// (a field it does not know) the keyed JSON, which the same version decodes.
fn link_payload(scene: &Scene) -> Vec<u8> {
    let compact = CompactScene::from_scene(scene);
    match compact.to_scene() {
        Ok(back) if &back == scene => serde_json::to_vec(&compact),
        _ => serde_json::to_vec(scene),
    }
    .expect(SCENE_SERIALISES)
}

/// Refuses a scene whose own link would not open it again: one that unpacks beyond
/// [`MAX_SCENE_BYTES`] (the reader stops there) or is longer than [`MAX_LINK_CHARS`] (the browser
/// drops it). Checked whenever a scene is loaded or edited, so `flockpath url` and the page's
/// address bar only ever write links that `flockpath run` and the page read.
///
/// Exact, and cheap for all but huge scenes: the link is packed (a deflate at level 9, about
/// 0.6 s natively for a 2 MB link) only when a bound says it might not fit (from about 1.4 MB
/// of link JSON).
///
/// Not checked: the pretty JSON [`scene_to_json`] writes against [`MAX_INPUT_BYTES`]. It spells
/// out every key and puts every number on its own line, so a scene whose link fits may write
/// more JSON than a file may hold (5,000 groups: 5.9 MB; 40,000: about 47 MB).
pub fn check_link_fits(scene: &Scene) -> Result<(), SceneError> {
    let payload = link_payload(scene);
    if payload.len() > MAX_SCENE_BYTES {
        return Err(SceneError::TooLarge {
            what: Code::WhatUnpackedScene,
            bytes: Some(payload.len()),
            limit: MAX_SCENE_BYTES,
        });
    }
    // Deflate stores an incompressible block with 5 bytes per 65,535, and base64 writes 4
    // characters per 3 bytes: a generous bound on the link without packing it.
    let stored = payload.len() + payload.len() / 64 + 1024;
    if FRAGMENT_VERSION.len() + 1 + stored.div_ceil(3) * 4 > MAX_LINK_CHARS {
        let chars = FRAGMENT_VERSION.len() + 1 + pack(&payload).len();
        if chars > MAX_LINK_CHARS {
            return Err(SceneError::TooLarge {
                what: Code::WhatSceneLink,
                bytes: Some(chars),
                limit: MAX_LINK_CHARS,
            });
        }
    }
    Ok(())
}

fn pack(bytes: &[u8]) -> String {
    URL_SAFE_NO_PAD.encode(miniz_oxide::deflate::compress_to_vec(bytes, 9))
}

/// Base64url-decodes and inflates a payload into text.
fn unpack(payload: &str) -> Result<String, SceneError> {
    let packed = URL_SAFE_NO_PAD.decode(payload.trim_end_matches('=')).map_err(|e| {
        SceneError::parse(Message::new(Code::SceneBadBase64).with("reason", base64_reason(&e)))
    })?;
    let bytes =
        miniz_oxide::inflate::decompress_to_vec_with_limit(&packed, MAX_SCENE_BYTES).map_err(|e| match e
            .status
        {
            miniz_oxide::inflate::TINFLStatus::HasMoreOutput => {
                SceneError::TooLarge { what: Code::WhatUnpackedScene, bytes: None, limit: MAX_SCENE_BYTES }
            }
            _ => SceneError::parse(Message::new(Code::SceneDamaged)),
        })?;
    String::from_utf8(bytes).map_err(|_| SceneError::parse(Message::new(Code::SceneNotText)))
}

/// base64's refusal as a message (its own words, from its typed error).
fn base64_reason(e: &base64::DecodeError) -> Message {
    match *e {
        base64::DecodeError::InvalidByte(offset, byte) => {
            Message::new(Code::Base64InvalidSymbol).with("symbol", byte).with("offset", offset)
        }
        base64::DecodeError::InvalidLastSymbol(offset, byte) => {
            Message::new(Code::Base64InvalidLastSymbol).with("symbol", byte).with("offset", offset)
        }
        base64::DecodeError::InvalidLength(length) => {
            Message::new(Code::Base64InvalidLength).with("length", length)
        }
        base64::DecodeError::InvalidPadding => Message::new(Code::Base64InvalidPadding),
    }
}

/// Decodes a fragment value of any readable version; also accepts a whole URL or a `#s=…`
/// fragment.
pub fn scene_from_fragment(input: &str) -> Result<Scene, SceneError> {
    let input = input.strip_prefix(BYTE_ORDER_MARK).unwrap_or(input);
    let value = link::option_or_fragment(input.trim(), "s");
    check_input_size(value)?;
    let (version, payload) = value.split_once('.').ok_or_else(|| {
        SceneError::parse(Message::new(Code::SceneNoVersion).with("expected", FRAGMENT_VERSION))
    })?;
    match version {
        "1" => scene_from_json(&unpack(payload)?),
        "2" => {
            let text = unpack(payload)?;
            if text.trim_start().starts_with('[') {
                let compact: CompactScene = deserialize(&text, Layout::Compact)?;
                let scene = compact.to_scene()?;
                scene.validate()?;
                check_link_fits(&scene)?;
                Ok(scene)
            } else {
                scene_from_json(&text)
            }
        }
        other => Err(SceneError::parse(
            Message::new(Code::SceneUnknownVersion)
                .with("version", other.chars().take(12).collect::<String>())
                .with("readable", READABLE_VERSIONS.to_vec()),
        )),
    }
}

/// Loads a scene from whatever a user pasted: JSON, a fragment value, a `#s=` fragment, a URL,
/// or a preset name (`pillars`).
pub fn scene_from_any(input: &str) -> Result<Scene, SceneError> {
    let input = input.strip_prefix(BYTE_ORDER_MARK).unwrap_or(input);
    check_input_size(input)?;
    let trimmed = input.trim();
    if trimmed.starts_with('{') {
        scene_from_json(trimmed)
    } else if trimmed.is_empty() {
        Err(SceneError::parse(Message::new(Code::SceneEmpty)))
    } else if looks_like_preset_name(trimmed) {
        crate::model::presets::lookup(trimmed).map(|p| (p.build)())
    } else {
        scene_from_fragment(trimmed)
    }
}

/// Whether `text` reads as a preset name (`open-field`) rather than a scene string: lower-case
/// letters, digits and dashes, starting with a letter. Scene strings start with their version
/// (`2.`), URLs hold `:` or `/`, and a pasted payload without its version has capitals.
fn looks_like_preset_name(text: &str) -> bool {
    text.len() <= 40
        && text.starts_with(|c: char| c.is_ascii_lowercase())
        && text.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-')
}

/// The classroom options of a link (`controls=`, `lock=`, `hide=` beside `s=`, in a URL, a
/// `#…` fragment or the fragment's text), read leniently: each refused option is reported and
/// left allowing everything. A link without them, every link written before they existed
/// included, allows everything.
pub fn classroom_from_link_lenient(input: &str) -> (Classroom, Vec<ClassroomError>) {
    let input = input.strip_prefix(BYTE_ORDER_MARK).unwrap_or(input).trim();
    let controls = link::option(input, Field::Controls.key()).map(link::percent_decoded);
    let lock = link::option(input, Field::Lock.key()).map(link::percent_decoded);
    let hide = link::option(input, Field::Hide.key()).map(link::percent_decoded);
    Classroom::from_options_lenient(Options {
        controls: controls.as_deref(),
        lock: lock.as_deref(),
        hide: hide.as_deref(),
    })
}

/// The classroom options of a link; the first refused option is the error.
pub fn classroom_from_link(input: &str) -> Result<Classroom, ClassroomError> {
    let (classroom, errors) = classroom_from_link_lenient(input);
    match errors.into_iter().next() {
        Some(e) => Err(e),
        None => Ok(classroom),
    }
}

/// A link's fragment (after `#`): `s=<scene>` then the classroom options that differ from
/// "everything allowed", so a link without options is exactly what it was before they existed.
pub fn link_fragment(scene: &Scene, classroom: &Classroom) -> String {
    let options = classroom.fragment();
    let scene = scene_to_fragment(scene);
    if options.is_empty() {
        format!("s={scene}")
    } else {
        format!("s={scene}&{options}")
    }
}

/// Version 2's compact scene: `[name, width, height, seed, obstacles, goals, groups, view]`, a
/// ninth element `terrain` when the scene has paths or hills, and a tenth `px_per_metre` when
/// the scale is not the default (then `terrain` is written, perhaps empty, to keep positions).
/// An eleventh, the scene's activity as its keyed JSON, follows when the scene has one (then
/// `terrain` and `px_per_metre` are written whatever they hold, to keep positions).
/// Links made before those existed have eight or nine elements and still decode, to a scene
/// without them; a scene at the default scale writes exactly what it wrote before the scale.
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
    #[serde(default, skip_serializing_if = "Option::is_none")] Option<CompactTerrain>,
    #[serde(default, skip_serializing_if = "Option::is_none")] Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")] Option<Activity>,
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

/// A goal: `[x, y, radius]`, or `[x, y, radius, motion]` for a moving one, or
/// `[x, y, radius, motion or null, on_arrival]` for a goal that does not gather (links made
/// before the option existed have three or four elements and gather).
#[derive(Debug, Serialize, Deserialize)]
#[serde(untagged)]
enum CompactGoal {
    Fixed([f32; 3]),
    Moving(f32, f32, f32, GoalMotion),
    WithArrival(f32, f32, f32, Option<GoalMotion>, OnArrival),
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
        let terrain = CompactTerrain(
            s.paths.iter().map(|p| (p.radius, p.points.clone())).collect(),
            s.hills.iter().map(|h| [h.center[0], h.center[1], h.radius, h.height]).collect(),
        );
        let activity = s.activity.clone();
        let scale = (activity.is_some() || s.px_per_metre.to_bits() != DEFAULT_PX_PER_METRE.to_bits())
            .then_some(s.px_per_metre);
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
            .map(|g| match (&g.motion, g.on_arrival) {
                (None, OnArrival::Gather) => CompactGoal::Fixed([g.position[0], g.position[1], g.radius]),
                (Some(m), OnArrival::Gather) => {
                    CompactGoal::Moving(g.position[0], g.position[1], g.radius, m.clone())
                }
                (motion, on_arrival) => CompactGoal::WithArrival(
                    g.position[0],
                    g.position[1],
                    g.radius,
                    motion.clone(),
                    on_arrival,
                ),
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
            (!terrain.is_empty() || scale.is_some()).then_some(terrain),
            scale,
            activity,
        )
    }

    fn to_scene(&self) -> Result<Scene, SceneError> {
        let CompactScene(name, width, height, seed, obstacles, goals, groups, view, terrain, scale, activity) =
            self;
        let empty = CompactTerrain::default();
        let terrain = terrain.as_ref().unwrap_or(&empty);
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
                CompactGoal::Moving(x, y, radius, motion) => Goal {
                    position: [*x, *y],
                    radius: *radius,
                    motion: Some(motion.clone()),
                    on_arrival: OnArrival::Gather,
                },
                CompactGoal::WithArrival(x, y, radius, motion, on_arrival) => Goal {
                    position: [*x, *y],
                    radius: *radius,
                    motion: motion.clone(),
                    on_arrival: *on_arrival,
                },
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
                    planner: planner_with(planner, params).map_err(|e| match e {
                        SceneError::Field(mut f) => {
                            f.path = format!("groups[{i}].{}", f.path);
                            SceneError::Field(f)
                        }
                        other => other,
                    })?,
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
            px_per_metre: scale.unwrap_or(DEFAULT_PX_PER_METRE),
            activity: activity.clone(),
        })
    }
}

/// A planner's parameter values in the order of its parameter table (trailing extension values
/// at their defaults left out), then, only when the planner holds any, one object with the
/// values that are not sliders (an IGSA group's edited waypoints). Links without that object
/// decode as before.
fn planner_params(config: &PlannerConfig) -> Vec<serde_json::Value> {
    let params = config.params_json();
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
    let extras: serde_json::Map<String, serde_json::Value> =
        params.into_iter().filter(|(key, _)| !specs.iter().any(|s| s.key == key.as_str())).collect();
    if !extras.is_empty() {
        values.push(serde_json::Value::Object(extras));
    }
    values
}

/// The planner `name` with the table's first `values.len()` parameters set (range-checked) and
/// the rest at their defaults. Refusals name the field below the group's `planner`
/// (`planner.params.max_speed`); the caller puts the group in front.
fn planner_with(name: &str, values: &[serde_json::Value]) -> Result<PlannerConfig, SceneError> {
    let kind = PlannerKind::from_name(name).ok_or_else(|| {
        let known: Vec<String> = PlannerKind::ALL.iter().map(|k| format!("\"{}\"", k.name())).collect();
        SceneError::field(
            "planner.kind",
            format!("{:?}", name.chars().take(40).collect::<String>()),
            format!("one of {}", known.join(", ")),
        )
    })?;
    let specs = kind.param_specs();
    let (values, extras) = match values.split_last() {
        // No table parameter is an object: a trailing object holds the non-slider values.
        Some((serde_json::Value::Object(extras), table)) => (table, Some(extras)),
        _ => (values, None),
    };
    if values.len() > specs.len() {
        return Err(SceneError::field(
            "planner.params",
            Message::new(Code::ValueListOfValues).with("count", values.len()),
            format!("at most {} values for {} (its parameter table)", specs.len(), kind.label()),
        ));
    }
    let mut params = kind.default_config().params_json();
    for (spec, value) in specs.iter().zip(values) {
        params.insert(spec.key.to_string(), value.clone());
    }
    for (key, value) in extras.into_iter().flatten() {
        params.insert(key.clone(), value.clone());
    }
    let keyed = serde_json::json!({ "kind": kind.name(), "params": params });
    let config: PlannerConfig = check(&keyed).map_err(|(segments, error)| {
        let path = format!("planner.{}", keyed_path(&segments));
        let value: Arg = walk(&keyed, &segments)
            .map_or_else(|| Message::new(Code::ValueRefused).into(), |v| render(v).into());
        match error.fault {
            Fault::UnknownKey { name, known } => {
                let allowed = format!("one of the keys {}", names_as_serde_lists(known));
                let path = if path.ends_with(&name) { path } else { joined(&path, &name) };
                SceneError::field(path, Message::new(Code::ValueUnknownKey), allowed)
            }
            Fault::MissingKey { name } => {
                let path = joined(&path, name);
                let allowed =
                    param_allowed(kind, &path).unwrap_or_else(|| "a value: this key is required".into());
                SceneError::field(path, Message::new(Code::ValueMissing), allowed)
            }
            _ => {
                let allowed = param_allowed(kind, &path)
                    .or_else(|| error.expected.and_then(expected_words))
                    .unwrap_or_else(|| "a value of another kind".into());
                SceneError::field(path, value, allowed)
            }
        }
    })?;
    config.check().map_err(|e| SceneError::field(format!("planner.params.{}", e.key), e.value, e.allowed))?;
    Ok(config)
}

/// Which names a decoded text's positions get: the keyed scene JSON's own keys, or the
/// positional compact form's, translated to the keyed names so messages read the same.
#[derive(Clone, Copy)]
enum Layout {
    Keyed,
    Compact,
}

use crate::model::shape::{check, path_at, Expected, Fault, Segment, ShapeError};

/// Deserialises `text`, refusing with the field's path, its value and what is allowed.
///
/// The text is read straight into `T` (fast, and every scene that loads is read this way);
/// only when that fails is it read again as a `serde_json::Value` and checked against `T` as
/// typed data ([`crate::model::shape`]), so a refusal is worded from what the types report, not
/// from the parser's English.
fn deserialize<T: serde::de::DeserializeOwned>(text: &str, layout: Layout) -> Result<T, SceneError> {
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let value = T::deserialize(&mut deserializer).map_err(|e| refusal::<T>(&e, text, layout))?;
    deserializer.end().map_err(|e| {
        SceneError::parse(
            Message::new(Code::SceneTrailingText).with("line", e.line()).with("column", e.column()),
        )
    })?;
    Ok(value)
}

/// Words for a refused decode: which field, what it held, what it may hold. `error` gives only
/// its kind (cut short or not) and position; the rest is read from the text as data.
fn refusal<T: serde::de::DeserializeOwned>(
    error: &serde_json::Error,
    text: &str,
    layout: Layout,
) -> SceneError {
    let (line, column) = (error.line(), error.column());
    if error.is_eof() {
        return SceneError::parse(
            Message::new(Code::SceneCutShort).with("line", line).with("column", column),
        );
    }
    let detail = Some(error.to_string());
    match serde_json::from_str::<serde_json::Value>(text) {
        Ok(json) => match check::<T>(&json) {
            Err((segments, fault)) => shape_refusal(&json, segments, fault, layout, (line, column), detail),
            // The typed check reads a key given twice as its last value; the parser refuses it.
            Ok(_) => SceneError::parse(
                Message::new(Code::SceneUnreadableAt).with("line", line).with("column", column),
            ),
        },
        Err(syntax) => syntax_refusal(text, &syntax, layout, detail),
    }
}

/// A text that is no JSON where the parser stopped: a word JSON does not have (`NaN`,
/// `Infinity`, `1e999`), a string that is no text, or another character out of place.
fn syntax_refusal(
    text: &str,
    error: &serde_json::Error,
    layout: Layout,
    detail: Option<String>,
) -> SceneError {
    let (line, column) = (error.line(), error.column());
    if error.is_eof() {
        return SceneError::parse(
            Message::new(Code::SceneCutShort).with("line", line).with("column", column),
        );
    }
    let offset = byte_offset(text, line, column);
    // A word JSON does not have; a number JSON has is not the fault (the parser stopped after it).
    let token =
        token_at(text, line, column).filter(|(_, _, word)| !word.parse::<f64>().is_ok_and(f64::is_finite));
    let bad_string = invalid_string_at(text, line, column);
    // The text's structure with a word JSON cannot hold replaced by 0, or a string that is no
    // text by "": it tells a compact circle [x, y, r] from a polygon and finds a group's planner.
    let (segments, structure) = match (&bad_string, &token) {
        (Some(bad), _) => (
            path_at(text, bad.start),
            serde_json::from_str(&format!("{}\"\"{}", &text[..bad.start], &text[bad.end..])).ok(),
        ),
        (None, Some((start, end, _))) => (
            path_at(text, *start),
            serde_json::from_str(&format!("{}0{}", &text[..*start], &text[*end..])).ok(),
        ),
        (None, None) => (path_at(text, offset), None),
    };
    let path = layout_path(layout, &segments, structure.as_ref());
    let unexpected = || {
        let character =
            text.get(offset.saturating_sub(1)..).and_then(|rest| rest.chars().next()).unwrap_or(' ');
        Message::new(Code::JsonUnexpected).with("character", character.to_string())
    };
    if let Some(bad) = bad_string {
        return with_detail(SceneError::field(path, bad.value, bad.allowed), detail);
    }
    match token {
        Some((_, _, word)) if !path.is_empty() => {
            let allowed = planner_param_allowed(&path, structure.as_ref())
                .or_else(|| allowed_for(&path))
                .unwrap_or_else(|| "a finite number (JSON has no NaN or Infinity)".into());
            with_detail(SceneError::field(path, word, allowed), detail)
        }
        _ if path.is_empty() => SceneError::parse(match layout {
            Layout::Keyed => Message::new(Code::SceneNotObject)
                .with("reason", unexpected())
                .with("line", line)
                .with("column", column),
            Layout::Compact => Message::new(Code::SceneNotV2).with("reason", unexpected()),
        }),
        _ => SceneError::parse(
            Message::new(Code::SceneNotJson)
                .with("reason", unexpected())
                .with("line", line)
                .with("column", column)
                .with("path", path),
        ),
    }
}

/// The byte offset of (1-based) `line`, `column` (serde_json counts columns in bytes).
fn byte_offset(text: &str, line: usize, column: usize) -> usize {
    let row_start: usize = text.split_inclusive('\n').take(line.saturating_sub(1)).map(str::len).sum();
    (row_start + column).min(text.len())
}

/// The keyed path of `segments` in `layout` (a compact form's positions named as the keyed
/// scene names them).
fn layout_path(layout: Layout, segments: &[Segment], structure: Option<&serde_json::Value>) -> String {
    match layout {
        Layout::Keyed => keyed_path(segments),
        Layout::Compact => compact_path(segments, structure),
    }
}

/// A JSON value that does not fit the scene's types, as a refusal: the field's path, its value
/// as written and what is allowed (the limits table's words for the field, else the kind of
/// value its type asks for).
fn shape_refusal(
    json: &serde_json::Value,
    mut segments: Vec<Segment>,
    mut error: ShapeError,
    layout: Layout,
    (line, column): (usize, usize),
    detail: Option<String>,
) -> SceneError {
    // Internally tagged obstacles and goal motions report faults at the object: read it again
    // as its variant's fields to find the field.
    if let Some((inner, inner_error)) = walk(json, &segments).and_then(tagged_field) {
        segments.extend(inner);
        error = inner_error;
    }
    let path = layout_path(layout, &segments, Some(json));
    let value: Option<Arg> = walk(json, &segments).map(|v| render(v).into());
    let about_a_key = matches!(error.fault, Fault::MissingKey { .. } | Fault::UnknownKey { .. });
    if path.is_empty() && !about_a_key {
        let found = Message::new(Code::ShapeFound)
            .with("value", walk(json, &segments).map(render).unwrap_or_default());
        return SceneError::parse(match layout {
            Layout::Keyed => Message::new(Code::SceneNotObject)
                .with("reason", found)
                .with("line", line)
                .with("column", column),
            Layout::Compact => Message::new(Code::SceneNotV2).with("reason", found),
        });
    }
    let refused = || value.clone().unwrap_or_else(|| Message::new(Code::ValueRefused).into());
    let hint = || planner_param_allowed(&path, Some(json)).or_else(|| allowed_for(&path));
    let field = match error.fault {
        Fault::UnknownKey { name, known } => {
            let allowed = if known.is_empty() {
                "no keys here".to_string()
            } else {
                format!("one of the keys {}", names_as_serde_lists(known))
            };
            let path = if path.ends_with(&name) { path } else { joined(&path, &name) };
            SceneError::field(path, Message::new(Code::ValueUnknownKey), allowed)
        }
        // A tagged planner's unknown key (beside `kind` and `params`) arrives as a refused text.
        Fault::BadValue { text: Some(_) } if matches!(error.expected, Some(Expected::Object(_))) => {
            let keys = match error.expected {
                Some(Expected::Object(keys)) => keys.iter().map(|k| format!("\"{k}\"")).collect::<Vec<_>>(),
                _ => Vec::new(),
            };
            SceneError::field(
                path,
                Message::new(Code::ValueUnknownKey),
                format!("one of the keys {}", keys.join(", ")),
            )
        }
        Fault::MissingKey { name } => {
            let path = joined(&path, name);
            let allowed = allowed_for(&path).unwrap_or_else(|| "a value: this key is required".into());
            SceneError::field(path, Message::new(Code::ValueMissing), allowed)
        }
        Fault::NoShapeFits => {
            let allowed = untagged_allowed(layout, &segments)
                .map(str::to_string)
                .or_else(hint)
                .or_else(|| error.expected.and_then(expected_words))
                .unwrap_or_else(|| "a value of another shape".into());
            SceneError::field(path, refused(), allowed)
        }
        Fault::UnknownVariant { known, .. } => {
            let allowed = hint().unwrap_or_else(|| format!("one of {}", names_as_serde_lists(known)));
            SceneError::field(path, refused(), allowed)
        }
        Fault::DuplicateKey { name } => {
            let path = joined(&path, name);
            let allowed = allowed_for(&path).unwrap_or_else(|| "one value".into());
            SceneError::field(path, refused(), allowed)
        }
        Fault::WrongKind | Fault::BadValue { .. } | Fault::Length { .. } => {
            let allowed = hint()
                .or_else(|| error.expected.and_then(expected_words))
                .or_else(|| tagged_allowed(&path).map(str::to_string))
                .unwrap_or_else(|| "a value of another kind".into());
            SceneError::field(path, refused(), allowed)
        }
    };
    with_detail(field, detail)
}

/// `path.key`, or `key` at the top.
fn joined(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// Names in quotes as a list: `"a"`, `"a" or "b"`, `"a", "b", "c"` (the words refusals have
/// always used for allowed keys and choices).
fn names_as_serde_lists(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
    match quoted.as_slice() {
        [a, b] => format!("{a} or {b}"),
        _ => quoted.join(", "),
    }
}

/// What an untagged choice at `segments` allows: a compact obstacle or goal, an activity's
/// condition.
fn untagged_allowed(layout: Layout, segments: &[Segment]) -> Option<&'static str> {
    let index = |k: usize| match segments.get(k) {
        Some(Segment::Seq { index }) => Some(*index),
        _ => None,
    };
    let in_conditions = segments.len() >= 2
        && matches!(segments.last(), Some(Segment::Seq { .. }))
        && matches!(&segments[segments.len() - 2], Segment::Map { key } if key == "conditions");
    match layout {
        _ if in_conditions => Some("a condition {\"metric\": key, \"op\": \">=\", \"value\": number} (optional \"group\" or \"pane\") or {\"before\": [{\"group\": i} | {\"pane\": i}, …], \"share\": 0.9}"),
        Layout::Compact if segments.len() == 2 && index(0) == Some(4) => {
            Some("a circle [x, y, radius], a rectangle [x0, y0, x1, y1] or a polygon [[x, y], …]")
        }
        Layout::Compact if segments.len() == 2 && index(0) == Some(5) => Some(
            "[x, y, radius], [x, y, radius, motion] or [x, y, radius, motion or null, \"gather\" | \"exit\"]",
        ),
        _ => None,
    }
}

/// What an internally tagged value at `path` allows when it is not even an object.
fn tagged_allowed(path: &str) -> Option<&'static str> {
    let pattern = crate::model::scene::index_free(path);
    match pattern.as_str() {
        "obstacles[]" => Some("an obstacle {\"shape\": \"circle\" | \"rect\" | \"polygon\", …}"),
        "goals[].motion" => Some("a goal motion {\"kind\": \"circle\" | \"polyline\", …}"),
        _ => None,
    }
}

/// The kind of value a type asks for, in a user's words.
fn expected_words(expected: Expected) -> Option<String> {
    Some(match expected {
        Expected::Number => "a number".into(),
        Expected::Whole { max } if max == u64::from(u32::MAX) => "a whole number 0…4294967295".into(),
        Expected::Whole { .. } => "a whole number ≥ 0".into(),
        Expected::Integer => "a whole number".into(),
        Expected::Text => "text in quotes".into(),
        Expected::Bool => "true or false".into(),
        Expected::List => "a list […]".into(),
        Expected::ListOf(n) => format!("a list of {n} numbers"),
        Expected::Object(_) => "an object {…}".into(),
        Expected::OneOf(names) => format!("one of {}", names_as_serde_lists(names)),
        Expected::Unit => "null".into(),
    })
}

/// What a planner parameter at `path` (`groups[2].planner.params.max_speed`) accepts, from the
/// table of the group's planner (read from `json`; any planner with that key if unknown).
fn planner_param_allowed(path: &str, json: Option<&serde_json::Value>) -> Option<String> {
    let (group, key) = path.strip_prefix("groups[")?.split_once("].planner.params.")?;
    let kind = json
        .and_then(|j| {
            j.get("groups")?.get(group.parse::<usize>().ok()?)?.get("planner")?.get("kind")?.as_str()
        })
        .and_then(PlannerKind::from_name);
    let key = key.split(['.', '[']).next()?;
    let kinds: Vec<PlannerKind> = kind.map_or_else(|| PlannerKind::ALL.to_vec(), |k| vec![k]);
    kinds.iter().find_map(|k| k.param_specs().iter().find(|s| s.key == key)).map(|s| s.allowed())
}

/// [`planner_param_allowed`] for a path below `planner` of a known planner.
fn param_allowed(kind: PlannerKind, path: &str) -> Option<String> {
    let key = path.strip_prefix("planner.params.")?.split(['.', '[']).next()?;
    kind.param_specs().iter().find(|s| s.key == key).map(|s| s.allowed())
}

fn with_detail(error: SceneError, detail: Option<String>) -> SceneError {
    match error {
        SceneError::Field(mut f) => {
            f.detail = detail;
            SceneError::Field(f)
        }
        other => other,
    }
}

/// The fields of an obstacle or a goal motion, without their tag: serde reads internally tagged
/// enums from a buffer, which loses the path below the object, so a refused one is read again
/// as one of these to name the field.
mod tagged {
    use serde::Deserialize;

    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    #[expect(dead_code, reason = "read only to find the refused field")]
    pub struct Circle {
        pub center: [f32; 2],
        pub radius: f32,
    }

    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    #[expect(dead_code, reason = "read only to find the refused field")]
    pub struct Rect {
        pub min: [f32; 2],
        pub max: [f32; 2],
    }

    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    #[expect(dead_code, reason = "read only to find the refused field")]
    pub struct Polygon {
        pub points: Vec<[f32; 2]>,
    }

    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    #[expect(dead_code, reason = "read only to find the refused field")]
    pub struct CircleMotion {
        pub center: [f32; 2],
        pub radius: f32,
        pub period_steps: f32,
    }

    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    #[expect(dead_code, reason = "read only to find the refused field")]
    pub struct PolylineMotion {
        pub points: Vec<[f32; 2]>,
        pub speed: f32,
    }
}

/// The path below an obstacle or goal motion `node` to its refused field and why, if one is
/// refused.
fn tagged_field(node: &serde_json::Value) -> Option<(Vec<Segment>, ShapeError)> {
    fn first_error<T: serde::de::DeserializeOwned>(
        fields: &serde_json::Value,
    ) -> Option<(Vec<Segment>, ShapeError)> {
        check::<T>(fields).err()
    }
    let mut fields = node.as_object()?.clone();
    let (tag, variant) = if let Some(shape) = fields.remove("shape") {
        ("shape", shape)
    } else {
        ("kind", fields.remove("kind")?)
    };
    let fields = serde_json::Value::Object(fields);
    let (path, error) = match (tag, variant.as_str()?) {
        ("shape", "circle") => first_error::<tagged::Circle>(&fields),
        ("shape", "rect") => first_error::<tagged::Rect>(&fields),
        ("shape", "polygon") => first_error::<tagged::Polygon>(&fields),
        ("kind", "circle") => first_error::<tagged::CircleMotion>(&fields),
        ("kind", "polyline") => first_error::<tagged::PolylineMotion>(&fields),
        _ => None,
    }?;
    (!path.is_empty() || matches!(error.fault, Fault::MissingKey { .. } | Fault::UnknownKey { .. }))
        .then_some((path, error))
}

/// Follows `segments` into `json`.
fn walk<'a>(json: &'a serde_json::Value, segments: &[Segment]) -> Option<&'a serde_json::Value> {
    segments.iter().try_fold(json, |node, segment| match segment {
        Segment::Seq { index } => node.get(*index),
        Segment::Map { key } => node.get(key),
        _ => Some(node),
    })
}

/// A value as written, shortened: `"abc"`, `4`, `[1,2,3]`.
fn render(value: &serde_json::Value) -> String {
    if let Some(x) = value.as_f64().filter(|x| x.abs() >= 1e7 || (*x != 0.0 && x.abs() < 1e-4)) {
        if value.is_f64() {
            return format!("{x:e}");
        }
    }
    let text = value.to_string();
    if text.chars().count() > 60 {
        format!("{}…", text.chars().take(57).collect::<String>())
    } else {
        text
    }
}

/// The word around (1-based) `line`, `column` of `text`: the number or name the parser stopped
/// at (`NaN`, `Infinity`, `1e999`), with its byte range in `text`.
fn token_at(text: &str, line: usize, column: usize) -> Option<(usize, usize, String)> {
    let row_start: usize = text.split_inclusive('\n').take(line.checked_sub(1)?).map(str::len).sum();
    let row = text.lines().nth(line - 1)?;
    // serde_json counts columns in bytes; the word is ASCII, so bytes serve as characters.
    let chars: Vec<char> = row.bytes().map(char::from).collect();
    let word = |c: char| c.is_ascii_alphanumeric() || matches!(c, '.' | '+' | '-');
    let mut at = column.min(chars.len());
    // The column names the character after the token or the token's first character.
    if at > 0 && !chars.get(at).copied().is_some_and(word) {
        at -= 1;
    }
    if !chars.get(at).copied().is_some_and(word) {
        return None;
    }
    let start = chars[..at].iter().rposition(|&c| !word(c)).map_or(0, |k| k + 1);
    let end = chars[at..].iter().position(|&c| !word(c)).map_or(chars.len(), |k| at + k);
    let token: String = chars[start..end].iter().take(40).collect();
    (!token.is_empty()).then_some((row_start + start, row_start + end, token))
}

/// A JSON string literal that does not hold text, found where the parser stopped.
struct InvalidString {
    /// Byte range of the literal in the text, quotes included.
    start: usize,
    end: usize,
    /// The fault as a refused value: `an invalid string (the lone surrogate \ud800)`.
    value: Message,
    /// The rule it breaks.
    allowed: &'static str,
}

/// What a text field allows when its string breaks JSON's rules for a surrogate escape.
const ALLOWED_SURROGATES: &str =
    "text in which each \\ud800…\\udbff escape is followed by a \\udc00…\\udfff one (a surrogate pair)";
/// … for an escape JSON does not have.
const ALLOWED_ESCAPES: &str =
    "text whose escapes are \\\" \\\\ \\/ \\b \\f \\n \\r \\t or \\u and 4 hex digits";
/// … for a control character written as it is.
const ALLOWED_CONTROL: &str = "text without raw control characters (write a line break as \\n)";

/// The string literal of `text` around (1-based) `line`, `column` and what makes it no text:
/// serde_json stops inside or just after it, and its own words ("lone leading surrogate in hex
/// escape", "unexpected end of hex escape") name neither the escape nor, for `"\ud800x"`, the
/// fault. `None` when the parser stopped outside a string or the string looks fine.
fn invalid_string_at(text: &str, line: usize, column: usize) -> Option<InvalidString> {
    let row_start: usize = text.split_inclusive('\n').take(line.checked_sub(1)?).map(str::len).sum();
    let at = row_start + column;
    // The literal holding `at`: scan from the start (strings can hold `[`, `"` escaped, …).
    let bytes = text.as_bytes();
    let (mut i, mut start) = (0, None);
    let (start, end) = loop {
        let b = *bytes.get(i)?;
        match (start, b) {
            (None, b'"') => start = Some(i),
            (Some(_), b'\\') => i += 1,
            (Some(s), b'"') => {
                // serde_json's column may lie one past the closing quote (`"\u12"` reads the
                // quote as the escape's third digit).
                if at <= i + 2 {
                    break (s, i + 1);
                }
                start = None;
            }
            _ => {}
        }
        i += 1;
        if start.is_none() && i > at {
            return None;
        }
    };
    let literal = &text[start + 1..end - 1];
    let fault = |value: Message, allowed| Some(InvalidString { start, end, value, allowed });
    fn hex(s: &str) -> Option<&str> {
        s.get(..4).filter(|h| h.bytes().all(|b| b.is_ascii_hexdigit()))
    }
    let mut rest = literal;
    while let Some(c) = rest.chars().next() {
        rest = &rest[c.len_utf8()..];
        if c < ' ' {
            let named =
                Message::new(Code::ValueRawControl).with("character", format!("U+{:04X}", u32::from(c)));
            return fault(named, ALLOWED_CONTROL);
        }
        if c != '\\' {
            continue;
        }
        let Some(e) = rest.chars().next() else { break };
        rest = &rest[e.len_utf8()..];
        match e {
            '"' | '\\' | '/' | 'b' | 'f' | 'n' | 'r' | 't' => {}
            'u' => {
                let Some(h) = hex(rest) else {
                    let written: String = rest.chars().take(4).collect();
                    let escape = format!("\\u{written}");
                    return fault(Message::new(Code::ValueBadEscape).with("escape", escape), ALLOWED_ESCAPES);
                };
                rest = &rest[4..];
                let n = u16::from_str_radix(h, 16).ok()?;
                let low_follows = || {
                    rest.strip_prefix("\\u")
                        .and_then(hex)
                        .and_then(|l| u16::from_str_radix(l, 16).ok())
                        .is_some_and(|l| (0xDC00..=0xDFFF).contains(&l))
                };
                match n {
                    0xD800..=0xDBFF if low_follows() => rest = &rest[6..],
                    0xD800..=0xDFFF => {
                        let escape = format!("\\u{h}");
                        return fault(
                            Message::new(Code::ValueLoneSurrogate).with("escape", escape),
                            ALLOWED_SURROGATES,
                        );
                    }
                    _ => {}
                }
            }
            other => {
                let escape = format!("\\{other}");
                return fault(Message::new(Code::ValueBadEscape).with("escape", escape), ALLOWED_ESCAPES);
            }
        }
    }
    None
}

/// A keyed path: `groups[2].planner.params.max_speed`.
fn keyed_path(segments: &[Segment]) -> String {
    let mut path = String::new();
    for segment in segments {
        match segment {
            Segment::Seq { index } => path.push_str(&format!("[{index}]")),
            Segment::Map { key } | Segment::Enum { variant: key } => {
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(key);
            }
            Segment::Unknown => {}
        }
    }
    path
}

/// A compact form's positional path in the keyed scene's names (`[6][2][7][2]` →
/// `groups[2].planner.params.max_speed`), so both forms of a link refuse in the same words.
fn compact_path(segments: &[Segment], json: Option<&serde_json::Value>) -> String {
    let index = |k: usize| match segments.get(k) {
        Some(Segment::Seq { index }) => Some(*index),
        _ => None,
    };
    let node = |k: usize| json.and_then(|j| walk(j, &segments[..k.min(segments.len())]));
    let rest = |k: usize| {
        let tail = keyed_path(segments.get(k..).unwrap_or_default());
        if tail.is_empty() || tail.starts_with('[') {
            tail
        } else {
            format!(".{tail}")
        }
    };
    let pair = |name: &str, k: usize| match index(k) {
        Some(c) => format!("{name}[{c}]{}", rest(k + 1)),
        None => name.to_string(),
    };
    let Some(top) = index(0) else { return keyed_path(segments) };
    match (top, index(1)) {
        (0, _) => "name".into(),
        (1, _) => "width".into(),
        (2, _) => "height".into(),
        (3, _) => "seed".into(),
        (4, None) => "obstacles".into(),
        (4, Some(i)) => {
            let arity = node(2).and_then(|o| o.as_array()).map(Vec::len);
            let field = match (arity, index(2)) {
                (_, None) => String::new(),
                (Some(3), Some(k)) if node(3).is_some_and(|v| !v.is_array()) => {
                    if k < 2 {
                        format!(".center[{k}]")
                    } else {
                        ".radius".into()
                    }
                }
                (Some(4), Some(k)) if node(3).is_some_and(|v| !v.is_array()) => {
                    format!(".{}[{}]", if k < 2 { "min" } else { "max" }, k % 2)
                }
                (_, Some(k)) => format!(".points[{k}]{}", rest(3)),
            };
            format!("obstacles[{i}]{field}")
        }
        (5, None) => "goals".into(),
        (5, Some(i)) => match index(2) {
            None => format!("goals[{i}]"),
            Some(k @ (0 | 1)) => format!("goals[{i}].position[{k}]"),
            Some(2) => format!("goals[{i}].radius"),
            Some(_) => format!("goals[{i}].motion{}", rest(3)),
        },
        (6, None) => "groups".into(),
        (6, Some(i)) => {
            let field = match index(2) {
                None => String::new(),
                Some(0) => ".name".into(),
                Some(1) => ".color".into(),
                Some(2) => ".count".into(),
                Some(3) => match index(3) {
                    Some(k) => format!(".spawn.{}[{}]", if k < 2 { "min" } else { "max" }, k % 2),
                    None => ".spawn".into(),
                },
                Some(4) => ".goal".into(),
                Some(5) => ".agent_radius".into(),
                Some(6) => ".planner.kind".into(),
                Some(_) => {
                    let kind = node(3)
                        .and_then(|g| g.get(6))
                        .and_then(|k| k.as_str())
                        .and_then(PlannerKind::from_name);
                    match (index(3), kind) {
                        (Some(k), Some(kind)) => match kind.param_specs().get(k) {
                            Some(spec) => format!(".planner.params.{}", spec.key),
                            None => format!(".planner.params{}", rest(4)),
                        },
                        _ => ".planner.params".into(),
                    }
                }
            };
            format!("groups[{i}]{field}")
        }
        (7, _) => match index(1) {
            Some(0) => "view.trails".into(),
            Some(1) => "view.trail_fade".into(),
            _ => "view".into(),
        },
        (8, Some(0)) => match (index(2), index(3)) {
            (Some(i), Some(0)) => format!("paths[{i}].radius"),
            (Some(i), Some(_)) => pair(&format!("paths[{i}].points"), 4),
            (Some(i), None) => format!("paths[{i}]"),
            _ => "paths".into(),
        },
        (8, Some(_)) => match (index(2), index(3)) {
            (Some(i), Some(k @ (0 | 1))) => format!("hills[{i}].center[{k}]"),
            (Some(i), Some(2)) => format!("hills[{i}].radius"),
            (Some(i), Some(_)) => format!("hills[{i}].height"),
            (Some(i), None) => format!("hills[{i}]"),
            _ => "hills".into(),
        },
        (9, _) => "px_per_metre".into(),
        (10, _) => format!("activity{}", rest(1)),
        _ => keyed_path(segments),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::presets;

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

    /// Regression (issue 24): a lone surrogate in a name (`"\ud800x"`) was refused as "a finite
    /// number (JSON has no NaN or Infinity)" with the value `ud800x`.
    #[test]
    fn a_string_that_is_no_text_is_refused_naming_its_fault() {
        let scene = (crate::model::presets::ALL[0].build)();
        let json = scene_to_json(&scene);
        let name = format!("\"name\": {}", serde_json::to_string(&scene.groups[0].name).expect("a name"));
        let with_name = |written: &str| json.replacen(&name, &format!("\"name\": \"{written}\""), 1);
        for (written, value, allowed) in [
            ("\\ud800x", "an invalid string (the lone surrogate \\ud800)", ALLOWED_SURROGATES),
            ("ab\\ud800\\u0041", "an invalid string (the lone surrogate \\ud800)", ALLOWED_SURROGATES),
            ("\\uDC00", "an invalid string (the lone surrogate \\uDC00)", ALLOWED_SURROGATES),
            ("a\\qb", "an invalid string (the escape \\q)", ALLOWED_ESCAPES),
            ("a\\u12", "an invalid string (the escape \\u12)", ALLOWED_ESCAPES),
            (
                "tab\there",
                "an invalid string (the control character U+0009 written as it is)",
                ALLOWED_CONTROL,
            ),
        ] {
            let text = with_name(written);
            assert_ne!(text, json);
            let e = scene_from_json(&text).expect_err(written);
            let SceneError::Field(f) = &e else { panic!("{written}: {e}") };
            assert_eq!(
                (f.path.as_str(), f.value.to_string().as_str(), f.allowed.as_str()),
                ("groups[0].name", value, allowed),
                "{written}"
            );
            assert!(!e.to_string().contains("finite number"), "{e}");
        }
        // A surrogate pair is text (U+1F600), and loads.
        assert!(scene_from_json(&with_name("\\ud83d\\ude00")).is_ok());
        // In a link's compact form, the same words and the keyed path.
        let fragment = scene_to_fragment(&scene);
        let compact = unpack(fragment.split_once('.').expect("version").1).expect("unpacks");
        let quoted = serde_json::to_string(&scene.groups[0].name).expect("a name");
        let broken = compact.replacen(&format!("[{quoted},"), "[\"\\ud800x\",", 1);
        assert_ne!(broken, compact, "the group's name is in the compact form");
        let e = scene_from_fragment(&format!("2.{}", pack(broken.as_bytes()))).expect_err("a lone surrogate");
        assert_eq!(
            e.to_string(),
            format!("groups[0].name is an invalid string (the lone surrogate \\ud800); allowed: {ALLOWED_SURROGATES}")
        );
    }

    #[test]
    fn truncated_fragments_fail_cleanly() {
        let frag = scene_to_fragment(&(presets::ALL[0].build)());
        for cut in 2..frag.len() {
            assert!(scene_from_fragment(&frag[..cut]).is_err(), "cut at {cut}");
        }
    }
}
