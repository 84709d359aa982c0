//! Scene plans: the cheapest composition of per-lobe, per-factor choices whose error against
//! Chiang et al. 2016's far field stays within a budget over the hair a scene contains, by
//! weighted operation counts (`cost = "ops"`) or by time measured on Mesa's llvmpipe among the
//! cheapest by operations (`cost = "llvmpipe"`, through [`crate::device`]).

mod catalogue;
mod measure;
mod published;
mod scene;
mod search;

pub use catalogue::*;
pub use measure::*;
pub use published::*;
pub use scene::*;
pub use search::*;
