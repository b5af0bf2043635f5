//! Which outputs of a node are requested: a bit set over output indices.
//!
//! An output is requested when it is wired to a node the evaluation needs, when the caller asks
//! for it (the editor for what it previews, `cnets run` for what it exports or prints, `cnets eval
//! --outputs`), and otherwise not: a node may skip the work of outputs nobody reads
//! ([`NodeContext::wants`](crate::NodeContext::wants)).

/// A set of output indices. Bit k stands for output k for k < 63; bit 63 stands for every output
/// from 63 on (nodes rarely have more than a dozen outputs; a cluster with more than 63 computes
/// those together).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct OutputMask(pub u64);

impl OutputMask {
    /// No output.
    pub const NONE: OutputMask = OutputMask(0);
    /// Every output of any node.
    pub const ALL: OutputMask = OutputMask(u64::MAX);

    /// The bit of output `k`.
    #[inline]
    fn bit(k: usize) -> u64 {
        1u64 << k.min(63)
    }

    /// The set holding output `k` only.
    #[inline]
    pub fn one(k: usize) -> Self {
        Self(Self::bit(k))
    }

    /// Every output of a node with `count` outputs.
    #[inline]
    pub fn first(count: usize) -> Self {
        if count >= 64 {
            Self::ALL
        } else {
            Self((1u64 << count) - 1)
        }
    }

    /// The outputs named in `names` among `outputs` (unknown names are ignored).
    pub fn of_names<'a>(
        outputs: impl IntoIterator<Item = &'a str>,
        names: &[impl AsRef<str>],
    ) -> Self {
        let mut mask = Self::NONE;
        for (k, name) in outputs.into_iter().enumerate() {
            if names.iter().any(|n| n.as_ref() == name) {
                mask.insert(k);
            }
        }
        mask
    }

    /// True when output `k` is in the set.
    #[inline]
    pub fn contains(self, k: usize) -> bool {
        self.0 & Self::bit(k) != 0
    }

    /// Adds output `k`.
    #[inline]
    pub fn insert(&mut self, k: usize) {
        self.0 |= Self::bit(k);
    }

    /// True when the set holds no output.
    #[inline]
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// True when every output of `other` is in this set.
    #[inline]
    pub fn covers(self, other: OutputMask) -> bool {
        other.0 & !self.0 == 0
    }

    /// The outputs in either set.
    #[inline]
    pub fn union(self, other: OutputMask) -> Self {
        Self(self.0 | other.0)
    }

    /// The outputs in both sets.
    #[inline]
    pub fn intersection(self, other: OutputMask) -> Self {
        Self(self.0 & other.0)
    }

    /// The outputs of this set that are not in `other`.
    #[inline]
    pub fn minus(self, other: OutputMask) -> Self {
        Self(self.0 & !other.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masks_hold_outputs_and_fold_the_high_ones() {
        let mut m = OutputMask::NONE;
        m.insert(2);
        assert!(m.contains(2) && !m.contains(1));
        assert!(OutputMask::first(3).covers(m));
        assert!(!m.covers(OutputMask::first(3)));
        assert_eq!(OutputMask::first(3).minus(m), OutputMask(0b011));
        // Outputs 63 and up share one bit.
        assert!(OutputMask::one(70).contains(63));
        assert_eq!(OutputMask::first(64), OutputMask::ALL);
        assert_eq!(
            OutputMask::of_names(["a", "b", "c"], &["c", "x"]),
            OutputMask::one(2)
        );
    }
}
