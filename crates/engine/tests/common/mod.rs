//! Small node types for engine tests.
#![allow(dead_code)]

use std::sync::Arc;

use cnets_engine::prelude::*;
use cnets_engine::{Graph, Registry};

node! {
    /// Passes a number through.
    #[node(id = "t.num", category = "Test")]
    pub fn num(
        /// The value.
        value: k::Number = 0.0,
    ) -> (
        /// The value.
        out: k::Number,
    ) {
        Ok((value,))
    }
}

node! {
    /// Adds two numbers.
    #[node(id = "t.add", category = "Test")]
    pub fn add(
        /// First.
        a: k::Number = 0.0,
        /// Second.
        b: k::Number = 0.0,
    ) -> (
        /// Sum.
        sum: k::Number,
    ) {
        Ok((a + b,))
    }
}

node! {
    /// The sign of a number (−1, 0 or 1): many inputs give equal outputs, for early-cutoff tests.
    #[node(id = "t.sign", category = "Test")]
    pub fn sign(
        /// Input.
        x: k::Number,
    ) -> (
        /// Sign.
        out: k::Number,
    ) {
        Ok((if x > 0.0 { 1.0 } else if x < 0.0 { -1.0 } else { 0.0 },))
    }
}

node! {
    /// Fails when x is negative.
    #[node(id = "t.check", category = "Test")]
    pub fn check(
        /// Input.
        x: k::Number,
    ) -> (
        /// The input.
        out: k::Number,
    ) {
        if x < 0.0 {
            return Err(NodeError::new(format!("x = {x} is negative")));
        }
        Ok((x,))
    }
}

node! {
    /// Panics when x is negative.
    #[node(id = "t.panicky", category = "Test")]
    pub fn panicky(
        /// Input.
        x: k::Number,
    ) -> (
        /// The input.
        out: k::Number,
    ) {
        let v: Vec<f64> = Vec::new();
        if x < 0.0 {
            return Ok((v[7],));
        }
        Ok((x,))
    }
}

node! {
    /// Sums a list.
    #[node(id = "t.sum", category = "Test")]
    pub fn sum(
        /// Items.
        xs: k::List<k::Number>,
    ) -> (
        /// Sum.
        total: k::Number,
        /// Count.
        count: k::Integer,
    ) {
        Ok((xs.iter().sum::<f64>(), xs.len()))
    }
}

node! {
    /// A polyline through points.
    #[node(id = "t.poly", category = "Test")]
    pub fn poly(
        /// The curve.
        curve: k::Polyline,
    ) -> (
        /// Point count.
        count: k::Integer,
    ) {
        Ok((curve.points.len(),))
    }
}

node! {
    /// Emits a list 0, 1, …, n−1.
    #[node(id = "t.series", category = "Test")]
    pub fn series(
        /// Count.
        n: k::Integer = 3,
    ) -> (
        /// Numbers.
        out: k::List<k::Number>,
    ) {
        Ok(((0..n).map(|i| i as f64).collect::<Vec<f64>>(),))
    }
}

node! {
    /// Emits a text.
    #[node(id = "t.text", category = "Test")]
    pub fn text(
        /// Text.
        value: k::Text = String::new(),
    ) -> (
        /// Text.
        out: k::Text,
    ) {
        Ok((value,))
    }
}

node! {
    /// An optional input.
    #[node(id = "t.maybe", category = "Test")]
    pub fn maybe(
        /// Optional.
        p: Option<k::Point>,
    ) -> (
        /// True when given.
        given: k::Boolean,
    ) {
        Ok((p.is_some(),))
    }
}

node! {
    /// Squares a number.
    #[node(id = "t.sq", category = "Test")]
    pub fn sq(
        /// Input.
        x: k::Number,
    ) -> (
        /// x².
        out: k::Number,
    ) {
        Ok((x * x,))
    }
}

node! {
    /// Absolute value (not smooth at 0).
    #[node(id = "t.abs", category = "Test")]
    pub fn abs(
        /// Input.
        x: k::Number,
    ) -> (
        /// |x|.
        out: k::Number,
    ) {
        Ok((x.abs(),))
    }
}

/// A registry with all test nodes.
pub fn registry() -> Arc<Registry> {
    let mut r = Registry::new();
    for def in [
        num(),
        add(),
        sign(),
        check(),
        panicky(),
        sum(),
        poly(),
        series(),
        text(),
        maybe(),
        sq(),
        abs(),
    ] {
        r.register(def);
    }
    for def in cnets_engine::cluster::nodes() {
        r.register(def);
    }
    Arc::new(r)
}

/// An empty graph over the test registry.
pub fn graph() -> Graph {
    Graph::new(registry())
}

/// A chain `n0 -> n1 -> … -> n{len-1}` of `t.add` nodes (each adds its `b`), fed by `head` (`t.num`).
pub fn chain(len: usize) -> Graph {
    let mut g = graph();
    g.add_node("head", "t.num").unwrap();
    let mut prev = ("head".to_string(), "out");
    for k in 0..len {
        let id = format!("n{k}");
        g.add_node(&id, "t.add").unwrap();
        g.set_value(&id, "b", Value::Number(1.0)).unwrap();
        g.connect(&prev.0, prev.1, &id, "a").unwrap();
        prev = (id, "sum");
    }
    g
}
