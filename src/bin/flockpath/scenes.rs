//! `flockpath presets`, `preset NAME`, `url FILE`, `scene STRING`, and reading a scene from any
//! of the forms a user has at hand (file, stdin, JSON, fragment, URL, preset name).

use crate::{failed, out, usage, CliError};
use flockpath::{presets, scene_from_any, scene_to_fragment, scene_to_json, Scene};
use std::io::Read as _;
use std::path::Path;

/// `flockpath preset NAME`.
#[derive(clap::Args, Debug)]
#[command(long_about = "Print the preset scene NAME as JSON")]
pub struct PresetArgs {
    /// Preset name (`flockpath presets` lists them)
    name: String,
}

/// `flockpath url FILE`.
#[derive(clap::Args, Debug)]
#[command(long_about = "Print the URL fragment value (the part after #s=) for the scene JSON in FILE")]
pub struct UrlArgs {
    /// A scene JSON file, `-` for stdin
    file: String,
}

/// `flockpath scene STRING`.
#[derive(clap::Args, Debug)]
#[command(long_about = "Print the scene JSON for a URL fragment value, #s= fragment or URL")]
pub struct SceneArgs {
    /// A fragment value (2.…), a #s=… fragment or a whole page URL
    string: String,
}

/// Lists the presets: name, padded, then description.
pub fn presets() -> Result<(), CliError> {
    let width = presets::ALL.iter().map(|p| p.name.len()).max().unwrap_or(0);
    let mut text = String::new();
    for p in presets::ALL {
        text.push_str(&format!("{:width$}  {}\n", p.name, p.description));
    }
    out(&text)
}

/// Prints one preset as JSON.
pub fn preset(args: &PresetArgs) -> Result<(), CliError> {
    let name = &args.name;
    let preset =
        presets::lookup(name).map_err(|e| usage(format!("{e}; `flockpath presets` describes them")))?;
    out(&format!("{}\n", scene_to_json(&(preset.build)())))
}

/// Prints the fragment value of a scene file.
pub fn url(args: &UrlArgs) -> Result<(), CliError> {
    let scene = load_scene(&args.file)?;
    out(&format!("{}\n", scene_to_fragment(&scene)))
}

/// Prints the scene JSON of a fragment or URL.
pub fn scene(args: &SceneArgs) -> Result<(), CliError> {
    let scene = scene_from_any(&args.string).map_err(|e| failed(format!("bad scene string: {e}")))?;
    out(&format!("{}\n", scene_to_json(&scene)))
}

/// Loads a scene from a file, stdin (`-`), inline JSON, a fragment value, a URL or a preset name.
pub fn load_scene(source: &str) -> Result<Scene, CliError> {
    let path = Path::new(source);
    let text = if source == "-" {
        let mut text = String::new();
        std::io::stdin().read_to_string(&mut text).map_err(|e| failed(format!("cannot read stdin: {e}")))?;
        text
    } else if path.is_file() {
        std::fs::read_to_string(path)
            .map_err(|e| failed(format!("cannot read scene file {source:?}: {e}")))?
    } else if presets::find(source).is_some() {
        // A preset name: `scene_from_any` builds it.
        source.to_string()
    } else if looks_like_path(source) {
        let hint = if source.contains(['/', '\\', '.']) {
            String::new()
        } else {
            let names: Vec<&str> = presets::ALL.iter().map(|p| p.name).collect();
            format!(", and no preset has that name (known: {})", names.join(", "))
        };
        return Err(failed(format!("cannot read scene file {source:?}: no such file{hint}")));
    } else {
        source.to_string()
    };
    let what = if source == "-" { "stdin".to_string() } else { format!("{source:?}") };
    let what =
        if what.len() > 60 { format!("{}…", what.chars().take(57).collect::<String>()) } else { what };
    scene_from_any(&text).map_err(|e| failed(format!("bad scene in {what}: {e}")))
}

/// A string that cannot be a scene string or JSON but reads like a file name.
fn looks_like_path(s: &str) -> bool {
    let t = s.trim_start();
    if t.starts_with('{') || t.contains("#s=") || t.contains("://") {
        return false;
    }
    // Fragment values are base64url (no `/`) after a version prefix such as `2.`.
    t.contains('/') || t.contains('\\') || t.ends_with(".json") || !t.contains('.')
}
