//! Fragment stage: lights, per-drawable looks and the colour of a lit surface point.
//!
//! All lighting is done in world space: normals are rotated by the body's rotation only (never
//! translated or scaled: box faces stay axis-aligned in body space, spheres scale uniformly), and the
//! lights are fixed world directions.

use glam::Vec3;

use super::{Drawable, Material};
use crate::color::Rgb;
use crate::geometry::Shape;

/// A directional key light, a weaker fill light from the other side, and ambient.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lights {
    /// Direction the key light travels (from the light into the scene), unit length. Shadows fall
    /// along it.
    pub key_dir: Vec3,
    /// Key light colour × intensity, linear factors.
    pub key: Vec3,
    /// Direction the fill light travels, unit length.
    pub fill_dir: Vec3,
    pub fill: Vec3,
    pub ambient: Vec3,
    /// Strength of the key light's Blinn–Phong highlight (smooth and textured modes).
    pub specular: f32,
}

impl Default for Lights {
    /// Key from above, left and in front of the default cameras (which look along +z); fill from the
    /// right and behind.
    fn default() -> Self {
        Self {
            key_dir: Vec3::new(0.45, -1.0, 0.55).normalize(),
            key: Vec3::new(0.78, 0.74, 0.66),
            fill_dir: Vec3::new(-0.7, -0.25, -0.45).normalize(),
            fill: Vec3::new(0.20, 0.23, 0.28),
            ambient: Vec3::new(0.30, 0.30, 0.33),
            specular: 0.35,
        }
    }
}

impl Lights {
    /// Ambient plus Lambert terms of both lights for unit normal `n`.
    #[inline]
    pub fn diffuse(&self, n: Vec3) -> Vec3 {
        self.ambient
            + self.key * (-n.dot(self.key_dir)).max(0.0)
            + self.fill * (-n.dot(self.fill_dir)).max(0.0)
    }

    /// Blinn–Phong highlight of the key light (exponent 32) for unit normal `n` and unit direction
    /// `to_eye` from the surface to the eye.
    #[inline]
    pub fn highlight(&self, n: Vec3, to_eye: Vec3) -> f32 {
        if n.dot(self.key_dir) >= 0.0 {
            return 0.0;
        }
        let h = (to_eye - self.key_dir).normalize_or_zero();
        let mut s = n.dot(h).max(0.0);
        for _ in 0..5 {
            s *= s;
        }
        s * self.specular
    }

    /// Colour of a surface of albedo `base` with unit normal `n` seen from `to_eye`.
    #[inline]
    pub fn shade(&self, base: Vec3, n: Vec3, to_eye: Vec3) -> Vec3 {
        base * self.diffuse(n) + self.key * self.highlight(n, to_eye)
    }
}

/// Icy blue that frozen drawables are mixed toward.
pub const ICE: Vec3 = Vec3::new(0.62, 0.85, 1.0);

/// How one drawable looks, resolved once per frame: albedo with state tints applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Look {
    /// Albedo in [0, 1]³ (may exceed 1 slightly when highlighted; clamped at output).
    pub base: Vec3,
    pub material: Material,
    pub is_sphere: bool,
}

impl Look {
    pub fn of(d: &Drawable) -> Self {
        let [r, g, b] = d.color.to_unit();
        let mut base = Vec3::new(r, g, b);
        if d.frozen {
            base = base.lerp(ICE, 0.6);
        }
        if d.asleep {
            base *= 0.72;
        }
        if d.highlighted {
            base = base * 1.2 + Vec3::splat(0.12);
        }
        Self {
            base,
            material: d.material,
            is_sphere: matches!(d.shape, Shape::Sphere { .. }),
        }
    }
}

/// Converts a linear colour to an output pixel (clamped; NaN → 0).
#[inline]
pub fn to_rgb(c: Vec3) -> Rgb {
    Rgb::from_unit(c.to_array())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose;

    #[test]
    fn a_face_toward_the_key_light_is_brighter_than_one_away_from_it() {
        let lights = Lights::default();
        let toward = lights.diffuse(-lights.key_dir);
        let away = lights.diffuse(lights.key_dir);
        assert!(toward.x > away.x + 0.5);
        assert!(
            away.min_element() > 0.0,
            "ambient and fill keep back faces visible"
        );
    }

    #[test]
    fn state_flags_change_the_look() {
        let mut d = Drawable::new(
            Shape::cuboid(Vec3::ONE),
            Pose::IDENTITY,
            Rgb::new(200, 100, 50),
            1,
        );
        let plain = Look::of(&d).base;
        d.frozen = true;
        let frozen = Look::of(&d).base;
        assert!(frozen.z > plain.z + 0.3, "frozen bodies turn blue");
        d.frozen = false;
        d.asleep = true;
        assert!(Look::of(&d).base.x < plain.x);
        d.asleep = false;
        d.highlighted = true;
        assert!(Look::of(&d).base.x > plain.x);
    }
}
