//! The result document: what a command answers, in no format. A [`Document`] has a title, a
//! few lines that say what was analysed, and sections (a heading, sentences, lists, key-value
//! rows with typed values and units, tables, warnings); the figures (drawings and charts,
//! chosen in one place, [`super::figures`]) and the data of the JSON contract
//! ([`Data`]) travel with it. One printer per format turns it into output:
//! [`super::text`] for the terminal, [`super::json`] for the JSON contract, [`super::csv`]
//! for the tables. A new format is one more printer.

use serde::Serialize;

/// What a command answers, ready for any printer.
#[derive(Debug, Default)]
pub struct Document {
    /// What was analysed, e.g. the scene file.
    pub title: String,
    /// What the title is, in a few lines (the structure, its loads).
    pub lead: Vec<String>,
    /// The results, one section per method or topic.
    pub sections: Vec<Section>,
    /// Drawings and charts asked for (their SVG, from [`super::figures`]).
    pub figures: Vec<Figure>,
    /// The same result as the JSON contract has it; `None` where the command has no JSON.
    pub data: Option<Data>,
}

impl Document {
    /// A document with a title and nothing else yet.
    pub fn new(title: impl Into<String>) -> Self {
        Document {
            title: title.into(),
            ..Default::default()
        }
    }

    /// Add a section, returning it to be filled.
    pub fn section(&mut self, heading: impl Into<String>) -> &mut Section {
        self.sections.push(Section::new(Some(heading.into())));
        let last = self.sections.len() - 1;
        &mut self.sections[last]
    }

    /// Add a section without a heading (statements that stand on their own).
    pub fn untitled(&mut self) -> &mut Section {
        self.sections.push(Section::new(None));
        let last = self.sections.len() - 1;
        &mut self.sections[last]
    }

    /// The same document carrying the JSON contract's data.
    pub fn with_data(mut self, data: Data) -> Self {
        self.data = Some(data);
        self
    }
}

/// One part of a document.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Section {
    /// The section's first line: the method and its headline result
    /// (`Static (lower bound): collapse multiplier lambda = 0.145673`).
    pub heading: Option<String>,
    pub blocks: Vec<Block>,
}

impl Section {
    pub fn new(heading: Option<String>) -> Self {
        Section {
            heading,
            blocks: Vec::new(),
        }
    }

    /// Set the heading (a section may learn its headline result after it was opened).
    pub fn head(&mut self, heading: impl Into<String>) -> &mut Self {
        self.heading = Some(heading.into());
        self
    }

    /// A sentence about the heading's result.
    pub fn line(&mut self, text: impl Into<String>) -> &mut Self {
        self.push(Block::Line(text.into()))
    }

    /// One item of a list under the last line (a hinge, a joint).
    pub fn item(&mut self, text: impl Into<String>) -> &mut Self {
        self.push(Block::Item(text.into()))
    }

    /// Several items.
    pub fn items(&mut self, items: impl IntoIterator<Item = String>) -> &mut Self {
        self.blocks.extend(items.into_iter().map(Block::Item));
        self
    }

    /// A statement that stands beside the heading, not under it (a rule, a verdict).
    pub fn statement(&mut self, text: impl Into<String>) -> &mut Self {
        self.push(Block::Statement(text.into()))
    }

    /// A warning the reader must not miss.
    pub fn warning(&mut self, text: impl Into<String>) -> &mut Self {
        self.push(Block::Warning(text.into()))
    }

    /// Text shown as it is, line by line in a fixed-width font (a file quoted in full).
    pub fn preformatted(&mut self, text: impl Into<String>) -> &mut Self {
        self.push(Block::Preformatted(text.into()))
    }

    /// Key-value rows.
    pub fn rows(&mut self, rows: Vec<Row>) -> &mut Self {
        self.push(Block::Rows(rows))
    }

    /// A table.
    pub fn table(&mut self, table: Table) -> &mut Self {
        self.push(Block::Table(table))
    }

    fn push(&mut self, block: Block) -> &mut Self {
        self.blocks.push(block);
        self
    }
}

/// The content of a section.
#[derive(Debug, Clone, PartialEq)]
pub enum Block {
    /// A sentence about the section's result (it may run over several lines).
    Line(String),
    /// An item of a list (one hinge, one joint).
    Item(String),
    /// A statement on its own (a rule, a verdict, a summary line).
    Statement(String),
    /// A warning.
    Warning(String),
    /// Text kept as it is, in a fixed-width font (a scene file quoted in full).
    Preformatted(String),
    /// Named values.
    Rows(Vec<Row>),
    Table(Table),
}

/// A named value, e.g. `t_min = 0.106 m`.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub key: String,
    pub value: Value,
}

impl Row {
    pub fn new(key: impl Into<String>, value: Value) -> Self {
        Row {
            key: key.into(),
            value,
        }
    }
}

/// A typed value: a printer chooses how to show it, the document says what it is.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number shown with `digits` decimals, in `unit` (empty: dimensionless).
    Number {
        value: f64,
        digits: usize,
        unit: &'static str,
    },
    /// A number in scientific notation with `digits` decimals (`1.0e-10`).
    Scientific { value: f64, digits: usize },
    /// A count.
    Count(u64),
    /// Words (or a value already in words, such as `none`).
    Text(String),
}

impl Value {
    /// A dimensionless number with `digits` decimals.
    pub fn number(value: f64, digits: usize) -> Self {
        Value::Number {
            value,
            digits,
            unit: "",
        }
    }

    /// An optional number, `missing` in words where there is none.
    pub fn maybe(value: Option<f64>, digits: usize, missing: &str) -> Self {
        value.map_or_else(
            || Value::Text(missing.to_string()),
            |v| Value::number(v, digits),
        )
    }

    pub fn text(words: impl Into<String>) -> Self {
        Value::Text(words.into())
    }

    /// The value as text, without its unit.
    pub fn show(&self) -> String {
        match self {
            Value::Number { value, digits, .. } => format!("{value:.digits$}"),
            Value::Scientific { value, digits } => format!("{value:.digits$e}"),
            Value::Count(n) => n.to_string(),
            Value::Text(t) => t.clone(),
        }
    }

    /// The value as text with its unit, `0.106 m`, `4.2 %`.
    pub fn with_unit(&self) -> String {
        match self.unit() {
            "" => self.show(),
            unit => format!("{} {unit}", self.show()),
        }
    }

    /// The unit, empty when none.
    pub fn unit(&self) -> &'static str {
        match self {
            Value::Number { unit, .. } => unit,
            _ => "",
        }
    }
}

/// How a column lines up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Align {
    Left,
    Right,
}

/// A column of a table: its header, width (in characters, for fixed-width printers) and
/// alignment, and the spaces before it.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    pub header: String,
    pub width: usize,
    pub align: Align,
    /// Spaces between this column and the one before it.
    pub gap: usize,
}

impl Column {
    /// A right-aligned column one space after the previous one.
    pub fn right(header: impl Into<String>, width: usize) -> Self {
        Column {
            header: header.into(),
            width,
            align: Align::Right,
            gap: 1,
        }
    }

    /// A left-aligned column one space after the previous one.
    pub fn left(header: impl Into<String>, width: usize) -> Self {
        Column {
            header: header.into(),
            width,
            align: Align::Left,
            gap: 1,
        }
    }

    /// Right-aligned columns, one space apart: `(header, width)` each.
    pub fn right_all(columns: &[(&str, usize)]) -> Vec<Column> {
        columns.iter().map(|&(h, w)| Column::right(h, w)).collect()
    }

    /// The same column `gap` spaces after the previous one.
    pub fn gap(mut self, gap: usize) -> Self {
        self.gap = gap;
        self
    }
}

/// A table: columns and rows of values.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    pub columns: Vec<Column>,
    pub rows: Vec<Vec<Value>>,
}

/// A drawing or a chart, as [`super::figures`] chose and drew it.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// What it shows (`structure`, `capacity`, `adrs`, `mechanism`, `chart`).
    pub name: &'static str,
    /// The SVG document.
    pub svg: String,
}

/// A document with a block of each kind, for the printers' tests: "Page", an intro, a
/// section "Results" with a line, two items, a row, a warning and a table whose first column
/// is headed `first`.
#[cfg(test)]
pub fn sample(first: &str) -> Document {
    let mut doc = Document::new("Page");
    doc.lead.push("An intro.".into());
    doc.section("Results")
        .line("A sentence.")
        .item("one")
        .item("two")
        .rows(vec![Row::new(
            "t",
            Value::Number {
                value: 0.25,
                digits: 2,
                unit: "m",
            },
        )])
        .warning("careful")
        .table(Table {
            columns: vec![Column::left(first, 3), Column::right("c", 4)],
            rows: vec![vec![Value::text("x"), Value::number(1.5, 1)]],
        });
    doc
}

/// The JSON contract's object of each command (`--json`), serialized as the object itself.
#[derive(Debug, Serialize)]
#[serde(untagged)]
pub enum Data {
    Analysis(Box<super::AnalysisReport>),
    MinThickness(Box<super::MinThicknessReport>),
    Assessment(Box<super::assessment::AssessmentReport>),
    Dem(Box<super::DemReport>),
    Dynamic(Box<super::DynamicReport>),
    Ida(Box<super::IdaReport>),
    PulseCurve(Box<super::PulseCurveReport>),
    Convergence(Box<crate::convergence::Convergence>),
    Retrofit(Box<super::retrofit::RetrofitReport>),
    Fragility(Box<super::fragility::FragilityReport>),
}
