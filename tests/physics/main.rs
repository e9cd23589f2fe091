//! The physics tests of deltasph: analytic solutions, published references and
//! conservation laws, one module per flow or property, in one test binary (one link).

mod body_energy;
mod conservation;
mod dam_break;
mod dam_break_3d;
mod floating_bodies;
mod floating_in_waves;
mod free_surface;
mod hydrostatic;
mod impinging_jet;
mod les;
mod loads;
mod long_runs;
mod measure;
mod moving_bodies;
mod open_boundaries;
mod oscillating_cylinder;
mod sections;
mod shifting;
mod surface_mesh;
mod taylor_green;
mod time_integration;
mod validation;
mod walls;
mod water_wedge;
mod waves;
mod wedge_entry;
