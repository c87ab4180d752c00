//! The image loader on arbitrary bytes: it returns an image or an error, never panics,
//! hangs or allocates beyond its size limit.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(field) = topocontour::io::decode_image(data, "fuzz") {
        assert_eq!(field.data.len(), field.width * field.height);
    }
});
