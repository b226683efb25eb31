// The URL fragment's options: `#s=<scene>&c=<comparison>&autoplay=1…`, one parser for every page
// and the embed. Values are the raw text; `fragmentValue` percent-decodes one where it can.

/** `key=value` options of a fragment (`#` optional), raw; the first of a repeated key wins. */
export function fragmentOptions(hash = location.hash) {
  const options = {};
  for (const part of hash.replace(/^#/, '').split('&')) {
    const eq = part.indexOf('=');
    if (eq <= 0) continue;
    const key = part.slice(0, eq);
    if (!Object.hasOwn(options, key)) options[key] = part.slice(eq + 1);
  }
  return options;
}

/** A fragment value percent-decoded, or as it is when it is not valid percent-encoding (the core
 * then names what is wrong with it). */
export function decodeValue(value) {
  try {
    return decodeURIComponent(value);
  } catch {
    return value;
  }
}

/** The decoded value of `key` in the fragment, or null when it has none. */
export function fragmentValue(key, hash = location.hash) {
  const options = fragmentOptions(hash);
  return Object.hasOwn(options, key) ? decodeValue(options[key]) : null;
}
