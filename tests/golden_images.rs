//! Golden images of the renderer: a visual regression fails a test.
//!
//! Each case renders a preset after a fixed number of steps (trails traced every step, one frame
//! at the end: a frame depends on the steps, not on how often it is drawn) and compares it with a
//! PNG in `tests/data/golden/`, pixel by pixel, allowing [`TOLERANCE`] per channel (anti-aliasing
//! may round differently where floating point differs). A failure names how many pixels differ,
//! the box they lie in and the first few, and writes the frame drawn and a difference image to
//! `test-artifacts/golden/`.
//!
//! A change to the picture that is meant (or a simulation change that moves the agents) is
//! accepted by regenerating the images, then looking at them before committing:
//!
//! ```sh
//! FLOCKPATH_BLESS=1 cargo test --test golden_images
//! ```

// PNG reading and writing (the `png` crate) is a native-only dev-dependency.
#![cfg(not(target_arch = "wasm32"))]

use flockpath::render::{Renderer, Theme};
use flockpath::{presets, Scene, World};
use std::fs::File;
use std::io::BufReader;
use std::path::{Path, PathBuf};

/// Largest difference (out of 255) per channel that still counts as the same pixel.
const TOLERANCE: u8 = 8;

/// A golden image: its file stem, the preset, the steps run and the theme.
struct Case {
    name: &'static str,
    build: fn() -> Scene,
    steps: u32,
    theme: Theme,
}

const CASES: [Case; 3] = [
    // The page's default scene, part-way through the pillars.
    Case { name: "pillars-step-300", build: presets::pillars, steps: 300, theme: Theme::Standard },
    // A moving goal: the ring must be a sixth of a turn from where it started, with the crowd.
    Case {
        name: "pso-circle-target-step-600",
        build: presets::pso_circle_target,
        steps: 600,
        theme: Theme::Standard,
    },
    // The projector theme: white field, darker obstacles, thicker trails, bigger agents.
    Case { name: "pillars-projector-step-300", build: presets::pillars, steps: 300, theme: Theme::Projector },
];

/// Canvas px per scene px: a page canvas on an ordinary screen.
const SCALE: f32 = 1.0;

fn blessing() -> bool {
    std::env::var_os("FLOCKPATH_BLESS").is_some()
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The frame of `case` as opaque RGBA: width, height, bytes.
fn render(case: &Case) -> (u32, u32, Vec<u8>) {
    let scene = (case.build)();
    let (w, h) = ((scene.width * SCALE) as u32, (scene.height * SCALE) as u32);
    let mut r = Renderer::new(w, h);
    r.set_theme(case.theme);
    let mut world = World::new(scene).expect("valid preset");
    r.render(&world);
    for _ in 0..case.steps {
        world.step();
        r.trace_step(&world);
    }
    r.render(&world);
    (w, h, r.pixels().to_vec())
}

fn write_png(path: &Path, w: u32, h: u32, rgba: &[u8]) {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).expect("creates the folder");
    }
    let file = File::create(path).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), w, h);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::High);
    let mut writer = encoder.write_header().expect("PNG header");
    writer.write_image_data(rgba).expect("PNG data");
}

/// The golden image as RGBA, or `None` when the file does not exist.
fn read_png(path: &Path) -> Option<(u32, u32, Vec<u8>)> {
    let file = File::open(path).ok()?;
    let mut reader = png::Decoder::new(BufReader::new(file)).read_info().expect("a PNG file");
    let mut buf = vec![0; reader.output_buffer_size().expect("a sane size")];
    let info = reader.next_frame(&mut buf).expect("PNG data");
    assert_eq!(
        (info.color_type, info.bit_depth),
        (png::ColorType::Rgba, png::BitDepth::Eight),
        "{}: expected 8-bit RGBA (regenerate it with FLOCKPATH_BLESS=1)",
        path.display()
    );
    buf.truncate(info.buffer_size());
    Some((info.width, info.height, buf))
}

/// Compares one case with its golden image; `Err` says what differs and where to look.
fn check(case: &Case) -> Result<String, String> {
    let golden = root().join("tests/data/golden").join(format!("{}.png", case.name));
    let (w, h, actual) = render(case);
    if blessing() {
        write_png(&golden, w, h, &actual);
        return Ok(format!("{}: blessed {} ({w}×{h})", case.name, golden.display()));
    }
    let artifacts = root().join("test-artifacts/golden");
    let actual_path = artifacts.join(format!("{}.actual.png", case.name));
    let Some((gw, gh, expected)) = read_png(&golden) else {
        write_png(&actual_path, w, h, &actual);
        return Err(format!(
            "{}: no golden image at {}; the frame drawn is at {}; create it with FLOCKPATH_BLESS=1 cargo test --test golden_images",
            case.name,
            golden.display(),
            actual_path.display()
        ));
    };
    if (gw, gh) != (w, h) {
        write_png(&actual_path, w, h, &actual);
        return Err(format!(
            "{}: the frame is {w}×{h}, the golden image {gw}×{gh}; the frame drawn is at {}",
            case.name,
            actual_path.display()
        ));
    }
    let mut diff = vec![0u8; actual.len()];
    let mut differing = Vec::new();
    let mut worst = 0u8;
    for (i, (a, e)) in actual.chunks_exact(4).zip(expected.chunks_exact(4)).enumerate() {
        let d = a.iter().zip(e).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0);
        worst = worst.max(d);
        let grey = e[..3].iter().map(|&c| u32::from(c)).sum::<u32>() / 3;
        // The difference image: the golden image faded to light grey, differing pixels red.
        let faded = (192 + grey / 4) as u8;
        let px = if d > TOLERANCE { [255, 0, 0, 255] } else { [faded, faded, faded, 255] };
        diff[i * 4..i * 4 + 4].copy_from_slice(&px);
        if d > TOLERANCE {
            differing.push(((i as u32 % w), (i as u32 / w), e[..3].to_vec(), a[..3].to_vec()));
        }
    }
    if differing.is_empty() {
        return Ok(format!(
            "{}: {w}×{h}, largest channel difference {worst} (tolerance {TOLERANCE})",
            case.name
        ));
    }
    write_png(&actual_path, w, h, &actual);
    let diff_path = artifacts.join(format!("{}.diff.png", case.name));
    write_png(&diff_path, w, h, &diff);
    let (x0, x1) = differing.iter().fold((u32::MAX, 0), |(lo, hi), d| (lo.min(d.0), hi.max(d.0)));
    let (y0, y1) = differing.iter().fold((u32::MAX, 0), |(lo, hi), d| (lo.min(d.1), hi.max(d.1)));
    let first: Vec<String> =
        differing.iter().take(8).map(|(x, y, e, a)| format!("({x}, {y}) golden {e:?} drawn {a:?}")).collect();
    Err(format!(
        "{}: {} of {} pixels differ by more than {TOLERANCE} (largest {worst}), within x {x0}…{x1}, y {y0}…{y1}; first: {}.\n  golden:     {}\n  drawn:      {}\n  difference: {} (differing pixels red)\n  If the change is meant, regenerate with FLOCKPATH_BLESS=1 cargo test --test golden_images and look at the images before committing.",
        case.name,
        differing.len(),
        w * h,
        first.join("; "),
        golden.display(),
        actual_path.display(),
        diff_path.display()
    ))
}

#[test]
fn frames_match_their_golden_images() {
    let mut failures = Vec::new();
    for case in &CASES {
        match check(case) {
            Ok(line) => println!("{line}"),
            Err(message) => failures.push(message),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The comparison can fail: a frame one step later differs from the golden image beyond the
/// tolerance (else the images would prove nothing).
#[test]
fn a_frame_one_step_off_does_not_match() {
    if blessing() {
        return;
    }
    let case = &CASES[0];
    let Some((_, _, expected)) =
        read_png(&root().join("tests/data/golden").join(format!("{}.png", case.name)))
    else {
        panic!("no golden image for {} (FLOCKPATH_BLESS=1 cargo test --test golden_images)", case.name);
    };
    let later = Case { steps: case.steps + 1, ..*case };
    let (_, _, actual) = render(&later);
    let differing = actual
        .chunks_exact(4)
        .zip(expected.chunks_exact(4))
        .filter(|(a, e)| a.iter().zip(*e).any(|(x, y)| x.abs_diff(*y) > TOLERANCE))
        .count();
    println!("{} one step later: {differing} pixels differ", case.name);
    assert!(differing > 50, "only {differing} pixels differ one step later");
}
