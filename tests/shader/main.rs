//! Executes and validates generated shader code without a GPU.
//!
//! - [`gpu`]: the tests' headless WebGPU device (`hairmath::device`, Mesa's llvmpipe in CI),
//!   which runs a WGSL module written to the emitter's binding contract and reads its RGB rows
//!   back, and times dispatches; the tolerances of the WGSL accuracy rules for comparing with the
//!   CPU.
//! - [`tools`]: `glslangValidator` and `spirv-val` on naga's GLSL and SPIR-V output.
//!
//! Under `CI=true` a missing Vulkan adapter or validator fails the tests; elsewhere they are
//! skipped with a message on stderr.

mod committed;
mod error_bound;
mod gerard_sh;
mod gpu;
mod models;
#[cfg(feature = "plan")]
mod plan;
mod tools;
