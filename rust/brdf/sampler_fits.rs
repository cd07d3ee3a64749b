//! placeholder
use super::cltc::CltcFit;
pub const OREN_NAYAR_QUALITATIVE: CltcFit<4, 3> =
    CltcFit { coefficients: [[[0.0; 3]; 4]; 5], free_at_normal: [false; 5] };
pub const OREN_NAYAR_FULL: CltcFit<4, 3> = CltcFit { coefficients: [[[0.0; 3]; 4]; 5], free_at_normal: [false; 5] };
pub const GINNEKEN_VGINNEKEN: CltcFit<4, 3> = CltcFit { coefficients: [[[0.0; 3]; 4]; 5], free_at_normal: [false; 5] };
pub const GINNEKEN_HEIGHT_CORRELATED: CltcFit<4, 3> =
    CltcFit { coefficients: [[[0.0; 3]; 4]; 5], free_at_normal: [false; 5] };
