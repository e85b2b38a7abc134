//! Fuzz target `conn`: see `ellipgrid_fuzz::conn`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| ellipgrid_fuzz::conn(data));
