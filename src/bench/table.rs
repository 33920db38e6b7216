//! Plain-text tables for benchmark reports (their JSON comes from `serde_json`).

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

#[cfg(test)]
mod tests {
    use super::*;

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
