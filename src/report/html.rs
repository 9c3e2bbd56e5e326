//! The HTML printer: chapters of [`Document`]s as one self-contained page (`voussoir
//! report`, docs/report.md). The figures' SVG is inline, the style sheet is in the page, and
//! nothing is fetched: no script, no font, no image file, no link out of the page. The
//! markup is XHTML-compatible (every element closed, every attribute quoted, text escaped),
//! so an XML parser reads it (tests/it/report_html.rs) as a browser does.
//!
//! Its print styles make a browser's "Print to PDF" (or `voussoir report --pdf`, headless
//! Chromium) an A4 document: a chapter starts a page where it asks to, a figure, a table row
//! and a heading with what follows it are never split across pages, and each page has a
//! header with the report's title and its page number (CSS paged media margin boxes).
//!
//! A list of contents (links within the page) opens it. Each chapter's title is a level-2
//! heading, its lead its first paragraphs, each section a
//! level-3 heading over its sentences (paragraphs), list items (a list), statements
//! (paragraphs in bold), warnings (boxed), key-value rows (a two-column table), tables and
//! preformatted text; then its figures, numbered through the report, each with its caption.

use super::document::{Align, Block, Document, Figure, Section, Table, Value};

/// One chapter of a page: a document, and whether it starts on a new page when printed.
#[derive(Debug)]
pub struct Chapter {
    pub doc: Document,
    pub new_page: bool,
}

/// Text escaped for an element's content or a quoted attribute.
pub fn escape(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&#39;"),
            c => s.push(c),
        }
    }
    s
}

/// Text as a CSS string's content (the page header): quotes and backslashes escaped, and the
/// characters an XML parser would read as markup inside `<style>` written as CSS escapes.
fn css_string(text: &str) -> String {
    let mut s = String::new();
    for c in text.chars() {
        match c {
            '"' | '\\' | '<' | '>' | '&' | '\n' => s.push_str(&format!("\\{:x} ", c as u32)),
            c => s.push(c),
        }
    }
    s
}

const STYLE: &str = r#"
:root { --ink: #1d1d1d; --muted: #5b5b5b; --rule: #c8c8c8; --accent: #7a3b1c; }
html { font-family: "DejaVu Serif", "Liberation Serif", "Times New Roman", serif; color: var(--ink); }
body { max-width: 180mm; margin: 0 auto; padding: 8mm 6mm; font-size: 10.5pt; line-height: 1.4; background: #ffffff; }
header.title { border-bottom: 2px solid var(--accent); margin-bottom: 6mm; }
header.title h1 { font-size: 20pt; margin: 0 0 2mm 0; color: var(--accent); }
header.title p { margin: 0 0 2mm 0; color: var(--muted); }
h2, h3, th, .rows th, figcaption, .statement { font-family: "DejaVu Sans", "Liberation Sans", Arial, sans-serif; }
h2 { font-size: 15pt; color: var(--accent); border-bottom: 1px solid var(--rule); padding-bottom: 1mm; margin: 8mm 0 3mm 0; }
h3 { font-size: 11pt; margin: 5mm 0 2mm 0; }
p { margin: 0 0 2mm 0; }
p.lead { color: var(--muted); }
p.statement { font-weight: bold; }
p.warning { border-left: 3px solid #b00020; padding: 1mm 3mm; background: #fbeaea; }
ul { margin: 0 0 3mm 0; padding-left: 6mm; }
table { border-collapse: collapse; margin: 2mm 0 4mm 0; font-size: 9.5pt; }
th, td { border-bottom: 1px solid var(--rule); padding: 0.8mm 2.5mm; text-align: left; vertical-align: top; }
th { font-size: 9pt; color: var(--muted); font-weight: bold; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
table.rows th { color: var(--ink); font-weight: normal; }
td.scene { font-family: "DejaVu Sans Mono", "Liberation Mono", monospace; font-size: 8.5pt; }
pre { font-family: "DejaVu Sans Mono", "Liberation Mono", monospace; font-size: 8pt; background: #f6f4f0; border: 1px solid var(--rule); padding: 2mm 3mm; white-space: pre-wrap; overflow-wrap: anywhere; }
nav.contents { font-family: "DejaVu Sans", "Liberation Sans", Arial, sans-serif; font-size: 9.5pt; border: 1px solid var(--rule); padding: 2mm 5mm; margin-bottom: 4mm; }
nav.contents ol { margin: 1mm 0; padding-left: 6mm; columns: 2; }
nav.contents a { color: var(--ink); text-decoration: none; }
p.contents-title { font-weight: bold; margin: 0; color: var(--muted); }
figure { margin: 4mm 0; text-align: center; }
figure svg { width: 100%; height: auto; max-height: 150mm; }
figcaption { font-size: 9pt; color: var(--muted); margin-top: 1mm; }
@media print {
  body { max-width: none; margin: 0; padding: 0; font-size: 10pt; }
  section.chapter.new-page { break-before: page; }
  h2, h3 { break-after: avoid; }
  figure, tr, pre, p.statement, p.warning { break-inside: avoid; }
  figure svg { max-height: 118mm; }
  thead { display: table-header-group; }
}
"#;

/// The page of `title`: its chapters in order, with the style sheet and every figure inline.
pub fn print(title: &str, chapters: &[Chapter]) -> String {
    let mut s = String::new();
    s.push_str("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n");
    s.push_str(&format!("<title>{}</title>\n<style>", escape(title)));
    s.push_str(STYLE);
    s.push_str(&format!(
        "@page {{ size: A4; margin: 20mm 16mm 18mm 16mm;\n  @top-left {{ content: \"{}\"; font: 8.5pt \"DejaVu Sans\", sans-serif; color: #5b5b5b; }}\n  @top-right {{ content: \"page \" counter(page) \" of \" counter(pages); font: 8.5pt \"DejaVu Sans\", sans-serif; color: #5b5b5b; }}\n}}\n",
        css_string(title)
    ));
    s.push_str("</style>\n</head>\n<body>\n");
    s.push_str(&format!(
        "<header class=\"title\">\n<h1>{}</h1>\n</header>\n",
        escape(title)
    ));
    // The contents, linked to the chapters in the page.
    s.push_str("<nav class=\"contents\">\n<p class=\"contents-title\">Contents</p>\n<ol>\n");
    for (i, chapter) in chapters.iter().enumerate() {
        s.push_str(&format!(
            "<li><a href=\"#chapter-{}\">{}</a></li>\n",
            i + 1,
            escape(&chapter.doc.title)
        ));
    }
    s.push_str("</ol>\n</nav>\n");
    let mut figure_number = 0;
    for (i, chapter) in chapters.iter().enumerate() {
        let doc = &chapter.doc;
        let class = if chapter.new_page && i > 0 {
            "chapter new-page"
        } else {
            "chapter"
        };
        s.push_str(&format!(
            "<section class=\"{class}\" id=\"chapter-{}\">\n<h2>{}. {}</h2>\n",
            i + 1,
            i + 1,
            escape(&doc.title)
        ));
        for p in &doc.lead {
            s.push_str(&format!("<p class=\"lead\">{}</p>\n", lines(p)));
        }
        for section in &doc.sections {
            print_section(&mut s, section);
        }
        for f in &doc.figures {
            figure_number += 1;
            print_figure(&mut s, f, figure_number);
        }
        s.push_str("</section>\n");
    }
    s.push_str("</body>\n</html>\n");
    s
}

/// Text with its line breaks kept.
fn lines(text: &str) -> String {
    text.split('\n')
        .map(escape)
        .collect::<Vec<_>>()
        .join("<br/>")
}

fn print_section(s: &mut String, section: &Section) {
    s.push_str("<div class=\"section\">\n");
    if let Some(h) = &section.heading {
        s.push_str(&format!("<h3>{}</h3>\n", lines(h)));
    }
    let mut in_list = false;
    for block in &section.blocks {
        let item = matches!(block, Block::Item(_));
        if in_list && !item {
            s.push_str("</ul>\n");
        }
        if item && !in_list {
            s.push_str("<ul>\n");
        }
        in_list = item;
        match block {
            Block::Line(t) => s.push_str(&format!("<p>{}</p>\n", lines(t))),
            Block::Item(t) => s.push_str(&format!("<li>{}</li>\n", lines(t))),
            Block::Statement(t) => {
                s.push_str(&format!("<p class=\"statement\">{}</p>\n", lines(t)))
            }
            Block::Warning(t) => {
                s.push_str(&format!("<p class=\"warning\">Warning: {}</p>\n", lines(t)))
            }
            Block::Preformatted(t) => s.push_str(&format!("<pre>{}</pre>\n", escape(t))),
            Block::Rows(rows) => {
                s.push_str("<table class=\"rows\">\n<tbody>\n");
                for r in rows {
                    s.push_str(&format!(
                        "<tr><th scope=\"row\">{}</th><td class=\"{}\">{}</td></tr>\n",
                        escape(&r.key),
                        if matches!(r.value, Value::Text(_)) {
                            "text"
                        } else {
                            "num"
                        },
                        escape(&r.value.with_unit())
                    ));
                }
                s.push_str("</tbody>\n</table>\n");
            }
            Block::Table(t) => table(s, t),
        }
    }
    if in_list {
        s.push_str("</ul>\n");
    }
    s.push_str("</div>\n");
}

fn table(s: &mut String, t: &Table) {
    let class = |a: Align| match a {
        Align::Left => "text",
        Align::Right => "num",
    };
    s.push_str("<table>\n<thead>\n<tr>");
    for c in &t.columns {
        s.push_str(&format!(
            "<th class=\"{}\">{}</th>",
            class(c.align),
            escape(&c.header)
        ));
    }
    s.push_str("</tr>\n</thead>\n<tbody>\n");
    for row in &t.rows {
        s.push_str("<tr>");
        for (c, v) in t.columns.iter().zip(row) {
            s.push_str(&format!(
                "<td class=\"{}\">{}</td>",
                class(c.align),
                escape(&v.with_unit())
            ));
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</tbody>\n</table>\n");
}

/// What a figure shows, for its caption.
fn caption(name: &str) -> &'static str {
    match name {
        "structure" => "the structure drawn to scale",
        "capacity" => "capacity curves of the governing mechanisms",
        "adrs" => "capacity against the demand spectrum (ADRS)",
        "mechanism" => "the governing mechanism, moved to true scale",
        _ => "chart",
    }
}

/// A figure inline: its SVG without the XML declaration and the namespace declarations (an
/// HTML parser places `<svg>` in its namespace; an XML parser reads it as plain markup), its
/// ids made unique in the page (`f3-...`, references rewritten), and its caption (what it
/// shows; the drawing's own title, with its numbers, is drawn in it).
fn print_figure(s: &mut String, f: &Figure, number: usize) {
    let mut svg = f.svg.trim().to_string();
    if svg.starts_with("<?xml") {
        if let Some(end) = svg.find("?>") {
            svg = svg[end + 2..].trim_start().to_string();
        }
    }
    for ns in [
        " xmlns=\"http://www.w3.org/2000/svg\"",
        " xmlns:xlink=\"http://www.w3.org/1999/xlink\"",
    ] {
        svg = svg.replace(ns, "");
    }
    let prefix = format!("f{number}-");
    svg = svg
        .replace(" id=\"", &format!(" id=\"{prefix}"))
        .replace("url(#", &format!("url(#{prefix}"))
        .replace("href=\"#", &format!("href=\"#{prefix}"));
    s.push_str(&format!("<figure id=\"figure-{number}\">\n"));
    s.push_str(&svg);
    s.push_str(&format!(
        "\n<figcaption>Figure {number}: {}</figcaption>\n</figure>\n",
        caption(f.name),
    ));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chapters_sections_and_tables_are_escaped_markup() {
        let mut doc = crate::report::document::sample("a<b");
        doc.title = "Results & more".into();
        doc.section("lambda < 1").line("x\"y");
        let html = print(
            "A \"title\"",
            &[Chapter {
                doc,
                new_page: false,
            }],
        );
        assert!(html.contains("<h2>1. Results &amp; more</h2>"), "{html}");
        assert!(html.contains("<p class=\"lead\">An intro.</p>"));
        assert!(html.contains("<h3>lambda &lt; 1</h3>\n<p>x&quot;y</p>"));
        assert!(html.contains("<ul>\n<li>one</li>\n<li>two</li>\n</ul>"));
        assert!(html.contains("<td class=\"num\">0.25 m</td>"));
        assert!(html.contains("<p class=\"warning\">Warning: careful</p>"));
        assert!(html.contains("<th class=\"text\">a&lt;b</th>"));
        assert!(html.contains("<td class=\"text\">x</td><td class=\"num\">1.5</td>"));
        assert!(html.contains("content: \"A \\22 title\\22 \""));
        assert!(html.contains("<li><a href=\"#chapter-1\">Results &amp; more</a></li>"));
    }

    #[test]
    fn a_figure_loses_its_declarations_and_its_ids_are_numbered() {
        let mut s = String::new();
        let f = Figure {
            name: "structure",
            svg: "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"><title>t</title><g id=\"a\" fill=\"url(#a)\"/></svg>".into(),
        };
        print_figure(&mut s, &f, 2);
        assert!(!s.contains("<?xml") && !s.contains("xmlns"), "{s}");
        assert!(s.contains("<g id=\"f2-a\" fill=\"url(#f2-a)\"/>"), "{s}");
        assert!(
            s.contains("Figure 2: the structure drawn to scale</figcaption>"),
            "{s}"
        );
    }
}
