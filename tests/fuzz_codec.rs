//! A stable-Rust mutation fuzzer for the scene decoder: `scene_from_any` must answer `Ok` or a
//! readable `Err` for anything a user can paste, and never panic.
//!
//! Inputs start from the corpus in `tests/data/fuzz-corpus/` (fragments of every released
//! version, preset JSON, tricky cases) and are mutated with byte flips, truncations, insertions,
//! deletions and splices. Half of the mutations act on the decompressed payload and repack it, so
//! the JSON and compact-scene parsers and the validator see damaged input too, not only inflate.
//! The generator is the crate's seeded `Rng`, so a failure names a reproducible iteration.
//!
//! `FLOCKPATH_FUZZ_ITERS=1000000 cargo test --release --test fuzz_codec` runs longer locally
//! (default 20,000 iterations); `FLOCKPATH_FUZZ_SEED` picks another sequence.
//!
//! Cost, not only panics: the corpus holds valid-but-expensive scenes (`cost-*`: the dense
//! spawns, packed crowds, huge populations and heavy IGSA planning of issue 12), and every
//! decoded input's work is counted by `flockpath::sim::cost::work` (lattice places the spawn
//! examined, the IGSA segments to plan, the flow fields' memory): an accepted scene must stay within
//! the stated budgets, and every `cost-*` entry must be refused or within them, without timing.

use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use base64::Engine as _;
use flockpath::rng::Rng;
use flockpath::sim::cost::{self, Work, MAX_FLOW_FIELD_BYTES, MAX_PLANNING_SEGMENT_CHECKS};
use flockpath::sim::spawn::MAX_SPAWN_PLACES;
use flockpath::{scene_from_any, PlannerConfig, PlannerKind, Region, Scene, SceneError};
use std::panic::{catch_unwind, AssertUnwindSafe};

const DEFAULT_ITERATIONS: u64 = 20_000;
/// Mutated inputs whose work is counted (each decoded one is spawned).
const DEFAULT_COST_ITERATIONS: u64 = 3_000;

fn corpus_files() -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir("tests/data/fuzz-corpus")
        .expect("the corpus folder exists")
        .flatten()
        .map(|e| e.path())
        .collect();
    files.sort();
    files
}

fn corpus() -> Vec<Vec<u8>> {
    corpus_files().iter().map(|p| std::fs::read(p).expect("corpus file reads")).collect()
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.trim().parse().ok()).unwrap_or(default)
}

/// The decompressed payload of a fragment (`v.payload`), if it has one.
fn unpacked(input: &[u8]) -> Option<(String, Vec<u8>)> {
    let text = std::str::from_utf8(input).ok()?;
    let (version, payload) = text.split_once('.')?;
    let packed = URL_SAFE_NO_PAD.decode(payload.trim()).ok()?;
    let bytes = miniz_oxide::inflate::decompress_to_vec_with_limit(&packed, 1 << 20).ok()?;
    Some((version.to_string(), bytes))
}

fn repacked(version: &str, bytes: &[u8]) -> Vec<u8> {
    let packed = miniz_oxide::deflate::compress_to_vec(bytes, 6);
    format!("{version}.{}", URL_SAFE_NO_PAD.encode(packed)).into_bytes()
}

/// Bytes that tend to matter to the parsers.
const INTERESTING: &[&[u8]] = &[
    b"[",
    b"]",
    b"{",
    b"}",
    b",",
    b"\"",
    b".",
    b"-",
    b"0",
    b"1e39",
    b"-0.0",
    b"NaN",
    b"null",
    b"true",
    b"#s=",
    b"&",
    b"=",
    b"4294967296",
    b"\\u0000",
    b"1.",
    b"2.",
];

fn mutate(rng: &mut Rng, input: &mut Vec<u8>, corpus: &[Vec<u8>]) {
    let rounds = 1 + rng.below(4);
    for _ in 0..rounds {
        let len = input.len() as u32;
        match rng.below(7) {
            0 if len > 0 => {
                let i = rng.below(len) as usize;
                input[i] ^= 1 << rng.below(8);
            }
            1 if len > 0 => input.truncate(rng.below(len) as usize),
            2 => {
                let i = rng.below(len + 1) as usize;
                input.insert(i, rng.next_u32() as u8);
            }
            3 if len > 0 => {
                let i = rng.below(len) as usize;
                let n = (1 + rng.below(8)) as usize;
                input.drain(i..(i + n).min(input.len()));
            }
            4 => {
                let token = INTERESTING[rng.below(INTERESTING.len() as u32) as usize];
                let i = rng.below(len + 1) as usize;
                input.splice(i..i, token.iter().copied());
            }
            5 => {
                // Splice a piece of another corpus entry in.
                let other = &corpus[rng.below(corpus.len() as u32) as usize];
                if !other.is_empty() {
                    let a = rng.below(other.len() as u32) as usize;
                    let b = (a + 1 + rng.below(64) as usize).min(other.len());
                    let i = rng.below(len + 1) as usize;
                    input.splice(i..i, other[a..b].iter().copied());
                }
            }
            _ if len > 1 => {
                // Duplicate a run (repeated structure, longer numbers).
                let a = rng.below(len) as usize;
                let b = (a + 1 + rng.below(16) as usize).min(input.len());
                let run: Vec<u8> = input[a..b].to_vec();
                input.splice(b..b, run);
            }
            _ => input.push(rng.next_u32() as u8),
        }
    }
}

/// A corpus entry picked at random and mutated: half the time its decompressed payload,
/// repacked, so the parsers behind the decompressor see damaged input too.
fn mutated_input(rng: &mut Rng, corpus: &[Vec<u8>]) -> Vec<u8> {
    let base = &corpus[rng.below(corpus.len() as u32) as usize];
    match unpacked(base) {
        Some((version, mut payload)) if rng.below(2) == 0 => {
            mutate(rng, &mut payload, corpus);
            repacked(&version, &payload)
        }
        _ => {
            let mut bytes = base.clone();
            mutate(rng, &mut bytes, corpus);
            bytes
        }
    }
}

#[test]
fn decoding_mutated_input_never_panics() {
    let corpus = corpus();
    assert!(corpus.len() >= 20, "the corpus holds {} entries", corpus.len());
    let iterations = env_number("FLOCKPATH_FUZZ_ITERS", DEFAULT_ITERATIONS);
    let seed = env_number("FLOCKPATH_FUZZ_SEED", 1) as u32;
    let mut rng = Rng::new(seed, 7);
    let (mut accepted, mut refused) = (0u64, 0u64);
    for iteration in 0..iterations {
        let input = mutated_input(&mut rng, &corpus);
        let text = String::from_utf8_lossy(&input).into_owned();
        match catch_unwind(AssertUnwindSafe(|| scene_from_any(&text))) {
            Ok(Ok(_)) => accepted += 1,
            Ok(Err(e)) => {
                assert!(!e.to_string().trim().is_empty(), "iteration {iteration}: empty message");
                refused += 1;
            }
            Err(_) => panic!(
                "iteration {iteration} (FLOCKPATH_FUZZ_SEED={seed}): scene_from_any panicked on {:?}",
                text.chars().take(300).collect::<String>()
            ),
        }
    }
    println!("fuzz: {iterations} inputs, {accepted} accepted, {refused} refused with a message");
    assert_eq!(accepted + refused, iterations);
    // Mutations that keep a scene valid exist (a flipped digit in a coordinate); if nothing is
    // ever accepted the mutator only exercises the first error path.
    assert!(accepted > 0, "no mutated input decoded: the fuzzer is not reaching the parsers");
}

#[test]
fn every_corpus_entry_decodes_or_is_refused_without_panicking() {
    for (i, entry) in corpus().iter().enumerate() {
        let text = String::from_utf8_lossy(entry).into_owned();
        let result = catch_unwind(AssertUnwindSafe(|| scene_from_any(&text)));
        assert!(result.is_ok(), "corpus entry {i} panicked");
    }
}

/// Checks the counted work of a decoded scene against the budgets: `Ok` when it is within them
/// (or refused with a message), `Err` naming the budget it breaks.
fn within_budget(scene: &Scene) -> Result<Option<Work>, String> {
    let work = match cost::work(scene) {
        Ok(work) => work,
        Err(e) => {
            assert!(!e.to_string().trim().is_empty(), "a refusal without a message");
            return Ok(None);
        }
    };
    let agents = scene.agent_count();
    let groups = scene.groups.iter().filter(|g| g.count > 0).count() as u64;
    // O(N) placement: the first lattices hold about as many places as agents; refinements
    // around obstacles grow geometrically (0.9 in spacing) up to the per-group cap.
    let spawn_bound = 8 * agents + groups * 6 * MAX_SPAWN_PLACES;
    if work.spawn_places > spawn_bound {
        return Err(format!("spawn examined {} places, over {spawn_bound}", work.spawn_places));
    }
    if work.flow_fields.bytes > MAX_FLOW_FIELD_BYTES {
        return Err(format!("flow fields keep {} bytes", work.flow_fields.bytes));
    }
    if work.planning_segment_checks > MAX_PLANNING_SEGMENT_CHECKS {
        return Err(format!("planning checks {} segments", work.planning_segment_checks));
    }
    Ok(Some(work))
}

#[test]
fn every_expensive_corpus_scene_is_refused_or_within_the_budgets() {
    let mut expensive = 0;
    for path in corpus_files() {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        if !name.starts_with("cost-") {
            continue;
        }
        expensive += 1;
        let text = std::fs::read_to_string(&path).expect("reads");
        let scene = scene_from_any(&text).unwrap_or_else(|e| panic!("{name} is a valid scene: {e}"));
        let verdict = within_budget(&scene).unwrap_or_else(|why| panic!("{name}: {why}"));
        println!("{name}: {}", verdict.map_or("refused".to_string(), |w| format!("{w:?}")));
    }
    assert!(expensive >= 8, "the corpus holds {expensive} expensive scenes");
}

#[test]
fn the_expensive_scenes_of_the_issue_are_refused_with_the_limit_named() {
    let refusal = |file: &str| {
        let text = std::fs::read_to_string(format!("tests/data/fuzz-corpus/{file}")).expect("reads");
        let scene = scene_from_any(&text).expect("valid");
        cost::work(&scene).expect_err(file)
    };
    for (file, words) in [
        ("cost-crash-200k-in-120x200.json", &["200000 agents", "at most 416", "density limit"][..]),
        ("cost-firefly-1000-in-10x10.json", &["1000 agents", "density limit"]),
        ("cost-pso-2000-in-50x100.json", &["2000 agents", "density limit"]),
        ("cost-forces-10x10-circle.json", &["1000 agents", "at most 0", "density limit"]),
        ("cost-igsa-max-params-three-groups.json", &["igsa", "16200000 path segments"]),
    ] {
        let e = refusal(file);
        let text = e.to_string();
        assert!(matches!(e, SceneError::Blocked(_) | SceneError::TooCostly(_)), "{file}: {e:?}");
        for w in words {
            assert!(text.contains(w), "{file}: {w:?} missing from {text:?}");
        }
    }
    // Issue 24: refused once by the step-time estimate (200,000 fireflies, "180 ms limit"), which
    // is gone now that the page steps in a worker: it loads.
    let text =
        std::fs::read_to_string("tests/data/fuzz-corpus/cost-firefly-200k-spread.json").expect("reads");
    let work = cost::work(&scene_from_any(&text).expect("valid")).expect("accepted");
    assert_eq!(work.flow_fields.fields, 0);
}

#[test]
fn mutated_scenes_that_decode_stay_within_the_work_budgets() {
    let corpus = corpus();
    let iterations = env_number("FLOCKPATH_FUZZ_COST_ITERS", DEFAULT_COST_ITERATIONS);
    let seed = env_number("FLOCKPATH_FUZZ_SEED", 1) as u32;
    let mut rng = Rng::new(seed, 8);
    let (mut counted, mut refused) = (0u64, 0u64);
    for iteration in 0..iterations {
        let input = mutated_input(&mut rng, &corpus);
        let Ok(scene) = scene_from_any(&String::from_utf8_lossy(&input)) else { continue };
        match within_budget(&scene) {
            Ok(Some(_)) => counted += 1,
            Ok(None) => refused += 1,
            Err(why) => panic!("iteration {iteration} (FLOCKPATH_FUZZ_SEED={seed}): accepted, but {why}"),
        }
    }
    println!("cost fuzz: {iterations} inputs, {counted} accepted within the budgets, {refused} refused");
    assert!(counted > 0, "no mutated scene was accepted: the cost check is not reached");
}

/// Scales what drives the work of a decoded scene: counts (log-uniform up to the maximum),
/// spawn regions, the world, planners and IGSA's optimizer size.
fn scale_work(rng: &mut Rng, scene: &mut Scene) {
    if rng.below(4) == 0 {
        let k = rng.range(0.2, 20.0);
        scene.width = (scene.width * k).clamp(10.0, 20_000.0);
        scene.height = (scene.height * k).clamp(10.0, 20_000.0);
    }
    let (w, h) = (scene.width, scene.height);
    for g in &mut scene.groups {
        g.count = rng.range(0.0, 200_000f32.ln()).exp() as u32;
        if rng.below(2) == 0 {
            let (x0, y0) = (rng.range(0.0, w), rng.range(0.0, h));
            g.spawn = Region { min: [x0, y0], max: [rng.range(x0, w), rng.range(y0, h)] };
        }
        g.spawn.min = [g.spawn.min[0].min(w), g.spawn.min[1].min(h)];
        g.spawn.max = [g.spawn.max[0].min(w), g.spawn.max[1].min(h)];
        if rng.below(3) == 0 {
            g.agent_radius = rng.range(0.5, 20.0);
        }
        if rng.below(2) == 0 {
            let kind = PlannerKind::ALL[rng.below(PlannerKind::ALL.len() as u32) as usize];
            g.planner = kind.default_config();
        }
        if let PlannerConfig::Igsa(p) = &mut g.planner {
            (p.population, p.iterations) = (5 + rng.below(196), 10 * (1 + rng.below(300)));
            p.waypoint_count = 1 + rng.below(8);
        }
    }
    scene.goals.retain(|goal| goal.position[0] <= w && goal.position[1] <= h);
    for g in &mut scene.groups {
        g.goal = g.goal.filter(|&k| (k as usize) < scene.goals.len());
    }
}

#[test]
fn scenes_scaled_towards_the_limits_are_refused_or_within_the_work_budgets() {
    let scenes: Vec<Scene> =
        corpus().iter().filter_map(|entry| scene_from_any(&String::from_utf8_lossy(entry)).ok()).collect();
    let iterations =
        env_number("FLOCKPATH_FUZZ_SCALE_ITERS", if cfg!(debug_assertions) { 150 } else { 1_000 });
    let mut rng = Rng::new(env_number("FLOCKPATH_FUZZ_SEED", 1) as u32, 9);
    let (mut counted, mut refused) = (0u64, 0u64);
    for iteration in 0..iterations {
        let mut scene = scenes[rng.below(scenes.len() as u32) as usize].clone();
        scale_work(&mut rng, &mut scene);
        match within_budget(&scene) {
            Ok(Some(_)) => counted += 1,
            Ok(None) => refused += 1,
            Err(why) => panic!("scaled scene {iteration}: accepted, but {why}"),
        }
    }
    println!("scaled: {iterations} scenes, {counted} accepted within the budgets, {refused} refused");
    assert!(counted > 0 && refused > 0, "{counted} accepted, {refused} refused: the limits are not reached");
}
