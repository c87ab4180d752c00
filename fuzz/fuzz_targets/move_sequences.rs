//! Fuzzes sequences of vertex moves and removals on a small ring set; every step is
//! checked like the property test (`topocontour::check::run_fuzz_bytes`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Err(e) = topocontour::check::run_fuzz_bytes(data) {
        panic!("{e}");
    }
});
