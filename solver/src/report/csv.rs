//! CSV fields as RFC 4180 writes them: the one quoting rule of
//! `contact.csv` and `reactions.csv`, and the numbers of `contact.csv`.

/// `text` as one CSV field: quoted (with doubled quotes) when it holds a
/// comma, a quote or a line break, else as it is.
pub fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

/// `v` in Rust's shortest round-trip form: positional, or with an
/// exponent where that is shorter (below 1e-4 and from 1e15 on).
pub fn num(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e15).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip() {
        for v in [
            0.0,
            -0.0,
            1.0,
            0.49492293187714653,
            -5.551115123125783e-17,
            1e-4,
            3e15,
            -1.5e300,
        ] {
            assert_eq!(num(v).parse::<f64>().unwrap().to_bits(), v.to_bits(), "{v}");
        }
        assert_eq!(num(-5.551115123125783e-17), "-5.551115123125783e-17");
        assert_eq!(num(0.25), "0.25");
    }

    #[test]
    fn fields_with_separators_are_quoted() {
        assert_eq!(field("interface"), "interface");
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("say \"x\""), "\"say \"\"x\"\"\"");
        assert_eq!(field("two\nlines"), "\"two\nlines\"");
        assert_eq!(field("cr\r"), "\"cr\r\"");
        assert_eq!(field(""), "");
    }
}
