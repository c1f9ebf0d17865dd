//! Bounds-checked reads of fixed-offset binary header fields (the instrument readers' headers):
//! every read returns `None` past the end of the bytes, never panics.

/// A header's bytes and byte order.
#[derive(Clone, Copy)]
pub(crate) struct Fields<'a> {
    pub b: &'a [u8],
    pub big: bool,
}

impl<'a> Fields<'a> {
    pub(crate) fn le(b: &'a [u8]) -> Self {
        Fields { b, big: false }
    }

    pub(crate) fn be(b: &'a [u8]) -> Self {
        Fields { b, big: true }
    }

    fn arr<const N: usize>(&self, at: usize) -> Option<[u8; N]> {
        let s = self.b.get(at..at.checked_add(N)?)?;
        s.try_into().ok()
    }

    pub(crate) fn u8(&self, at: usize) -> Option<u8> {
        self.b.get(at).copied()
    }

    pub(crate) fn u16(&self, at: usize) -> Option<u16> {
        let a = self.arr(at)?;
        Some(if self.big { u16::from_be_bytes(a) } else { u16::from_le_bytes(a) })
    }

    pub(crate) fn i16(&self, at: usize) -> Option<i16> {
        let a = self.arr(at)?;
        Some(if self.big { i16::from_be_bytes(a) } else { i16::from_le_bytes(a) })
    }

    pub(crate) fn u32(&self, at: usize) -> Option<u32> {
        let a = self.arr(at)?;
        Some(if self.big { u32::from_be_bytes(a) } else { u32::from_le_bytes(a) })
    }

    pub(crate) fn i32(&self, at: usize) -> Option<i32> {
        let a = self.arr(at)?;
        Some(if self.big { i32::from_be_bytes(a) } else { i32::from_le_bytes(a) })
    }

    pub(crate) fn u64(&self, at: usize) -> Option<u64> {
        let a = self.arr(at)?;
        Some(if self.big { u64::from_be_bytes(a) } else { u64::from_le_bytes(a) })
    }

    pub(crate) fn f32(&self, at: usize) -> Option<f64> {
        let a = self.arr(at)?;
        Some(f64::from(if self.big { f32::from_be_bytes(a) } else { f32::from_le_bytes(a) }))
    }

    pub(crate) fn f64(&self, at: usize) -> Option<f64> {
        let a = self.arr(at)?;
        Some(if self.big { f64::from_be_bytes(a) } else { f64::from_le_bytes(a) })
    }
}
