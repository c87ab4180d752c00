//! Image loading: PNG, JPEG, TIFF, 8 and 16 bit, colour to luminance.

use topocontour::io::load_image;

fn tmp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("topocontour-load-{}-{name}", std::process::id()))
}

#[test]
fn sixteen_bit_tiff_keeps_its_precision() {
    let img = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(4, 3, |x, y| {
        image::Luma([(x * 1000 + y * 7) as u16])
    });
    let p = tmp("a.tif");
    img.save(&p).unwrap();
    let f = load_image(&p).unwrap();
    assert_eq!((f.width, f.height), (4, 3));
    assert!((f.at(3, 2) as f64 - 3014.0 / 65535.0).abs() < 1e-6);
}

#[test]
fn colour_png_and_jpeg_become_luminance() {
    let img = image::RgbImage::from_fn(8, 8, |x, _| {
        if x < 4 {
            image::Rgb([255, 255, 255])
        } else {
            image::Rgb([0, 0, 0])
        }
    });
    for ext in ["png", "jpg", "tif"] {
        let p = tmp(&format!("c.{ext}"));
        img.save(&p).unwrap();
        let f = load_image(&p).unwrap();
        assert!(
            f.at(0, 0) > 0.9 && f.at(7, 7) < 0.1,
            "{ext}: {} {}",
            f.at(0, 0),
            f.at(7, 7)
        );
    }
}
