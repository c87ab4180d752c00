//! Session files on arbitrary bytes: parsing returns a session or an error; a session
//! that parses runs its job (on a small image of its own, for at most 30 frames) to a
//! result or an error, never a panic, a hang or an allocation beyond the limits.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;
use topocontour::evolution::Field;
use topocontour::io::session::Session;
use topocontour::io::ImageInfo;
use topocontour::job::Stop;

fuzz_target!(|data: &[u8]| {
    let Ok(session) = Session::parse(data, Path::new("fuzz.json")) else {
        return;
    };
    let mut job = session.job(Path::new("fuzz.json"), None);
    job.stop = Stop::AtFrame(session.frames.min(30));
    // A dark disc on a bright background, 48²: what the shapes meet.
    let data = (0..48 * 48)
        .map(|i| {
            let (x, y) = ((i % 48) as f32 - 24.0, (i / 48) as f32 - 24.0);
            if x * x + y * y < 100.0 {
                40.0
            } else {
                200.0
            }
        })
        .collect();
    let info = ImageInfo {
        pages: 1,
        pixel_size: None,
    };
    if let Ok(run) = job.run_on(Field::new(48, 48, data), info) {
        assert!(run.ev.contours().contour_count() < 1 << 20);
    }
});
