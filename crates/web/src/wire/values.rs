//! Node statuses and values across the wire (a value nests at most [`MAX_DEPTH`] lists deep).

use cnets_editor::worker::NodeStatus;
use cnets_engine::Value;
use cnets_geometry::Polyline;

use super::WireError;
use super::codec::{Reader, Res, Writer};

const OK: u8 = 0;
const ERROR: u8 = 1;
const BLOCKED: u8 = 2;
const DISABLED: u8 = 3;
const IDLE: u8 = 4;
const RUNNING: u8 = 5;

pub(super) fn status(w: &mut Writer, s: &NodeStatus) {
    match s {
        NodeStatus::Ok {
            warnings,
            outputs,
            time_ms,
            readout,
            ran_on,
        } => {
            w.u8(OK);
            w.strs(warnings);
            w.strs(outputs);
            w.f64(*time_ms);
            w.opt(readout.as_ref(), |w, t| w.str(t));
            w.opt(ran_on.as_ref(), |w, values| {
                w.len(values.len());
                for v in values {
                    value(w, v);
                }
            });
        }
        NodeStatus::Error(m) => {
            w.u8(ERROR);
            w.str(m);
        }
        NodeStatus::Blocked(m) => {
            w.u8(BLOCKED);
            w.str(m);
        }
        NodeStatus::Disabled => w.u8(DISABLED),
        NodeStatus::Idle => w.u8(IDLE),
        NodeStatus::Running { last_ms } => {
            w.u8(RUNNING);
            w.f64(*last_ms);
        }
    }
}

pub(super) fn read_status(r: &mut Reader) -> Res<NodeStatus> {
    Ok(match r.u8()? {
        OK => NodeStatus::Ok {
            warnings: r.strings()?,
            outputs: r.strings()?,
            time_ms: r.f64()?,
            readout: r.opt(Reader::string)?,
            ran_on: r.opt(|r| {
                let n = r.len(1)?;
                (0..n).map(|_| read_value(r, 0)).collect()
            })?,
        },
        ERROR => NodeStatus::Error(r.string()?),
        BLOCKED => NodeStatus::Blocked(r.string()?),
        DISABLED => NodeStatus::Disabled,
        IDLE => NodeStatus::Idle,
        RUNNING => NodeStatus::Running { last_ms: r.f64()? },
        _ => return Err(WireError("unknown node status")),
    })
}

/// The values a graph mapper ran on: what its widget reads (numbers, text, points, curves and
/// lists of them); anything else crosses as `Null`.
pub(super) fn value(w: &mut Writer, v: &Value) {
    match v {
        Value::Number(x) => {
            w.u8(1);
            w.f64(*x);
        }
        Value::Integer(i) => {
            w.u8(2);
            w.u64(*i as u64);
        }
        Value::Boolean(b) => {
            w.u8(3);
            w.bool(*b);
        }
        Value::Text(t) => {
            w.u8(4);
            w.str(t);
        }
        Value::Point(p) => {
            w.u8(5);
            w.dvec3(*p);
        }
        Value::Vector(p) => {
            w.u8(6);
            w.dvec3(*p);
        }
        Value::Polyline(p) => {
            w.u8(7);
            w.dvec3s(&p.points);
            w.bool(p.closed);
        }
        Value::List(_) => {
            let items = v.as_list().unwrap_or(&[]);
            w.u8(8);
            w.len(items.len());
            for item in items {
                value(w, item);
            }
        }
        _ => w.u8(0),
    }
}

/// Lists nest at most this deep in a message (a mapper's inputs are flat or one level deep).
const MAX_DEPTH: usize = 32;

pub(super) fn read_value(r: &mut Reader, depth: usize) -> Res<Value> {
    if depth > MAX_DEPTH {
        return Err(WireError("values nested too deep"));
    }
    Ok(match r.u8()? {
        0 => Value::Null,
        1 => Value::Number(r.f64()?),
        2 => Value::Integer(r.u64()? as i64),
        3 => Value::Boolean(r.bool()?),
        4 => Value::text(r.string()?),
        5 => Value::Point(r.dvec3()?),
        6 => Value::Vector(r.dvec3()?),
        7 => {
            let points = r.dvec3s()?;
            let closed = r.bool()?;
            Value::from(Polyline { points, closed })
        }
        8 => {
            let n = r.len(1)?;
            // Sized once: a list of millions of items is not grown by doubling.
            let mut items = Vec::with_capacity(n);
            for _ in 0..n {
                items.push(read_value(r, depth + 1)?);
            }
            Value::list(items)
        }
        _ => return Err(WireError("unknown value")),
    })
}
