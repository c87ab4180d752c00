//! What the user's shapes say about the image: the median under the seeds (object),
//! inside polygons when they outline objects (a tracked cell's contour carried into the
//! next frame; a drawn polygon or a seed's basin may hold background too), and along the
//! inside of rectangles (background, for a wrap).

use super::field::Field;
use crate::shape::Shape;

/// What the shapes say: medians of the image.
pub(crate) struct Hints {
    /// Under the seeds (object).
    pub object: Option<f64>,
    /// Along the inside of rectangles (background, for a wrap).
    pub background: Option<f64>,
    /// Inside the polygons, when they outline objects.
    pub outlined: Option<f64>,
}

/// The medians of [`Hints`] under `init`; inside the polygons only with `outlines` (the
/// fill is skipped where it would not be read: a seed's basins cover the image).
pub(crate) fn hints(field: &Field, init: &[Shape], outlines: bool) -> Hints {
    let mut obj = Vec::new();
    let mut outlined = Vec::new();
    let mut bg = Vec::new();
    for s in init {
        match s {
            Shape::Disk { center, radius } => {
                // Pixel centres in the disk, the loops clipped to the image: the cost is
                // the disk's part in the image, whatever the radius.
                let r = radius.max(1.0);
                let span = |c: f64, n: usize| {
                    let lo = (c - r - 0.5).ceil().clamp(0.0, n as f64) as usize;
                    let hi = (c + r - 0.5).floor().clamp(-1.0, n as f64 - 1.0);
                    lo..(hi + 1.0) as usize
                };
                for y in span(center.y, field.height) {
                    let dy = y as f64 + 0.5 - center.y;
                    for x in span(center.x, field.width) {
                        let dx = x as f64 + 0.5 - center.x;
                        if dx * dx + dy * dy <= r * r {
                            obj.push(field.at(x, y) as f64);
                        }
                    }
                }
            }
            Shape::Rect { min, max } => {
                // Pixels whose centre lies within `band` of a side: whole rows near the
                // top and bottom, the ends of the rows between.
                let band = 4.0;
                let near_x = |x: usize| {
                    let fx = x as f64 + 0.5;
                    fx - min.x < band || max.x - fx < band
                };
                let (x0, x1) = (
                    min.x.max(0.0) as usize,
                    max.x.min(field.width as f64) as usize,
                );
                for y in (min.y.max(0.0) as usize)..(max.y.min(field.height as f64) as usize) {
                    let fy = y as f64 + 0.5;
                    let whole = fy - min.y < band || max.y - fy < band;
                    let mut left = x0;
                    while left < x1 && (whole || near_x(left)) {
                        left += 1;
                    }
                    let mut right = x1;
                    while right > left && near_x(right - 1) {
                        right -= 1;
                    }
                    for x in (x0..left).chain(right..x1) {
                        bg.push(field.at(x, y) as f64);
                    }
                }
            }
            Shape::Polygon(_) if !outlines => {}
            Shape::Polygon(ring) => crate::geometry::fill_even_odd(
                std::slice::from_ref(ring),
                field.width,
                field.height,
                |i| outlined.push(field.data[i] as f64),
            ),
        }
    }
    Hints {
        object: median(&mut obj),
        background: median(&mut bg),
        outlined: median(&mut outlined),
    }
}

/// The median of `v` (the upper one of an even count; `None` when empty), which it
/// reorders.
pub(crate) fn median(v: &mut [f64]) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    let m = v.len() / 2;
    v.select_nth_unstable_by(m, |a, b| a.total_cmp(b));
    Some(v[m])
}
