#![no_main]
// Placeholder: the real target is written with its crate.
libfuzzer_sys::fuzz_target!(|_data: &[u8]| {});
