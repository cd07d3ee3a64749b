//! Number and list syntax of Mitsuba's XML attributes, reproduced exactly so that a value
//! Mitsuba accepts is accepted here and one it rejects is rejected
//! (`src/core/string.cpp::stof`/`tokenize`, `src/core/parser.cpp` integer/boolean cases).

/// Splits on spaces and commas, dropping empty pieces (Mitsuba's `string::tokenize(s, ", ")`).
/// XML attribute-value normalization has already turned tabs and newlines into spaces.
pub(crate) fn tokenize(s: &str) -> Vec<&str> {
    s.split([' ', ',']).filter(|t| !t.is_empty()).collect()
}

/// A float the way Mitsuba's `string::stof<double>` reads it: leading and trailing spaces or
/// tabs are allowed, one leading `+` is skipped, then the whole rest must be a number
/// (exponents, `inf` and `nan` included, as with fast_float). `None` if malformed.
pub(crate) fn parse_f64(s: &str) -> Option<f64> {
    let t = s.trim_matches([' ', '\t']);
    let t = t.strip_prefix('+').unwrap_or(t);
    // Rust would accept a second sign after the skipped `+`; fast_float does not.
    if t.starts_with('+') {
        return None;
    }
    t.parse::<f64>().ok()
}

/// An integer the way Mitsuba's `<integer>` reads it (`std::from_chars` into int64 after
/// skipping leading whitespace, trailing whitespace allowed): no `+`, no decimal point, no
/// overflow. `None` if malformed.
pub(crate) fn parse_i64(s: &str) -> Option<i64> {
    let t = s.trim_matches(|c: char| c.is_ascii_whitespace());
    if t.starts_with('+') {
        return None;
    }
    t.parse::<i64>().ok()
}

/// `true`/`false`, case-insensitive, nothing else (no trimming: Mitsuba's `string::iequals`).
pub(crate) fn parse_bool(s: &str) -> Option<bool> {
    if s.eq_ignore_ascii_case("true") {
        Some(true)
    } else if s.eq_ignore_ascii_case("false") {
        Some(false)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_follow_stof() {
        assert_eq!(parse_f64(" +1.5e2\t"), Some(150.0));
        assert_eq!(parse_f64(".5"), Some(0.5));
        assert_eq!(parse_f64("+-2"), Some(-2.0));
        assert!(parse_f64("inf").unwrap().is_infinite());
        for bad in ["", "++1", "1,0", "1 2", "abc", "1e", "0x10"] {
            assert_eq!(parse_f64(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn integers_follow_from_chars() {
        assert_eq!(parse_i64(" -42 "), Some(-42));
        for bad in ["+4", "1.0", "4x", "", "99999999999999999999"] {
            assert_eq!(parse_i64(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn tokenize_drops_empty_pieces() {
        assert_eq!(tokenize(" 1, 2 ,,3 "), vec!["1", "2", "3"]);
    }
}
