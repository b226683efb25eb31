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

use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use base64::Engine as _;
use flockpath::rng::Rng;
use flockpath::scene_from_any;
use std::panic::{catch_unwind, AssertUnwindSafe};

const DEFAULT_ITERATIONS: u64 = 20_000;

fn corpus() -> Vec<Vec<u8>> {
    let mut files: Vec<_> = std::fs::read_dir("tests/data/fuzz-corpus")
        .expect("the corpus folder exists")
        .flatten()
        .map(|e| e.path())
        .collect();
    files.sort();
    files.iter().map(|p| std::fs::read(p).expect("corpus file reads")).collect()
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

#[test]
fn decoding_mutated_input_never_panics() {
    let corpus = corpus();
    assert!(corpus.len() >= 20, "the corpus holds {} entries", corpus.len());
    let iterations = env_number("FLOCKPATH_FUZZ_ITERS", DEFAULT_ITERATIONS);
    let seed = env_number("FLOCKPATH_FUZZ_SEED", 1) as u32;
    let mut rng = Rng::new(seed, 7);
    let (mut accepted, mut refused) = (0u64, 0u64);
    for iteration in 0..iterations {
        let base = &corpus[rng.below(corpus.len() as u32) as usize];
        let input = match unpacked(base) {
            Some((version, mut payload)) if rng.below(2) == 0 => {
                mutate(&mut rng, &mut payload, &corpus);
                repacked(&version, &payload)
            }
            _ => {
                let mut bytes = base.clone();
                mutate(&mut rng, &mut bytes, &corpus);
                bytes
            }
        };
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
