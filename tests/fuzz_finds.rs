//! Inputs the fuzzer (`fuzz/`, target `move_sequences`) once failed on, replayed as
//! named regression tests.

fn replay(name: &str) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_finds")
        .join(name);
    let data = std::fs::read(path).unwrap();
    topocontour::check::run_fuzz_bytes(&data).unwrap();
}

/// Fuzz find: an outer ring ended up nested directly inside another outer ring.
#[test]
fn fuzz_find_outer_inside_outer() {
    replay("outer_inside_outer.bin");
}
