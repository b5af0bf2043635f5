//! The wire's encoding: little-endian numbers, length-prefixed texts and lists, plain data as its
//! bytes. Reading checks every length against what is left, so a malformed message is an error,
//! not a panic or a huge allocation.

use bytemuck::Pod;
use cnets_geometry::DVec3;

use super::WireError;

/// A decoding's result.
pub(super) type Res<T> = Result<T, WireError>;

#[derive(Default)]
/// Writes a message.
pub(super) struct Writer(pub(super) Vec<u8>);

impl Writer {
    pub(super) fn raw(&mut self, b: &[u8]) {
        self.0.extend_from_slice(b);
    }
    pub(super) fn u8(&mut self, x: u8) {
        self.0.push(x);
    }
    pub(super) fn bool(&mut self, x: bool) {
        self.u8(u8::from(x));
    }
    pub(super) fn u32(&mut self, x: u32) {
        self.raw(&x.to_le_bytes());
    }
    pub(super) fn u64(&mut self, x: u64) {
        self.raw(&x.to_le_bytes());
    }
    pub(super) fn f64(&mut self, x: f64) {
        self.raw(&x.to_le_bytes());
    }
    pub(super) fn len(&mut self, n: usize) {
        self.u64(n as u64);
    }
    pub(super) fn bytes(&mut self, b: &[u8]) {
        self.len(b.len());
        self.raw(b);
    }
    pub(super) fn str(&mut self, s: &str) {
        self.bytes(s.as_bytes());
    }
    pub(super) fn strs(&mut self, items: &[String]) {
        self.len(items.len());
        for s in items {
            self.str(s);
        }
    }
    pub(super) fn opt<T>(&mut self, x: Option<&T>, f: impl FnOnce(&mut Self, &T)) {
        self.bool(x.is_some());
        if let Some(x) = x {
            f(self, x);
        }
    }
    /// A slice of plain data as its bytes (GPU buffers, indices, numbers), prefixed by its count.
    pub(super) fn pods<T: Pod>(&mut self, items: &[T]) {
        self.len(items.len());
        self.raw(bytemuck::cast_slice(items));
    }
    pub(super) fn dvec3(&mut self, p: DVec3) {
        for x in p.to_array() {
            self.f64(x);
        }
    }
    pub(super) fn dvec3s(&mut self, points: &[DVec3]) {
        let flat: Vec<[f64; 3]> = points.iter().map(|p| p.to_array()).collect();
        self.pods(&flat);
    }
}

/// Reads a message.
pub(super) struct Reader<'a> {
    buf: &'a [u8],
}

impl<'a> Reader<'a> {
    pub(super) fn new(buf: &'a [u8]) -> Self {
        Self { buf }
    }
    pub(super) fn take(&mut self, n: usize) -> Res<&'a [u8]> {
        if n > self.buf.len() {
            return Err(WireError("it ends early"));
        }
        let (head, tail) = self.buf.split_at(n);
        self.buf = tail;
        Ok(head)
    }
    pub(super) fn end(&self) -> Res<()> {
        if self.buf.is_empty() {
            Ok(())
        } else {
            Err(WireError("bytes left over"))
        }
    }
    pub(super) fn array<const N: usize>(&mut self) -> Res<[u8; N]> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.take(N)?);
        Ok(a)
    }
    pub(super) fn u8(&mut self) -> Res<u8> {
        Ok(self.take(1)?[0])
    }
    pub(super) fn bool(&mut self) -> Res<bool> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(WireError("a flag is neither 0 nor 1")),
        }
    }
    pub(super) fn u32(&mut self) -> Res<u32> {
        Ok(u32::from_le_bytes(self.array()?))
    }
    pub(super) fn u64(&mut self) -> Res<u64> {
        Ok(u64::from_le_bytes(self.array()?))
    }
    pub(super) fn usize(&mut self) -> Res<usize> {
        usize::try_from(self.u64()?).map_err(|_| WireError("a count too large for this machine"))
    }
    pub(super) fn f64(&mut self) -> Res<f64> {
        Ok(f64::from_le_bytes(self.array()?))
    }
    /// A count of items of at least `min_size` bytes each: never more than the bytes left allow.
    pub(super) fn len(&mut self, min_size: usize) -> Res<usize> {
        let n = self.usize()?;
        if n.saturating_mul(min_size.max(1)) > self.buf.len() {
            return Err(WireError("a count larger than the message"));
        }
        Ok(n)
    }
    pub(super) fn bytes(&mut self) -> Res<&'a [u8]> {
        let n = self.len(1)?;
        self.take(n)
    }
    pub(super) fn string(&mut self) -> Res<String> {
        String::from_utf8(self.bytes()?.to_vec()).map_err(|_| WireError("a text is not UTF-8"))
    }
    pub(super) fn strings(&mut self) -> Res<Vec<String>> {
        let n = self.len(8)?;
        (0..n).map(|_| self.string()).collect()
    }
    pub(super) fn opt<T>(&mut self, f: impl FnOnce(&mut Self) -> Res<T>) -> Res<Option<T>> {
        if self.bool()? {
            f(self).map(Some)
        } else {
            Ok(None)
        }
    }
    pub(super) fn pods<T: Pod>(&mut self) -> Res<Vec<T>> {
        let size = std::mem::size_of::<T>();
        let n = self.len(size)?;
        Ok(bytemuck::pod_collect_to_vec(self.take(n * size)?))
    }
    pub(super) fn dvec3(&mut self) -> Res<DVec3> {
        Ok(DVec3::new(self.f64()?, self.f64()?, self.f64()?))
    }
    pub(super) fn dvec3s(&mut self) -> Res<Vec<DVec3>> {
        let flat: Vec<[f64; 3]> = self.pods()?;
        Ok(flat.into_iter().map(DVec3::from_array).collect())
    }
}
