//! Delimited text ↔ fields: what the list editor pastes from and copies to a spreadsheet.
//!
//! **Reading** picks the separator from the text: a tab when there is one (what spreadsheets put
//! on the clipboard), else a semicolon (the CSV of spreadsheets set to a comma decimal
//! separator), else a comma. A field may be quoted as in RFC 4180 (`"a, b"`, `""` for a quote
//! inside; a quoted field may span lines), which is how spreadsheets copy a text holding a tab or
//! a line break. Windows line ends are read as line ends; the empty lines at the end are dropped.
//! Written here rather than with the `csv` crate: the separator is guessed from the text, the
//! quoting is the small part of RFC 4180 spreadsheets use, and the editor gains no dependency.
//!
//! **Writing** ([`format`]) gives TSV: fields joined by tabs, lines by `\n`; a field holding a
//! tab, a line break or a quote (or starting with a quote) is quoted, so [`parse`] reads back the
//! same fields.
//!
//! **Numbers** use `.` as the decimal point. [`format_number`] writes the shortest text that
//! reads back as the same `f64` (bit for bit), so nothing is rounded when shown or copied.

use super::errors::{CellError, Expected};

/// The separator of a delimited text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Separator {
    /// `\t` (spreadsheets' clipboard, TSV).
    Tab,
    /// `;` (CSV where the comma is the decimal separator).
    Semicolon,
    /// `,` (CSV).
    Comma,
}

impl Separator {
    /// The separator of `text`: a tab if it has one, else a semicolon, else a comma.
    pub fn of(text: &str) -> Self {
        if text.contains('\t') {
            Separator::Tab
        } else if text.contains(';') {
            Separator::Semicolon
        } else {
            Separator::Comma
        }
    }

    fn char(self) -> char {
        match self {
            Separator::Tab => '\t',
            Separator::Semicolon => ';',
            Separator::Comma => ',',
        }
    }
}

/// The lines of `text`, each its fields (separator from [`Separator::of`]).
pub fn parse(text: &str) -> Vec<Vec<String>> {
    parse_with(text, Separator::of(text))
}

/// The lines of `text`, each its fields, split at `separator`.
pub fn parse_with(text: &str, separator: Separator) -> Vec<Vec<String>> {
    let sep = separator.char();
    // Each line with whether it is blank (one empty, unquoted field).
    let mut lines: Vec<(Vec<String>, bool)> = Vec::new();
    let mut line: Vec<String> = Vec::new();
    let mut field = String::new();
    let mut quoted_on_line = false;
    let mut at_field_start = true;
    let mut chars = text.chars().peekable();
    let mut end_line = |line: &mut Vec<String>, field: &mut String, quoted: bool| {
        line.push(std::mem::take(field));
        let blank = !quoted && line.len() == 1 && line[0].trim().is_empty();
        lines.push((std::mem::take(line), blank));
    };
    while let Some(c) = chars.next() {
        if at_field_start && c == '"' {
            quoted_on_line = true;
            at_field_start = false;
            // A quoted field: up to the closing quote; `""` is a quote.
            while let Some(q) = chars.next() {
                match q {
                    '"' if chars.peek() == Some(&'"') => {
                        chars.next();
                        field.push('"');
                    }
                    '"' => break,
                    // A Windows line end inside quotes is a line break.
                    '\r' if chars.peek() == Some(&'\n') => {}
                    q => field.push(q),
                }
            }
            continue;
        }
        at_field_start = false;
        match c {
            c if c == sep => {
                line.push(std::mem::take(&mut field));
                at_field_start = true;
            }
            '\r' if chars.peek() == Some(&'\n') => {}
            '\n' => {
                end_line(&mut line, &mut field, quoted_on_line);
                quoted_on_line = false;
                at_field_start = true;
            }
            c => field.push(c),
        }
    }
    if !field.is_empty() || !line.is_empty() || quoted_on_line {
        end_line(&mut line, &mut field, quoted_on_line);
    }
    // A text ending with line breaks has no empty rows after its last line.
    while lines.last().is_some_and(|(_, blank)| *blank) {
        lines.pop();
    }
    lines.into_iter().map(|(fields, _)| fields).collect()
}

/// Tab-separated text of `lines` (fields quoted when they must be, see the module doc).
pub fn format(lines: &[Vec<String>]) -> String {
    let mut out = String::new();
    for line in lines {
        for (k, field) in line.iter().enumerate() {
            if k > 0 {
                out.push('\t');
            }
            if field.contains(['\t', '\n', '\r', '"']) {
                out.push('"');
                out.push_str(&field.replace('"', "\"\""));
                out.push('"');
            } else {
                out.push_str(field);
            }
        }
        out.push('\n');
    }
    out
}

/// The shortest text that reads back as `x` bit for bit (`0.5`, `-0`, `1e-7`, `inf`, `NaN`):
/// Rust's shortest round-trip digits, without a trailing `.0`.
pub fn format_number(x: f64) -> String {
    let s = format!("{x:?}");
    match s.strip_suffix(".0") {
        Some(whole) => whole.to_string(),
        None => s,
    }
}

/// A number written with `.` as the decimal point (`1.5`, `-2e-3`, `inf`, `NaN`; spaces around it
/// are ignored). The error says why in a few words.
pub fn parse_number(text: &str) -> Result<f64, CellError> {
    let t = text.trim();
    if t.is_empty() {
        return Err(CellError::Empty(Expected::Number));
    }
    t.parse::<f64>().map_err(|_| {
        let text = t.to_string();
        if t.contains(',') && t.replace(',', ".").parse::<f64>().is_ok() {
            CellError::DecimalComma { text }
        } else {
            CellError::Not {
                text,
                expected: Expected::Number,
            }
        }
    })
}

/// A whole number (`3`, `-12`; also `3.0` or `1e3`, which are whole).
pub fn parse_integer(text: &str) -> Result<i64, CellError> {
    let t = text.trim();
    if t.is_empty() {
        return Err(CellError::Empty(Expected::WholeNumber));
    }
    if let Ok(i) = t.parse::<i64>() {
        return Ok(i);
    }
    match t.parse::<f64>() {
        // Exactly representable whole numbers only (|x| < 2^53).
        Ok(x) if x.fract() == 0.0 && x.abs() < 9.007_199_254_740_992e15 => Ok(x as i64),
        _ => Err(CellError::Not {
            text: t.to_string(),
            expected: Expected::WholeNumber,
        }),
    }
}

/// `true` or `false` (any case, as spreadsheets write `TRUE`).
pub fn parse_boolean(text: &str) -> Result<bool, CellError> {
    let t = text.trim();
    if t.eq_ignore_ascii_case("true") {
        Ok(true)
    } else if t.eq_ignore_ascii_case("false") {
        Ok(false)
    } else {
        Err(CellError::Not {
            text: t.to_string(),
            expected: Expected::Boolean,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fields(lines: &[&[&str]]) -> Vec<Vec<String>> {
        lines
            .iter()
            .map(|l| l.iter().map(|f| f.to_string()).collect())
            .collect()
    }

    #[test]
    fn tabs_win_then_semicolons_then_commas() {
        assert_eq!(
            parse("1\t2,5\n3\t4\n"),
            fields(&[&["1", "2,5"], &["3", "4"]])
        );
        assert_eq!(parse("1,5;2\r\n3;4"), fields(&[&["1,5", "2"], &["3", "4"]]));
        assert_eq!(
            parse("1, 2,3\n4,5,6"),
            fields(&[&["1", " 2", "3"], &["4", "5", "6"]])
        );
        assert_eq!(Separator::of("a b"), Separator::Comma);
    }

    #[test]
    fn one_column_and_trailing_line_breaks() {
        assert_eq!(parse("0.5\n0.25\n\n\n"), fields(&[&["0.5"], &["0.25"]]));
        assert_eq!(parse(""), Vec::<Vec<String>>::new());
        assert_eq!(parse("\n"), Vec::<Vec<String>>::new());
        // An empty line in the middle is a row with one empty field.
        assert_eq!(parse("1\n\n2"), fields(&[&["1"], &[""], &["2"]]));
    }

    #[test]
    fn quoted_fields_hold_separators_quotes_and_line_breaks() {
        assert_eq!(
            parse("\"a\tb\"\t\"say \"\"hi\"\"\"\n\"two\nlines\"\tx\n"),
            fields(&[&["a\tb", "say \"hi\""], &["two\nlines", "x"]])
        );
        assert_eq!(parse("\"\""), fields(&[&[""]]));
        assert_eq!(parse("\"a,b\",c"), fields(&[&["a,b", "c"]]));
    }

    #[test]
    fn written_tsv_reads_back_as_the_same_fields() {
        let lines = fields(&[
            &["0.1", "-0", "1e-7"],
            &["text with\ttab", "\"quoted\"", "line\nbreak"],
            &["", "plain", "x"],
        ]);
        assert_eq!(parse(&format(&lines)), lines);
    }

    #[test]
    fn numbers_are_written_in_full_and_read_back_bit_for_bit() {
        for x in [
            0.0,
            -0.0,
            0.1,
            1.0 / 3.0,
            0.401_791_393_756_866_46,
            -2.5e-300,
            1e21,
            123_456_789.123_456_78,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            let text = format_number(x);
            let back = parse_number(&text).unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{x:?} → {text} → {back:?}");
        }
        assert_eq!(format_number(1.0), "1");
        assert_eq!(format_number(0.5), "0.5");
        assert_eq!(format_number(-0.0), "-0");
        assert_eq!(format_number(0.30000000000000004), "0.30000000000000004");
        assert!(parse_number(&format_number(f64::NAN)).unwrap().is_nan());
    }

    #[test]
    fn bad_numbers_say_why() {
        assert!(
            parse_number("1,5")
                .unwrap_err()
                .to_string()
                .contains("'.' as the decimal point")
        );
        assert_eq!(
            parse_number("abc").unwrap_err().to_string(),
            "'abc' is not a number"
        );
        assert_eq!(parse_number("  "), Err(CellError::Empty(Expected::Number)));
        assert_eq!(parse_number(" 2.5 "), Ok(2.5));
        assert_eq!(parse_integer("3"), Ok(3));
        assert_eq!(parse_integer("3.0"), Ok(3));
        assert_eq!(parse_integer("-1e3"), Ok(-1000));
        assert_eq!(
            parse_integer("2.5").unwrap_err().to_string(),
            "'2.5' is not a whole number"
        );
        assert_eq!(parse_boolean("TRUE"), Ok(true));
        assert_eq!(parse_boolean("false"), Ok(false));
        assert!(parse_boolean("yes").is_err());
    }
}
