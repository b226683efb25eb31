//! `flockpath scorm`: the SCORM 1.2 package of an activity link, for an LMS.

use crate::{failed, out, usage, CliError};
use flockpath::model::refusal::Refusal as _;
use flockpath::package::scorm::{is_page_file, scorm_package, ScormError};
use std::path::{Path, PathBuf};

/// `flockpath scorm --link LINK --www DIR --out FILE`.
#[derive(clap::Args, Debug)]
#[command(long_about = "Package an activity as a SCORM 1.2 zip for an LMS (Moodle, Canvas, Blackboard, \
Brightspace): imsmanifest.xml, a launch page, the scene and the embed view's files from --www. \
In the LMS it reports lesson_status (passed or failed by the check) and score.raw (0-100: the \
check, and the prediction when it has an expected answer), and keeps the student's prediction \
in suspend_data.")]
pub struct ScormArgs {
    /// The activity: a page link (index.html#s=…&lock=…), a #s= fragment, a fragment value,
    /// scene JSON, or a scene JSON file; classroom options in the link go into the package
    #[arg(long)]
    link: String,
    /// The built page folder (after `bash scripts/build-wasm.sh`)
    #[arg(long, default_value = "www")]
    www: PathBuf,
    /// The zip to write
    #[arg(long)]
    out: PathBuf,
}

/// Writes the package and prints what went in.
pub fn scorm(args: &ScormArgs) -> Result<(), CliError> {
    let link = if Path::new(&args.link).is_file() {
        std::fs::read_to_string(&args.link)
            .map_err(|e| failed(format!("cannot read scene file {:?}: {e}", args.link)))?
    } else {
        args.link.clone()
    };
    if !args.www.is_dir() {
        return Err(usage(format!("--www {:?} is not a folder (the built page: www/)", args.www)));
    }
    let files = page_files(&args.www)?;
    let package = scorm_package(&link, &files).map_err(|e| match e {
        ScormError::MissingFile(_) => failed(format!("{e} (in --www {:?})", args.www)),
        e => failed(format!("cannot package this activity: {}", e.message())),
    })?;
    std::fs::write(&args.out, &package.zip)
        .map_err(|e| failed(format!("cannot write --out {:?}: {e}", args.out)))?;
    out(&format!(
        "wrote {}: SCORM 1.2, {} files, {} bytes\ntitle: {}\nlaunch: {}\n",
        args.out.display(),
        package.files.len(),
        package.zip.len(),
        package.title,
        package.launch,
    ))
}

/// The page files under `www` that a package takes, as `(path relative to www, bytes)`.
fn page_files(www: &Path) -> Result<Vec<(String, Vec<u8>)>, CliError> {
    let mut found = Vec::new();
    let mut folders = vec![PathBuf::new()];
    while let Some(relative) = folders.pop() {
        let dir = www.join(&relative);
        let entries = std::fs::read_dir(&dir).map_err(|e| failed(format!("cannot list {dir:?}: {e}")))?;
        for entry in entries {
            let entry = entry.map_err(|e| failed(format!("cannot list {dir:?}: {e}")))?;
            let Some(name) = entry.file_name().to_str().map(str::to_string) else { continue };
            let path = relative.join(&name);
            let kind = entry.file_type().map_err(|e| failed(format!("cannot read {path:?}: {e}")))?;
            if kind.is_dir() {
                folders.push(path);
                continue;
            }
            let key: Vec<String> =
                path.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
            let key = key.join("/");
            if is_page_file(&key) {
                let bytes = std::fs::read(entry.path())
                    .map_err(|e| failed(format!("cannot read {:?}: {e}", entry.path())))?;
                found.push((key, bytes));
            }
        }
    }
    Ok(found)
}
