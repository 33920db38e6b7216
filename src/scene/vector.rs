//! Numbers in scene files: `[x, y, z]` has exactly three, and each fits an f32.
//!
//! serde's own `[f32; 3]` reads the first three elements and never looks further, so
//! `position = [0, 3, 0, 1]` and `target = [0, 1, 0, "junk"]` were accepted with the rest silently
//! dropped. [`Floats`] counts what is there and refuses any other length, saying how many it found.
//!
//! serde's own `f32` turns a finite TOML float beyond f32's range into infinity, so
//! `gravity = [0, 1e39, 0]` was refused as "must be finite, got [0, inf, 0]", a value the file never
//! held. [`Float`] refuses it as written ("1e39"), while `inf` and `nan` pass through to the checks
//! that say which key must be finite.

use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, Deserialize, Deserializer, IgnoredAny, SeqAccess, Visitor};
use serde::{Serialize, Serializer};

/// One number that fits an f32 (integers are accepted and converted; `inf` and `nan` are kept).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Float(pub f32);

struct FloatVisitor;

impl Visitor<'_> for FloatVisitor {
    type Value = Float;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a number within ±3.4e38 (a 32-bit float)")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Float, E> {
        let x = v as f32;
        if v.is_finite() && !x.is_finite() {
            // `{:e}` is short whatever the size: 1e308, not 309 digits.
            return Err(E::custom(format!(
                "{v:e} is beyond what a 32-bit float holds (±3.4e38)"
            )));
        }
        Ok(Float(x))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Float, E> {
        Ok(Float(v as f32))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Float, E> {
        Ok(Float(v as f32))
    }
}

impl<'de> Deserialize<'de> for Float {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_f32(FloatVisitor)
    }
}

/// As an f32: the toml writer prints an f32 in its shortest round-trip form (see `scene::schema`).
impl Serialize for Float {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_f32(self.0)
    }
}

/// Exactly `N` numbers, each a [`Float`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Floats<const N: usize>(pub [f32; N]);

struct FloatsVisitor<const N: usize>(PhantomData<[f32; N]>);

impl<'de, const N: usize> Visitor<'de> for FloatsVisitor<N> {
    type Value = Floats<N>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "an array of exactly {N} numbers")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Floats<N>, A::Error> {
        let mut values = [0.0; N];
        for (i, value) in values.iter_mut().enumerate() {
            *value = seq
                .next_element::<Float>()?
                .ok_or_else(|| de::Error::invalid_length(i, &self))?
                .0;
        }
        let mut extra = 0;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            extra += 1;
        }
        if extra > 0 {
            return Err(de::Error::invalid_length(N + extra, &self));
        }
        Ok(Floats(values))
    }
}

impl<'de, const N: usize> Deserialize<'de> for Floats<N> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_seq(FloatsVisitor::<N>(PhantomData))
    }
}

impl<const N: usize> Serialize for Floats<N> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.0.iter())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Deserialize, Debug)]
    struct Doc {
        v: Floats<3>,
    }

    fn parse(text: &str) -> Result<Floats<3>, String> {
        toml::from_str::<Doc>(text)
            .map(|d| d.v)
            .map_err(|e| e.message().to_owned())
    }

    #[test]
    fn three_numbers_are_read_and_integers_converted() {
        assert_eq!(parse("v = [1, 2.5, -3]"), Ok(Floats([1.0, 2.5, -3.0])));
    }

    #[test]
    fn any_other_length_is_refused_with_the_length_found() {
        assert_eq!(
            parse("v = [0, 3, 0, 1]").unwrap_err(),
            "invalid length 4, expected an array of exactly 3 numbers"
        );
        assert_eq!(
            parse("v = [0, 3]").unwrap_err(),
            "invalid length 2, expected an array of exactly 3 numbers"
        );
        assert!(
            parse("v = [0, 1, 0, \"junk\"]")
                .unwrap_err()
                .contains("length 4")
        );
    }

    #[test]
    fn a_finite_number_beyond_f32_is_refused_as_written_and_infinity_is_kept() {
        assert_eq!(
            parse("v = [0, 1e308, 0]").unwrap_err(),
            "1e308 is beyond what a 32-bit float holds (±3.4e38)"
        );
        assert_eq!(
            parse("v = [-3.5e38, 0, 0]").unwrap_err(),
            "-3.5e38 is beyond what a 32-bit float holds (±3.4e38)"
        );
        let v = parse("v = [-inf, 3.4e38, 7]").unwrap().0;
        assert_eq!(v, [f32::NEG_INFINITY, 3.4e38, 7.0]);
        assert!(parse("v = [nan, 0, 0]").unwrap().0[0].is_nan());
    }

    #[test]
    fn a_wrong_element_type_is_refused() {
        assert!(
            parse("v = [0, \"x\", 0]")
                .unwrap_err()
                .contains("invalid type")
        );
    }
}
