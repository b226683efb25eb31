//! A SCORM 1.2 package of an activity, and the rule that turns a run of it into the score and
//! lesson status the package reports to the LMS.
//!
//! The package is a zip: `imsmanifest.xml` (one organization with one item, one SCO resource
//! listing every file), the launch page `activity.html`, the scene as `activity.json`, and the
//! page files the embed view needs (`embed.html`, its scripts, the wasm). The launch page opens
//! `embed.html#s=<scene>&<classroom options>&scorm=1`: the link's own scene and options, plus the
//! flag that has the page look for the LMS's SCORM runtime (`www/js/core/scorm.js`).
//!
//! Grading ([`grade`]): the check decides passed (met) or failed (missed); the score is 0–100:
//! the check is worth 100, or 50 when the prediction has an expected answer, which is then worth
//! the other 50. An open question (no expected answer) is asked but not scored.
//!
//! ```
//! use flockpath::package::scorm::{grade, LessonStatus};
//! use flockpath::model::activity::Activity;
//! use flockpath::sim::activity_check::Status;
//! let activity: Activity = serde_json::from_str(r#"{"prompt": "Cross the field.",
//!   "prediction": {"question": "Do most arrive?", "choices": ["yes", "no"], "expected": 0},
//!   "check": {"steps": 600, "conditions": [{"metric": "arrived_share", "op": ">=", "value": 0.5}]}}"#)
//!   .expect("an activity");
//! let g = grade(&activity, Status::Met, Some(1));
//! assert_eq!((g.lesson_status, g.score_raw), (LessonStatus::Passed, Some(50)));
//! ```

use super::zip::{ZipError, ZipWriter};
use crate::model::activity::{Activity, Condition};
use crate::model::classroom::ClassroomError;
use crate::model::codec::{classroom_from_link, link_fragment, scene_from_any, scene_to_json};
use crate::model::refusal::{Code, Message, Refusal};
use crate::model::scene::{Scene, SceneError};
use crate::sim::activity_check::Status;
use serde::Serialize;
use std::fmt;

/// The SCO's launch page: opens the embed view on the package's scene.
pub const LAUNCH_FILE: &str = "activity.html";
/// The scene with its activity as JSON, for whoever opens the package (the launch page carries
/// the same scene in its link).
pub const SCENE_FILE: &str = "activity.json";
/// The manifest an LMS reads first.
pub const MANIFEST_FILE: &str = "imsmanifest.xml";
/// Page files (relative to `www/`) the launch page needs by name; beside them every module of
/// `js/core/` (the embed view's imports; [`is_page_file`]).
pub const REQUIRED_PAGE_FILES: &[&str] =
    &["embed.html", "js/embed/main.js", "js/flock-path.js", "pkg/flockpath.js", "pkg/flockpath_bg.wasm"];
/// The longest title the manifest gets (characters): LMS course lists show one line.
pub const MAX_TITLE_CHARS: usize = 100;

/// Whether the page file `path` (relative to `www/`, `/`-separated) goes into a package: the
/// embed view, its scripts and strings, and the wasm with its glue. The service worker, the
/// other pages and their styles stay out (an LMS serves the package; it is not the playground).
pub fn is_page_file(path: &str) -> bool {
    REQUIRED_PAGE_FILES.contains(&path) || (path.starts_with("js/core/") && path.ends_with(".js"))
}

/// Why a package cannot be made.
#[derive(Debug)]
pub enum ScormError {
    /// The link's scene does not read.
    Scene(SceneError),
    /// The link's classroom options do not read.
    Classroom(ClassroomError),
    /// The scene has no activity.
    NoActivity,
    /// The activity has no check to score.
    NoCheck,
    /// The check names compare-page panes, which the embed view cannot decide.
    CompareOnly,
    /// A file of [`REQUIRED_PAGE_FILES`] was not given.
    MissingFile(String),
    /// The zip refused a file.
    Zip(ZipError),
}

impl Refusal for ScormError {
    fn message(&self) -> Message {
        match self {
            ScormError::Scene(e) => e.message(),
            ScormError::Classroom(e) => e.message(),
            ScormError::NoActivity => Message::new(Code::ScormNoActivity),
            ScormError::NoCheck => Message::new(Code::ScormNoCheck),
            ScormError::CompareOnly => Message::new(Code::ScormCompareOnly),
            ScormError::MissingFile(name) => Message::new(Code::ScormMissingFile).with("name", name.clone()),
            ScormError::Zip(e) => e.message(),
        }
    }
}

impl fmt::Display for ScormError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.message().fmt(f)
    }
}

impl std::error::Error for ScormError {}

/// What [`scorm_package`] made: the zip and, for reports, what is in it.
#[derive(Clone, Debug)]
pub struct ScormPackage {
    /// The zip's bytes.
    pub zip: Vec<u8>,
    /// Every file in the zip, in order (the manifest first).
    pub files: Vec<String>,
    /// The title the LMS shows (the prompt's first line).
    pub title: String,
    /// The launch page's target: `embed.html#…&scorm=1`.
    pub launch: String,
}

/// The scene of `link` (a link, a `#s=…` fragment, a fragment value, scene JSON, a preset name)
/// with its classroom options, checked for packaging: it has an activity with a check that one
/// scene can decide.
pub fn packaged_scene(link: &str) -> Result<(Scene, String), ScormError> {
    let scene = scene_from_any(link).map_err(ScormError::Scene)?;
    let classroom = classroom_from_link(link).map_err(ScormError::Classroom)?;
    let activity = scene.activity.as_ref().ok_or(ScormError::NoActivity)?;
    let check = activity.check.as_ref().ok_or(ScormError::NoCheck)?;
    let names_pane = |c: &Condition| match c {
        Condition::Metric(m) => m.pane.is_some(),
        Condition::Before(b) => {
            b.before.iter().any(|s| matches!(s, crate::model::activity::Subject::Pane(_)))
        }
    };
    if check.conditions.iter().any(names_pane) {
        return Err(ScormError::CompareOnly);
    }
    let fragment = link_fragment(&scene, &classroom);
    Ok((scene, fragment))
}

/// The package of the activity in `link`, with `page_files` (`(path relative to www/, bytes)`):
/// those [`is_page_file`] accepts go in, the rest are skipped; each of
/// [`REQUIRED_PAGE_FILES`] must be there.
pub fn scorm_package(link: &str, page_files: &[(String, Vec<u8>)]) -> Result<ScormPackage, ScormError> {
    let (scene, fragment) = packaged_scene(link)?;
    for required in REQUIRED_PAGE_FILES {
        if !page_files.iter().any(|(name, _)| name == required) {
            return Err(ScormError::MissingFile((*required).to_string()));
        }
    }
    let prompt = scene.activity.as_ref().map_or("", |a| a.prompt.as_str());
    let title = title_of(prompt, &scene.name);
    let launch = format!("embed.html#{fragment}&scorm=1");
    let mut pages: Vec<&(String, Vec<u8>)> =
        page_files.iter().filter(|(name, _)| is_page_file(name)).collect();
    pages.sort_by(|a, b| a.0.cmp(&b.0));

    let mut files: Vec<String> = vec![LAUNCH_FILE.to_string(), SCENE_FILE.to_string()];
    files.extend(pages.iter().map(|(name, _)| name.clone()));
    let identifier = format!("flockpath-{:08x}", super::zip::crc32(fragment.as_bytes()));
    let manifest = manifest_xml(&identifier, &title, &files);

    let mut zip = ZipWriter::new();
    zip.add(MANIFEST_FILE, manifest.as_bytes()).map_err(ScormError::Zip)?;
    zip.add(LAUNCH_FILE, launch_page(&title, &launch).as_bytes()).map_err(ScormError::Zip)?;
    zip.add(SCENE_FILE, format!("{}\n", scene_to_json(&scene)).as_bytes()).map_err(ScormError::Zip)?;
    for (name, bytes) in &pages {
        zip.add(name, bytes).map_err(ScormError::Zip)?;
    }
    let files: Vec<String> = zip.names().map(str::to_string).collect();
    Ok(ScormPackage { zip: zip.finish(), files, title, launch })
}

/// The title: the prompt's first non-empty line, shortened to [`MAX_TITLE_CHARS`]; the scene's
/// name when the prompt has none.
fn title_of(prompt: &str, scene_name: &str) -> String {
    let line = prompt.lines().map(str::trim).find(|l| !l.is_empty()).unwrap_or(scene_name.trim());
    let line = if line.is_empty() { "flockpath activity" } else { line };
    if line.chars().count() <= MAX_TITLE_CHARS {
        line.to_string()
    } else {
        let mut short: String = line.chars().take(MAX_TITLE_CHARS - 1).collect();
        short.push('…');
        short
    }
}

/// `text` with the five XML (and HTML) special characters escaped, for text and attributes.
pub fn xml_escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // Control characters are not allowed in XML 1.0; a prompt has no use for them.
            c if c.is_control() && !matches!(c, '\n' | '\t') => {}
            c => out.push(c),
        }
    }
    out
}

/// The SCORM 1.2 manifest (IMS Content Packaging 1.1.2 with ADL's `adlcp` extension): one
/// organization, one item, one SCO whose files are `files` plus the manifest.
pub fn manifest_xml(identifier: &str, title: &str, files: &[String]) -> String {
    let title = xml_escape(title);
    let mut file_lines = String::new();
    for file in files {
        file_lines.push_str(&format!("      <file href=\"{}\"/>\n", xml_escape(file)));
    }
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<manifest identifier="{id}" version="1.0"
    xmlns="http://www.imsproject.org/xsd/imscp_rootv1p1p2"
    xmlns:adlcp="http://www.adlnet.org/xsd/adlcp_rootv1p2"
    xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
    xsi:schemaLocation="http://www.imsproject.org/xsd/imscp_rootv1p1p2 imscp_rootv1p1p2.xsd http://www.imsglobal.org/xsd/imsmd_rootv1p2p1 imsmd_rootv1p2p1.xsd http://www.adlnet.org/xsd/adlcp_rootv1p2 adlcp_rootv1p2.xsd">
  <metadata>
    <schema>ADL SCORM</schema>
    <schemaversion>1.2</schemaversion>
  </metadata>
  <organizations default="{id}-org">
    <organization identifier="{id}-org">
      <title>{title}</title>
      <item identifier="{id}-item" identifierref="{id}-sco" isvisible="true">
        <title>{title}</title>
      </item>
    </organization>
  </organizations>
  <resources>
    <resource identifier="{id}-sco" type="webcontent" adlcp:scormtype="sco" href="{launch}">
{file_lines}    </resource>
  </resources>
</manifest>
"#,
        id = xml_escape(identifier),
        launch = LAUNCH_FILE,
    )
}

/// The launch page: forwards to the embed view with the scene (a meta refresh, no script, so a
/// strict LMS content policy does not stop it), with a link for a browser that does not follow.
pub fn launch_page(title: &str, launch: &str) -> String {
    let title = xml_escape(title);
    let target = xml_escape(launch);
    format!(
        r#"<!doctype html>
<html lang="en">
<head>
  <meta charset="utf-8">
  <meta name="viewport" content="width=device-width, initial-scale=1">
  <title>{title}</title>
  <link rel="icon" href="data:,">
  <meta http-equiv="refresh" content="0; url={target}">
</head>
<body>
  <p><a href="{target}">{title}</a></p>
</body>
</html>
"#
    )
}

/// A SCORM 1.2 `cmi.core.lesson_status` value the package sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LessonStatus {
    /// Opened, the check not decided yet.
    Incomplete,
    /// Run, but the check could not be decided here.
    Completed,
    /// The check was met.
    Passed,
    /// The check was missed.
    Failed,
}

/// What the package reports for one run: the lesson status and the score (0–100; none until
/// the check is decided).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Grade {
    /// `cmi.core.lesson_status`.
    pub lesson_status: LessonStatus,
    /// `cmi.core.score.raw` (of `score.min` 0 and `score.max` 100), or none.
    pub score_raw: Option<u8>,
}

/// Points for a met check when the prediction is scored too (the prediction gets the rest).
pub const CHECK_POINTS_WITH_PREDICTION: u8 = 50;
/// The whole score.
pub const MAX_SCORE: u8 = 100;

/// The grade of a run of `activity` whose check stands at `status`, with the student's
/// prediction `answer` (a choice's index from 0, or none). See the module's rule.
pub fn grade(activity: &Activity, status: Status, answer: Option<u32>) -> Grade {
    let lesson_status = match status {
        Status::Running => LessonStatus::Incomplete,
        Status::Unavailable => LessonStatus::Completed,
        Status::Met => LessonStatus::Passed,
        Status::Missed => LessonStatus::Failed,
    };
    if !matches!(status, Status::Met | Status::Missed) {
        return Grade { lesson_status, score_raw: None };
    }
    let met = status == Status::Met;
    let expected = activity.prediction.as_ref().and_then(|p| p.expected);
    let score = match expected {
        Some(expected) => {
            let check = if met { CHECK_POINTS_WITH_PREDICTION } else { 0 };
            let right = if answer == Some(expected) { MAX_SCORE - CHECK_POINTS_WITH_PREDICTION } else { 0 };
            check + right
        }
        None if met => MAX_SCORE,
        None => 0,
    };
    Grade { lesson_status, score_raw: Some(score) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn activity(expected: Option<u32>) -> Activity {
        let prediction = expected.map_or(String::new(), |e| {
            format!(r#","prediction": {{"question": "Q?", "choices": ["a", "b", "c"], "expected": {e}}}"#)
        });
        serde_json::from_str(&format!(
            r#"{{"prompt": "P"{prediction},
                "check": {{"steps": 60, "conditions": [{{"metric": "arrived_share", "op": ">=", "value": 0.5}}]}}}}"#
        ))
        .expect("an activity")
    }

    #[test]
    fn the_check_and_the_prediction_share_the_score() {
        let a = activity(Some(2));
        let score = |status, answer| grade(&a, status, answer).score_raw;
        assert_eq!(score(Status::Met, Some(2)), Some(100));
        assert_eq!(score(Status::Met, Some(0)), Some(50));
        assert_eq!(score(Status::Missed, Some(2)), Some(50));
        assert_eq!(score(Status::Missed, None), Some(0));
        assert_eq!(score(Status::Running, Some(2)), None);
        assert_eq!(grade(&a, Status::Missed, Some(2)).lesson_status, LessonStatus::Failed);
    }

    #[test]
    fn without_an_expected_answer_the_check_is_the_whole_score() {
        let a = activity(None);
        assert_eq!(
            grade(&a, Status::Met, Some(1)),
            Grade { lesson_status: LessonStatus::Passed, score_raw: Some(100) }
        );
        assert_eq!(grade(&a, Status::Missed, None).score_raw, Some(0));
        assert_eq!(grade(&a, Status::Unavailable, None).lesson_status, LessonStatus::Completed);
    }

    #[test]
    fn markup_in_a_title_is_escaped() {
        assert_eq!(xml_escape(r#"<b a="1">&'"#), "&lt;b a=&quot;1&quot;&gt;&amp;&apos;");
        let xml = manifest_xml("x", "<script>", &["a&b.js".to_string()]);
        assert!(
            xml.contains("<title>&lt;script&gt;</title>") && xml.contains(r#"href="a&amp;b.js""#),
            "{xml}"
        );
    }

    #[test]
    fn titles_are_one_short_line() {
        assert_eq!(title_of("\n  First line\nsecond", "scene"), "First line");
        assert_eq!(title_of("", "pillars"), "pillars");
        let long = "x".repeat(300);
        assert_eq!(title_of(&long, "").chars().count(), MAX_TITLE_CHARS);
    }

    #[test]
    fn only_the_embed_view_and_its_modules_are_page_files() {
        for yes in ["embed.html", "js/core/boot.js", "js/core/strings/zh.js", "pkg/flockpath_bg.wasm"] {
            assert!(is_page_file(yes), "{yes}");
        }
        for no in ["index.html", "sw.js", "js/play/main.js", "pkg/precache.js", "style.css"] {
            assert!(!is_page_file(no), "{no}");
        }
    }
}
