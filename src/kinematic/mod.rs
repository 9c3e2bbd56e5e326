//! Kinematic (upper-bound) limit analysis: filled by the kinematic issue.
