//! The SCORM package natively: `flockpath scorm` on the example of docs/course-notes.md over a
//! stand-in page folder writes a zip whose central directory Python's `zipfile` and Info-ZIP's
//! `unzip` read (CRC-32 included), whose manifest lists every file in it and nothing else, and
//! which holds the embed view's files and not the playground's. Links it cannot grade are refused.

use flockpath::package::scorm::{scorm_package, ScormError};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The link of the `flockpath scorm --link '…'` example in docs/course-notes.md.
fn documented_link() -> String {
    let doc = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/course-notes.md"))
        .expect("docs/course-notes.md");
    let line =
        doc.lines().find(|l| l.starts_with("flockpath scorm --link '")).expect("the documented example");
    let start = line.find('\'').expect("quote") + 1;
    let end = start + line[start..].find('\'').expect("closing quote");
    line[start..end].to_string()
}

/// A fresh folder for this test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flockpath-scorm-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// A stand-in for the built page folder: the embed view's files, and some that must stay out.
fn page_folder(dir: &Path) -> PathBuf {
    let www = dir.join("www");
    for (name, text) in [
        ("embed.html", "<!doctype html><title>embed</title>"),
        ("index.html", "<!doctype html><title>playground</title>"),
        ("sw.js", "// the service worker"),
        ("style.css", "body {}"),
        ("js/embed/main.js", "import '../flock-path.js';"),
        ("js/flock-path.js", "export {};"),
        ("js/core/boot.js", "export {};"),
        ("js/core/scorm.js", "export {};"),
        ("js/core/strings/zh.js", "export default { '活动': '活动' };"),
        ("js/play/main.js", "// the playground's"),
        ("pkg/flockpath.js", "export default function init() {}"),
        ("pkg/precache.js", "self.FLOCKPATH_PRECACHE = {};"),
    ] {
        let path = www.join(name);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("folder");
        std::fs::write(path, text).expect("file");
    }
    // Bytes of every value, so a wrong offset or CRC shows.
    let wasm: Vec<u8> = (0..70_000u32).map(|i| (i * 7 % 256) as u8).collect();
    std::fs::write(www.join("pkg/flockpath_bg.wasm"), wasm).expect("wasm");
    www
}

fn run(program: &str, args: &[&str]) -> String {
    let out = Command::new(program).args(args).output().unwrap_or_else(|e| panic!("{program} runs: {e}"));
    assert!(out.status.success(), "{program} {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The `<file href="…"/>` entries of a manifest.
fn manifest_files(xml: &str) -> BTreeSet<String> {
    xml.lines()
        .filter_map(|l| l.trim().strip_prefix("<file href=\"")?.strip_suffix("\"/>").map(str::to_string))
        .collect()
}

#[test]
fn the_documented_package_has_a_readable_directory_and_a_manifest_of_every_file() {
    let dir = scratch("documented");
    let www = page_folder(&dir);
    let zip = dir.join("crossing-scorm.zip");
    let link = documented_link();
    let printed = run(
        env!("CARGO_BIN_EXE_flockpath"),
        &["scorm", "--link", &link, "--www", &www.to_string_lossy(), "--out", &zip.to_string_lossy()],
    );
    assert!(printed.contains("SCORM 1.2, 11 files"), "{printed}");

    // Python's zipfile: the listing (central directory) and a CRC check of every member.
    let zip_arg = zip.to_string_lossy().into_owned();
    let python_list = run("python3", &["-m", "zipfile", "-l", &zip_arg]);
    let tested = run("python3", &["-m", "zipfile", "-t", &zip_arg]);
    assert!(tested.contains("Done testing"), "{tested}");
    let python_names: BTreeSet<String> =
        python_list.lines().skip(1).filter_map(|l| l.split_whitespace().next().map(str::to_string)).collect();
    // Info-ZIP's unzip, when the machine has it: the same names, and `-t` finds no error.
    if Command::new("unzip").arg("-v").output().is_ok() {
        let listing = run("unzip", &["-Z1", &zip_arg]);
        let unzip_names: BTreeSet<String> = listing.lines().map(str::to_string).collect();
        assert_eq!(unzip_names, python_names);
        assert!(run("unzip", &["-t", &zip_arg]).contains("No errors detected"));
    }

    let expected: BTreeSet<String> = [
        "imsmanifest.xml",
        "activity.html",
        "activity.json",
        "embed.html",
        "js/embed/main.js",
        "js/flock-path.js",
        "js/core/boot.js",
        "js/core/scorm.js",
        "js/core/strings/zh.js",
        "pkg/flockpath.js",
        "pkg/flockpath_bg.wasm",
    ]
    .into_iter()
    .map(str::to_string)
    .collect();
    assert_eq!(python_names, expected, "the embed view's files, not the playground's");

    // The manifest names every file of the zip (itself aside) and no other.
    let extracted = dir.join("unpacked");
    run("python3", &["-m", "zipfile", "-e", &zip_arg, &extracted.to_string_lossy()]);
    let manifest = std::fs::read_to_string(extracted.join("imsmanifest.xml")).expect("manifest");
    let mut listed = manifest_files(&manifest);
    listed.insert("imsmanifest.xml".to_string());
    assert_eq!(listed, python_names);
    assert!(manifest.contains("<schemaversion>1.2</schemaversion>"), "{manifest}");
    assert!(manifest.contains(r#"adlcp:scormtype="sco" href="activity.html""#), "{manifest}");
    // The stored bytes are the file's bytes.
    let wasm = std::fs::read(extracted.join("pkg/flockpath_bg.wasm")).expect("wasm");
    assert_eq!(wasm, std::fs::read(www.join("pkg/flockpath_bg.wasm")).expect("source wasm"));
    // The launch page opens the embed view on the link's scene and classroom options.
    let launch = std::fs::read_to_string(extracted.join("activity.html")).expect("launch page");
    assert!(launch.contains("url=embed.html#s=2."), "{launch}");
    assert!(launch.contains("&amp;lock=obstacles,goals,groups,paths&amp;scorm=1"), "{launch}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_same_activity_gives_the_same_bytes() {
    let files = vec![
        ("embed.html".to_string(), b"e".to_vec()),
        ("js/embed/main.js".to_string(), b"m".to_vec()),
        ("js/flock-path.js".to_string(), b"f".to_vec()),
        ("pkg/flockpath.js".to_string(), b"g".to_vec()),
        ("pkg/flockpath_bg.wasm".to_string(), vec![0, 97, 115, 109]),
    ];
    let link = documented_link();
    let a = scorm_package(&link, &files).expect("a package");
    let mut reversed = files.clone();
    reversed.reverse();
    let b = scorm_package(&link, &reversed).expect("a package");
    assert_eq!(a.zip, b.zip, "fixed timestamps and sorted files: the bytes follow the inputs only");
}

#[test]
fn links_without_something_to_grade_are_refused() {
    let files: Vec<(String, Vec<u8>)> = Vec::new();
    assert!(matches!(scorm_package("pillars", &files), Err(ScormError::NoActivity)));
    let mut scene = (flockpath::presets::find("pillars").expect("preset").build)();
    scene.activity = Some(serde_json::from_str(r#"{"prompt": "Just look."}"#).expect("activity"));
    let json = flockpath::scene_to_json(&scene);
    assert!(matches!(scorm_package(&json, &files), Err(ScormError::NoCheck)));
    scene.activity = Some(
        serde_json::from_str(
            r#"{"prompt": "P", "check": {"steps": 60, "conditions": [
                {"metric": "arrived_share", "op": ">=", "value": 0.5, "pane": 1}]}}"#,
        )
        .expect("activity"),
    );
    let json = flockpath::scene_to_json(&scene);
    assert!(matches!(scorm_package(&json, &files), Err(ScormError::CompareOnly)));
    let e = scorm_package(&documented_link(), &files).expect_err("no page files");
    assert!(matches!(&e, ScormError::MissingFile(name) if name == "embed.html"), "{e}");
}

#[test]
fn the_cli_names_what_is_missing() {
    let dir = scratch("refused");
    let out = Command::new(env!("CARGO_BIN_EXE_flockpath"))
        .args(["scorm", "--link", "pillars", "--www", &dir.to_string_lossy(), "--out"])
        .arg(dir.join("x.zip"))
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("has no activity"), "{err}");
    assert!(!dir.join("x.zip").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
