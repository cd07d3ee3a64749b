//! The direction configurations of the reference tables in `docs/models.md#reference-values`:
//! `matte tables` prints the kernels' values at them, and the kernels' tests
//! (`tests/kernels/reference_tables.rs`) check those values against the independent float64
//! references that `tests/kernels/reference_tables/generate.py` computes at the same
//! configurations.

/// Table 1's columns: `(θi, θo, Δφ)` in degrees, f at reflectance 0.8.
pub const TABLE1_COLUMNS: [(f32, f32, f32); 10] = [
    (0.0, 0.0, 0.0),
    (30.0, 30.0, 0.0),
    (60.0, 60.0, 0.0),
    (60.0, 60.0, 180.0),
    (45.0, 45.0, 90.0),
    (75.0, 75.0, 0.0),
    (75.0, 75.0, 180.0),
    (80.0, 10.0, 0.0),
    (10.0, 80.0, 0.0),
    (60.0, 20.0, 180.0),
];
