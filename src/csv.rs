//! CSV as RFC 4180 writes it, for every CSV the project writes (metric series, comparison tables,
//! the validation report): a field holding a comma, a quote or a line break (`\n` or `\r`) is
//! quoted, its quotes doubled; any other field is written as it is.

use std::borrow::Cow;

/// `text` as one CSV field.
pub fn field(text: &str) -> Cow<'_, str> {
    if text.contains([',', '"', '\n', '\r']) {
        Cow::Owned(format!("\"{}\"", text.replace('"', "\"\"")))
    } else {
        Cow::Borrowed(text)
    }
}

#[cfg(test)]
mod tests {
    use super::field;

    #[test]
    fn quotes_only_what_needs_it() {
        assert_eq!(field("PSO crowd"), "PSO crowd");
        assert_eq!(field("Boids, seek 2"), "\"Boids, seek 2\"");
        assert_eq!(field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(field("two\nlines"), "\"two\nlines\"");
        assert_eq!(field("carriage\rreturn"), "\"carriage\rreturn\"");
        assert_eq!(field(""), "");
    }
}
