//! Addresses of numbers inside a graph: `node.port`, `node.port[2]`, `node.port[3][1]` (list items,
//! then point/vector components 0–2).

use std::fmt;

use crate::value::Value;

/// A number inside a node's input or output value.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct ValuePath {
    /// Node id.
    pub node: String,
    /// Input or output name.
    pub port: String,
    /// Indices into nested lists, the last possibly a point/vector component.
    pub indices: Vec<usize>,
}

impl fmt::Display for ValuePath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}.{}", self.node, self.port)?;
        for i in &self.indices {
            write!(f, "[{i}]")?;
        }
        Ok(())
    }
}

impl ValuePath {
    /// Parses `node.port[i][j]…`.
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad =
            || format!("'{text}' is not a reference like \"node.port\" or \"node.port[2][1]\"");
        let (head, mut rest) = match text.find('[') {
            Some(k) => (&text[..k], &text[k..]),
            None => (text, ""),
        };
        let (node, port) = head.split_once('.').ok_or_else(bad)?;
        let ok = |s: &str| {
            !s.is_empty()
                && s.chars()
                    .all(|c| c.is_alphanumeric() || c == '_' || c == '-')
        };
        if !ok(node) || !ok(port) {
            return Err(bad());
        }
        let mut indices = Vec::new();
        while !rest.is_empty() {
            let close = rest.find(']').ok_or_else(bad)?;
            let inner = rest.get(1..close).ok_or_else(bad)?;
            indices.push(inner.trim().parse::<usize>().map_err(|_| bad())?);
            rest = &rest[close + 1..];
            if !rest.is_empty() && !rest.starts_with('[') {
                return Err(bad());
            }
        }
        Ok(Self {
            node: node.to_string(),
            port: port.to_string(),
            indices,
        })
    }

    /// The number at this path inside `value`.
    pub fn get(&self, value: &Value) -> Result<f64, String> {
        let mut cur = value;
        for (depth, &i) in self.indices.iter().enumerate() {
            match cur {
                Value::List(items) => {
                    cur = items
                        .get(i)
                        .ok_or_else(|| self.out_of_range(depth, items.len()))?;
                }
                Value::Point(p) | Value::Vector(p) if depth + 1 == self.indices.len() => {
                    return p
                        .to_array()
                        .get(i)
                        .copied()
                        .ok_or_else(|| self.out_of_range(depth, 3));
                }
                other => return Err(format!("{self}: index [{i}] into {}", other.type_name())),
            }
        }
        cur.as_f64()
            .ok_or_else(|| format!("{self} is {}, not a number", cur.type_name()))
    }

    /// `value` with the number at this path replaced by `x`.
    pub fn set(&self, value: &Value, x: f64) -> Result<Value, String> {
        set_at(value, &self.indices, x).map_err(|e| format!("{self}: {e}"))
    }

    fn out_of_range(&self, depth: usize, len: usize) -> String {
        format!(
            "{self}: index [{}] is out of range (length {len})",
            self.indices[depth]
        )
    }
}

fn set_at(value: &Value, indices: &[usize], x: f64) -> Result<Value, String> {
    let Some((&i, rest)) = indices.split_first() else {
        return match value {
            Value::Number(_) | Value::Null => Ok(Value::Number(x)),
            Value::Integer(_) => Ok(Value::Number(x)),
            other => Err(format!("{} is not a number", other.type_name())),
        };
    };
    match value {
        Value::List(items) => {
            let item = items
                .get(i)
                .ok_or_else(|| format!("index [{i}] is out of range (length {})", items.len()))?;
            let new = set_at(item, rest, x)?;
            let mut items = items.to_vec();
            items[i] = new;
            Ok(Value::list(items))
        }
        Value::Point(p) | Value::Vector(p) if rest.is_empty() && i < 3 => {
            let mut q = *p;
            q[i] = x;
            Ok(if matches!(value, Value::Point(_)) {
                Value::Point(q)
            } else {
                Value::Vector(q)
            })
        }
        other => Err(format!("index [{i}] into {}", other.type_name())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn parse_get_and_set() {
        let p = ValuePath::parse("map.handles[1][2]").unwrap();
        assert_eq!(p.to_string(), "map.handles[1][2]");
        let v = Value::list(vec![
            Value::Point(DVec3::ZERO),
            Value::Point(DVec3::new(1.0, 2.0, 3.0)),
        ]);
        assert_eq!(p.get(&v), Ok(3.0));
        let w = p.set(&v, 9.0).unwrap();
        assert_eq!(p.get(&w), Ok(9.0));
        assert_eq!(p.get(&v), Ok(3.0), "the original is unchanged");
        assert_eq!(
            ValuePath::parse("a.b")
                .unwrap()
                .set(&Value::Number(1.0), 2.0),
            Ok(Value::Number(2.0))
        );
        for bad in ["a", "a.b[", "a.b[x]", ".b", "a.b[1]x"] {
            assert!(ValuePath::parse(bad).is_err(), "{bad}");
        }
        assert!(
            ValuePath::parse("a.b[5]")
                .unwrap()
                .get(&v)
                .unwrap_err()
                .contains("out of range")
        );
    }
}
