//! The words every method answers in: the status of a structure under its loads, the
//! direction of the seismic action, and the multiplier beyond which a structure is said not to
//! collapse. Every analysis module depends on this one; it depends on none.

/// What an analysis concludes about a structure under its loads (the static program, the
/// kinematic searches and the assessment all answer in these words).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// A finite collapse multiplier was found.
    Collapse,
    /// Equilibrium is possible for every lambda (the program is unbounded).
    NoCollapse,
    /// No equilibrium even at lambda = 0: the structure cannot carry its permanent loads.
    CannotStand,
}

impl Status {
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Collapse => "collapse",
            Status::NoCollapse => "no_collapse",
            Status::CannotStand => "cannot_stand",
        }
    }
}

/// Direction of the horizontal acceleration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// Toward +x (left to right), the spec's positive lambda.
    #[default]
    Right,
    /// Toward -x.
    Left,
}

impl Direction {
    /// +1 for right, -1 for left.
    pub fn sign(self) -> f64 {
        match self {
            Direction::Right => 1.0,
            Direction::Left => -1.0,
        }
    }
}

/// Beyond this multiplier (a ground tilt of 89.99 deg) a structure is said not to collapse.
pub const LAMBDA_CAP: f64 = 1e4;
