//! The corpus section of `nudge bench physics`: each family's worst error against ms/step, for
//! sub-steps 1, 2, 4 and 8 (one iteration, sleeping off, like the hard-case sweep).

use std::io::{self, Write};

use serde::Serialize;

use crate::bench::table::Table;
use crate::testing::corpus::{Unit, families, worst};
use crate::testing::hard_case::Knobs;

/// Sub-step counts the corpus is swept over.
pub const SUBSTEPS: [u32; 4] = [1, 2, 4, 8];

/// One family at one sub-step count.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CorpusRow {
    /// The family's name.
    pub family: String,
    /// Members in the family.
    pub members: usize,
    /// Sub-steps per step of this run.
    pub substeps: u32,
    /// Mean over the members of their median ms per step.
    #[serde(serialize_with = "crate::bench::physics::rounded_ms")]
    pub ms_per_step: f64,
    /// The worst member's error (NaN if some run failed to measure), in `unit`.
    pub worst_error: f32,
    /// What the error is measured in ("relative" or "metres" in JSON).
    pub unit: Unit,
    /// The worst member's label.
    pub worst_member: String,
    /// Members over their tolerance at these knobs.
    pub failing: usize,
}

/// Runs every family at every sub-step count of [`SUBSTEPS`] (progress on stderr).
pub fn run() -> Vec<CorpusRow> {
    let mut rows = Vec::new();
    for family in families() {
        for substeps in SUBSTEPS {
            crate::bench::progress!(
                "bench physics: corpus {} substeps={substeps}          \r",
                family.name
            );
            let knobs = Knobs {
                substeps,
                iterations: 1,
                sleep: false,
                ..Knobs::default()
            };
            let summary = worst(&family, knobs);
            rows.push(CorpusRow {
                family: family.name.to_string(),
                members: family.members.len(),
                substeps,
                ms_per_step: summary.ms_per_step,
                worst_error: summary.error,
                unit: family.unit,
                worst_member: summary.label,
                failing: summary.failing,
            });
        }
    }
    rows
}

/// Prints the rows as a table.
pub fn print_table(rows: &[CorpusRow], out: &mut dyn Write) -> io::Result<()> {
    writeln!(
        out,
        "physics: corpus (worst member per family, error relative or in mm; sleeping off)"
    )?;
    let mut table = Table::new(&[
        "family",
        "members",
        "substeps",
        "ms/step",
        "worst error",
        "worst member",
        "failing",
    ]);
    for row in rows {
        table.push(vec![
            row.family.clone(),
            row.members.to_string(),
            row.substeps.to_string(),
            format!("{:.4}", row.ms_per_step),
            row.unit.format(row.worst_error),
            row.worst_member.clone(),
            row.failing.to_string(),
        ]);
    }
    table.write(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_shows_relative_errors_in_percent_and_lengths_in_millimetres() {
        let row = |family: &str, unit, worst_error| CorpusRow {
            family: family.into(),
            members: 1,
            substeps: 4,
            ms_per_step: 0.01,
            worst_error,
            unit,
            worst_member: "m".into(),
            failing: 0,
        };
        let mut out = Vec::new();
        print_table(
            &[
                row("spin", Unit::Relative, 0.0123),
                row("tower", Unit::Metres, 0.0321),
            ],
            &mut out,
        )
        .unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(text.contains("1.230%"), "{text}");
        assert!(text.contains("32.1000 mm"), "{text}");
    }
}
