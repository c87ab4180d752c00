//! The quiet-move certificate's count over the staggered hash: the boxes a query reads,
//! as a rectangle of half-boxes a walk can test.

use super::{Reach, StaggeredHash};
use crate::contours::broad_phase::Countable;
use crate::geometry::Aabb;

/// What the quiet-move certificate counts: the boxes a query reads. They are a rectangle
/// of half-boxes, which is what a walk tests (one comparison per axis on the vertex's
/// half-box, no look at its four boxes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HashRegion {
    boxes: Reach,
    /// Half-boxes `lo ..= lo + size` per axis (wide: 2c − o may leave i32's range).
    lo: [i64; 2],
    size: [u64; 2],
}

impl Countable for StaggeredHash {
    type Region = HashRegion;

    #[inline]
    fn region(&self, b: &Aabb) -> Option<(HashRegion, u32)> {
        let r = self.reach(b);
        // Box c of the system with offset o holds half-boxes 2c − o and 2c − o + 1.
        let (ox, oy) = ((r.sys & 1) as i64, (r.sys >> 1) as i64);
        let region = HashRegion {
            boxes: r,
            lo: [2 * r.lo[0] as i64 - ox, 2 * r.lo[1] as i64 - oy],
            size: [
                (2 * (r.hi[0] as i64 - r.lo[0] as i64) + 1) as u64,
                (2 * (r.hi[1] as i64 - r.lo[1] as i64) + 1) as u64,
            ],
        };
        if r.lo == r.hi {
            return Some((region, self.fill[self.bucket_of(r.lo, r.sys) as usize]));
        }
        if r.boxes() > 4 {
            return None;
        }
        // A bucket shared by two of the boxes is counted twice: the sum only grows, and
        // the exact count decides.
        let mut n = 0;
        for y in r.lo[1]..=r.hi[1] {
            for x in r.lo[0]..=r.hi[0] {
                n += self.fill[self.bucket_of([x, y], r.sys) as usize];
            }
        }
        Some((region, n))
    }

    fn exact_count(&self, r: &HashRegion) -> u32 {
        let mut n = 0;
        self.for_each_in(&r.boxes, |_| n += 1);
        n
    }

    #[inline]
    fn in_region(&self, v: u32, r: &HashRegion) -> bool {
        // The box, not the bucket: a walk must not count another box hashed alike.
        let k = self.half[v as usize];
        ((k[0] as i64).wrapping_sub(r.lo[0]) as u64) <= r.size[0]
            && ((k[1] as i64).wrapping_sub(r.lo[1]) as u64) <= r.size[1]
    }
}
