//! The text boundary check: printed tables and summaries must not hold a number that Rust
//! formatted from a NaN or an infinity (`NaN`, `inf`, `-inf`, `+inf`).
//!
//! A word counts as such a number only where a number could stand: after the start of a
//! line, a space, a sign, `=`, `(`, `[`, `,`, `:` or a quote, and before the end, a space,
//! `,`, `)`, `]`, `;`, `%`, `°`, `×` or a quote. So "information", "infeasible" or a path
//! such as `out/inf/x.svg` are not flagged.

/// Characters that may precede a number in the commands' text output.
fn opens_number(c: char) -> bool {
    c.is_whitespace() || matches!(c, '+' | '-' | '=' | '(' | '[' | ',' | ':' | '"' | '\'')
}

/// Characters that may follow a number in the commands' text output.
fn closes_number(c: char) -> bool {
    c.is_whitespace() || matches!(c, ',' | ')' | ']' | ';' | '%' | '°' | '×' | '"' | '\'')
}

/// The first line (1-based) and word of `text` that is a formatted non-finite number.
pub fn find_non_finite(text: &str) -> Option<(usize, &'static str)> {
    for (n, line) in text.lines().enumerate() {
        for word in ["NaN", "inf"] {
            for (at, _) in line.match_indices(word) {
                let before = line[..at].chars().next_back();
                let after = line[at + word.len()..].chars().next();
                if before.is_none_or(opens_number) && after.is_none_or(closes_number) {
                    return Some((n + 1, word));
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::find_non_finite;

    #[test]
    fn formatted_non_finite_numbers_are_found() {
        for (x, word) in [
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "inf"),
        ] {
            for text in [
                format!("area ratio {x:.4}\n"),
                format!("ok\nexpansion min {x:+.4}  max 0.1\n"),
                format!("rotation up to {:.2}°", x.to_degrees()),
                format!("residual {x:.2e} L"),
                format!("t = {x:.3}  (contact_limit)"),
                format!("[{x}, 1]"),
                format!("{x}"),
            ] {
                assert_eq!(find_non_finite(&text).map(|f| f.1), Some(word), "{text:?}");
            }
        }
        assert_eq!(find_non_finite("a\nb -inf\n"), Some((2, "inf")));
    }

    #[test]
    fn words_and_paths_are_not_numbers() {
        for text in [
            "information about infeasible designs",
            "written to out/inf/frame.svg",
            "design IH28:0.5:1x1:a-b  NaNometer",
            "end contact_limit; min 0.1000 max 0.4142",
            "",
        ] {
            assert_eq!(find_non_finite(text), None, "{text:?}");
        }
    }
}
