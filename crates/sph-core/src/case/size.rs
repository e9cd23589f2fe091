//! The size of a run, known before a single particle is built: how many particles the
//! case asks for, the memory they will take at the run's peak, and whether the machine
//! holds it.
//!
//! The memory model is fitted to the peak resident memory measured on the dam breaks
//! (`/usr/bin/time -v`, one process, 2 threads): per particle, `COLUMNS[D]` bytes of
//! columns and per-step arrays plus `LIST_PAIR[D]` bytes per neighbour held in the
//! lists, which reach `R + s` with the skin s the flow's speed asks for (see
//! [`crate::neighbours::ListPolicy`]); plus [`BASE`] for the program itself.
//! Measured (h/Δx = 1.33 and 2, lists at the start's skin 0.1R): 2D, 4.2·10⁵ particles,
//! 1140 and 1981 B a particle; 3D, 1.6·10⁶ particles, 2289 and 7236 B.

use super::schema::Case;
use crate::error::{Result, SphError};
use crate::neighbours::{MIN_SKIN, SKIN_OVER_REACH};

/// The most particles a case may ask for: 2^30, whatever the machine.
pub const MAX_PARTICLES: f64 = 1_073_741_824.0;

/// Bytes a particle takes besides its lists, by dimension (2D, 3D).
const COLUMNS: [f64; 2] = [473.0, 233.0];
/// Bytes per neighbour held in the lists (index, culled copy, build buffers).
const LIST_PAIR: [f64; 2] = [24.8, 19.6];
/// The program, its libraries and thread stacks.
const BASE: f64 = 12.0 * 1024.0 * 1024.0;

/// The environment variable that sets the memory a run may take, in GiB, in place of
/// the memory the machine reports available.
pub const MEMORY_VARIABLE: &str = "DELTASPH_MEMORY_GIB";

/// What a case will take, estimated before it is built.
#[derive(Debug, Clone, Copy)]
pub struct SizeEstimate {
    /// Fluid and wall particles of the fluid blocks, tanks, wall boxes and shapes
    /// whose size is known without reading a file.
    pub particles: f64,
    /// Neighbours a particle in the bulk holds in its lists at the flow's speed.
    pub listed: f64,
    /// Peak resident memory \[bytes\] of one process running the whole case.
    pub bytes: f64,
}

impl SizeEstimate {
    /// The peak memory of one of `processes` processes: each builds every particle's
    /// columns before keeping its share, and holds the lists of its share.
    pub fn bytes_per_process(&self, dimension: usize, processes: usize) -> f64 {
        let lists = self.particles * LIST_PAIR[dimension - 2] * self.listed;
        self.bytes - lists + lists / processes.max(1) as f64
    }
}

/// `x` bytes as a short human-readable size.
pub fn bytes_text(x: f64) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut value = x;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    format!("{value:.1} {}", UNITS[unit])
}

impl Case {
    /// The particles and memory this case asks for (see the module's documentation).
    pub fn size(&self) -> SizeEstimate {
        let dx = self.dx();
        let cells = |lo: &[f64], hi: &[f64], pad: f64| -> f64 {
            lo.iter()
                .zip(hi)
                .map(|(l, h)| ((h - l + 2.0 * pad) / dx).round().max(0.0))
                .product()
        };
        let fluid: f64 = self
            .fluid_block
            .iter()
            .map(|b| cells(&b.lo, &b.hi, 0.0))
            .sum();
        let tanks: f64 = self
            .tank
            .iter()
            .map(|t| {
                cells(&t.lo, &t.hi, t.layer_count(self) as f64 * dx) - cells(&t.lo, &t.hi, 0.0)
            })
            .sum();
        let walls: f64 = self.wall.iter().map(|b| cells(&b.lo, &b.hi, 0.0)).sum();
        let particles = fluid + tanks + walls;
        let listed = self.listed_neighbours();
        let d = self.dimension.clamp(2, 3) - 2;
        let bytes = BASE + particles * (COLUMNS[d] + LIST_PAIR[d] * listed);
        SizeEstimate {
            particles,
            listed,
            bytes,
        }
    }

    /// Neighbours within the list radius `R + s` of a particle in the bulk, with the
    /// skin a step at the flow's speed asks for: `s = max(0.1R, 6 · 1.2 U Δt)`,
    /// `Δt = CFL h/c0` and `U/c0` the Mach number of the sound-speed rule.
    fn listed_neighbours(&self) -> f64 {
        let mach = 1.0 / self.fluid.sound_speed_factor.max(1.0);
        let reach = 1.2 * mach * self.scheme.cfl() * self.h();
        let support = self.support();
        let radius = (support + (MIN_SKIN * support).max(SKIN_OVER_REACH * reach)) / self.dx();
        match self.dimension {
            2 => std::f64::consts::PI * radius * radius,
            _ => 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3),
        }
    }

    /// Refuses a spacing that would ask for more particles than any machine holds
    /// (before a single one is built).
    pub(super) fn check_particle_count(&self) -> Result<()> {
        let total = self.size().particles;
        if total > MAX_PARTICLES {
            return Err(SphError::invalid(
                "particles.spacing",
                self.particles.spacing,
                format!(
                    "a spacing giving at most {MAX_PARTICLES:.1e} particles (this one gives \
                     about {total:.1e})"
                ),
            ));
        }
        Ok(())
    }

    /// Refuses a case whose estimated peak memory on each of `processes` processes
    /// exceeds what the machine has available (or [`MEMORY_VARIABLE`] allows), before
    /// anything is allocated.
    pub fn check_memory(&self, processes: usize) -> Result<()> {
        let Some((available, source)) = memory_limit()? else {
            return Ok(());
        };
        let size = self.size();
        let need = size.bytes_per_process(self.dimension, processes);
        if need > available {
            return Err(SphError::invalid(
                "particles.spacing",
                self.particles.spacing,
                format!(
                    "a spacing this machine can hold: about {:.1e} particles need {} per \
                     process and {source} is {} (set {MEMORY_VARIABLE} to allow more)",
                    size.particles,
                    bytes_text(need),
                    bytes_text(available)
                ),
            ));
        }
        Ok(())
    }
}

/// The memory a run may take and where that figure comes from: [`MEMORY_VARIABLE`]
/// when set, else the memory the machine reports available (`MemAvailable` of
/// `/proc/meminfo`); `None` where neither is known.
pub fn memory_limit() -> Result<Option<(f64, &'static str)>> {
    if let Ok(text) = std::env::var(MEMORY_VARIABLE) {
        let gib: f64 = text.trim().parse().unwrap_or(f64::NAN);
        if !(gib > 0.0 && gib.is_finite()) {
            return Err(SphError::invalid(
                MEMORY_VARIABLE,
                text,
                "a positive number of GiB",
            ));
        }
        return Ok(Some((gib * 1024.0_f64.powi(3), MEMORY_VARIABLE)));
    }
    let Ok(meminfo) = std::fs::read_to_string("/proc/meminfo") else {
        return Ok(None);
    };
    Ok(meminfo
        .lines()
        .find_map(|line| line.strip_prefix("MemAvailable:"))
        .and_then(|rest| {
            rest.trim()
                .trim_end_matches("kB")
                .trim()
                .parse::<f64>()
                .ok()
        })
        .map(|kib| (kib * 1024.0, "the memory available")))
}
