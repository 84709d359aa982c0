//! Azimuthal scattering in the fibre's normal plane: the exit angle Phi(p, h), the
//! attenuations A_p(h), and the azimuthal roughness distributions D (trimmed logistic and
//! wrapped Gaussian) with their sampling.

mod attenuation;
mod distribution;
mod exit_angle;
mod marschner;
mod path;

pub use attenuation::{
    attenuations, attenuations_at_offset, attenuations_from_fresnel, LOBES_WITH_RESIDUAL,
};
pub use distribution::{
    logistic, logistic_cdf, sample_trimmed_logistic, sample_wrapped_gaussian, trimmed_logistic,
    trimmed_mass, wrapped_gaussian, TrimmedLogistic, WRAPPED_GAUSSIAN_TERMS,
};
pub(crate) use exit_angle::azimuths_from_exit_angles;
pub use exit_angle::{exit_angle, exit_angle_of_offset, refracted_offset};
pub use marschner::{
    marschner_attenuation, marschner_critical_angle, marschner_exit_angle,
    marschner_exit_angle_derivative, marschner_fresnel, marschner_np, marschner_roots, trt_caustic,
    CausticParams, CausticSettings, MarschnerPath, RootList, TrtCaustic, MARSCHNER_MAX_P,
    MIN_DPHI_DH, ROOT_CAPACITY,
};
pub use path::{FibrePath, Refraction};
