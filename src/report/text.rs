//! The terminal's printer: a [`Document`] as plain text. The title on the first line, the
//! lead under it (indented), then each section after a blank line: its heading flush left,
//! its sentences indented by two spaces, list items by four, statements and warnings flush
//! left, key-value rows as `key = value unit`, tables in fixed-width columns. Figures are
//! files of their own (written by the command), not text.

use super::document::{Align, Block, Document, Section, Table, Value};

/// The document as the terminal shows it.
pub fn print(doc: &Document) -> String {
    let mut s = String::new();
    if !doc.title.is_empty() {
        s.push_str(&doc.title);
        s.push('\n');
    }
    for line in &doc.lead {
        indented(&mut s, "  ", line);
    }
    for (i, section) in doc.sections.iter().enumerate() {
        if i > 0 || !doc.lead.is_empty() {
            s.push('\n');
        }
        print_section(&mut s, section);
    }
    s
}

/// One section: heading, then its blocks.
fn print_section(s: &mut String, section: &Section) {
    if let Some(h) = &section.heading {
        s.push_str(h);
        s.push('\n');
    }
    for block in &section.blocks {
        match block {
            Block::Line(t) => indented(s, "  ", t),
            Block::Item(t) => indented(s, "    ", t),
            Block::Statement(t) => indented(s, "", t),
            Block::Warning(t) => indented(s, "", &format!("warning: {t}")),
            Block::Preformatted(t) => indented(s, "    ", t),
            Block::Rows(rows) => {
                for r in rows {
                    let value = r.value.with_unit();
                    indented(s, "  ", &format!("{} = {value}", r.key));
                }
            }
            Block::Table(t) => table(s, t),
        }
    }
}

/// Each line of `text` after `prefix`.
fn indented(s: &mut String, prefix: &str, text: &str) {
    for line in text.split('\n') {
        s.push_str(prefix);
        s.push_str(line);
        s.push('\n');
    }
}

/// A table in fixed-width columns, indented by two spaces; trailing spaces trimmed.
fn table(s: &mut String, t: &Table) {
    let cells = |values: &mut dyn Iterator<Item = String>| {
        let mut line = String::from("  ");
        for (i, (c, v)) in t.columns.iter().zip(values).enumerate() {
            if i > 0 {
                line.push_str(&" ".repeat(c.gap));
            }
            let w = c.width;
            line.push_str(&match c.align {
                Align::Left => format!("{v:<w$}"),
                Align::Right => format!("{v:>w$}"),
            });
        }
        line.trim_end().to_string()
    };
    let header = cells(&mut t.columns.iter().map(|c| c.header.clone()));
    s.push_str(&header);
    s.push('\n');
    for row in &t.rows {
        let line = cells(&mut row.iter().map(Value::show));
        s.push_str(&line);
        s.push('\n');
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::document::{Column, Row};

    #[test]
    fn sections_lines_items_and_tables_line_up() {
        let mut doc = Document::new("scene.toml");
        doc.lead.push("an arch\nits loads".into());
        doc.section("Static: lambda = 0.1")
            .line("hinges:")
            .item("joint 1")
            .rows(vec![Row::new(
                "t",
                Value::Number {
                    value: 0.25,
                    digits: 2,
                    unit: "m",
                },
            )])
            .warning("careful");
        doc.untitled().table(Table {
            columns: vec![Column::left("a", 3), Column::right("b", 4).gap(2)],
            rows: vec![vec![Value::text("x"), Value::number(1.5, 1)]],
        });
        assert_eq!(
            print(&doc),
            "scene.toml\n  an arch\n  its loads\n\nStatic: lambda = 0.1\n  hinges:\n    joint 1\n  t = 0.25 m\nwarning: careful\n\n  a       b\n  x     1.5\n"
        );
    }
}
