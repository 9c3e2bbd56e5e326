//! stub
use super::KinematicError;
use crate::scene::Scene;
#[derive(Debug, Clone)]
pub struct ContinuousResult;
#[derive(Debug, Clone)]
pub struct ContinuousHinge;
#[derive(Debug, Clone)]
pub enum HingeLocation {}
#[derive(Debug, Clone)]
pub struct MinThickness;
pub fn continuous(_s: &Scene) -> Result<ContinuousResult, KinematicError> { todo!() }
pub fn continuous_min_thickness(_s: &Scene) -> Result<MinThickness, KinematicError> { todo!() }
