//! Fuzz target `vtk`: see `ellipgrid_fuzz::vtk`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| ellipgrid_fuzz::vtk(data));
