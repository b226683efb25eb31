//! Scene ↔ JSON and scene ↔ URL fragment. Versioned, compact, and never panics on bad input.
//!
//! Fragment format `1.<payload>`: the scene's compact JSON, raw-deflated (miniz_oxide) and
//! URL-safe base64 without padding. The version prefix lets later formats keep old links working.

use crate::scene::{Scene, SceneError};
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use base64::Engine as _;

/// The fragment version written today.
pub const FRAGMENT_VERSION: &str = "1";
/// Largest decompressed scene accepted from a URL (bytes): a guard against deflate bombs.
const MAX_SCENE_BYTES: usize = 4 << 20;
/// Largest text accepted from a URL or file (bytes).
const MAX_INPUT_BYTES: usize = 8 << 20;

/// Parses and validates a scene from JSON text.
pub fn scene_from_json(text: &str) -> Result<Scene, SceneError> {
    if text.len() > MAX_INPUT_BYTES {
        return Err(SceneError::Parse(format!(
            "the scene text is {} bytes, over the 8 MiB limit",
            text.len()
        )));
    }
    let scene: Scene = serde_json::from_str(text).map_err(|e| SceneError::Parse(e.to_string()))?;
    scene.validate()?;
    Ok(scene)
}

/// The scene as pretty JSON.
pub fn scene_to_json(scene: &Scene) -> String {
    serde_json::to_string_pretty(scene).unwrap_or_default()
}

/// The URL fragment value (`s=` part) for a scene.
pub fn scene_to_fragment(scene: &Scene) -> String {
    let json = serde_json::to_vec(scene).unwrap_or_default();
    let packed = miniz_oxide::deflate::compress_to_vec(&json, 9);
    format!("{FRAGMENT_VERSION}.{}", URL_SAFE_NO_PAD.encode(packed))
}

/// Decodes a fragment value; also accepts a whole URL or a `#s=…` fragment.
pub fn scene_from_fragment(input: &str) -> Result<Scene, SceneError> {
    let value = fragment_value(input.trim());
    let (version, payload) = value.split_once('.').ok_or_else(|| {
        SceneError::Parse("the scene string has no version prefix (expected \"1.…\")".into())
    })?;
    match version {
        "1" => {
            let packed = URL_SAFE_NO_PAD.decode(payload.trim_end_matches('=')).map_err(|e| {
                SceneError::Parse(format!("the scene string is not valid base64 ({e}); was it cut short?"))
            })?;
            let json = miniz_oxide::inflate::decompress_to_vec_with_limit(&packed, MAX_SCENE_BYTES).map_err(
                |e| SceneError::Parse(format!("the scene string is damaged or truncated ({:?})", e.status)),
            )?;
            let text = std::str::from_utf8(&json)
                .map_err(|_| SceneError::Parse("the scene string does not hold text".into()))?;
            scene_from_json(text)
        }
        other => Err(SceneError::Parse(format!(
            "unknown scene format version {:?}; this flockpath reads version {FRAGMENT_VERSION}",
            other.chars().take(12).collect::<String>()
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets;

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
