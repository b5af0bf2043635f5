//! Picking items by pattern: `list.cull`, `list.dispatch`, `list.weave`.

use cnets_engine::prelude::*;

fn check_pattern(pattern: &[bool]) -> Result<(), NodeError> {
    if pattern.is_empty() {
        return Err("the pattern is empty: give at least one true or false".into());
    }
    Ok(())
}

node! {
    /// Keeps the items where the pattern is true; the pattern repeats along the list
    /// ([1..6] with [true, false] → [1, 3, 5]).
    #[node(id = "list.cull", category = "Lists")]
    pub fn cull(
        /// The list.
        list: k::List<k::Any>,
        /// Which items to keep, repeated cyclically.
        pattern: k::List<k::Boolean>,
    ) -> (
        /// The kept items.
        list: k::List<k::Any>,
    ) {
        check_pattern(&pattern)?;
        let kept = list
            .into_iter()
            .enumerate()
            .filter(|(k, _)| pattern[k % pattern.len()])
            .map(|(_, v)| v)
            .collect::<Vec<_>>();
        Ok((kept,))
    }
}

node! {
    /// Sends every item to `a` where the pattern is true and to `b` where it is false; the pattern
    /// repeats along the list.
    #[node(id = "list.dispatch", category = "Lists")]
    pub fn dispatch(
        /// The list.
        list: k::List<k::Any>,
        /// Where each item goes (true: a, false: b), repeated cyclically.
        pattern: k::List<k::Boolean>,
    ) -> (
        /// Items where the pattern is true.
        a: k::List<k::Any>,
        /// Items where the pattern is false.
        b: k::List<k::Any>,
    ) {
        check_pattern(&pattern)?;
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for (k, v) in list.into_iter().enumerate() {
            if pattern[k % pattern.len()] { a.push(v) } else { b.push(v) }
        }
        Ok((a, b))
    }
}

node! {
    /// Interleaves lists: takes the next item of list `pattern[0]`, then of `pattern[1]`, … and
    /// repeats the pattern ([[1,2,3],[10,20,30]] with [0, 1] → [1,10,2,20,3,30]). A list that runs
    /// out is skipped, so the leftovers of longer lists follow in pattern order; lists the pattern
    /// does not name are left out. No pattern: 0, 1, …, k−1.
    #[node(id = "list.weave", category = "Lists")]
    pub fn weave(
        /// The lists to interleave (a list of lists).
        lists: k::Tree<k::Any>,
        /// Which list each taken item comes from (optional).
        pattern: Option<k::List<k::Integer>>,
    ) -> (
        /// The woven list.
        list: k::List<k::Any>,
    ) {
        let Some(outer) = lists.as_list() else {
            return Err("lists must be a list of lists".into());
        };
        let branches: Vec<&[Value]> = outer
            .iter()
            .map(|v| v.as_list().unwrap_or(std::slice::from_ref(v)))
            .collect();
        let pattern: Vec<usize> = match pattern {
            None => (0..branches.len()).collect(),
            Some(p) if p.is_empty() => return Err("the pattern is empty".into()),
            Some(p) => p
                .iter()
                .map(|&i| {
                    usize::try_from(i).ok().filter(|&i| i < branches.len()).ok_or_else(|| {
                        NodeError::new(format!(
                            "pattern names list {i}, but there are {} lists (0 to {})",
                            branches.len(),
                            branches.len().saturating_sub(1)
                        ))
                    })
                })
                .collect::<Result<_, _>>()?,
        };
        let mut named = vec![false; branches.len()];
        pattern.iter().for_each(|&i| named[i] = true);
        let total: usize = branches
            .iter()
            .zip(&named)
            .filter(|(_, n)| **n)
            .map(|(b, _)| b.len())
            .sum();
        let mut cursors = vec![0usize; branches.len()];
        let mut out = Vec::with_capacity(total);
        while out.len() < total {
            for &i in &pattern {
                if let Some(v) = branches[i].get(cursors[i]) {
                    out.push(v.clone());
                    cursors[i] += 1;
                }
            }
        }
        Ok((out,))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{bools, ints, nums, run_named};

    #[test]
    fn cull_and_dispatch_repeat_the_pattern() {
        let list = nums(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        let pattern = bools(&[true, false]);
        let out = run_named(
            &cull(),
            &[("list", list.clone()), ("pattern", pattern.clone())],
        );
        assert_eq!(out.unwrap()[0], nums(&[1.0, 3.0, 5.0]));
        let out = run_named(&dispatch(), &[("list", list.clone()), ("pattern", pattern)]).unwrap();
        assert_eq!(out, vec![nums(&[1.0, 3.0, 5.0]), nums(&[2.0, 4.0, 6.0])]);
        let three = bools(&[false, false, true]);
        let out = run_named(&cull(), &[("list", list.clone()), ("pattern", three)]);
        assert_eq!(out.unwrap()[0], nums(&[3.0, 6.0]));
        let e = run_named(&cull(), &[("list", list), ("pattern", bools(&[]))]);
        assert!(e.unwrap_err().contains("empty"));
    }

    #[test]
    fn weave_interleaves_and_appends_leftovers_in_pattern_order() {
        let lists = Value::list(vec![nums(&[1.0, 2.0, 3.0]), nums(&[10.0, 20.0, 30.0])]);
        let out = run_named(
            &weave(),
            &[("lists", lists.clone()), ("pattern", ints(&[0, 1]))],
        );
        assert_eq!(out.unwrap()[0], nums(&[1.0, 10.0, 2.0, 20.0, 3.0, 30.0]));
        let out = run_named(&weave(), &[("lists", lists)]).unwrap();
        assert_eq!(
            out[0],
            nums(&[1.0, 10.0, 2.0, 20.0, 3.0, 30.0]),
            "default pattern"
        );
        let uneven = Value::list(vec![
            nums(&[1.0]),
            nums(&[10.0, 20.0, 30.0]),
            nums(&[100.0, 200.0]),
        ]);
        let out = run_named(
            &weave(),
            &[("lists", uneven.clone()), ("pattern", ints(&[2, 0, 1]))],
        );
        assert_eq!(
            out.unwrap()[0],
            nums(&[100.0, 1.0, 10.0, 200.0, 20.0, 30.0])
        );
        let out = run_named(
            &weave(),
            &[("lists", uneven.clone()), ("pattern", ints(&[1, 1, 0]))],
        );
        assert_eq!(
            out.unwrap()[0],
            nums(&[10.0, 20.0, 1.0, 30.0]),
            "list 2 is not named"
        );
        let e = run_named(&weave(), &[("lists", uneven), ("pattern", ints(&[3]))]).unwrap_err();
        assert!(e.contains("pattern names list 3"), "{e}");
    }
}
