//! Discrete element check: filled by the DEM issue.
