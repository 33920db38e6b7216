//! The corpus of `nudge::bench::corpus` at the default knobs: every member of every family within
//! its tolerance. One test per family; a failure lists every member that missed, with what it
//! measured.

use nudge::bench::corpus::{self, Family};
use nudge::bench::hard_case::Knobs;

/// Runs every member of `family` at the defaults and panics listing those over their tolerance.
fn holds(family: Family) {
    let mut failures = Vec::new();
    for member in &family.members {
        let out = (member.run)(Knobs::default());
        eprintln!(
            "{}: {} error {:.5} (tolerance {}) {}",
            family.name, member.label, out.error, member.tolerance, out.detail
        );
        if !corpus::within(out.error, member.tolerance) {
            failures.push(format!(
                "{}: error {} > {}: {}",
                member.label, out.error, member.tolerance, out.detail
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} ({}):\n{}",
        family.name,
        family.answer,
        failures.join("\n")
    );
}

/// The family of `corpus::families()` named `name`.
fn family(name: &str) -> Family {
    corpus::families()
        .into_iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no family named {name}"))
}

#[test]
fn balls_meeting_head_on_leave_as_the_impact_law_says() {
    holds(family("balls head-on"));
}

#[test]
fn a_ball_hitting_a_moving_box_leaves_as_the_impact_law_says() {
    holds(family("ball hits moving box"));
}
