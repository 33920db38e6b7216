//! The README's controls table against the key table (`app::input::keys`): every input the app takes is in
//! the README, and the README names no input the app does not take. The key map used to live in
//! three places that drifted apart.

use nudge::app::input::keys::readme_names;

/// The first column of each row of the README's controls table.
fn readme_inputs() -> Vec<String> {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let section = readme
        .split("\n## Controls\n")
        .nth(1)
        .expect("a Controls section");
    section
        .lines()
        .skip_while(|line| !line.starts_with('|'))
        .take_while(|line| line.starts_with('|'))
        // The header and the rule under it.
        .skip(2)
        .map(|row| row.split('|').nth(1).unwrap().trim().to_string())
        .collect()
}

#[test]
fn the_readme_controls_table_names_every_input_of_the_key_table_and_no_other() {
    let mut names = readme_names();
    // Longest first, so `Tab` is not found inside `Shift+Tab`, nor `s` inside Shift+`s`.
    names.sort_by_key(|name| std::cmp::Reverse(name.len()));
    let mut found = vec![false; names.len()];
    let inputs = readme_inputs();
    assert!(inputs.len() > 10, "{inputs:?}");
    for cell in &inputs {
        let mut rest = cell.clone();
        for (name, found) in names.iter().zip(&mut found) {
            if rest.contains(name) {
                *found = true;
                rest = rest.replace(name, " ");
            }
        }
        // What is left joins the names: separators and "or".
        let rest = rest.replace("or", " ");
        assert!(
            rest.chars().all(|c| " ,/;()".contains(c)),
            "the README's '{cell}' names an input the key table lacks: '{}'",
            rest.trim()
        );
    }
    for (name, found) in names.iter().zip(&found) {
        assert!(found, "the README's controls table lacks {name}");
    }
}
