//! Image loading: PNG, JPEG, TIFF, 8 and 16 bit, colour to luminance.

mod common;

use topocontour::io::load_image;

/// The path `name` in a fresh folder of its own, removed with the returned guard.
fn tmp(name: &str) -> common::Scratch {
    common::Scratch::file(name)
}

#[test]
fn sixteen_bit_tiff_keeps_its_precision() {
    let img = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(4, 3, |x, y| {
        image::Luma([(x * 10000 + y * 7) as u16])
    });
    let p = tmp("a.tif");
    img.save(&p).unwrap();
    let f = load_image(&p).unwrap();
    assert_eq!((f.width, f.height), (4, 3));
    assert!((f.at(3, 2) as f64 - 30014.0 / 65535.0).abs() < 1e-6);
}

#[test]
fn a_sixteen_bit_image_of_a_narrow_range_reads_as_its_full_range() {
    // A camera's 97–276 in a 16-bit file: read as it is, its contrast is below the
    // model's least and the whole image was one object.
    let disk = |x: u32, y: u32| (x as f64 - 16.0).hypot(y as f64 - 16.0) < 8.0;
    let img = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(32, 32, |x, y| {
        image::Luma([if disk(x, y) { 97 } else { 276 }])
    });
    let p = tmp("narrow.tif");
    img.save(&p).unwrap();
    let f = load_image(&p).unwrap();
    assert_eq!((f.at(16, 16), f.at(1, 1)), (0.0, 1.0));
    // An array handed over (Python, napari) reads the same.
    let v: Vec<u16> = img.into_raw();
    let g = topocontour::io::field_from_samples("a", 32, 32, topocontour::io::Samples::U16(&v));
    assert_eq!(g.unwrap().data, f.data);
    let json = tmp("narrow.json");
    let out = common::bin()
        .args(["segment", "--object", "dark", "--auto-seeds", "--json"])
        .arg(&*json)
        .arg(&*p)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains(": 1 object,"), "{err}");
}

#[test]
fn a_few_bright_pixels_on_a_dim_ground_stay_brighter_than_it() {
    // Three pixels of 25 on a ground of 5 (8-bit): under 0.1 % of the image, so a
    // 99.9 % quantile would clamp them into the ground; the stretch goes by the extremes.
    let img = image::GrayImage::from_fn(64, 64, |x, y| {
        image::Luma([if y == 10 && (10..13).contains(&x) {
            25
        } else {
            5
        }])
    });
    let p = tmp("dim.png");
    img.save(&p).unwrap();
    let f = load_image(&p).unwrap();
    assert_eq!((f.at(11, 10), f.at(40, 40)), (1.0, 0.0));
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

/// A little-endian 8-bit RGB TIFF of `pages` pages of `w`×`h`, each stored as three
/// planes one after the other (PlanarConfiguration 2, as tifffile writes a (3, H, W)
/// array): red `r`, green `g`, blue `b` everywhere.
fn planar_rgb(pages: usize, w: u32, h: u32, (r, g, b): (u8, u8, u8)) -> Vec<u8> {
    let mut out = b"II*\0\0\0\0\0".to_vec();
    let plane = w * h;
    let mut dirs = Vec::new();
    for _ in 0..pages {
        let data = out.len() as u32;
        for v in [r, g, b] {
            out.extend(std::iter::repeat_n(v, plane as usize));
        }
        let bits = out.len() as u32;
        out.extend([8u16, 8, 8].iter().flat_map(|v| v.to_le_bytes()));
        let offsets = out.len() as u32;
        out.extend((0..3).flat_map(|k| (data + k * plane).to_le_bytes()));
        let counts = out.len() as u32;
        out.extend((0..3).flat_map(|_| plane.to_le_bytes()));
        dirs.push((bits, offsets, counts));
    }
    let first = out.len() as u32;
    out[4..8].copy_from_slice(&first.to_le_bytes());
    for (i, (bits, offsets, counts)) in dirs.into_iter().enumerate() {
        let entries: [(u16, u16, u32, u32); 10] = [
            (256, 4, 1, w),
            (257, 4, 1, h),
            (258, 3, 3, bits),
            (259, 3, 1, 1),
            (262, 3, 1, 2),
            (273, 4, 3, offsets),
            (277, 3, 1, 3),
            (278, 4, 1, h),
            (279, 4, 3, counts),
            (284, 3, 1, 2),
        ];
        common::tiff_directory(&mut out, &entries, i + 1 == pages);
    }
    out
}

#[test]
fn planar_rgb_pages_become_luminance_of_all_three_planes() {
    let p = tmp("planar.tif");
    std::fs::write(&p, planar_rgb(2, 6, 4, (255, 0, 0))).unwrap();
    // Page 2 is decoded here, page 1 by the image crate: both read red, not the first
    // plane as grey (1.0) nor a refusal.
    for page in 0..2 {
        let (f, info) = topocontour::io::load_image_page(&p, page).unwrap();
        assert_eq!((f.width, f.height, info.pages), (6, 4, 2));
        assert!(
            (f.at(2, 1) - 0.2126).abs() < 1e-3,
            "page {page}: {}",
            f.at(2, 1)
        );
    }
}

#[test]
fn a_movie_of_one_colour_page_says_so() {
    // Three frames written as one (3, H, W) array become one RGB page.
    let (p, out) = (tmp("one-colour-page.tif"), tmp("one-colour-page-out"));
    std::fs::write(&p, planar_rgb(1, 16, 16, (10, 200, 30))).unwrap();
    common::refused(
        common::bin()
            .arg("track")
            .arg(&*p)
            .args(["--object", "dark", "--ctc"])
            .arg(&*out),
        "one page of 3 samples per pixel",
    );
    assert!(!out.exists());
}
