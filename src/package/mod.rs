//! Packages that hand a scene to other systems: a store-only zip writer and the SCORM 1.2
//! package of an activity (what an LMS imports, runs and grades).
//!
//! Layer: package. Uses `model` (the scene, its activity, the link codec) and `sim` (the
//! activity check's status). The CLI and the page's Export dialog build the same bytes from the
//! same files.

pub mod scorm;
pub mod zip;
