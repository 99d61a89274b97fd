//! [`ObsRow`]: one item (row) of a batch of observations as writable array leaves, so that
//! an environment writes its observation straight into a vector environment's batch
//! ([`Env::write_observation_row`](crate::Env::write_observation_row)) instead of into
//! its own buffer that the vector environment then copies.
//!
//! The leaves of an observation are its arrays in the space's order: an array space has
//! one leaf, a Dict or Tuple space whose entries are arrays one leaf per entry. A wrapper
//! whose observation is its inner environment's arrays rearranged (filtered, reordered,
//! concatenated) hands its inner environment a row [`ObsRow::rearranged`] by a [`Pick`]
//! per inner leaf.

use crate::dtype::{DType, Scalar};
use crate::error::{Error, Result};
use crate::value::ArrayValue;
use std::marker::PhantomData;

/// The most leaves one row holds ([`RowLeaves`] is a fixed-size array, so building a row
/// allocates nothing).
pub const MAX_ROW_LEAVES: usize = 64;

/// Where one leaf of a row lives: `len` elements of `dtype` at a raw address (or no
/// address: a leaf the row's consumer does not want, see [`Pick::Absent`]). Only an
/// [`ObsRow`] writes through it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RowLeaf {
    dtype: DType,
    ptr: *mut u8,
    len: usize,
}

// SAFETY: a `RowLeaf` is an address, never dereferenced except through an `ObsRow`, whose
// constructor's contract makes the writes exclusive.
unsafe impl Send for RowLeaf {}
// SAFETY: as above; a shared `RowLeaf` only reads its own fields.
unsafe impl Sync for RowLeaf {}

impl RowLeaf {
    /// A leaf that is not wanted: writes to it are skipped.
    pub const ABSENT: RowLeaf = RowLeaf {
        dtype: DType::U8,
        ptr: std::ptr::null_mut(),
        len: 0,
    };

    /// Row `i` of `batch`, an array whose first axis is the batch (`None` when `i` is out
    /// of range or the array is not in standard layout).
    pub fn of_batch_row(batch: &mut ArrayValue, i: usize) -> Option<RowLeaf> {
        crate::for_each_array!(batch, a => Self::of_typed_batch_row(a, i))
    }

    /// [`RowLeaf::of_batch_row`] of a typed array.
    pub fn of_typed_batch_row<T: Scalar>(
        batch: &mut ndarray::ArrayD<T>,
        i: usize,
    ) -> Option<RowLeaf> {
        let n = *batch.shape().first()?;
        if i >= n || !batch.is_standard_layout() {
            return None;
        }
        let len = batch.shape()[1..].iter().product::<usize>();
        let slice = batch.as_slice_mut()?;
        let row = &mut slice[i * len..(i + 1) * len];
        Some(RowLeaf {
            dtype: T::DTYPE,
            ptr: row.as_mut_ptr().cast(),
            len,
        })
    }

    /// The whole of `array` as one leaf (`None` unless in standard layout).
    pub fn of_array(array: &mut ArrayValue) -> Option<RowLeaf> {
        fn go<T: Scalar>(a: &mut ndarray::ArrayD<T>) -> Option<RowLeaf> {
            let slice = a.as_slice_mut()?;
            Some(RowLeaf {
                dtype: T::DTYPE,
                ptr: slice.as_mut_ptr().cast(),
                len: slice.len(),
            })
        }
        crate::for_each_array!(array, a => go(a))
    }

    /// The element type.
    pub fn dtype(&self) -> DType {
        self.dtype
    }

    /// The number of elements (0 for an absent leaf).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the leaf has no elements.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Whether the leaf is [`RowLeaf::ABSENT`].
    pub fn is_absent(&self) -> bool {
        self.ptr.is_null()
    }

    /// The address of the first element (null for an absent leaf), for checking where a
    /// row points.
    pub fn as_ptr(&self) -> *const u8 {
        self.ptr
    }
}

/// How a wrapper's inner leaf is found in the wrapper's row (one per inner leaf, in the
/// inner observation's order).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pick {
    /// The wrapper drops this leaf: it is not written.
    Absent,
    /// The wrapper's leaf `k`, whole.
    Leaf(usize),
    /// Elements `start..start + len` of the wrapper's leaf `leaf` (a concatenation); the
    /// inner values are converted to that leaf's dtype.
    Segment {
        /// The wrapper's leaf.
        leaf: usize,
        /// The first element.
        start: usize,
        /// The number of elements.
        len: usize,
    },
}

/// Up to [`MAX_ROW_LEAVES`] leaves, without allocating.
#[derive(Debug, Clone, Copy)]
pub struct RowLeaves {
    leaves: [RowLeaf; MAX_ROW_LEAVES],
    len: usize,
}

impl Default for RowLeaves {
    fn default() -> Self {
        Self::new()
    }
}

impl RowLeaves {
    /// No leaves.
    pub const fn new() -> Self {
        Self {
            leaves: [RowLeaf::ABSENT; MAX_ROW_LEAVES],
            len: 0,
        }
    }

    /// Appends `leaf`.
    ///
    /// # Errors
    /// [`Error::Unsupported`] beyond [`MAX_ROW_LEAVES`] leaves.
    pub fn push(&mut self, leaf: RowLeaf) -> Result<()> {
        if self.len == MAX_ROW_LEAVES {
            return Err(Error::unsupported(format!(
                "a row holds at most {MAX_ROW_LEAVES} arrays"
            )));
        }
        self.leaves[self.len] = leaf;
        self.len += 1;
        Ok(())
    }

    /// Removes every leaf.
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// The leaves.
    pub fn as_slice(&self) -> &[RowLeaf] {
        &self.leaves[..self.len]
    }
}

/// One row of a batch, writable: each leaf is an exclusive `&'a mut [T]` of its dtype.
#[derive(Debug)]
pub struct ObsRow<'a> {
    leaves: &'a [RowLeaf],
    _writes: PhantomData<&'a mut [u8]>,
}

impl<'a> ObsRow<'a> {
    /// A row over `leaves`.
    ///
    /// # Safety
    /// Every leaf that is not absent points to `len` initialised, aligned elements of its
    /// dtype that stay allocated for `'a`, that nothing else reads or writes for `'a`, and
    /// that no other leaf of `leaves` overlaps.
    pub unsafe fn from_raw(leaves: &'a [RowLeaf]) -> Self {
        Self {
            leaves,
            _writes: PhantomData,
        }
    }

    /// The number of leaves.
    pub fn len(&self) -> usize {
        self.leaves.len()
    }

    /// Whether the row has no leaves.
    pub fn is_empty(&self) -> bool {
        self.leaves.is_empty()
    }

    /// Leaf `k`'s description (`None` out of range).
    pub fn leaf(&self, k: usize) -> Option<RowLeaf> {
        self.leaves.get(k).copied()
    }

    /// Leaf `k` as a typed slice, when it is present and has dtype `T`.
    pub fn slice_mut<T: Scalar>(&mut self, k: usize) -> Option<&mut [T]> {
        let leaf = self.leaves.get(k)?;
        if leaf.is_absent() || leaf.dtype != T::DTYPE {
            return None;
        }
        // SAFETY: `from_raw`'s contract: the leaf is `len` exclusive, aligned elements of
        // `T` for `'a`, and `&mut self` makes this the only borrow of them.
        Some(unsafe { std::slice::from_raw_parts_mut(leaf.ptr.cast::<T>(), leaf.len) })
    }

    /// Checks that leaf `k` exists and holds `len` elements (an absent leaf passes).
    ///
    /// # Errors
    /// [`Error::Contract`] naming the mismatch.
    pub fn check_leaf(&self, k: usize, len: usize) -> Result<()> {
        match self.leaves.get(k) {
            Some(l) if l.is_absent() || l.len == len => Ok(()),
            Some(l) => Err(row_mismatch(format!(
                "leaf {k} holds {} elements, the observation {len}",
                l.len
            ))),
            None => Err(row_mismatch(format!(
                "the row has {} leaves, the observation at least {}",
                self.leaves.len(),
                k + 1
            ))),
        }
    }

    /// Writes `values` into leaf `k`, each as `T` first (the observation's dtype), then
    /// converted to the leaf's dtype as `np.asarray(x, dtype)` does; an absent leaf is
    /// skipped. Same dtypes copy the bits.
    ///
    /// # Errors
    /// [`Error::Contract`] when the leaf does not exist or its length differs from
    /// `values`'.
    pub fn write<T: Scalar>(&mut self, k: usize, values: &[T]) -> Result<()> {
        self.check_leaf(k, values.len())?;
        let leaf = self.leaves[k];
        if leaf.is_absent() {
            return Ok(());
        }
        if leaf.dtype == T::DTYPE {
            if let Some(dst) = self.slice_mut::<T>(k) {
                dst.copy_from_slice(values);
            }
            return Ok(());
        }
        self.write_with(k, values.len(), |i| values[i].to_f64());
        Ok(())
    }

    /// Writes `len` values, `value(i)` for element `i` given as `f64` after its conversion
    /// to the observation's dtype `T`, into leaf `k` (converted to the leaf's dtype; an
    /// absent leaf is skipped).
    ///
    /// # Errors
    /// As [`ObsRow::write`].
    pub fn write_f64_as<T: Scalar>(
        &mut self,
        k: usize,
        len: usize,
        mut value: impl FnMut(usize) -> f64,
    ) -> Result<()> {
        self.check_leaf(k, len)?;
        if self.leaves[k].is_absent() {
            return Ok(());
        }
        self.write_with(k, len, |i| T::from_f64(value(i)).to_f64());
        Ok(())
    }

    /// Writes an array value into leaf `k` ([`ObsRow::write`] with its dtype).
    ///
    /// # Errors
    /// As [`ObsRow::write`]; [`Error::Contract`] for an array not in standard layout.
    pub fn write_array(&mut self, k: usize, value: &ArrayValue) -> Result<()> {
        crate::for_each_array!(value, a => match a.as_slice() {
            Some(s) => self.write(k, s),
            None => Err(row_mismatch(format!("array {k} is not in standard layout"))),
        })
    }

    /// Stores `value(i)` (exact `f64` values of the observation's elements) into the
    /// present leaf `k` of length `len`, converted to its dtype.
    fn write_with(&mut self, k: usize, len: usize, mut value: impl FnMut(usize) -> f64) {
        fn fill<T: Scalar>(dst: &mut [T], value: &mut impl FnMut(usize) -> f64) {
            for (i, d) in dst.iter_mut().enumerate() {
                *d = T::from_f64(value(i));
            }
        }
        debug_assert_eq!(self.leaves[k].len, len);
        match self.leaves[k].dtype {
            DType::I8 => fill(self.slice_mut::<i8>(k).unwrap_or_default(), &mut value),
            DType::I16 => fill(self.slice_mut::<i16>(k).unwrap_or_default(), &mut value),
            DType::I32 => fill(self.slice_mut::<i32>(k).unwrap_or_default(), &mut value),
            DType::I64 => fill(self.slice_mut::<i64>(k).unwrap_or_default(), &mut value),
            DType::U8 => fill(self.slice_mut::<u8>(k).unwrap_or_default(), &mut value),
            DType::F32 => fill(self.slice_mut::<f32>(k).unwrap_or_default(), &mut value),
            DType::F64 => fill(self.slice_mut::<f64>(k).unwrap_or_default(), &mut value),
            DType::Bool => fill(self.slice_mut::<bool>(k).unwrap_or_default(), &mut value),
        }
    }

    /// The row a wrapper's inner environment writes: inner leaf `j` is `plan[j]` of this
    /// row, built in `buf` (nothing is allocated). Leaves are checked to be in range and
    /// not to overlap, so the inner row's writes stay inside this row's leaves.
    ///
    /// # Errors
    /// [`Error::Contract`] for a pick outside this row, two picks that overlap, or more
    /// than [`MAX_ROW_LEAVES`] picks.
    pub fn rearranged<'b>(
        &'b mut self,
        plan: &[Pick],
        buf: &'b mut RowLeaves,
    ) -> Result<ObsRow<'b>> {
        buf.clear();
        for (j, pick) in plan.iter().enumerate() {
            let (k, start, len) = match *pick {
                Pick::Absent => {
                    buf.push(RowLeaf::ABSENT)?;
                    continue;
                }
                Pick::Leaf(k) => (k, 0, self.leaf(k).map_or(0, |l| l.len)),
                Pick::Segment { leaf, start, len } => (leaf, start, len),
            };
            let outer = self.leaf(k).ok_or_else(|| {
                row_mismatch(format!("pick {j} names leaf {k} of {}", self.len()))
            })?;
            if start.checked_add(len).is_none_or(|end| end > outer.len) {
                return Err(row_mismatch(format!(
                    "pick {j} takes {start}..{} of leaf {k}'s {} elements",
                    start.saturating_add(len),
                    outer.len
                )));
            }
            let leaf = if outer.is_absent() {
                RowLeaf::ABSENT
            } else {
                RowLeaf {
                    dtype: outer.dtype,
                    // SAFETY: `start + len <= outer.len`, so the offset stays inside the
                    // leaf's allocation.
                    ptr: unsafe { outer.ptr.add(start * outer.dtype.size()) },
                    len,
                }
            };
            for (i, other) in buf.as_slice().iter().enumerate() {
                if overlaps(other, &leaf) {
                    return Err(row_mismatch(format!("picks {i} and {j} overlap")));
                }
            }
            buf.push(leaf)?;
        }
        // SAFETY: every leaf lies inside one of this row's leaves (checked above), no two
        // overlap, and the new row borrows this one mutably for `'b`.
        Ok(unsafe { ObsRow::from_raw(buf.as_slice()) })
    }
}

fn overlaps(a: &RowLeaf, b: &RowLeaf) -> bool {
    if a.is_absent() || b.is_absent() || a.len == 0 || b.len == 0 {
        return false;
    }
    let (a0, b0) = (a.ptr as usize, b.ptr as usize);
    let a1 = a0 + a.len * a.dtype.size();
    let b1 = b0 + b.len * b.dtype.size();
    a0 < b1 && b0 < a1
}

fn row_mismatch(message: String) -> Error {
    Error::Contract {
        check: "observation row".into(),
        message: message.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::ArrayD;

    fn batch<T: Scalar>(shape: &[usize]) -> ArrayValue
    where
        ArrayD<T>: Into<ArrayValue>,
    {
        ArrayD::<T>::from_elem(shape, T::zero()).into()
    }

    #[test]
    fn a_row_writes_its_item_of_the_batch_converting_dtypes() {
        let mut images = batch::<u8>(&[3, 2, 2]);
        let mut flat = batch::<f32>(&[3, 6]);
        let mut leaves = RowLeaves::new();
        leaves
            .push(RowLeaf::of_batch_row(&mut images, 1).unwrap())
            .unwrap();
        leaves
            .push(RowLeaf::of_batch_row(&mut flat, 1).unwrap())
            .unwrap();
        assert!(RowLeaf::of_batch_row(&mut flat, 3).is_none());
        // SAFETY: the leaves are rows of the two local batches, untouched while `row` lives.
        let mut row = unsafe { ObsRow::from_raw(leaves.as_slice()) };
        row.write::<u8>(0, &[1, 2, 3, 255]).unwrap();
        // The flat leaf: two segments, a u8 image and f64 values stored as f32.
        let plan = [
            Pick::Segment {
                leaf: 1,
                start: 0,
                len: 4,
            },
            Pick::Absent,
            Pick::Segment {
                leaf: 1,
                start: 4,
                len: 2,
            },
        ];
        let mut buf = RowLeaves::new();
        let mut inner = row.rearranged(&plan, &mut buf).unwrap();
        inner.write::<u8>(0, &[9, 8, 7, 6]).unwrap();
        inner.write::<f64>(1, &[1.0, 2.0]).unwrap();
        inner.write_f64_as::<f64>(2, 2, |i| 0.1 * i as f64).unwrap();
        assert!(inner.write::<f64>(2, &[1.0]).is_err(), "wrong length");
        assert!(inner.write::<f64>(3, &[1.0]).is_err(), "no such leaf");
        let images = images.to_f64_vec();
        assert_eq!(&images[4..8], &[1.0, 2.0, 3.0, 255.0]);
        assert!(images[..4].iter().chain(&images[8..]).all(|&v| v == 0.0));
        let flat = flat.to_f64_vec();
        assert_eq!(&flat[6..10], &[9.0, 8.0, 7.0, 6.0]);
        assert_eq!(flat[10], 0.0);
        assert_eq!(flat[11], f64::from(0.1f64 as f32));
        assert!(flat[..6].iter().chain(&flat[12..]).all(|&v| v == 0.0));
    }

    #[test]
    fn rearranged_rows_refuse_picks_outside_or_overlapping() {
        let mut flat = batch::<f32>(&[2, 4]);
        let mut leaves = RowLeaves::new();
        leaves
            .push(RowLeaf::of_batch_row(&mut flat, 0).unwrap())
            .unwrap();
        // SAFETY: one row of the local batch.
        let mut row = unsafe { ObsRow::from_raw(leaves.as_slice()) };
        let mut buf = RowLeaves::new();
        let seg = |start, len| Pick::Segment {
            leaf: 0,
            start,
            len,
        };
        assert!(row.rearranged(&[seg(2, 3)], &mut buf).is_err());
        assert!(row.rearranged(&[seg(0, 3), seg(2, 2)], &mut buf).is_err());
        assert!(row.rearranged(&[Pick::Leaf(1)], &mut buf).is_err());
        assert!(
            row.rearranged(&[Pick::Leaf(0), Pick::Leaf(0)], &mut buf)
                .is_err()
        );
        assert!(row.rearranged(&[seg(0, 2), seg(2, 2)], &mut buf).is_ok());
        assert!(flat.to_f64_vec().iter().all(|&v| v == 0.0));
    }
}
