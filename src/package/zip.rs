//! A store-only zip writer: the archive format every LMS imports a SCORM package in.
//!
//! Entries are stored, not compressed: the largest file of a package is the wasm, which the
//! server compresses in transit anyway, and a stored archive needs no deflate code beyond the
//! CRC-32 the format asks for. No zip64: each file and the whole archive stay under 4 GiB and
//! 65,535 entries, far above a package's ~3 MB and ~60 files. Every entry carries the same fixed
//! timestamp (1980-01-01 00:00, the format's earliest), so the same files give the same bytes
//! on every machine and in the browser: a package can be compared by its digest.

use crate::model::refusal::{Code, Message, Refusal};
use std::collections::BTreeSet;
use std::fmt;

/// Largest size a stored entry or the archive may reach without zip64 (bytes).
pub const MAX_ZIP_BYTES: u64 = u32::MAX as u64;
/// Most entries an archive may hold without zip64.
pub const MAX_ZIP_ENTRIES: usize = u16::MAX as usize;

const LOCAL_HEADER: u32 = 0x0403_4b50;
const CENTRAL_HEADER: u32 = 0x0201_4b50;
const END_OF_CENTRAL_DIRECTORY: u32 = 0x0605_4b50;
/// Version 1.0: what extracting a stored entry needs.
const VERSION_NEEDED: u16 = 10;
/// General-purpose flag bit 11: the name is UTF-8.
const FLAG_UTF8_NAME: u16 = 1 << 11;
/// Compression method 0: stored.
const METHOD_STORED: u16 = 0;
/// MS-DOS date 1980-01-01 (day 1, month 1, year 0 = 1980); the time is 00:00:00.
const DOS_DATE: u16 = (1 << 5) | 1;

/// Why an entry or an archive cannot be written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ZipError {
    /// A name that is empty, absolute, has `..`, `\` or an empty part, or is over 65,535 bytes.
    BadName(String),
    /// The same name twice.
    Duplicate(String),
    /// The archive would pass 4 GiB or 65,535 entries.
    TooLarge,
}

impl Refusal for ZipError {
    fn message(&self) -> Message {
        match self {
            ZipError::BadName(name) => Message::new(Code::ZipBadName).with("name", name.clone()),
            ZipError::Duplicate(name) => Message::new(Code::ZipDuplicate).with("name", name.clone()),
            ZipError::TooLarge => Message::new(Code::ZipTooLarge)
                .with("bytes", i64::from(u32::MAX))
                .with("entries", MAX_ZIP_ENTRIES as i64),
        }
    }
}

impl fmt::Display for ZipError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.message().fmt(f)
    }
}

impl std::error::Error for ZipError {}

/// The CRC-32 table of the reflected polynomial 0xEDB88320 (zip's, PNG's, gzip's).
const CRC_TABLE: [u32; 256] = {
    let mut table = [0u32; 256];
    let mut n = 0;
    while n < 256 {
        let mut c = n as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 == 1 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
            k += 1;
        }
        table[n] = c;
        n += 1;
    }
    table
};

/// The CRC-32 of `data`, as zip stores it.
pub fn crc32(data: &[u8]) -> u32 {
    let mut crc = u32::MAX;
    for &byte in data {
        crc = CRC_TABLE[((crc ^ u32::from(byte)) & 0xff) as usize] ^ (crc >> 8);
    }
    !crc
}

/// Whether `name` can be an entry's path: relative, `/`-separated, no `..`, `.` or empty parts.
/// (A `..` would let an unpacking LMS write outside the package's folder.)
pub fn is_valid_entry_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= usize::from(u16::MAX)
        && !name.contains('\\')
        && !name.contains('\0')
        && name.split('/').all(|part| !part.is_empty() && part != "." && part != "..")
}

/// One entry's central-directory facts.
struct Entry {
    name: String,
    crc: u32,
    size: u32,
    offset: u32,
}

/// A zip archive being written in memory: [`ZipWriter::add`] each file, then [`ZipWriter::finish`].
#[derive(Default)]
pub struct ZipWriter {
    bytes: Vec<u8>,
    entries: Vec<Entry>,
    names: BTreeSet<String>,
}

fn put16(out: &mut Vec<u8>, v: u16) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn put32(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}

impl ZipWriter {
    /// An empty archive.
    pub fn new() -> Self {
        Self::default()
    }

    /// The entries' names so far, in the order added.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().map(|e| e.name.as_str())
    }

    /// Adds the file `name` (a relative `/`-separated path) holding `data`, stored.
    pub fn add(&mut self, name: &str, data: &[u8]) -> Result<(), ZipError> {
        if !is_valid_entry_name(name) {
            return Err(ZipError::BadName(name.to_string()));
        }
        if self.names.contains(name) {
            return Err(ZipError::Duplicate(name.to_string()));
        }
        // This entry, its central record and the end record must all stay below 4 GiB.
        let needed = self.bytes.len() as u64
            + 30
            + 2 * name.len() as u64
            + data.len() as u64
            + self.entries.iter().map(|e| 46 + e.name.len() as u64).sum::<u64>()
            + 46
            + 22;
        if self.entries.len() >= MAX_ZIP_ENTRIES || needed > MAX_ZIP_BYTES {
            return Err(ZipError::TooLarge);
        }
        let (Ok(offset), Ok(size), Ok(name_len)) =
            (u32::try_from(self.bytes.len()), u32::try_from(data.len()), u16::try_from(name.len()))
        else {
            return Err(ZipError::TooLarge);
        };
        let crc = crc32(data);
        let out = &mut self.bytes;
        put32(out, LOCAL_HEADER);
        put16(out, VERSION_NEEDED);
        put16(out, FLAG_UTF8_NAME);
        put16(out, METHOD_STORED);
        put16(out, 0);
        put16(out, DOS_DATE);
        put32(out, crc);
        put32(out, size);
        put32(out, size);
        put16(out, name_len);
        put16(out, 0);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);
        self.names.insert(name.to_string());
        self.entries.push(Entry { name: name.to_string(), crc, size, offset });
        Ok(())
    }

    /// The archive's bytes: the entries, the central directory and its end record.
    pub fn finish(self) -> Vec<u8> {
        let mut out = self.bytes;
        // `add` kept the whole archive below 4 GiB and 65,535 entries, so these fit.
        let directory_offset = u32::try_from(out.len()).unwrap_or(u32::MAX);
        for e in &self.entries {
            put32(&mut out, CENTRAL_HEADER);
            put16(&mut out, VERSION_NEEDED);
            put16(&mut out, VERSION_NEEDED);
            put16(&mut out, FLAG_UTF8_NAME);
            put16(&mut out, METHOD_STORED);
            put16(&mut out, 0);
            put16(&mut out, DOS_DATE);
            put32(&mut out, e.crc);
            put32(&mut out, e.size);
            put32(&mut out, e.size);
            put16(&mut out, u16::try_from(e.name.len()).unwrap_or(u16::MAX));
            put16(&mut out, 0); // extra field
            put16(&mut out, 0); // comment
            put16(&mut out, 0); // disk number
            put16(&mut out, 0); // internal attributes
            put32(&mut out, 0); // external attributes
            put32(&mut out, e.offset);
            out.extend_from_slice(e.name.as_bytes());
        }
        let directory_size = u32::try_from(out.len()).unwrap_or(u32::MAX) - directory_offset;
        let count = u16::try_from(self.entries.len()).unwrap_or(u16::MAX);
        put32(&mut out, END_OF_CENTRAL_DIRECTORY);
        put16(&mut out, 0); // this disk
        put16(&mut out, 0); // the directory's disk
        put16(&mut out, count);
        put16(&mut out, count);
        put32(&mut out, directory_size);
        put32(&mut out, directory_offset);
        put16(&mut out, 0); // comment length
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_matches_the_standard_check_value() {
        // The check value of CRC-32/ISO-HDLC (zip's): the CRC of the ASCII digits 1…9.
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        assert_eq!(crc32(b""), 0);
    }

    #[test]
    fn names_that_could_escape_the_folder_are_refused() {
        for bad in ["", "/abs", "a/../b", "..", "a//b", "a\\b", "./a", "a/"] {
            assert!(!is_valid_entry_name(bad), "{bad:?}");
            assert_eq!(ZipWriter::new().add(bad, b"x"), Err(ZipError::BadName(bad.to_string())));
        }
        assert!(is_valid_entry_name("js/core/boot.js"));
    }

    #[test]
    fn a_name_is_written_once() {
        let mut zip = ZipWriter::new();
        zip.add("a.txt", b"1").expect("first");
        assert_eq!(zip.add("a.txt", b"2"), Err(ZipError::Duplicate("a.txt".into())));
    }

    #[test]
    fn the_end_record_points_at_the_directory() {
        let mut zip = ZipWriter::new();
        zip.add("a.txt", b"hello").expect("a");
        zip.add("dir/b.bin", &[0, 1, 2]).expect("b");
        let bytes = zip.finish();
        let end = &bytes[bytes.len() - 22..];
        assert_eq!(u32::from_le_bytes([end[0], end[1], end[2], end[3]]), END_OF_CENTRAL_DIRECTORY);
        assert_eq!(u16::from_le_bytes([end[10], end[11]]), 2);
        let size = u32::from_le_bytes([end[12], end[13], end[14], end[15]]) as usize;
        let offset = u32::from_le_bytes([end[16], end[17], end[18], end[19]]) as usize;
        assert_eq!(offset + size, bytes.len() - 22);
        assert_eq!(&bytes[offset..offset + 4], &CENTRAL_HEADER.to_le_bytes());
        // Local headers: 30 bytes + name + data each.
        assert_eq!(offset, (30 + 5 + 5) + (30 + 9 + 3));
    }
}
