//! Images of grooms, for measuring shading techniques against a reference (Gerard's section 4:
//! "a path-traced reference render using the single scattering approximation"): an
//! orthographic camera, the first strand each pixel's ray meets, a procedural sky and a
//! directional light, and three ways to shade the hit point ([`shading`]):
//!
//! - the reference, Gerard's "ground truth" (single scattering): the integral over the sphere
//!   of `L_env(w) V(x, w) S(w, wo)` with the exact transmittance (the strands' cylinders,
//!   [`crate::strands::occluders`]) and the Chiang far field as `S`, plus the light's
//!   `L V(x, wl) S(wl, wo)`. [`meridian`] integrates it along great circles, `V` in closed
//!   form along each ([`crate::strands::pencil`]), which converges where a rule of points
//!   cannot (the strands' shadows are thinner than any practical spacing of directions);
//!   [`shading::reference_radiance`] by a Fibonacci rule of equal weights, the independent
//!   check of the smooth part;
//! - Gerard's shading ([`crate::models::gerard_sh::GerardSh`]) with the transmittance's baked
//!   coefficients interpolated along the segment (as a rasteriser interpolates vertex
//!   attributes) and the sky projected to spherical harmonics;
//! - a classic model (Kajiya-Kay) given the same inputs as Gerard's: `V` from the same
//!   coefficients, the sky itself integrated by a Fibonacci rule.
//!
//! [`compare_gerard`] renders the three and measures the two approximations against the
//! reference.
//!
//! [`swatch`] renders a procedural hair swatch two ways: a path tracer with the Chiang model
//! (multiple importance sampling, Russian roulette) and a single-scattering direct-light
//! shader for any model, under the same light.
//!
//! Conventions: the camera looks along -Z, so every hit is seen from `wo = +Z`; the shading
//! point is the point of the strand's axis nearest to the ray's entry into its cylinder (the
//! points a transmittance bake samples are on the axis); the first hit is shaded opaque (no
//! transparency compositing), the same for every technique, so that the images differ only by
//! the shading.

mod camera;
mod comparison;
mod image;
mod lighting;
pub mod meridian;
mod output;
pub mod shading;
pub mod swatch;

pub use camera::{first_hits, Camera, Hit};
#[cfg(feature = "fit")]
pub use comparison::kajiya_kay_best_fit;
pub use comparison::{
    compare_gerard, gerard_graph, gerard_ops, phase_projection_error, Approximations,
    GerardComparison, GerardConfig, GerardRender, GerardScene, GerardSources, PhaseAbsorption,
    RenderSettings, Stage,
};
pub use image::{image_error, render, Image, ImageError};
pub use lighting::{DirectionalLight, Sky, UP};
pub use meridian::{meridian_radiance, MeridianRule};
pub use output::side_by_side;
#[cfg(feature = "png")]
pub use output::write_png;
