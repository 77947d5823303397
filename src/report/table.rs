//! A table of measurements, written as Markdown (in the report) and CSV (beside it).

/// Rows of cells under a header; numbers are formatted by the caller.
#[derive(Clone, Debug, Default)]
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// An empty table with these column names.
    pub fn new(header: &[&str]) -> Table {
        Table {
            header: header.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row.
    pub fn push(&mut self, row: Vec<String>) {
        self.rows.push(row);
    }

    /// GitHub-flavoured Markdown.
    pub fn markdown(&self) -> String {
        let line = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
        let mut text = line(&self.header);
        text.push_str(&line(&vec!["---".to_string(); self.header.len()]));
        for row in &self.rows {
            text.push_str(&line(row));
        }
        text
    }

    /// Comma-separated values, cells quoted when they hold a comma or a quote.
    pub fn csv(&self) -> String {
        let cell = |c: &String| {
            if c.contains(',') || c.contains('"') {
                format!("\"{}\"", c.replace('"', "\"\""))
            } else {
                c.clone()
            }
        };
        std::iter::once(&self.header)
            .chain(&self.rows)
            .map(|row| row.iter().map(cell).collect::<Vec<_>>().join(",") + "\n")
            .collect()
    }
}

/// A number with `digits` significant digits (scientific far from 1).
pub fn number(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let magnitude = x.abs().log10().floor() as i32;
    if (-3..5).contains(&magnitude) {
        let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.prec$e}", prec = digits.saturating_sub(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_and_csv_of_a_small_table() {
        let mut table = Table::new(&["name", "value"]);
        table.push(vec!["a, b".into(), number(0.012345, 3)]);
        assert_eq!(
            table.markdown(),
            "| name | value |\n| --- | --- |\n| a, b | 0.0123 |\n"
        );
        assert_eq!(table.csv(), "name,value\n\"a, b\",0.0123\n");
        assert_eq!(number(1.5e-7, 2), "1.5e-7");
    }
}
