//! Uniform random numbers from a seeded PCG generator, for the code that draws samples (the
//! swatch path tracer, the test kit's sampling harnesses).

use crate::bcsdf::RandomNumbers;
use rand_pcg::rand_core::RngCore;
use rand_pcg::Pcg64Mcg;

/// A uniform number in `[0, 1)` from `rng` (53 random bits).
pub(crate) fn uniform(rng: &mut Pcg64Mcg) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// The four uniform numbers one importance sample consumes.
pub(crate) fn random_numbers(rng: &mut Pcg64Mcg) -> RandomNumbers<f64> {
    RandomNumbers {
        lobe: uniform(rng),
        longitudinal: uniform(rng),
        cone: uniform(rng),
        offset: uniform(rng),
    }
}
