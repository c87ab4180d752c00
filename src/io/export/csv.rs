//! Measurements as CSV, one row per region, with the pixel size and calibrated
//! measurements when known. `id` is the object's number, the value of its pixels in the
//! label image ([`super::object_number`]); `contour` is its outer ring's id in the JSON.

use super::{csv_quoted, fmt, object_number, Outputs};
use crate::evolution::regions;

/// `v` in plain decimals (never e-notation, which spreadsheets and some readers take
/// for text) with six significant digits, trailing zeros dropped; empty if not finite.
pub(crate) fn plain(v: f64) -> String {
    if !v.is_finite() {
        return String::new();
    }
    if v == 0.0 {
        return "0".into();
    }
    let decimals = (5 - v.abs().log10().floor() as i64).clamp(0, 330) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').into()
    } else {
        s
    }
}

impl Outputs<'_> {
    /// Measurements, one row per region.
    pub fn csv(&self) -> String {
        let mut s = String::from(
            "image,id,area,perimeter,circularity,centroid_x,centroid_y,holes,pixel_size,unit,area_calibrated,perimeter_calibrated,contour\n",
        );
        let image = csv_quoted(self.image);
        // Calibrated columns stay empty without a pixel size.
        let (size, unit) = match &self.pixel {
            Some(p) => (format!("{}", p.size), csv_quoted(&p.unit)),
            None => (String::new(), String::new()),
        };
        for (k, r) in regions(self.set).iter().enumerate() {
            let (area, perimeter) = match &self.pixel {
                Some(p) => (plain(r.area * p.size * p.size), plain(r.perimeter * p.size)),
                None => (String::new(), String::new()),
            };
            s.push_str(&format!(
                "{image},{},{},{},{},{},{},{},{size},{unit},{area},{perimeter},{}\n",
                object_number(k),
                fmt(r.area),
                fmt(r.perimeter),
                fmt(r.circularity),
                fmt(r.centroid.x),
                fmt(r.centroid.y),
                r.holes.len(),
                r.id
            ));
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::plain;

    #[test]
    fn plain_numbers_have_no_exponent() {
        assert_eq!(plain(0.0), "0");
        assert_eq!(plain(1234.5678), "1234.57");
        assert_eq!(plain(0.000123456789), "0.000123457");
        assert_eq!(plain(1e-12), "0.000000000001");
        assert_eq!(plain(2.5e9), "2500000000");
        assert_eq!(plain(-0.5), "-0.5");
        assert_eq!(plain(f64::INFINITY), "");
    }
}
