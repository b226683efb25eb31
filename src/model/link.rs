//! Reading a link's options (`index.html#s=…&lock=goals`, a bare fragment, or its text): the one
//! parser of the core, with the page's rules (www/js/core/fragment.js): options are `key=value`
//! parts of what follows the last `#` (the whole input when it has none), split at `&`; the first
//! of a repeated key wins; a value is raw until the option's reader decodes it.

use std::borrow::Cow;

/// What follows the last `#` of `input`, or all of it.
pub fn fragment(input: &str) -> &str {
    input.rsplit_once('#').map_or(input, |(_, f)| f)
}

/// The raw value of option `key`, the first when repeated, or `None`.
pub fn option<'a>(input: &'a str, key: &str) -> Option<&'a str> {
    fragment(input)
        .split('&')
        .find_map(|part| part.split_once('=').filter(|(k, _)| *k == key).map(|(_, v)| v))
}

/// The value of option `key`, or the fragment itself when the link has no such option (a pasted
/// `s=` value alone, `2.PU_R…`).
pub fn option_or_fragment<'a>(input: &'a str, key: &str) -> &'a str {
    option(input, key).unwrap_or_else(|| fragment(input))
}

/// `%XX` escapes decoded where they spell ASCII (a pasted link may carry `%2C` for a comma);
/// anything else stays as written, and the option's parser names it.
pub fn percent_decoded(value: &str) -> Cow<'_, str> {
    if !value.contains('%') {
        return value.into();
    }
    let bytes = value.as_bytes();
    let mut out = String::with_capacity(value.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = value.get(i + 1..i + 3).and_then(|h| u8::from_str_radix(h, 16).ok()).filter(u8::is_ascii);
        match hex {
            Some(byte) if bytes[i] == b'%' => {
                out.push(char::from(byte));
                i += 3;
            }
            _ => {
                let c = value[i..].chars().next().unwrap_or('\u{fffd}');
                out.push(c);
                i += c.len_utf8();
            }
        }
    }
    out.into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_are_read_as_the_page_reads_them() {
        assert_eq!(option("x#s=2.a&lock=goals&lock=paths", "lock"), Some("goals"), "the first wins");
        assert_eq!(option("2.abc", "lock"), None);
        assert_eq!(option("https://a.org/p?x=1#c=boids~pso&s=2.x", "c"), Some("boids~pso"));
        assert_eq!(option_or_fragment("https://a.org/index.html#s=2.xyz&lock=goals", "s"), "2.xyz");
        assert_eq!(option_or_fragment("2.xyz", "s"), "2.xyz", "a bare value is the fragment");
        assert_eq!(option_or_fragment("a#b#s=1", "s"), "1", "after the last #");
    }

    #[test]
    fn link_options_are_percent_decoded_where_they_spell_ascii() {
        assert_eq!(percent_decoded("obstacles%2Cgoals%2cpaths"), "obstacles,goals,paths");
        assert_eq!(percent_decoded("é%2Cü%zz%4%C3%A9%"), "é,ü%zz%4%C3%A9%");
    }
}
