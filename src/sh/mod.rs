//! Real spherical harmonics: evaluation, projection, rotation, exact Wigner 3-j symbols, Gaunt
//! coefficients and products.
//!
//! Convention (DESIGN.md): real, orthonormal SH with the Condon-Shortley phase, coefficient
//! index `l (l + 1) + m`, `sin(|m| phi)` for m < 0 (the convention of google/spherical-harmonics,
//! Sloan and DirectXMath). For example `Y(1, -1) = -0.4886025 y`.

pub mod basis;
pub mod projection;
pub mod rotation;
pub mod window;

pub mod gaunt;
pub mod product;
pub mod wigner;
