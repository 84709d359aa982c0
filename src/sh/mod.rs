//! Real spherical harmonics: evaluation, projection, rotation, exact Wigner 3-j symbols, Gaunt
//! coefficients and products.
//!
//! Convention (docs/ARCHITECTURE.md): real, orthonormal SH with the Condon-Shortley phase, coefficient
//! index `l (l + 1) + m`, `sin(|m| phi)` for m < 0 (the convention of google/spherical-harmonics,
//! Sloan and DirectXMath). For example `Y(1, -1) = -0.4886025 y`.

mod basis;
mod gaunt;
mod product;
mod projection;
mod rotation;
mod wigner;
mod window;

pub use basis::*;
pub use gaunt::*;
pub use product::*;
pub use projection::*;
pub use rotation::*;
pub use wigner::*;
pub use window::*;
