//! A binary mask on a box of the image ([`Patch`]) and what the cuts of touching nuclei
//! ([`super::declump`]) ask of it: morphology by distance (erode, dilate), holes filled,
//! 4-connected components, the convex hull and the fit of the moment ellipse.

use super::distance::distance_transform;
use super::field::neighbours4;
use crate::geometry::{fill_even_odd, Point};

/// A binary mask on a box of the image: `w`×`h` pixels whose first lies at `origin` of
/// an image of size `image`.
#[derive(Clone)]
pub(crate) struct Patch {
    pub(crate) w: usize,
    pub(crate) h: usize,
    pub(crate) px: Vec<bool>,
    pub(crate) origin: (isize, isize),
    pub(crate) image: (usize, usize),
}

impl Patch {
    pub(crate) fn count(&self) -> usize {
        self.px.iter().filter(|&&p| p).count()
    }

    pub(crate) fn like(&self, px: Vec<bool>) -> Patch {
        Patch { px, ..*self }
    }

    /// Euclidean distance of each pixel to the nearest pixel of the mask (0 on it).
    pub(crate) fn distance_to(&self) -> Vec<f32> {
        let not: Vec<bool> = self.px.iter().map(|&p| !p).collect();
        distance_transform(&not, self.w, self.h).data
    }

    pub(crate) fn erode(&self, r: f64) -> Patch {
        let d = distance_transform(&self.px, self.w, self.h).data;
        self.like(d.iter().map(|&v| v as f64 > r).collect())
    }

    pub(crate) fn dilate(&self, r: f64) -> Patch {
        self.like(self.distance_to().iter().map(|&v| v as f64 <= r).collect())
    }

    /// The mask with its holes (background not 4-connected to the box's edge) filled.
    pub(crate) fn filled(&self) -> Patch {
        let (w, h) = (self.w, self.h);
        let mut outside = vec![false; w * h];
        let mut stack: Vec<usize> = (0..w * h)
            .filter(|&i| {
                let (x, y) = (i % w, i / w);
                (x == 0 || y == 0 || x + 1 == w || y + 1 == h) && !self.px[i]
            })
            .collect();
        for &i in &stack {
            outside[i] = true;
        }
        while let Some(i) = stack.pop() {
            for j in neighbours4(i, w, h) {
                if !outside[j] && !self.px[j] {
                    outside[j] = true;
                    stack.push(j);
                }
            }
        }
        self.like(outside.iter().map(|&o| !o).collect())
    }

    /// 4-connected components: (labels 1..=n, sizes).
    pub(crate) fn components(&self) -> (Vec<u32>, Vec<usize>) {
        let (w, h) = (self.w, self.h);
        let mut label = vec![0u32; w * h];
        let mut sizes = Vec::new();
        for s in 0..w * h {
            if !self.px[s] || label[s] != 0 {
                continue;
            }
            let l = sizes.len() as u32 + 1;
            let (mut stack, mut n) = (vec![s], 0);
            label[s] = l;
            while let Some(i) = stack.pop() {
                n += 1;
                for j in neighbours4(i, w, h) {
                    if self.px[j] && label[j] == 0 {
                        label[j] = l;
                        stack.push(j);
                    }
                }
            }
            sizes.push(n);
        }
        (label, sizes)
    }

    /// The pixels whose centres lie in the convex hull of the mask's pixels (each pixel
    /// taken as the midpoints of its four sides, so a one-pixel line has an area).
    pub(crate) fn hull(&self) -> Patch {
        let w = self.w;
        let mut pts = Vec::new();
        for (i, _) in self.px.iter().enumerate().filter(|(_, &p)| p) {
            let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
            pts.extend([
                Point::new(x - 0.5, y),
                Point::new(x + 0.5, y),
                Point::new(x, y - 0.5),
                Point::new(x, y + 0.5),
            ]);
        }
        let ring = convex_hull(pts);
        let mut px = self.px.clone();
        fill_even_odd(&[ring], self.w, self.h, |i| px[i] = true);
        self.like(px)
    }

    /// Overlap (intersection over union) of the mask with the ellipse of its second
    /// moments (semi-axes twice the standard deviations along the principal axes), both
    /// counted in pixels inside the image: an object cut by the border is compared with
    /// its ellipse cut there too.
    pub(crate) fn ellipse_fit(&self) -> f64 {
        let w = self.w;
        let pts: Vec<(f64, f64)> = (0..self.px.len())
            .filter(|&i| self.px[i])
            .map(|i| ((i % w) as f64, (i / w) as f64))
            .collect();
        let n = pts.len() as f64;
        let (mx, my) = pts.iter().fold((0.0, 0.0), |(a, b), p| (a + p.0, b + p.1));
        let (mx, my) = (mx / n, my / n);
        let (mut cxx, mut cyy, mut cxy) = (0.0, 0.0, 0.0);
        for &(x, y) in &pts {
            cxx += (x - mx) * (x - mx);
            cyy += (y - my) * (y - my);
            cxy += (x - mx) * (y - my);
        }
        let (cxx, cyy, cxy) = (cxx / n, cyy / n, cxy / n);
        let mid = 0.5 * (cxx + cyy);
        let rad = (0.25 * (cxx - cyy).powi(2) + cxy * cxy).sqrt();
        let a = 2.0 * (mid + rad).sqrt();
        let b = (2.0 * (mid - rad).max(0.0).sqrt()).max(1.0);
        let th = 0.5 * (2.0 * cxy).atan2(cxx - cyy);
        let (c, s) = (th.cos(), th.sin());
        let in_ellipse = |x: f64, y: f64| {
            let (dx, dy) = (x - mx, y - my);
            let (u, v) = (dx * c + dy * s, -dx * s + dy * c);
            (u / a).powi(2) + (v / b).powi(2) <= 1.0
        };
        let inside = pts.iter().filter(|&&(x, y)| in_ellipse(x, y)).count() as f64;
        let (ox, oy) = self.origin;
        let (iw, ih) = (self.image.0 as isize, self.image.1 as isize);
        let reach = a.ceil() as isize + 1;
        let (cx, cy) = (mx.round() as isize, my.round() as isize);
        let mut area = 0.0;
        for y in (cy - reach).max(-oy)..=(cy + reach).min(ih - 1 - oy) {
            for x in (cx - reach).max(-ox)..=(cx + reach).min(iw - 1 - ox) {
                if in_ellipse(x as f64, y as f64) {
                    area += 1.0;
                }
            }
        }
        inside / (area + n - inside)
    }
}

/// Andrew's monotone chain; collinear points dropped.
pub(crate) fn convex_hull(mut pts: Vec<Point>) -> Vec<Point> {
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let turn = |a: Point, b: Point, c: Point| (b - a).cross(c - b);
    let mut hull: Vec<Point> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Point>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) fn ellipse(w: usize, h: usize, c: (f64, f64), a: f64, b: f64) -> Vec<bool> {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64 - c.0, (i / w) as f64 - c.1);
                (x / a).powi(2) + (y / b).powi(2) <= 1.0
            })
            .collect()
    }

    /// A patch that is the whole image.
    pub(crate) fn patch(w: usize, h: usize, px: Vec<bool>) -> Patch {
        Patch {
            w,
            h,
            px,
            origin: (0, 0),
            image: (w, h),
        }
    }

    #[test]
    fn an_ellipse_fits_itself_and_a_peanut_does_not() {
        let one = patch(60, 40, ellipse(60, 40, (30.0, 20.0), 14.0, 8.0));
        assert!(one.ellipse_fit() > 0.95, "{}", one.ellipse_fit());
        let (l, r) = (
            ellipse(60, 40, (20.0, 20.0), 10.0, 9.0),
            ellipse(60, 40, (38.0, 20.0), 10.0, 9.0),
        );
        let two = one.like(l.iter().zip(&r).map(|(&a, &b)| a || b).collect());
        assert!(
            two.ellipse_fit() < one.ellipse_fit() - 0.03,
            "{}",
            two.ellipse_fit()
        );
        // Cut by the image's edge, half an ellipse still fits its own (cut) ellipse.
        let half = Patch {
            origin: (-30, 0),
            image: (30, 40),
            ..one.clone()
        };
        let right: Vec<bool> = (0..60 * 40).map(|i| i % 60 >= 30 && one.px[i]).collect();
        assert!(half.like(right).ellipse_fit() > 0.85);
    }

    #[test]
    fn convex_hull_of_a_square_and_its_centre() {
        let p = |x, y| Point::new(x, y);
        let hull = convex_hull(vec![
            p(0.0, 0.0),
            p(2.0, 0.0),
            p(1.0, 1.0),
            p(2.0, 2.0),
            p(0.0, 2.0),
            p(1.0, 0.0),
        ]);
        assert_eq!(hull.len(), 4);
        assert!((crate::geometry::signed_area(&hull).abs() - 4.0).abs() < 1e-12);
    }
}
