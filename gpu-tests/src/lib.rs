//! Device tests of the `diffraction` crate's WGSL shaders: see `tests/` and `docs/gpu.md`.
