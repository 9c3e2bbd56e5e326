//! The action: what the collapse multiplier `lambda` multiplies.
//!
//! Every method finds the largest `lambda` for which the blocks can carry the permanent loads
//! plus `lambda` times the action. Which loads form the action is data of the model, chosen
//! by the scene's `[action] kind` and resolved per block when the model is built
//! ([`crate::model::LoadCase`]):
//!
//! - [`Action::Seismic`] (the default, and the seed paper's load model): the equivalent
//!   static seismic force `lambda m g (d, r)` on every seismic mass (self-weight and the loads
//!   marked `seismic`), `d = +-1` the direction of the ground motion and `r` the vertical
//!   ratio. `lambda` is then the collapse acceleration as a fraction of g.
//! - [`Action::Live`]: the loads marked `live = true`, as given, and nothing else; the
//!   self-weight and the other loads stay as they are. `lambda` is then the **adequacy
//!   factor** of arch assessment: the structure becomes a mechanism when the live loads are
//!   `lambda` times as given (Heyman, *The Masonry Arch*, 1982; Gilbert, RING's "adequacy
//!   factor"). The direction of a ground motion has no meaning for it.
//!
//! The bound theorems hold for either action unchanged: they need only that the variable
//! loads grow in proportion to one multiplier while the others stay fixed (Heyman 1966; with
//! finite friction the usual caveat of associative flow applies to both).

/// What `lambda` multiplies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Action {
    /// `lambda g` horizontally (and `lambda r g` vertically) on every seismic mass.
    #[default]
    Seismic,
    /// The loads marked live, times `lambda`: the adequacy factor.
    Live,
}

impl Action {
    /// The scene's word for the action (`[action] kind`), as the JSON writes it.
    pub fn as_str(&self) -> &'static str {
        match self {
            Action::Seismic => "seismic",
            Action::Live => "live",
        }
    }

    /// What the multiplier is called in words a report reads.
    pub fn multiplier_words(&self) -> &'static str {
        match self {
            Action::Seismic => "collapse multiplier",
            Action::Live => "adequacy factor",
        }
    }

    /// Every action, in the order the scene documents them.
    pub const ALL: [Action; 2] = [Action::Seismic, Action::Live];
}

impl std::fmt::Display for Action {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for Action {
    type Err = String;
    fn from_str(s: &str) -> Result<Action, String> {
        Action::ALL
            .into_iter()
            .find(|a| a.as_str() == s)
            .ok_or_else(|| format!("must be \"seismic\" or \"live\", not \"{s}\""))
    }
}
