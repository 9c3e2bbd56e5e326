pub mod assembly;
pub mod dem;
pub mod error;
pub mod geometry;
pub mod kinematic;
pub mod lp;
pub mod scene;
pub mod thrustline;
