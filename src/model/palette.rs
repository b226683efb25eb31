//! The default group colours: the Okabe–Ito palette (Okabe & Ito 2008, "Color Universal
//! Design"), whose eight colours stay distinct for the common forms of colour-vision deficiency
//! (protanopia, deuteranopia, tritanopia) and in greyscale print. Presets use it, a group without
//! a colour gets its first entry, and the page hands the entries to new groups in this order
//! (`www/js/play/app.js` keeps the same list).
//!
//! Order: the darker colours first, since agents are drawn on a light field; yellow (the one with
//! little contrast on it) comes last.

/// Blue, the first group's colour.
pub const BLUE: &str = "#0072b2";
/// Vermillion.
pub const VERMILLION: &str = "#d55e00";
/// Bluish green.
pub const BLUISH_GREEN: &str = "#009e73";
/// Reddish purple.
pub const REDDISH_PURPLE: &str = "#cc79a7";
/// Orange.
pub const ORANGE: &str = "#e69f00";
/// Sky blue.
pub const SKY_BLUE: &str = "#56b4e9";
/// Black.
pub const BLACK: &str = "#000000";
/// Yellow.
pub const YELLOW: &str = "#f0e442";

/// The palette in the order new groups take it.
pub const GROUP_PALETTE: [&str; 8] =
    [BLUE, VERMILLION, BLUISH_GREEN, REDDISH_PURPLE, ORANGE, SKY_BLUE, BLACK, YELLOW];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scene::is_hex_color;

    #[test]
    fn every_entry_is_a_distinct_lowercase_hex_colour() {
        for (i, c) in GROUP_PALETTE.iter().enumerate() {
            assert!(is_hex_color(c) && c.to_lowercase() == *c, "{c}");
            assert!(!GROUP_PALETTE[..i].contains(c), "{c} twice");
        }
    }
}
