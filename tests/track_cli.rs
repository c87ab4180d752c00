//! `topocontour track` on small 16-bit TIFF movies made here: the Cell Tracking Challenge
//! layout it writes, and bad movies refused with one line, exit 2 and no output.

use std::path::{Path, PathBuf};
use std::process::Command;
use tiff::encoder::{colortype::Gray16, TiffEncoder};

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("topocontour-track-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// A 16-bit movie in a narrow range (100 background, 260 cells, as a dim camera gives):
/// page t holds a disk at x = 30 + 2t of size `sizes[t]`.
fn movie(path: &Path, sizes: &[(u32, u32)]) {
    let mut enc = TiffEncoder::new(std::fs::File::create(path).unwrap()).unwrap();
    for (t, &(w, h)) in sizes.iter().enumerate() {
        let cx = 30.0 + 2.0 * t as f64;
        let data: Vec<u16> = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                if (x - cx).hypot(y - 32.0) < 12.0 {
                    260
                } else {
                    100
                }
            })
            .collect();
        enc.write_image::<Gray16>(w, h, &data).unwrap();
    }
}

fn track(movie: &Path, out: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_topocontour"))
        .args([
            "track",
            &movie.display().to_string(),
            "--object",
            "bright",
            "--ctc",
        ])
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn a_sixteen_bit_movie_gives_the_ctc_layout() {
    let (m, out) = (tmp("ok.tif"), tmp("ok-res"));
    movie(&m, &[(80, 64); 4]);
    let run = track(&m, &out);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(out.join("res_track.txt")).unwrap(),
        "1 0 3 0\n"
    );
    for t in 0..4 {
        let mask = image::open(out.join(format!("mask{t:03}.tif")))
            .unwrap()
            .into_luma16();
        assert_eq!(mask.dimensions(), (80, 64));
        let cx = 30 + 2 * t;
        assert_eq!(mask.get_pixel(cx, 32).0[0], 1, "frame {t}");
        assert_eq!(mask.get_pixel(2, 2).0[0], 0);
    }
}

#[test]
fn bad_movies_are_refused_before_any_output() {
    for (name, sizes, says) in [
        ("one", vec![(80, 64)], "at least two"),
        ("sizes", vec![(80, 64), (80, 64), (64, 64)], "same size"),
    ] {
        let (m, out) = (tmp(&format!("{name}.tif")), tmp(&format!("{name}-res")));
        movie(&m, &sizes);
        let run = track(&m, &out);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{name}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(says), "{err}");
        assert!(!out.exists(), "{name}: output written");
    }
    // A page that does not decode: the file cut in the middle of the second page's data.
    let (m, out) = (tmp("cut.tif"), tmp("cut-res"));
    movie(&m, &[(80, 64); 3]);
    let bytes = std::fs::read(&m).unwrap();
    std::fs::write(&m, &bytes[..bytes.len() * 5 / 12]).unwrap();
    let run = track(&m, &out);
    assert_eq!(run.status.code(), Some(2));
    assert!(!out.exists());
}
