//! `voussoir validate`: every validation case recomputed, printed as a table, and the
//! validation page written with `--markdown`.

use super::{write_atomically, Format, Outputs};
use voussoir::error::Error;
use voussoir::report;

#[derive(clap::Args)]
pub struct Args {
    /// Write the validation page (Markdown) to this file, e.g. docs/validation.md
    #[arg(long, value_name = "FILE")]
    markdown: Option<std::path::PathBuf>,
}

pub fn run(args: Args) -> Result<String, Error> {
    Outputs::new()
        .output("--markdown", args.markdown.as_deref(), Format::Markdown)
        .check()?;
    let cases = voussoir::validation::cases()?;
    let doc = report::validation::document(&cases, env!("CARGO_PKG_VERSION"));
    if let Some(path) = &args.markdown {
        let page = report::markdown::print(&doc);
        write_atomically(path, |w| {
            w.extend_from_slice(page.as_bytes());
            w.push(b'\n');
            Ok(())
        })?;
    }
    let mut out = report::text::print(&doc);
    if cases.iter().any(|c| !c.agrees()) {
        out.push_str("\nwarning: some cases lie outside their tolerance (agrees = NO)\n");
    }
    Ok(out)
}
