//! The one-line summary of a literal list shown on its node instead of the list itself:
//! `4 points`, `12 numbers, 0 … 1`, `40 × 41 numbers, 0.31 … 0.69`, `40 × 41 numbers, all 0.5`,
//! `3 rows of 2–4 numbers, 0.1 … 7`. Numbers here are rounded to three significant digits (the
//! table shows them in full).

use cnets_engine::Value;

/// The summary of a literal value (a list or a polyline; other values: their type).
pub fn summary(value: &Value) -> String {
    match value {
        Value::Polyline(p) => {
            let closed = if p.closed { ", closed" } else { "" };
            format!("{}{closed}", count(p.points.len(), ("point", "points")))
        }
        Value::List(items) if items.is_empty() => "empty list".to_string(),
        Value::List(items) => table(items)
            .or_else(|| flat(items))
            .unwrap_or_else(|| count(items.len(), ("item", "items"))),
        other => other.type_name(),
    }
}

/// `1 point`, `4 points`: `n` and the noun, singular or plural.
pub fn count(n: usize, (one, many): (&str, &str)) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The name of a value's kind, singular and plural (numbers and integers are counted apart).
fn noun(v: &Value) -> Option<(&'static str, &'static str)> {
    Some(match v {
        Value::Number(_) => ("number", "numbers"),
        Value::Integer(_) => ("integer", "integers"),
        Value::Boolean(_) => ("boolean", "booleans"),
        Value::Text(_) => ("text", "texts"),
        Value::Point(_) => ("point", "points"),
        Value::Vector(_) => ("vector", "vectors"),
        Value::Plane(_) => ("plane", "planes"),
        Value::Polyline(_) => ("polyline", "polylines"),
        Value::Lines(_) => ("set of lines", "sets of lines"),
        Value::QuadMesh(_) => ("quad mesh", "quad meshes"),
        Value::Mesh(_) => ("mesh", "meshes"),
        Value::Record(_) => ("record", "records"),
        Value::Null | Value::List(_) => return None,
    })
}

/// The noun of numbers: integers when all are, else numbers.
fn number_noun(all_integers: bool) -> (&'static str, &'static str) {
    if all_integers {
        ("integer", "integers")
    } else {
        ("number", "numbers")
    }
}

/// A flat list whose items are all of one kind (numbers and integers count as numbers).
fn flat(items: &[Value]) -> Option<String> {
    let numbers: Option<Vec<f64>> = items.iter().map(Value::as_f64).collect();
    if let Some(numbers) = numbers {
        let all_integers = items.iter().all(|v| matches!(v, Value::Integer(_)));
        let noun = number_noun(all_integers);
        return Some(with_range(count(numbers.len(), noun), &numbers));
    }
    let first = noun(&items[0])?;
    if !items.iter().all(|v| noun(v) == Some(first)) {
        return None;
    }
    let mut s = count(items.len(), first);
    if first.0 == "boolean" {
        let on = items
            .iter()
            .filter(|v| matches!(v, Value::Boolean(true)))
            .count();
        s.push_str(&format!(" ({on} true)"));
    }
    Some(s)
}

/// A table: every item a list (or, among lists, a point or vector: three numbers the file reader
/// took for a point) of numbers, or of items of one other kind.
fn table(rows: &[Value]) -> Option<String> {
    if !rows.iter().any(|r| matches!(r, Value::List(_))) {
        return None;
    }
    let mut widths = Vec::with_capacity(rows.len());
    let mut numbers = Vec::new();
    let mut all_numbers = true;
    let mut all_integers = true;
    let mut kinds = std::collections::BTreeSet::new();
    for row in rows {
        match row {
            Value::List(cells) => {
                widths.push(cells.len());
                for cell in cells.iter() {
                    match cell.as_f64() {
                        Some(x) => {
                            numbers.push(x);
                            all_integers &= matches!(cell, Value::Integer(_));
                        }
                        None => all_numbers = false,
                    }
                    kinds.insert(noun(cell)?);
                }
            }
            Value::Point(p) | Value::Vector(p) => {
                widths.push(3);
                numbers.extend(p.to_array());
                all_integers = false;
                kinds.insert(("number", "numbers"));
            }
            _ => return None,
        }
    }
    let noun = if all_numbers && !numbers.is_empty() {
        number_noun(all_integers)
    } else if kinds.len() == 1 {
        kinds.pop_first()?
    } else {
        return Some(count(rows.len(), ("row", "rows")));
    };
    let (lo, hi) = (widths.iter().min()?, widths.iter().max()?);
    let shape = if lo == hi {
        format!("{} × {hi} {}", rows.len(), noun.1)
    } else {
        format!(
            "{} of {lo}–{hi} {}",
            count(rows.len(), ("row", "rows")),
            noun.1
        )
    };
    Some(if all_numbers {
        with_range(shape, &numbers)
    } else {
        shape
    })
}

/// `text, lo … hi` over the finite numbers (`text, all x` when they are equal, `text, x` for one).
fn with_range(text: String, numbers: &[f64]) -> String {
    let finite = numbers.iter().copied().filter(|x| x.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    });
    if lo > hi {
        text
    } else if lo == hi && numbers.len() == 1 {
        format!("{text}, {}", short(lo))
    } else if lo == hi {
        format!("{text}, all {}", short(lo))
    } else {
        format!("{text}, {} … {}", short(lo), short(hi))
    }
}

/// `x` to three significant digits: `0.31`, `12.5`, `1235`, `2.5e-4`, `1.23e6`.
pub fn short(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    let a = x.abs();
    if !(1e-3..1e5).contains(&a) {
        let s = format!("{x:.2e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        &s
    };
    if s == "-0" { "0".into() } else { s.to_string() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_geometry::{DVec3, Polyline};
    use std::sync::Arc;

    fn numbers(xs: &[f64]) -> Value {
        Value::list(xs.iter().map(|&x| Value::Number(x)).collect())
    }

    #[test]
    fn lists_of_points_and_polylines() {
        let points = Value::list(vec![Value::Point(DVec3::ZERO); 4]);
        assert_eq!(summary(&points), "4 points");
        let one = Value::list(vec![Value::Vector(DVec3::Z)]);
        assert_eq!(summary(&one), "1 vector");
        let closed = Value::Polyline(Arc::new(Polyline {
            points: vec![DVec3::ZERO; 5],
            closed: true,
        }));
        assert_eq!(summary(&closed), "5 points, closed");
        let profiles = Value::list(vec![Value::Polyline(Arc::new(Polyline::open(vec![]))); 2]);
        assert_eq!(summary(&profiles), "2 polylines");
    }

    #[test]
    fn numbers_with_their_range() {
        let xs: Vec<f64> = (0..12).map(|k| k as f64 / 11.0).collect();
        assert_eq!(summary(&numbers(&xs)), "12 numbers, 0 … 1");
        assert_eq!(summary(&numbers(&[0.5])), "1 number, 0.5");
        assert_eq!(summary(&numbers(&[0.5, 0.5])), "2 numbers, all 0.5");
        let ints = Value::list(vec![
            Value::Integer(5),
            Value::Integer(1),
            Value::Integer(3),
        ]);
        assert_eq!(summary(&ints), "3 integers, 1 … 5");
        let mixed = Value::list(vec![Value::Integer(5), Value::Number(0.25)]);
        assert_eq!(summary(&mixed), "2 numbers, 0.25 … 5");
        assert_eq!(summary(&numbers(&[f64::NAN, 2.0, 1.0])), "3 numbers, 1 … 2");
    }

    #[test]
    fn tables_rows_by_columns() {
        let row = |k: usize| {
            numbers(
                &(0..41)
                    .map(|j| 0.31 + 0.38 * ((k * 41 + j) as f64 / 1639.0))
                    .collect::<Vec<_>>(),
            )
        };
        let table = Value::list((0..40).map(row).collect());
        assert_eq!(summary(&table), "40 × 41 numbers, 0.31 … 0.69");
        let flat = Value::list(vec![numbers(&[0.5; 41]); 40]);
        assert_eq!(summary(&flat), "40 × 41 numbers, all 0.5");
        let ragged = Value::list(vec![
            numbers(&[0.1, 0.2, 0.3, 0.4]),
            Value::Point(DVec3::new(1.0, 2.0, 3.0)),
            Value::list(vec![Value::Integer(7), 0.5.into()]),
        ]);
        assert_eq!(summary(&ragged), "3 rows of 2–4 numbers, 0.1 … 7");
        let column = Value::list(vec![numbers(&[1.0]), numbers(&[2.0])]);
        assert_eq!(summary(&column), "2 × 1 numbers, 1 … 2");
        let texts = Value::list(vec![Value::list(vec![Value::text("a"), Value::text("b")])]);
        assert_eq!(summary(&texts), "1 × 2 texts");
    }

    #[test]
    fn other_lists() {
        assert_eq!(summary(&Value::list(vec![])), "empty list");
        let mixed = Value::list(vec![
            Value::text("a"),
            Value::Number(1.0),
            Value::Boolean(true),
        ]);
        assert_eq!(summary(&mixed), "3 items");
        let flags = Value::list(vec![Value::Boolean(true), Value::Boolean(false)]);
        assert_eq!(summary(&flags), "2 booleans (1 true)");
        let texts = Value::list(vec![Value::text("a"); 3]);
        assert_eq!(summary(&texts), "3 texts");
    }

    #[test]
    fn short_numbers() {
        assert_eq!(short(0.31), "0.31");
        assert_eq!(short(0.995), "0.995");
        assert_eq!(short(12.5), "12.5");
        assert_eq!(short(1234.6), "1235");
        assert_eq!(short(-24.0), "-24");
        assert_eq!(short(0.00025), "2.5e-4");
        assert_eq!(short(1_234_567.0), "1.23e6");
        assert_eq!(short(-0.0), "0");
    }
}
