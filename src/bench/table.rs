//! Plain-text tables and hand-written JSON for benchmark reports (no serde_json dependency).

use std::io::{self, Write};

/// A table of strings printed with every column padded to its widest cell; a column whose cells are all
/// numbers is right-aligned, header included.
#[derive(Clone, Debug, Default)]
pub struct Table {
    pub headers: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    pub fn new(headers: &[&str]) -> Self {
        Self {
            headers: headers.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    pub fn push(&mut self, row: Vec<String>) {
        self.rows.push(row);
    }

    /// Writes the header, a rule and the rows; columns separated by two spaces, no trailing spaces.
    pub fn write(&self, out: &mut dyn Write) -> io::Result<()> {
        let columns = self
            .rows
            .iter()
            .map(Vec::len)
            .chain([self.headers.len()])
            .max()
            .unwrap_or(0);
        let mut widths = vec![0; columns];
        for row in self.rows.iter().chain([&self.headers]) {
            for (i, cell) in row.iter().enumerate() {
                widths[i] = widths[i].max(cell.chars().count());
            }
        }
        let numeric: Vec<bool> = (0..columns)
            .map(|i| {
                !self.rows.is_empty()
                    && self
                        .rows
                        .iter()
                        .all(|row| row.get(i).is_none_or(|cell| cell.parse::<f64>().is_ok()))
            })
            .collect();
        let write_row = |out: &mut dyn Write, row: &[String]| -> io::Result<()> {
            let mut line = String::new();
            for (i, cell) in row.iter().enumerate() {
                if i > 0 {
                    line.push_str("  ");
                }
                let pad = widths[i] - cell.chars().count();
                if numeric[i] {
                    line.extend(std::iter::repeat_n(' ', pad));
                    line.push_str(cell);
                } else {
                    line.push_str(cell);
                    line.extend(std::iter::repeat_n(' ', pad));
                }
            }
            writeln!(out, "{}", line.trim_end())
        };
        write_row(out, &self.headers)?;
        let rule: usize = widths.iter().sum::<usize>() + 2 * columns.saturating_sub(1);
        writeln!(out, "{}", "-".repeat(rule))?;
        for row in &self.rows {
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
            "case        ms\n--------------\nstack      1.5\npyramid  12.25\n"
        );
    }
}
