//! Fuzz target `plot3d`: see `ellipgrid_fuzz::plot3d`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| ellipgrid_fuzz::plot3d(data));
