//! Geometric vocabulary shared by shapes, emitters and integrators: rays with Mitsuba's
//! self-intersection offsets, orthonormal frames and the sample warps.

pub mod orthonormal_frame;
pub mod ray;
pub mod warp;

pub use orthonormal_frame::Frame;
pub use ray::Ray;
