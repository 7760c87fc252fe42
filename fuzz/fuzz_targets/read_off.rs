//! Feeds arbitrary bytes to the OFF reader and checks its guarantees whenever it accepts
//! them (see `envelope_fuzz::check_reader`). A failure prints the input as a pasteable Rust
//! byte string.
#![no_main]

use envelope_io::Format;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Err(why) = envelope_fuzz::check_reader(data, Format::Off) {
        envelope_fuzz::fail_with_input(&why, data);
    }
});
