//! What the commands answer and how it is printed. Each command's result becomes one
//! [`Document`] ([`documents`]: sections, key-value rows, tables; the JSON contract's data
//! with it), with the drawings and charts chosen in one place ([`figures`]); one printer per
//! format turns it into output: [`text`] (the terminal), [`json`] (the JSON contract, its
//! serde structs in [`json`] and [`assessment`]), [`csv`] (the thrust line and the
//! document's tables), [`markdown`] (a page, such as docs/validation.md), [`html`] (the hand-in report of
//! [`dossier`], `voussoir report`). [`words`] holds the words they share; [`animation`] the HTML page of a
//! dynamic run.

pub mod animation;
pub mod assessment;
pub mod csv;
pub mod document;
pub mod documents;
pub mod dossier;
pub mod figures;
pub mod fragility;
pub mod html;
pub mod json;
pub mod markdown;
pub mod retrofit;
pub mod text;
pub mod validation;
pub mod words;

pub use self::csv::write_thrust_csv;
pub use crate::geometry::trim;
pub use document::{Data, Document, Figure};
pub use figures::{analysis_svg, dem_drawing_title, drawing_title};
pub use json::*;
pub use words::*;

/// How a document is printed, as the command line asks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// For a person at a terminal.
    Text,
    /// The JSON contract.
    Json,
}

/// `doc` printed in `format`.
pub fn print(doc: &Document, format: Format) -> String {
    match format {
        Format::Text => text::print(doc),
        Format::Json => json::print(doc),
    }
}
