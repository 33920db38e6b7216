//! Fixed-length number arrays in scene files: `[x, y, z]` has exactly three numbers.
//!
//! serde's own `[f32; 3]` reads the first three elements and never looks further, so
//! `position = [0, 3, 0, 1]` and `target = [0, 1, 0, "junk"]` were accepted with the rest silently
//! dropped. [`Floats`] counts what is there and refuses any other length, saying how many it found.

use std::fmt;
use std::marker::PhantomData;

use serde::de::{self, Deserialize, Deserializer, IgnoredAny, SeqAccess, Visitor};
use serde::{Serialize, Serializer};

/// Exactly `N` numbers (integers are accepted and converted).
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
                .next_element()?
                .ok_or_else(|| de::Error::invalid_length(i, &self))?;
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
    fn a_wrong_element_type_is_refused() {
        assert!(
            parse("v = [0, \"x\", 0]")
                .unwrap_err()
                .contains("invalid type")
        );
    }
}
