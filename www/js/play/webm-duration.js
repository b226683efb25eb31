// Gives a recorded WebM its duration. Chromium's MediaRecorder writes the Segment's Info without a
// Duration element (it streams and does not know the end), so players show no length and cannot
// seek. Once the recording stopped, the length is known: this writes it into Info. WebM is EBML
// (Matroska): elements are an ID and a size, both variable-length integers, then the payload.

const EBML_HEADER = 0x1a45dfa3;
const SEGMENT = 0x18538067;
const INFO = 0x1549a966;
const TIMECODE_SCALE = 0x2ad7b1;
const DURATION = 0x4489;
/** Matroska's default TimecodeScale: durations count in this many nanoseconds (1 ms). */
const DEFAULT_TIMECODE_SCALE = 1_000_000;

/** An element ID at `at` (its marker bits kept, as IDs are written): `{ value, length }`. */
function readId(bytes, at) {
  const first = bytes[at];
  let length = 1;
  while (length <= 4 && !(first & (0x80 >> (length - 1)))) length += 1;
  if (length > 4 || at + length > bytes.length) return null;
  let value = 0;
  for (let i = 0; i < length; i += 1) value = value * 256 + bytes[at + i];
  return { value, length };
}

/** A size at `at` (marker bit removed): `{ value, length, unknown }` (all ones: unknown size). */
function readSize(bytes, at) {
  const first = bytes[at];
  let length = 1;
  while (length <= 8 && !(first & (0x80 >> (length - 1)))) length += 1;
  if (length > 8 || at + length > bytes.length) return null;
  let value = first & (0xff >> length);
  let allOnes = value === 0xff >> length;
  for (let i = 1; i < length; i += 1) {
    value = value * 256 + bytes[at + i];
    allOnes &&= bytes[at + i] === 0xff;
  }
  return { value, length, unknown: allOnes };
}

/** One element's header at `at`: id, payload start and size (null if it does not parse). */
function element(bytes, at) {
  const id = readId(bytes, at);
  if (!id) return null;
  const size = readSize(bytes, at + id.length);
  if (!size) return null;
  return { id: id.value, start: at + id.length + size.length, size: size.value, unknown: size.unknown };
}

/** An unsigned integer payload. */
function readUint(bytes, at, size) {
  let value = 0;
  for (let i = 0; i < size; i += 1) value = value * 256 + bytes[at + i];
  return value;
}

/** A size as an 8-byte variable-length integer (room for any Info). */
function sizeBytes(value) {
  const out = new Uint8Array(8);
  out[0] = 0x01;
  let rest = value;
  for (let i = 7; i >= 1; i -= 1) {
    out[i] = rest % 256;
    rest = Math.floor(rest / 256);
  }
  return out;
}

/** The Duration element for `ms` milliseconds in `scale` ns units, as a 64-bit float. */
function durationElement(ms, scale) {
  const out = new Uint8Array(11);
  out.set([0x44, 0x89, 0x88]);
  new DataView(out.buffer).setFloat64(3, (ms * 1_000_000) / scale);
  return out;
}

/**
 * `bytes` (a WebM file) with its Segment Info's Duration set to `ms` milliseconds: written over an
 * existing Duration, else added at the end of Info. Returns the bytes unchanged when they do not
 * parse as WebM (the recording is still saved).
 */
export function withDuration(bytes, ms) {
  const header = element(bytes, 0);
  if (!header || header.id !== EBML_HEADER) return bytes;
  const segment = element(bytes, header.start + header.size);
  if (!segment || segment.id !== SEGMENT) return bytes;
  // Info comes before the first Cluster; Chromium writes it first.
  let at = segment.start;
  let info = null;
  for (let i = 0; i < 8 && at < bytes.length; i += 1) {
    const child = element(bytes, at);
    if (!child || child.unknown) return bytes;
    if (child.id === INFO) {
      info = { ...child, at };
      break;
    }
    at = child.start + child.size;
  }
  if (!info || info.start + info.size > bytes.length) return bytes;
  let scale = DEFAULT_TIMECODE_SCALE;
  for (let p = info.start; p < info.start + info.size; ) {
    const child = element(bytes, p);
    if (!child) return bytes;
    if (child.id === TIMECODE_SCALE) scale = readUint(bytes, child.start, child.size) || scale;
    if (child.id === DURATION && (child.size === 8 || child.size === 4)) {
      const out = bytes.slice();
      const view = new DataView(out.buffer, out.byteOffset + child.start, child.size);
      if (child.size === 8) view.setFloat64(0, (ms * 1_000_000) / scale);
      else view.setFloat32(0, (ms * 1_000_000) / scale);
      return out;
    }
    p = child.start + child.size;
  }
  const duration = durationElement(ms, scale);
  const infoId = bytes.subarray(info.at, info.at + 4);
  const parts = [
    bytes.subarray(0, info.at),
    infoId,
    sizeBytes(info.size + duration.length),
    bytes.subarray(info.start, info.start + info.size),
    duration,
    bytes.subarray(info.start + info.size),
  ];
  const out = new Uint8Array(parts.reduce((n, part) => n + part.length, 0));
  let offset = 0;
  for (const part of parts) {
    out.set(part, offset);
    offset += part.length;
  }
  return out;
}
