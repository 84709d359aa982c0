//! The Wigner argument parser ([`hairmath::sh::HalfInt`]'s `FromStr`) on arbitrary text: no
//! panic, and a parsed value prints as text that parses back to it.
#![no_main]

use hairmath::sh::HalfInt;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    if let Ok(value) = text.parse::<HalfInt>() {
        let again: HalfInt = value.to_string().parse().expect("a printed value parses");
        assert_eq!(again, value, "{text:?}");
    }
});
