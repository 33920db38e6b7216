//! Plain-text tables and hand-written JSON for benchmark reports (no serde_json dependency).

use std::io::{self, Write};

/// A table of strings printed as a Markdown table (so it reads in a terminal and pastes into the README):
/// every column padded to its widest cell; a column whose cells are all numbers is right-aligned (`---:`).
#[derive(Clone, Debug, Default)]
pub struct Table {
    /// Column titles.
    pub headers: Vec<String>,
    /// Body rows; a short row leaves its last cells empty.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// An empty table with these column titles.
    pub fn new(headers: &[&str]) -> Self {
        Self {
            headers: headers.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row.
    pub fn push(&mut self, row: Vec<String>) {
        self.rows.push(row);
    }

    /// Writes the header row, the alignment row and the body rows. A `|` inside a cell is escaped.
    pub fn write(&self, out: &mut dyn Write) -> io::Result<()> {
        let escape = |cell: &str| cell.replace('|', "\\|");
        let headers: Vec<String> = self.headers.iter().map(|h| escape(h)).collect();
        let rows: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|row| row.iter().map(|c| escape(c)).collect())
            .collect();
        let columns = rows
            .iter()
            .map(Vec::len)
            .chain([headers.len()])
            .max()
            .unwrap_or(0);
        let mut widths = vec![3; columns];
        for row in rows.iter().chain([&headers]) {
            for (i, cell) in row.iter().enumerate() {
                widths[i] = widths[i].max(cell.chars().count());
            }
        }
        let numeric: Vec<bool> = (0..columns)
            .map(|i| {
                !rows.is_empty()
                    && rows
                        .iter()
                        .all(|row| row.get(i).is_none_or(|cell| cell.parse::<f64>().is_ok()))
            })
            .collect();
        let write_row = |out: &mut dyn Write, row: &[String]| -> io::Result<()> {
            let mut line = String::from("|");
            for i in 0..columns {
                let cell = row.get(i).map_or("", String::as_str);
                let pad = widths[i] - cell.chars().count();
                line.push(' ');
                if numeric[i] {
                    line.extend(std::iter::repeat_n(' ', pad));
                    line.push_str(cell);
                } else {
                    line.push_str(cell);
                    line.extend(std::iter::repeat_n(' ', pad));
                }
                line.push_str(" |");
            }
            writeln!(out, "{line}")
        };
        write_row(out, &headers)?;
        let mut rule = String::from("|");
        for i in 0..columns {
            rule.push_str(&"-".repeat(widths[i] + 1));
            rule.push_str(if numeric[i] { ":|" } else { "-|" });
        }
        writeln!(out, "{rule}")?;
        for row in &rows {
            write_row(out, row)?;
        }
        Ok(())
    }
}

/// `text` as a JSON string literal, quotes included (RFC 8259 §7: `"`, `\` and control characters escaped).
pub fn json_string(text: &str) -> String {
    let mut s = String::with_capacity(text.len() + 2);
    s.push('"');
    for c in text.chars() {
        match c {
            '"' => s.push_str("\\\""),
            '\\' => s.push_str("\\\\"),
            '\n' => s.push_str("\\n"),
            '\r' => s.push_str("\\r"),
            '\t' => s.push_str("\\t"),
            c if (c as u32) < 0x20 => s.push_str(&format!("\\u{:04x}", c as u32)),
            c => s.push(c),
        }
    }
    s.push('"');
    s
}

/// `x` as a JSON number, or `null` when it is NaN or infinite (JSON has no such numbers).
pub fn json_number(x: f64) -> String {
    if x.is_finite() {
        // Display never uses an exponent and round-trips; "-0" is valid JSON.
        format!("{x}")
    } else {
        "null".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_strings_escape_quotes_backslashes_and_control_characters() {
        assert_eq!(
            json_string("a\"b\\c\nd\u{1}é"),
            "\"a\\\"b\\\\c\\nd\\u0001é\""
        );
    }

    #[test]
    fn table_cells_holding_a_pipe_keep_the_columns() {
        let mut table = Table::new(&["metric"]);
        table.push(vec!["|L| drift".into()]);
        let mut out = Vec::new();
        table.write(&mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(text.ends_with("| \\|L\\| drift |\n"), "{text}");
    }

    #[test]
    fn json_numbers_are_null_when_not_finite() {
        assert_eq!(json_number(f64::NAN), "null");
        assert_eq!(json_number(f64::INFINITY), "null");
        assert_eq!(json_number(0.25), "0.25");
        assert_eq!(json_number(1e-7), "0.0000001");
    }

    #[test]
    fn table_columns_line_up_with_numbers_right_aligned() {
        let mut table = Table::new(&["case", "ms"]);
        table.push(vec!["stack".into(), "1.5".into()]);
        table.push(vec!["pyramid".into(), "12.25".into()]);
        let mut out = Vec::new();
        table.write(&mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert_eq!(
            text,
            "| case    |    ms |\n|---------|------:|\n| stack   |   1.5 |\n| pyramid | 12.25 |\n"
        );
    }
}
