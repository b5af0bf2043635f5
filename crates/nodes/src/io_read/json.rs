//! JSON polylines in the runner's encoding: a polyline is `{"points": [[x, y, z], …], "closed":
//! bool}` or a bare array of `[x, y, z]` points (open); the file holds one polyline or a list
//! (nested to any depth) of them. The `closed` flag is taken as written.

use cnets_engine::ValueType;
use cnets_engine::prelude::*;
use cnets_engine::value::json::{Document, from_document};

use super::ReadError;

fn collect(v: &Value, out: &mut Vec<Polyline>) -> Result<(), String> {
    match v {
        Value::Polyline(p) => {
            out.push((**p).clone());
            Ok(())
        }
        Value::List(items) => items.iter().try_for_each(|i| collect(i, out)),
        Value::Null => Err("the file holds null where a polyline was expected".into()),
        other => Err(format!("expected polylines, found {}", other.type_name())),
    }
}

/// Parses JSON text into polylines; a syntax error has its line and column as fields.
pub fn parse(text: &str) -> Result<Vec<Polyline>, ReadError> {
    let doc: Document = serde_json::from_str(text).map_err(|e| {
        // serde_json's message ends with " at line L column C": the place is kept as fields.
        let message = e.to_string();
        let message = message
            .rsplit_once(" at line ")
            .map_or(message.as_str(), |(m, _)| m);
        match (e.line(), e.column()) {
            (0, _) => ReadError::from(format!("invalid JSON: {message}")),
            (l, 0) => ReadError::at(l, format!("invalid JSON: {message}")),
            (l, c) => ReadError::at_column(l, c, format!("invalid JSON: {message}")),
        }
    })?;
    let value = from_document(doc, &ValueType::Polyline).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    collect(&value, &mut out)?;
    for (k, p) in out.iter().enumerate() {
        if let Some(i) = p.points.iter().position(|q| !q.is_finite()) {
            return Err(format!("polyline {k}, point {i} is not finite").into());
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objects_arrays_and_nested_lists() {
        let text = r#"[
            {"points": [[0,0,0],[1,0,0],[1,1,0]], "closed": true},
            [[0,0,1],[0,0,2]],
            [[[5,5,5],[6,6,6]]]
        ]"#;
        let ps = parse(text).unwrap();
        assert_eq!(ps.len(), 3);
        assert!(ps[0].closed);
        assert_eq!(ps[1].points[1], DVec3::new(0.0, 0.0, 2.0));
        assert_eq!(ps[2].points[0], DVec3::splat(5.0));
        let one = parse(r#"{"points": [[0,0,0],[1,2,3]]}"#).unwrap();
        assert_eq!(one.len(), 1);
        assert!(!one[0].closed);
    }

    #[test]
    fn bad_json_is_explained() {
        assert!(parse("{").unwrap_err().to_string().contains("invalid JSON"));
        assert!(parse("[1, 2]").is_err());
        // A syntax error's place is a field.
        let e = parse("[\n  [0, 0, 0],\n  [1, 0 0]\n]").unwrap_err();
        assert_eq!(e.line, Some(3), "{e}");
        assert!(e.column.is_some(), "{e}");
        assert!(
            parse(r#"{"closed": true}"#)
                .unwrap_err()
                .to_string()
                .contains("points")
        );
        assert!(parse(r#"[{"points": [[0,0,0],[1,0]]}]"#).is_err());
    }
}
