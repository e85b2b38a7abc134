//! Fuzz target `smooth`: see `ellipgrid_fuzz::smooth`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| ellipgrid_fuzz::smooth(data));
