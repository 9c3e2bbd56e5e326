//! What the CLI prints, one file per format: the JSON contract ([`json`]), the thrust-line
//! CSV ([`csv`]), the human summaries and titles ([`summary`]) and the animation of a dynamic
//! run ([`animation`]).

pub mod animation;
pub mod assessment;
pub mod csv;
pub mod json;
pub mod summary;

pub use self::csv::write_thrust_csv;
pub use crate::geometry::trim;
pub use json::*;
pub use summary::*;

/// The drawing of one analysis, as `voussoir analyze --svg` writes it and `voussoir serve`
/// returns it: the blocks, the thrust line, the hinges, the sliding joints, the mechanism and
/// the loads, under the analysis's title.
pub fn analysis_svg(
    scene: &crate::scene::Scene,
    a: &crate::analysis::SceneAnalysis,
    direction: crate::outcome::Direction,
) -> Result<String, crate::drawing::svg::SvgError> {
    use crate::drawing::svg::{structure_svg, Drawing, Mechanism};
    let result = &a.lower;
    let drawing = Drawing {
        title: drawing_title(scene, a),
        forces: result.forces.as_deref(),
        hinges: &result.hinges,
        sliding: &result.sliding,
        mechanism: (!result.mechanism.is_empty()).then_some(Mechanism {
            velocities: &result.mechanism,
            amplification: None,
        }),
        // A live action shakes nothing: no seismic arrow; its loads are labelled as multiplied.
        load: (a.model.loads.action() == crate::model::Action::Seismic).then_some(direction),
        loads: Some(&a.model.loads),
        ..Default::default()
    };
    structure_svg(&a.model.assembly, &drawing)
}
