//! Bodies that move: wall regions driven by a prescribed rigid motion
//! ([`prescribed`]: expressions, or tables through [`table`]) or free rigid bodies
//! moved by the fluid, gravity and springs ([`free`], mass properties from the
//! geometry by [`mass`]), placed with their velocity and acceleration ([`rigid`]) at
//! the time of every force evaluation, so that the fluid sees them where they are
//! within each stage of the integrator (free bodies advance with those stages).
//!
//! Wall particles are not integrated: the motion sets `x`, `u` and the wall
//! acceleration `a_w` (in [`Particles::wall_acceleration`], kept only when a body
//! moves), which the wall model reads: the no-slip velocity `2u_w - ũ` and the pressure
//! extrapolation's `(g - a_w)·r` term (see [`crate::boundary::walls`]).

pub mod contact;
pub mod free;
pub mod mass;
pub mod prescribed;
pub mod rigid;
pub mod table;

use crate::boundary::bodies::{Body, Load};
use crate::case::{BodyMotion, Case, MotionChoice};
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::geometry::solid::Solid;
use crate::particles::{Particles, Vector};
use crate::waves::active_absorption::{self, ActiveAbsorption};
use free::FreeBody;
use mass::{Region, Solidity};
use nalgebra::Vector3;
use prescribed::PrescribedMotion;
use rayon::prelude::*;
use rigid::{embed, Pose};
use std::ops::Range;

/// How many times over the run a motion is sampled when the case is built, to refuse
/// one that is not finite or leaves the domain.
const SAMPLES: usize = 1000;

/// What moves a body.
enum Drive<const D: usize> {
    Prescribed(PrescribedMotion<D>),
    Free(Box<FreeBody<D>>),
}

/// One moving body: the ids of its particles and where each sits relative to the
/// pivot (a free body's reference point) at t = 0.
struct Moving<const D: usize> {
    ids: Range<u32>,
    /// `r0 = x(0) - P(0)`, by `id - ids.start`.
    offsets: Vec<Vector<D>>,
    drive: Drive<D>,
    /// The region as a homogeneous solid (free bodies only), for `sph-cli check`.
    solidity: Option<Solidity>,
}

/// The moving bodies of a run.
pub struct Motions<const D: usize> {
    bodies: Vec<Moving<D>>,
    /// Every body's ids and name (`shape[0] (box)`), for contacts.
    names: Vec<(Range<u32>, String)>,
    /// The fluid's density, for the draft `sph-cli check` reports.
    rho0: f64,
}

impl<const D: usize> Motions<D> {
    /// The moving bodies of `case` (`None` when every body is fixed) from the built
    /// particles at their places of t = 0, `solids` the `[[shape]]` walls' solids by
    /// shape index. Refused in one line: a prescribed motion that is not finite over
    /// the run, does not start at rest where the body is built, or takes a body out of
    /// the domain along an open direction.
    pub fn of(
        case: &Case,
        bodies: &[Body],
        particles: &Particles<D>,
        domain: &Domain<D>,
        solids: &[(usize, Solid)],
    ) -> Result<Option<Self>> {
        let mut moving = Vec::new();
        let mut names = Vec::new();
        for (motion, body) in case.body_motions().into_iter().zip(bodies) {
            names.push((body.ids.clone(), format!("{} ({})", motion.key, body.name)));
            let (drive, solidity) = match (motion.motion, motion.prescribed, motion.free) {
                (MotionChoice::Prescribed, Some(table), _) => {
                    let key = format!("{}.prescribed", motion.key);
                    let g = case.gravity().iter().map(|g| g * g).sum::<f64>().sqrt();
                    let mut m = PrescribedMotion::new(key, table, case.time.end, g)?;
                    if let Some(waves) = table.waves.as_ref().filter(|w| w.active_absorption) {
                        m.absorption = Some(Box::new(absorption(
                            case, waves, &m.key, particles, &body.ids,
                        )?));
                    }
                    (Drive::Prescribed(m), None)
                }
                (MotionChoice::Free, _, Some(_)) => {
                    let (body, solidity) = free_body(case, &motion, solids);
                    (Drive::Free(Box::new(body)), Some(solidity))
                }
                _ => continue,
            };
            let pivot = drive.pivot();
            let ids = body.ids.clone();
            let mut offsets = vec![Vector::zeros(); ids.len()];
            for (x, &id) in particles.x.iter().zip(&particles.id) {
                if ids.contains(&id) {
                    offsets[(id - ids.start) as usize] = x - pivot;
                }
            }
            let body = Moving {
                ids,
                offsets,
                drive,
                solidity,
            };
            body.check(case.time.end, domain)?;
            moving.push(body);
        }
        let motions = Self {
            bodies: moving,
            names,
            rho0: case.fluid.density,
        };
        if let Some(t) = motions.touch(particles, 0.5 * case.dx()) {
            return Err(SphError::invalid(
                format!("{}.free", t.free.split(' ').next().unwrap_or_default()),
                format!(
                    "a body overlapping {} at the start (walls {:.4e} m apart near {})",
                    t.other,
                    t.distance,
                    crate::domain::point_text(&t.position)
                ),
                "bodies apart at the start: contact between bodies is not modelled",
            ));
        }
        Ok((!motions.bodies.is_empty()).then_some(motions))
    }

    /// Where a free body's walls come within `gap` of another body's, if anywhere (see
    /// [`contact`]).
    pub fn touch(&self, p: &Particles<D>, gap: f64) -> Option<contact::Touch<D>> {
        let free: Vec<(Range<u32>, String)> = (self.bodies.iter())
            .filter(|b| matches!(b.drive, Drive::Free(_)))
            .filter_map(|b| self.names.iter().find(|(ids, _)| *ids == b.ids).cloned())
            .collect();
        if free.is_empty() {
            return None;
        }
        contact::first_touch(p, &free, &self.names, gap)
    }

    /// One line per moving body for `sph-cli check`: for a prescribed motion, how far
    /// its pivot goes and how far it turns over `[0, end]`, and its walls' largest
    /// speed and acceleration (sampled at the corners of its initial bounding box), to
    /// catch a unit slip before a run; for a free body, its mass, centre of mass,
    /// inertia and the draft at which it floats upright.
    pub fn describe(&self, end: f64) -> String {
        let mut text = String::new();
        for body in &self.bodies {
            text += &match &body.drive {
                Drive::Prescribed(m) => body.describe_motion(m, end),
                Drive::Free(f) => describe_free(f, body.solidity.as_ref(), self.rho0),
            };
        }
        text
    }

    /// Every moving body's pose at time `t` as its prescribed motion has it (`None`
    /// for a free body, whose motion is not known ahead), in case order.
    pub fn scheduled_poses(&self, t: f64) -> Vec<Option<Pose<D>>> {
        (self.bodies.iter())
            .map(|b| match &b.drive {
                Drive::Prescribed(m) => Some(m.pose(t)),
                Drive::Free(_) => None,
            })
            .collect()
    }

    /// Every moving body's pose at time `t` (a free body's is its current one), in
    /// case order.
    pub fn poses(&self, t: f64) -> Vec<Pose<D>> {
        self.bodies.iter().map(|b| b.drive.pose(t)).collect()
    }

    /// Puts every moving body's particles where the motions have them at time `t`, with
    /// their velocities and accelerations (positions brought into the periodic box).
    pub fn place(&self, p: &mut Particles<D>, t: f64, domain: &Domain<D>) {
        let poses = self.poses(t);
        let acceleration = (p.wall_acceleration.as_mut())
            .expect("the wall acceleration is kept in runs with moving bodies");
        (p.x.par_iter_mut())
            .zip(p.u.par_iter_mut())
            .zip(acceleration.par_iter_mut())
            .zip(p.id.par_iter())
            .for_each(|(((x, u), a), id)| {
                let Some(k) = self.bodies.iter().position(|b| b.ids.contains(id)) else {
                    return;
                };
                let body = &self.bodies[k];
                let r0 = &body.offsets[(id - body.ids.start) as usize];
                (*x, *u, *a) = poses[k].point(r0);
                domain.wrap(x);
            });
    }

    /// The wave makers' active absorptions, in case order.
    fn absorbing(&self) -> impl Iterator<Item = &PrescribedMotion<D>> {
        self.bodies.iter().filter_map(|b| match &b.drive {
            Drive::Prescribed(m) if m.absorption.is_some() => Some(m),
            _ => None,
        })
    }

    /// The lines of the absorbing wave makers' gauges (x in 2D, (x, y) in 3D), in case
    /// order.
    pub fn absorbing_lines(&self) -> Vec<Vec<f64>> {
        (self.absorbing())
            .filter_map(|m| m.absorption.as_deref().map(|(_, line)| line.clone()))
            .collect()
    }

    /// The wave makers' active absorptions, in case order, to update.
    fn absorbing_mut(&mut self) -> impl Iterator<Item = &mut ActiveAbsorption> {
        self.bodies.iter_mut().filter_map(|b| match &mut b.drive {
            Drive::Prescribed(m) => m.absorption.as_deref_mut().map(|(a, _)| a),
            Drive::Free(_) => None,
        })
    }

    /// Gives each absorbing wave maker its gauge's reading at `t` (in the order of
    /// [`Self::absorbing_lines`]), from which it sets its correction.
    pub fn absorb(&mut self, t: f64, elevations: &[f64]) {
        let ramps: Vec<f64> = self.absorbing().map(|m| m.ramp_at(t)[0]).collect();
        for ((a, &eta), s) in self.absorbing_mut().zip(elevations).zip(ramps) {
            a.update(t, eta, s);
        }
    }

    /// Each absorbing wave maker's state for a restart file, in case order.
    pub fn absorption_records(&self) -> Vec<active_absorption::Record> {
        (self.absorbing())
            .filter_map(|m| m.absorption.as_deref().map(|(a, _)| a.record()))
            .collect()
    }

    /// Restores what [`Self::absorption_records`] gave; false when the records do not
    /// match the absorbing wave makers.
    pub fn restore_absorption(&mut self, records: &[active_absorption::Record]) -> bool {
        if records.len() != self.absorbing().count() {
            return false;
        }
        for (a, record) in self.absorbing_mut().zip(records) {
            a.restore(record);
        }
        true
    }

    /// The free bodies, in case order.
    pub fn free_bodies(&mut self) -> impl Iterator<Item = &mut FreeBody<D>> {
        self.bodies.iter_mut().filter_map(|b| match &mut b.drive {
            Drive::Free(f) => Some(f.as_mut()),
            Drive::Prescribed(_) => None,
        })
    }

    /// The free bodies, in case order, to read.
    fn free(&self) -> impl Iterator<Item = &FreeBody<D>> {
        self.bodies.iter().filter_map(|b| match &b.drive {
            Drive::Free(f) => Some(f.as_ref()),
            Drive::Prescribed(_) => None,
        })
    }

    /// Each free body's record for a restart file, in case order.
    pub fn free_records(&self) -> Vec<[f64; free::RECORD]> {
        self.free().map(FreeBody::record).collect()
    }

    /// The free bodies' mechanical energy (see [`FreeBody::energy`]).
    pub fn free_energy(&self) -> f64 {
        self.free().fold(0.0, |e, b| e + b.energy())
    }

    /// The power the fluid and the dampers delivered to the free bodies at the last
    /// evaluation (see [`FreeBody::power`]).
    pub fn free_power(&self) -> f64 {
        self.free().fold(0.0, |e, b| e + b.power)
    }

    /// How many of the bodies are free.
    pub fn free_count(&self) -> usize {
        self.free().count()
    }

    /// The free body (its index among the free bodies) each particle belongs to, for
    /// [`crate::scheme::model::Model::wall_loads`].
    pub fn free_owners(&self, p: &Particles<D>) -> Vec<Option<usize>> {
        let free: Vec<&Range<u32>> = (self.bodies.iter())
            .filter(|b| matches!(b.drive, Drive::Free(_)))
            .map(|b| &b.ids)
            .collect();
        (p.id.par_iter())
            .map(|id| free.iter().position(|ids| ids.contains(id)))
            .collect()
    }

    /// Gives each free body the fluid's load at the current state (moments about the
    /// origin), from which it takes its rates.
    pub fn take_loads(&mut self, loads: &[Load<D>]) {
        for (body, load) in self.free_bodies().zip(loads) {
            body.take_load(load);
        }
    }

    /// The smallest of the free bodies' own limits on Δt (infinite without any).
    pub fn max_dt(&self) -> f64 {
        self.free()
            .map(FreeBody::max_dt)
            .fold(f64::INFINITY, f64::min)
    }
}

/// A wave maker's active absorption, its gauge's line `x_g = R + Δx/2 + S` in front of
/// the paddle's face at rest (the largest x of its particles plus Δx/2): a kernel
/// support `R` and the stroke `S` clear of the paddle (which moves up to `S/2` making
/// waves and about as much absorbing them), so that Γ there sees no wall; in 3D at the
/// middle of the paddle's width. Refused where `k x_g` passes
/// [`crate::waves::active_absorption::MAX_PHASE`] (waves too short for the resolution).
fn absorption<const D: usize>(
    case: &Case,
    waves: &crate::case::WavesConfig,
    key: &str,
    particles: &Particles<D>,
    ids: &Range<u32>,
) -> Result<(ActiveAbsorption, Vec<f64>)> {
    use crate::waves::active_absorption::MAX_PHASE;
    let g = case.gravity().iter().map(|g| g * g).sum::<f64>().sqrt();
    let (lo, hi) = (particles.x.iter().zip(&particles.id))
        .filter(|(_, id)| ids.contains(id))
        .fold(
            (Vector::<D>::repeat(f64::MAX), Vector::<D>::repeat(f64::MIN)),
            |(lo, hi), (x, _)| (lo.inf(x), hi.sup(x)),
        );
    let face = hi[0] + 0.5 * case.dx();
    let distance = case.support() + 0.5 * case.dx() + waves.stroke(g);
    let omega = 2.0 * std::f64::consts::PI / waves.period(g);
    let a = ActiveAbsorption::new(&waves.maker(g), omega, distance, g);
    if a.phase() > MAX_PHASE {
        return Err(SphError::invalid(
            format!("{key}.waves.active_absorption"),
            "true",
            format!(
                "waves long beside the kernel: the gauge {distance:.4} m in front of the \
                 paddle sits at k x = {:.3} rad, more than {MAX_PHASE} (a finer spacing or \
                 longer waves)",
                a.phase()
            ),
        ));
    }
    let line = (0..D - 1)
        .map(|d| {
            if d == 0 {
                face + distance
            } else {
                0.5 * (lo[d] + hi[d])
            }
        })
        .collect();
    Ok((a, line))
}

/// The free body of a region (validated `free` table) and its region as a solid.
fn free_body<const D: usize>(
    case: &Case,
    motion: &BodyMotion,
    solids: &[(usize, Solid)],
) -> (FreeBody<D>, Solidity) {
    let config = motion.free.expect("a free body has its table");
    let region = match motion.key.starts_with("wall") {
        true => {
            let w = &case.wall[motion.index];
            Region::Box(&w.lo, &w.hi)
        }
        false => {
            let (_, solid) = (solids.iter())
                .find(|(k, _)| *k == motion.index)
                .expect("every wall shape has its solid");
            Region::Solid(solid)
        }
    };
    let gravity: Vector<D> = Vector::from_fn(|d, _| case.gravity()[d]);
    let up = match gravity.norm() {
        0.0 => Vector3::ith(D - 1, 1.0),
        g => -embed(&gravity) / g,
    };
    let solidity = Solidity::of(&region, D, &up);
    let density = config.density.unwrap_or(1.0);
    let key = format!("{}.free", motion.key);
    let body = FreeBody::new(key, config, solidity.guess(density), &gravity);
    (body, solidity)
}

/// The line of `sph-cli check` for a free body.
fn describe_free<const D: usize>(
    f: &FreeBody<D>,
    solidity: Option<&Solidity>,
    rho0: f64,
) -> String {
    let region = f.key.trim_end_matches(".free");
    let com = crate::domain::point_text(&rigid::project::<D>(&f.centre_of_mass));
    let inertia = if D == 2 {
        format!("{:.4e} kg m²/m about z", f.inertia[(2, 2)])
    } else {
        let i = &f.inertia;
        format!(
            "[{:.4e}, {:.4e}, {:.4e}; {:.4e}, {:.4e}, {:.4e}] kg m² (xx yy zz xy xz yz)",
            i[(0, 0)],
            i[(1, 1)],
            i[(2, 2)],
            i[(0, 1)],
            i[(0, 2)],
            i[(1, 2)]
        )
    };
    let unit = if D == 2 { "kg/m" } else { "kg" };
    let floats = match solidity.and_then(|s| s.draft(f.mass, rho0).map(|d| (d, s))) {
        Some((draft, _)) => format!("floats upright at a draft of {draft:.4e} m"),
        None => "is denser than the fluid: it sinks".to_string(),
    };
    format!(
        "free body {region}: mass {:.4e} {unit}, centre of mass {com} m, inertia {inertia}; \
         it {floats}\n",
        f.mass
    )
}

impl<const D: usize> Drive<D> {
    /// The pivot at t = 0 (a free body's reference point).
    fn pivot(&self) -> Vector<D> {
        match self {
            Drive::Prescribed(m) => m.pivot,
            Drive::Free(f) => rigid::project(&f.reference()),
        }
    }

    fn pose(&self, t: f64) -> Pose<D> {
        match self {
            Drive::Prescribed(m) => m.pose(t),
            Drive::Free(f) => f.pose(),
        }
    }
}

/// The names of the moving bodies among `bodies` (the case's, in its order).
pub fn moving_names(case: &Case, bodies: &[Body]) -> Vec<String> {
    (bodies.iter().zip(case.body_motions()))
        .filter(|(_, m)| m.motion != MotionChoice::Fixed)
        .map(|(b, _)| b.name.clone())
        .collect()
}

impl<const D: usize> Moving<D> {
    /// A prescribed motion sampled over `[0, end]`: finite, starting at rest, and
    /// keeping the corners of the body's initial bounding box (which hold the body in
    /// every pose) inside the domain along its open directions. A free body's motion
    /// is not known before the run.
    fn check(&self, end: f64, domain: &Domain<D>) -> Result<()> {
        let Drive::Prescribed(motion) = &self.drive else {
            return Ok(());
        };
        let times = sample_times(end);
        motion.check(&times)?;
        for &t in &times {
            let pose = motion.pose(t);
            for r0 in self.corners() {
                let (x, _, _) = pose.point(&r0);
                if domain.escaped(&x) {
                    return Err(SphError::invalid(
                        &motion.key,
                        format!(
                            "a motion that takes the body to {} at t = {t:.6} s",
                            crate::domain::point_text(&x)
                        ),
                        format!(
                            "a motion that keeps the body inside the domain {} (set [domain] \
                             to hold it)",
                            domain.describe()
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The line of `sph-cli check` for a prescribed motion.
    fn describe_motion(&self, motion: &PrescribedMotion<D>, end: f64) -> String {
        let (mut moved, mut turned, mut speed, mut accel) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
        for t in sample_times(end) {
            let pose = motion.pose(t);
            moved = moved.max((pose.pivot - motion.pivot).norm());
            turned = turned.max(pose.phi.norm());
            for r0 in self.corners() {
                let (_, u, a) = pose.point(&r0);
                (speed, accel) = (speed.max(u.norm()), accel.max(a.norm()));
            }
        }
        let region = motion.key.trim_end_matches(".prescribed");
        let mut waves = (motion.waves.as_ref()).map_or(String::new(), |w| format!("  {w}\n"));
        if let Some((a, line)) = motion.absorption.as_deref() {
            let at: Vec<String> = line.iter().map(|v| format!("{v:.4}")).collect();
            let at = match D {
                2 => format!("x = {}", at[0]),
                _ => format!("(x, y) = ({})", at.join(", ")),
            };
            waves += &format!(
                "  active absorption from a gauge {:.4} m in front of the paddle at {at} m \
                 (k x = {:.3} rad)\n",
                a.distance,
                a.phase()
            );
        }
        format!(
            "motion of {region}: over the run the pivot moves up to {moved:.4e} m and \
             turns up to {turned:.4e} rad; its walls reach {speed:.4e} m/s and \
             {accel:.4e} m/s²\n{waves}"
        )
    }

    /// The corners of the body's initial bounding box, from the pivot: in every pose
    /// they hold the body, and bound its points' distance from any axis through the
    /// pivot.
    fn corners(&self) -> Vec<Vector<D>> {
        let (lo, hi) = (self.offsets.iter()).fold(
            (Vector::<D>::repeat(f64::MAX), Vector::<D>::repeat(f64::MIN)),
            |(lo, hi), r| (lo.inf(r), hi.sup(r)),
        );
        (0..1usize << D)
            .map(|c| Vector::<D>::from_fn(|d, _| if c >> d & 1 == 0 { lo[d] } else { hi[d] }))
            .collect()
    }
}

/// [`SAMPLES`] + 1 times spread evenly over `[0, end]`.
fn sample_times(end: f64) -> Vec<f64> {
    (0..=SAMPLES)
        .map(|k| end * k as f64 / SAMPLES as f64)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry;

    /// A tank of water with a baffle moving by `displacement` over 1 s.
    fn baffle(displacement: &str) -> Result<Option<Motions<2>>> {
        let text = format!(
            "dimension = 2\n[particles]\nspacing = 0.01\n[fluid]\ndensity = 1000.0\n\
             gravity = [0.0, -9.81]\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [0.2, 0.1]\n\
             [[tank]]\nlo = [0.0, 0.0]\nhi = [0.5, 0.3]\n[[wall]]\nlo = [0.3, 0.1]\n\
             hi = [0.4, 0.2]\nmotion = \"prescribed\"\n[wall.prescribed]\n\
             displacement = [\"{displacement}\", \"0\"]\n[time]\nend = 1.0\n"
        );
        let case = Case::from_toml_str(&text).unwrap();
        let setup = geometry::build::<2>(&case).unwrap();
        Motions::of(
            &case,
            &setup.bodies,
            &setup.particles,
            &setup.domain,
            &setup.wall_solids,
        )
    }

    #[test]
    fn bodies_move_rigidly_and_stay_in_the_domain() {
        let motions = baffle("0.05*sin(PI*t)").unwrap().unwrap();
        let body = &motions.bodies[0];
        let pose = body.drive.pose(0.5);
        let (x, u, a) = pose.point(&body.offsets[0]);
        let x0 = body.drive.pivot() + body.offsets[0];
        assert!((x - x0 - Vector::<2>::new(0.05, 0.0)).norm() < 1e-15);
        assert!(u.norm() < 1e-15);
        let pi = std::f64::consts::PI;
        assert!((a[0] + 0.05 * pi * pi).abs() < 1e-13 && a[1] == 0.0);
        // the default domain reaches half the particles' extent past them, to x = 0.83 m
        let e = baffle("0.8*t").err().unwrap().to_string();
        assert!(
            e.starts_with("wall[0].prescribed = a motion that takes the body to (0.8")
                && e.contains("expected a motion that keeps the body inside the domain"),
            "{e}"
        );
    }
}
