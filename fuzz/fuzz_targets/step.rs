//! Fuzz target `step`: see `ellipgrid_fuzz::step`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| ellipgrid_fuzz::step(data));
