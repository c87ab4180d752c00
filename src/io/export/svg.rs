//! SVG: one path per outer ring with its holes, even-odd fill.

use super::{fmt, Outputs};
use crate::contours::ContourId;
use crate::evolution::regions;

impl Outputs<'_> {
    /// SVG: one path per outer ring with its holes, even-odd fill, the image as viewBox.
    pub fn svg(&self) -> String {
        let mut s = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n",
            w = self.width,
            h = self.height
        );
        for r in regions(self.set) {
            let rings: Vec<ContourId> = std::iter::once(r.id)
                .chain(r.holes.iter().copied())
                .collect();
            s.push_str(&format!(
                "  <path id=\"contour-{}\" fill=\"#e8a33d\" fill-opacity=\"0.5\" fill-rule=\"evenodd\" d=\"{}\"/>\n",
                r.id,
                self.path_d(&rings)
            ));
        }
        s.push_str("</svg>\n");
        s
    }

    /// The SVG path of `rings` (absolute moves and lines, closed).
    fn path_d(&self, rings: &[ContourId]) -> String {
        let mut d = String::new();
        for &r in rings {
            for (i, p) in self.set.ring_points(r).iter().enumerate() {
                d.push_str(if i == 0 { "M" } else { "L" });
                d.push_str(&fmt(p.x));
                d.push(' ');
                d.push_str(&fmt(p.y));
            }
            d.push('Z');
        }
        d
    }
}
