//! Bodies that move: wall regions driven by a prescribed rigid motion
//! ([`prescribed`]: expressions, or tables through [`table`]), placed with their velocity and acceleration ([`rigid`]) at the
//! time of every force evaluation, so that the fluid sees them where they are within
//! each stage of the integrator.
//!
//! Wall particles are not integrated: the motion sets `x`, `u` and the wall
//! acceleration `a_w` (in [`Particles::wall_acceleration`], kept only when a body
//! moves), which the wall model reads: the no-slip velocity `2u_w - ũ` and the pressure
//! extrapolation's `(g - a_w)·r` term (see [`crate::boundary::walls`]).

pub mod prescribed;
pub mod rigid;
pub mod table;

use crate::boundary::bodies::Body;
use crate::case::{Case, MotionChoice};
use crate::domain::Domain;
use crate::error::{Result, SphError};
use crate::particles::{Particles, Vector};
use prescribed::PrescribedMotion;
use rayon::prelude::*;
use rigid::Pose;
use std::ops::Range;

/// How many times over the run a motion is sampled when the case is built, to refuse
/// one that is not finite or leaves the domain.
const SAMPLES: usize = 1000;

/// One moving body: the ids of its particles and where each sits relative to the
/// pivot at t = 0.
struct Moving<const D: usize> {
    ids: Range<u32>,
    /// `r0 = x(0) - P(0)`, by `id - ids.start`.
    offsets: Vec<Vector<D>>,
    motion: PrescribedMotion<D>,
}

/// The moving bodies of a run.
pub struct Motions<const D: usize> {
    bodies: Vec<Moving<D>>,
}

impl<const D: usize> Motions<D> {
    /// The moving bodies of `case` (`None` when every body is fixed) from the built
    /// particles, at their places of t = 0. Refused in one line: a motion that is not
    /// finite over the run, does not start at rest where the body is built, or takes
    /// a body out of the domain along an open direction.
    pub fn of(
        case: &Case,
        bodies: &[Body],
        particles: &Particles<D>,
        domain: &Domain<D>,
    ) -> Result<Option<Self>> {
        let mut moving = Vec::new();
        for ((key, motion, table), body) in case.body_motions().into_iter().zip(bodies) {
            let (MotionChoice::Prescribed, Some(table)) = (motion, table) else {
                continue;
            };
            let motion = PrescribedMotion::new(format!("{key}.prescribed"), table, case.time.end)?;
            let ids = body.ids.clone();
            let mut offsets = vec![Vector::zeros(); ids.len()];
            for (x, &id) in particles.x.iter().zip(&particles.id) {
                if ids.contains(&id) {
                    offsets[(id - ids.start) as usize] = x - motion.pivot;
                }
            }
            let body = Moving {
                ids,
                offsets,
                motion,
            };
            body.check(case.time.end, domain)?;
            moving.push(body);
        }
        Ok((!moving.is_empty()).then_some(Self { bodies: moving }))
    }

    /// One line per moving body for `sph-cli check`: how far its pivot goes and how far
    /// it turns over `[0, end]`, and its walls' largest speed and acceleration (sampled
    /// at the corners of its initial bounding box), to catch a unit slip before a run.
    pub fn describe(&self, end: f64) -> String {
        let mut text = String::new();
        for body in &self.bodies {
            let (mut moved, mut turned, mut speed, mut accel) =
                (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
            for t in sample_times(end) {
                let pose = body.motion.pose(t);
                moved = moved.max((pose.pivot - body.motion.pivot).norm());
                turned = turned.max(pose.phi.norm());
                for r0 in body.corners() {
                    let (_, u, a) = pose.point(&r0);
                    (speed, accel) = (speed.max(u.norm()), accel.max(a.norm()));
                }
            }
            let region = body.motion.key.trim_end_matches(".prescribed");
            text += &format!(
                "motion of {region}: over the run the pivot moves up to {moved:.4e} m and \
                 turns up to {turned:.4e} rad; its walls reach {speed:.4e} m/s and \
                 {accel:.4e} m/s²\n"
            );
        }
        text
    }

    /// Every moving body's pose at time `t`, in case order.
    pub fn poses(&self, t: f64) -> Vec<Pose<D>> {
        self.bodies.iter().map(|b| b.motion.pose(t)).collect()
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
}

/// The names of the moving bodies among `bodies` (the case's, in its order).
pub fn moving_names(case: &Case, bodies: &[Body]) -> Vec<String> {
    (bodies.iter().zip(case.body_motions()))
        .filter(|(_, (_, motion, _))| *motion != MotionChoice::Fixed)
        .map(|(b, _)| b.name.clone())
        .collect()
}

impl<const D: usize> Moving<D> {
    /// The motion sampled over `[0, end]`: finite, starting at rest, and keeping the
    /// corners of the body's initial bounding box (which hold the body in every pose)
    /// inside the domain along its open directions.
    fn check(&self, end: f64, domain: &Domain<D>) -> Result<()> {
        let times = sample_times(end);
        self.motion.check(&times)?;
        for &t in &times {
            let pose = self.motion.pose(t);
            for r0 in self.corners() {
                let (x, _, _) = pose.point(&r0);
                if domain.escaped(&x) {
                    return Err(SphError::invalid(
                        &self.motion.key,
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
        Motions::of(&case, &setup.bodies, &setup.particles, &setup.domain)
    }

    #[test]
    fn bodies_move_rigidly_and_stay_in_the_domain() {
        let motions = baffle("0.05*sin(PI*t)").unwrap().unwrap();
        let body = &motions.bodies[0];
        let pose = body.motion.pose(0.5);
        let (x, u, a) = pose.point(&body.offsets[0]);
        let x0 = body.motion.pivot + body.offsets[0];
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
