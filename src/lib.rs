pub mod assembly;
pub mod error;
pub mod geometry;
pub mod lp;
pub mod scene;
