//! The integration tests, one binary (each file a module): the library and its CLI checked
//! from outside, as a user and an independent check would. One binary links the library once
//! instead of once per file (docs/performance.md has the build times).

mod common;

mod arcade;
mod architecture;
mod assess;
mod bad_input;
mod blocks;
mod bounds;
mod cli;
mod cli_dem;
mod convergence;
mod crushing;
mod dem;
mod dem_brackets;
mod dem_dynamic;
mod dem_fuzz;
mod dem_moreau;
mod dem_record;
mod dem_rest;
mod extremes;
mod fixed_blocks;
mod fragility;
mod friction;
mod general_kinematic;
mod hazard;
mod incremental;
mod json_contract;
mod json_unchanged;
mod kinematic;
mod live_loads;
mod loads;
mod local_search;
mod non_associative;
mod passive_fill;
mod piers;
mod proptest_scenes;
mod records;
mod reduced;
mod report_html;
mod reports;
mod retrofit;
mod rolling;
mod serve_api;
mod simplex;
mod static_bound;
mod strips;
mod studies;
mod svg;
mod sweep;
mod ties;
mod validation;
