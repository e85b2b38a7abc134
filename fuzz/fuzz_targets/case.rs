//! Fuzz target `case`: see `ellipgrid_fuzz::case`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| ellipgrid_fuzz::case(data));
