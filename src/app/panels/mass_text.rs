//! Masses as the status bar says them: under a kilogram, grams to three significant digits, so a
//! body shrunk to 5 cm reads "65.4 g", not "0.000 kg".

/// "5.0 kg", "524 g", "0.520 g" (kilograms keep one decimal, as the bar always wrote them).
pub fn mass(kg: f32) -> String {
    if kg >= 1.0 {
        return format!("{kg:.1} kg");
    }
    let g = kg * 1e3;
    // Three significant digits: two decimals more than the leading digit's place.
    let lead = if g > 0.0 { g.log10().floor() as i32 } else { 0 };
    let decimals = (2 - lead).clamp(0, 9) as usize;
    format!("{g:.decimals$} g")
}

#[cfg(test)]
mod tests {
    use super::mass;

    #[test]
    fn small_masses_keep_three_significant_digits_in_grams() {
        assert_eq!(mass(5.0), "5.0 kg");
        assert_eq!(mass(250.0), "250.0 kg");
        assert_eq!(mass(0.524), "524 g");
        assert_eq!(mass(0.0654), "65.4 g");
        assert_eq!(mass(0.00052), "0.520 g");
        assert_eq!(mass(0.0000032), "0.00320 g");
        assert_eq!(mass(0.0), "0.00 g");
    }
}
