//! The instruction set batch kernels run on, chosen at run time.
//!
//! [`crate::bcsdf::HostBatch`] instantiates a model on the lanes of the host's widest
//! instruction set ([`InstructionSet::host`], detected once per process) and runs its kernel
//! inside [`with_avx512`] or [`with_avx2`], functions compiled with those target features.
//! Only code inlined into them gets the features (and only there do the intrinsics of
//! [`super::isa`] inline), so the job's closure is `#[inline(always)]`, and so is every
//! function a kernel calls on its hot path: a function that is not inlined is compiled once,
//! with the build's baseline features, and calls each intrinsic out of line.

use std::sync::OnceLock;

/// An instruction set a batch kernel can run on: what [`InstructionSet::host`] detects, and
/// what a [`crate::bcsdf::HostBatch`] evaluates with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum InstructionSet {
    /// x86-64 with AVX-512 (F, VL, BW, DQ), AVX2, FMA, BMI1/2, LZCNT and POPCNT: 16 lanes per
    /// register.
    Avx512,
    /// x86-64 with AVX2, FMA, BMI1/2, LZCNT and POPCNT: 8 lanes per register.
    Avx2,
    /// The target features the crate is compiled with (SSE2 for a default x86-64 build, NEON on
    /// aarch64).
    Baseline,
}

impl InstructionSet {
    /// Every instruction set, widest first.
    pub const ALL: [InstructionSet; 3] = [
        InstructionSet::Avx512,
        InstructionSet::Avx2,
        InstructionSet::Baseline,
    ];

    /// The widest instruction set this CPU supports, detected on the first call.
    pub fn host() -> InstructionSet {
        static HOST: OnceLock<InstructionSet> = OnceLock::new();
        *HOST.get_or_init(|| {
            InstructionSet::ALL
                .into_iter()
                .find(|set| set.is_supported())
                .unwrap_or(InstructionSet::Baseline)
        })
    }

    /// Whether this CPU runs the instruction set.
    pub fn is_supported(self) -> bool {
        match self {
            #[cfg(target_arch = "x86_64")]
            InstructionSet::Avx512 => {
                InstructionSet::Avx2.is_supported()
                    && std::is_x86_feature_detected!("avx512f")
                    && std::is_x86_feature_detected!("avx512vl")
                    && std::is_x86_feature_detected!("avx512bw")
                    && std::is_x86_feature_detected!("avx512dq")
            }
            #[cfg(target_arch = "x86_64")]
            InstructionSet::Avx2 => {
                std::is_x86_feature_detected!("avx2")
                    && std::is_x86_feature_detected!("fma")
                    && std::is_x86_feature_detected!("bmi1")
                    && std::is_x86_feature_detected!("bmi2")
                    && std::is_x86_feature_detected!("lzcnt")
                    && std::is_x86_feature_detected!("popcnt")
            }
            InstructionSet::Baseline => true,
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }
}

/// `job` compiled with AVX-512 ([`InstructionSet::Avx512`]); the caller checks that the CPU
/// supports it ([`InstructionSet::is_supported`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl,avx512bw,avx512dq,avx2,fma,bmi1,bmi2,lzcnt,popcnt")]
pub(crate) fn with_avx512<T>(job: impl FnOnce() -> T) -> T {
    job()
}

/// `job` compiled with AVX2 and FMA ([`InstructionSet::Avx2`]); the caller checks that the
/// CPU supports it.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt,popcnt")]
pub(crate) fn with_avx2<T>(job: impl FnOnce() -> T) -> T {
    job()
}
