//! The Markdown printer: a [`Document`] as a page (docs/validation.md is one). The title is a
//! level-1 heading, the lead its paragraphs, each section a level-2 heading (or none) over
//! its sentences (paragraphs), list items (a bulleted list), statements (paragraphs),
//! warnings (block quotes), key-value rows (a list of `key: value unit`) and tables (pipe
//! tables, the column alignment kept). Figures are files of their own, not text.

use super::document::{Align, Block, Document, Table, Value};

/// The document as a Markdown page.
pub fn print(doc: &Document) -> String {
    let mut s = String::new();
    if !doc.title.is_empty() {
        s.push_str(&format!("# {}\n\n", doc.title));
    }
    for p in &doc.lead {
        s.push_str(p);
        s.push_str("\n\n");
    }
    for section in &doc.sections {
        if let Some(h) = &section.heading {
            s.push_str(&format!("## {h}\n\n"));
        }
        let mut in_list = false;
        for block in &section.blocks {
            let list = matches!(block, Block::Item(_) | Block::Rows(_));
            if in_list && !list {
                s.push('\n');
            }
            in_list = list;
            match block {
                Block::Line(t) | Block::Statement(t) => {
                    s.push_str(t);
                    s.push_str("\n\n");
                }
                Block::Item(t) => s.push_str(&format!("- {}\n", t.replace('\n', " "))),
                Block::Warning(t) => s.push_str(&format!("> **Warning:** {t}\n\n")),
                Block::Preformatted(t) => s.push_str(&format!("```\n{}\n```\n\n", t.trim_end())),
                Block::Rows(rows) => {
                    for r in rows {
                        let unit = match r.value.unit() {
                            "" => String::new(),
                            u => format!(" {u}"),
                        };
                        s.push_str(&format!("- {}: {}{unit}\n", r.key, r.value.show()));
                    }
                }
                Block::Table(t) => table(&mut s, t),
            }
        }
        if in_list {
            s.push('\n');
        }
    }
    while s.ends_with("\n\n") {
        s.pop();
    }
    s
}

/// A pipe table; `|` inside a cell escaped.
fn table(s: &mut String, t: &Table) {
    let cell = |v: String| v.replace('|', "\\|");
    let header: Vec<String> = t.columns.iter().map(|c| cell(c.header.clone())).collect();
    s.push_str(&format!("| {} |\n", header.join(" | ")));
    let rule: Vec<&str> = t
        .columns
        .iter()
        .map(|c| match c.align {
            Align::Left => "---",
            Align::Right => "---:",
        })
        .collect();
    s.push_str(&format!("|{}|\n", rule.join("|")));
    for row in &t.rows {
        let cells: Vec<String> = row.iter().map(|v| cell(Value::show(v))).collect();
        s.push_str(&format!("| {} |\n", cells.join(" | ")));
    }
    s.push('\n');
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headings_paragraphs_lists_and_tables() {
        let doc = crate::report::document::sample("a|b");
        assert_eq!(
            print(&doc),
            "# Page\n\nAn intro.\n\n## Results\n\nA sentence.\n\n- one\n- two\n- t: 0.25 m\n\n> **Warning:** careful\n\n| a\\|b | c |\n|---|---:|\n| x | 1.5 |\n"
        );
    }
}
