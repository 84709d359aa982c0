//! Trace tests of the real-time models' closed forms (`hairmath::models`).

#[allow(unused_imports)]
use super::*;

traced_tests! {}
