//! Free rigid bodies: a wall region moved by the fluid's load, gravity and its
//! springs, with any degrees of freedom locked, about its centre of mass or a hinge.
//!
//! The state of a body is its reference point `X` (the centre of mass, or the hinge),
//! the velocity `V` of that point, its orientation `R` and angular velocity `Ω`
//! (spatial frame). With `F`, `T` the force and the moment about `X` of the fluid,
//! gravity and the springs, and `I_w = R I Rᵀ` the inertia about `X`:
//!
//! `dX/dt = V`,  `m dV/dt = F` (the free components),
//! `dR/dt = [Ω]× R`,  `I_w dΩ/dt = T - Ω × I_w Ω` (Euler's equations in the spatial
//! frame), restricted to the free rotation axes `P`: `dΩ/dt = P (Pᵀ I_w P)⁻¹ Pᵀ (T - Ω × I_w Ω)`,
//! the locked axes' rows taken by the constraint's reaction moment.
//!
//! A hinged body rotates about the fixed hinge, its inertia shifted there (parallel
//! axis theorem) and gravity's moment `(X_c - X) × m g` acting; otherwise `X` is the
//! centre of mass and gravity adds `m g` to `F` only.
//!
//! The integrators advance the state with the same stages as the fluid (see
//! [`RigidState::advanced`]), so the coupling has no lag: each stage's body pose
//! comes from the stage's rates. The orientation is advanced by the exponential map,
//! `R ← exp(c [Ω]×) R`, exact for a spin about a fixed axis.

use super::rigid::{embed, project, Pose};
use crate::boundary::bodies::Load;
use crate::case::{FreeConfig, SpringConfig};
use crate::particles::Vector;
use nalgebra::{DMatrix, DVector, Matrix3, UnitQuaternion, Vector3};
use std::ops::{Add, Mul};

type V3 = Vector3<f64>;

/// The numbers of a free body's record in a restart file: its [`RigidState`] and the
/// last rates' linear and angular accelerations.
pub const RECORD: usize = 20;

/// The rates of a rigid state: of the reference point's position (its velocity), of
/// its velocity, of the orientation (the angular velocity) and of the angular velocity.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Rate {
    pub velocity: V3,
    pub acceleration: V3,
    pub omega: V3,
    pub alpha: V3,
}

impl Add for Rate {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            velocity: self.velocity + o.velocity,
            acceleration: self.acceleration + o.acceleration,
            omega: self.omega + o.omega,
            alpha: self.alpha + o.alpha,
        }
    }
}

impl Mul<f64> for Rate {
    type Output = Self;
    fn mul(self, c: f64) -> Self {
        Self {
            velocity: self.velocity * c,
            acceleration: self.acceleration * c,
            omega: self.omega * c,
            alpha: self.alpha * c,
        }
    }
}

/// Where a rigid body is and how it moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidState {
    /// The reference point: the centre of mass, or the hinge.
    pub position: V3,
    pub velocity: V3,
    pub orientation: UnitQuaternion<f64>,
    /// Ω, spatial frame.
    pub omega: V3,
    /// The rotation about z accumulated from t = 0, not wrapped (the 2D angle).
    pub angle: f64,
}

impl RigidState {
    /// The state `c` on from this one at `rate`: `X + c V̇`, `V + c A`,
    /// `exp(c [Ω̄]×) R`, `Ω + c α` (`Ω̄` the rate's angular velocity). With the
    /// integrators' weighted rates this is each RK4 stage and each half of the
    /// symplectic scheme; it is exact for constant velocities.
    pub fn advanced(&self, rate: &Rate, c: f64) -> Self {
        Self {
            position: self.position + rate.velocity * c,
            velocity: self.velocity + rate.acceleration * c,
            orientation: UnitQuaternion::from_scaled_axis(rate.omega * c) * self.orientation,
            omega: self.omega + rate.alpha * c,
            angle: self.angle + rate.omega.z * c,
        }
    }

    /// The state as 14 numbers (position, velocity, quaternion w i j k, Ω, angle), for
    /// restart files.
    pub fn to_array(&self) -> [f64; 14] {
        let (x, v, q, w) = (self.position, self.velocity, self.orientation, self.omega);
        [
            x.x, x.y, x.z, v.x, v.y, v.z, q.w, q.i, q.j, q.k, w.x, w.y, w.z, self.angle,
        ]
    }

    /// The state of [`Self::to_array`].
    pub fn from_array(a: &[f64; 14]) -> Self {
        let q = nalgebra::Quaternion::new(a[6], a[7], a[8], a[9]);
        Self {
            position: V3::new(a[0], a[1], a[2]),
            velocity: V3::new(a[3], a[4], a[5]),
            orientation: UnitQuaternion::new_unchecked(q),
            omega: V3::new(a[10], a[11], a[12]),
            angle: a[13],
        }
    }
}

/// A spring and damper from a point of the body to a fixed anchor.
#[derive(Debug, Clone)]
struct Spring {
    /// The point, from the reference point at t = 0.
    offset: V3,
    anchor: V3,
    stiffness: f64,
    rest: f64,
    damping: f64,
    slack: bool,
}

impl Spring {
    fn new<const D: usize>(s: &SpringConfig, reference: &V3) -> Self {
        let point = embed::<D>(&Vector::from_fn(|d, _| s.point[d]));
        let anchor = embed::<D>(&Vector::from_fn(|d, _| s.anchor[d]));
        Self {
            offset: point - reference,
            anchor,
            stiffness: s.stiffness,
            rest: s.rest_length.unwrap_or((point - anchor).norm()),
            damping: s.damping.unwrap_or(0.0),
            slack: s.slack.unwrap_or(false),
        }
    }

    /// The line from the anchor to the point at state `s` (`None` while a slack line
    /// is shorter than its rest length, or the point sits on the anchor).
    fn stretch(&self, s: &RigidState) -> Option<Stretch> {
        let arm = s.orientation * self.offset;
        let line = s.position + arm - self.anchor;
        let length = line.norm();
        if length == 0.0 || (self.slack && length < self.rest) {
            return None;
        }
        let n = line / length;
        Some(Stretch {
            arm,
            n,
            extension: length - self.rest,
            speed: (s.velocity + s.omega.cross(&arm)).dot(&n),
        })
    }

    /// The force on the body and the arm from the reference point where it acts:
    /// `-T n`, `T = k (L - L0) + c dL/dt` along `n` from the anchor to the point (none
    /// while a slack line is shorter than its rest length).
    fn force(&self, s: &RigidState) -> (V3, V3) {
        match self.stretch(s) {
            Some(l) => (
                -l.n * (self.stiffness * l.extension + self.damping * l.speed),
                l.arm,
            ),
            None => (V3::zeros(), s.orientation * self.offset),
        }
    }

    /// The spring's stored energy `k (L - L0)²/2` and the damper's power `-c (dL/dt)²`.
    fn energy_and_damping(&self, s: &RigidState) -> (f64, f64) {
        self.stretch(s).map_or((0.0, 0.0), |l| {
            let energy = 0.5 * self.stiffness * l.extension * l.extension;
            (energy, -self.damping * l.speed * l.speed)
        })
    }
}

/// A taut spring's line at a state.
struct Stretch {
    /// From the reference point to the spring's point.
    arm: V3,
    /// The unit vector from the anchor to the point.
    n: V3,
    /// `L - L0`.
    extension: f64,
    /// `dL/dt`.
    speed: f64,
}

/// A free body of the case: constants, state, and the integrators' scratch.
#[derive(Debug, Clone)]
pub struct FreeBody<const D: usize> {
    /// `wall[1].free`, ...
    pub key: String,
    pub mass: f64,
    /// The centre of mass at t = 0.
    pub centre_of_mass: V3,
    /// Inertia about the centre of mass, t = 0 frame.
    pub inertia: Matrix3<f64>,
    /// From the reference point to the centre of mass at t = 0 (zero unless hinged).
    com_offset: V3,
    /// Inertia about the reference point, t = 0 frame.
    inertia_ref: Matrix3<f64>,
    /// Which components of the reference point's acceleration are free.
    translates: V3,
    /// The free rotation axes.
    axes: Vec<V3>,
    gravity: V3,
    springs: Vec<Spring>,
    /// The current state, and the state at the step's start.
    pub state: RigidState,
    pub start: RigidState,
    /// The rates at the last evaluation, and the integrator's weighted sum of rates.
    pub rate: Rate,
    pub sum: Rate,
    /// The power the fluid and the dampers delivered at the last evaluation,
    /// `F·V + M·Ω - Σ c (dL/dt)²` (moment about the reference point).
    pub power: f64,
}

/// The mass properties of a free body before its case's values replace them.
pub struct MassGuess {
    pub mass: f64,
    pub centre_of_mass: V3,
    /// About the centre of mass.
    pub inertia: Matrix3<f64>,
}

impl<const D: usize> FreeBody<D> {
    /// The body of `config` (validated) with the mass properties `guess` where the
    /// case gives none, under `gravity`.
    pub fn new(key: String, config: &FreeConfig, guess: MassGuess, gravity: &Vector<D>) -> Self {
        let point =
            |v: &Option<Vec<f64>>| (v.as_ref()).map(|v| embed::<D>(&Vector::from_fn(|d, _| v[d])));
        let mass = config.mass.unwrap_or(guess.mass);
        let centre = point(&config.centre_of_mass).unwrap_or(guess.centre_of_mass);
        let inertia = match &config.inertia {
            Some(v) => inertia_tensor(v),
            // the homogeneous region's, scaled to the mass and moved to the centre
            None => {
                shifted(&guess.inertia, &(centre - guess.centre_of_mass), guess.mass)
                    * (mass / guess.mass)
            }
        };
        let reference = point(&config.hinge).unwrap_or(centre);
        let locked = config.locked.clone().unwrap_or_default();
        let free = |name: &str| !locked.iter().any(|l| l == name);
        let translates = V3::from_fn(|d, _| {
            let axis = ["x", "y", "z"][d];
            f64::from(u8::from(d < D && config.hinge.is_none() && free(axis)))
        });
        let axes: Vec<V3> = (0..3)
            .filter(|&d| (D == 3 || d == 2) && free(["rx", "ry", "rz"][d]))
            .map(|d| V3::ith(d, 1.0))
            .collect();
        let velocity = point(&config.velocity).unwrap_or_default();
        let omega = match config.angular_velocity.as_deref() {
            Some([w]) => V3::new(0.0, 0.0, *w),
            Some(w) => V3::from_fn(|d, _| w[d]),
            None => V3::zeros(),
        };
        let state = RigidState {
            position: reference,
            velocity,
            orientation: UnitQuaternion::identity(),
            omega,
            angle: 0.0,
        };
        let springs = (config.springs.iter().flatten())
            .map(|s| Spring::new::<D>(s, &reference))
            .collect();
        Self {
            key,
            mass,
            centre_of_mass: centre,
            inertia,
            com_offset: centre - reference,
            inertia_ref: shifted(&inertia, &(reference - centre), mass),
            translates,
            axes,
            gravity: embed(gravity),
            springs,
            state,
            start: state,
            rate: Rate::default(),
            sum: Rate::default(),
            power: 0.0,
        }
    }

    /// The rates at the current state under the fluid's `load` (its moment about the
    /// origin): Newton's and Euler's equations of the module documentation.
    pub fn take_load(&mut self, load: &Load<D>) {
        let s = &self.state;
        let fluid = embed(&load.force());
        let weight = self.gravity * self.mass;
        let arm = s.orientation * self.com_offset;
        let mut force = fluid + weight;
        let fluid_moment = load.moment - s.position.cross(&fluid);
        let mut moment = fluid_moment + arm.cross(&weight);
        for spring in &self.springs {
            let (f, at) = spring.force(s);
            force += f;
            moment += at.cross(&f);
        }
        let damping: f64 = (self.springs.iter())
            .map(|k| k.energy_and_damping(s).1)
            .sum();
        self.power = fluid.dot(&s.velocity) + fluid_moment.dot(&s.omega) + damping;
        let acceleration = (force / self.mass).component_mul(&self.translates);
        let rotation = s.orientation.to_rotation_matrix();
        let inertia = rotation.matrix() * self.inertia_ref * rotation.matrix().transpose();
        let torque = moment - s.omega.cross(&(inertia * s.omega));
        self.rate = Rate {
            velocity: s.velocity,
            acceleration,
            omega: s.omega,
            alpha: constrained(&self.axes, &inertia, &torque),
        };
    }

    /// The body's mechanical energy: kinetic `m |V_c|²/2 + Ω·I_c Ω/2` (`V_c` the centre
    /// of mass's velocity, `I_c` the inertia about it in the current frame), gravity's
    /// `-m g·X_c` and the springs' `k (L - L0)²/2`.
    pub fn energy(&self) -> f64 {
        let s = &self.state;
        let arm = s.orientation * self.com_offset;
        let centre_velocity = s.velocity + s.omega.cross(&arm);
        let rotation = s.orientation.to_rotation_matrix();
        let inertia = rotation.matrix() * self.inertia * rotation.matrix().transpose();
        let kinetic = 0.5 * (self.mass * centre_velocity.norm_squared())
            + 0.5 * s.omega.dot(&(inertia * s.omega));
        let potential = -self.mass * self.gravity.dot(&(s.position + arm));
        let springs: f64 = (self.springs.iter())
            .map(|k| k.energy_and_damping(s).0)
            .sum();
        kinetic + potential + springs
    }

    /// The pose of the reference point, with the last rates' accelerations (those of
    /// the wall particles, lagging one evaluation behind the state).
    pub fn pose(&self) -> Pose<D> {
        let s = &self.state;
        let phi = if D == 2 {
            V3::new(0.0, 0.0, s.angle)
        } else {
            s.orientation.scaled_axis()
        };
        Pose {
            pivot: project(&s.position),
            phi,
            rotation: s.orientation.to_rotation_matrix(),
            velocity: project(&s.velocity),
            acceleration: project(&self.rate.acceleration),
            omega: s.omega,
            alpha: self.rate.alpha,
        }
    }

    /// The smallest of the body's own limits on Δt: 20 steps per period of its
    /// springs, `2π √(m/Σk)`, and the damping's relaxation time `m/Σc`.
    pub fn max_dt(&self) -> f64 {
        // folds from +0 (an empty f64 sum is -0, and m/-0 = -inf)
        let stiffness = self.springs.iter().fold(0.0, |k, s| k + s.stiffness);
        let damping = self.springs.iter().fold(0.0, |c, s| c + s.damping);
        let period = std::f64::consts::TAU * (self.mass / stiffness).sqrt();
        (period / 20.0).min(self.mass / damping)
    }

    /// The state and the last rates' accelerations, for restart files.
    pub fn record(&self) -> [f64; RECORD] {
        let (state, a, alpha) = (
            self.state.to_array(),
            self.rate.acceleration,
            self.rate.alpha,
        );
        std::array::from_fn(|k| match k {
            0..14 => state[k],
            14..17 => a[k - 14],
            _ => alpha[k - 17],
        })
    }

    /// Takes back the state of [`Self::record`].
    pub fn restore(&mut self, r: &[f64; RECORD]) {
        self.state = RigidState::from_array(&std::array::from_fn(|k| r[k]));
        self.rate.acceleration = V3::new(r[14], r[15], r[16]);
        self.rate.alpha = V3::new(r[17], r[18], r[19]);
    }

    /// Where the reference point is at t = 0.
    pub fn reference(&self) -> V3 {
        self.centre_of_mass - self.com_offset
    }
}

/// `dΩ/dt` on the free `axes` from `I_w dΩ/dt = torque`: the reduced system
/// `(Pᵀ I_w P) w = Pᵀ torque`, `dΩ/dt = P w`.
fn constrained(axes: &[V3], inertia: &Matrix3<f64>, torque: &V3) -> V3 {
    let k = axes.len();
    if k == 0 {
        return V3::zeros();
    }
    let reduced = DMatrix::from_fn(k, k, |a, b| axes[a].dot(&(inertia * axes[b])));
    let rhs = DVector::from_fn(k, |a, _| axes[a].dot(torque));
    let w = (reduced.cholesky())
        .map(|c| c.solve(&rhs))
        .unwrap_or_else(|| DVector::zeros(k));
    (axes.iter().zip(w.iter())).map(|(axis, w)| axis * *w).sum()
}

/// The inertia tensor `i` about a point moved by `d` for a body of mass `m` (parallel
/// axis theorem, from the centre of mass): `i + m (|d|² I - d dᵀ)`.
fn shifted(i: &Matrix3<f64>, d: &V3, m: f64) -> Matrix3<f64> {
    i + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * m
}

/// The inertia tensor of a case's `inertia` values (validated): one value (2D, about
/// z: the same on every axis, of which only z is used), three principal values or the
/// six components `Ixx, Iyy, Izz, Ixy, Ixz, Iyz`.
pub fn inertia_tensor(v: &[f64]) -> Matrix3<f64> {
    match *v {
        [i] => Matrix3::from_diagonal_element(i),
        [a, b, c] => Matrix3::from_diagonal(&V3::new(a, b, c)),
        [xx, yy, zz, xy, xz, yz] => Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz),
        _ => Matrix3::zeros(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body<const D: usize>(toml: &str, gravity: Vector<D>) -> FreeBody<D> {
        let config: FreeConfig = toml::from_str(toml).unwrap();
        let guess = MassGuess {
            mass: 2.0,
            centre_of_mass: V3::new(1.0, 2.0, 0.0),
            inertia: Matrix3::from_diagonal(&V3::new(0.5, 0.7, 0.9)),
        };
        FreeBody::new("wall[0].free".into(), &config, guess, &gravity)
    }

    /// RK4 on the body alone (no fluid load), as the fluid's integrator stages it.
    fn rk4<const D: usize>(b: &mut FreeBody<D>, dt: f64, steps: usize) {
        let none = Load::<D>::default();
        for _ in 0..steps {
            b.take_load(&none);
            b.start = b.state;
            b.sum = b.rate;
            b.state = b.start.advanced(&b.rate, 0.5 * dt);
            for (weight, c) in [(2.0, 0.5 * dt), (2.0, dt)] {
                b.take_load(&none);
                b.sum = b.sum + b.rate * weight;
                b.state = b.start.advanced(&b.rate, c);
            }
            b.take_load(&none);
            b.state = b.start.advanced(&(b.sum + b.rate), dt / 6.0);
        }
    }

    #[test]
    fn a_torque_free_spin_about_a_principal_axis_is_exact() {
        let mut b = body::<3>(
            "mass = 2.0\nvelocity = [0.1, -0.2, 0.3]\nangular_velocity = [0.0, 3.0, 0.0]",
            Vector::<3>::zeros(),
        );
        rk4(&mut b, 0.01, 500);
        let t = 5.0;
        let expected = UnitQuaternion::from_scaled_axis(V3::new(0.0, 3.0 * t, 0.0));
        assert!(b.state.orientation.angle_to(&expected) < 1e-12);
        let moved = b.state.position - V3::new(1.0, 2.0, 0.0);
        assert!((moved - V3::new(0.1, -0.2, 0.3) * t).norm() < 1e-13);
        assert!((b.state.omega - V3::new(0.0, 3.0, 0.0)).norm() < 1e-14);
    }

    #[test]
    fn a_tumbling_body_keeps_its_angular_momentum_and_energy_to_second_order() {
        let drift = |dt: f64| {
            let mut b = body::<3>(
                "mass = 2.0\nangular_velocity = [1.0, 0.1, 2.0]",
                Vector::<3>::zeros(),
            );
            let momentum = |b: &FreeBody<3>| {
                let r = b.state.orientation.to_rotation_matrix();
                r.matrix() * b.inertia * r.matrix().transpose() * b.state.omega
            };
            let energy = |b: &FreeBody<3>| 0.5 * b.state.omega.dot(&momentum(b));
            let (l0, e0) = (momentum(&b), energy(&b));
            rk4(&mut b, dt, (5.0 / dt).round() as usize);
            (
                (momentum(&b) - l0).norm() / l0.norm(),
                (energy(&b) / e0 - 1.0).abs(),
            )
        };
        let (coarse, fine) = (drift(0.004), drift(0.002));
        eprintln!("tumbling over 5 s: |ΔL|/L, |ΔE|/E {coarse:?} at Δt 0.004, {fine:?} at 0.002");
        // the exponential map with the stages' weighted Ω is second order in the turn
        assert!(fine.0 < 2e-7 && fine.1 < 2e-7, "{fine:?}");
        assert!(coarse.0 / fine.0 > 3.5, "{coarse:?} {fine:?}");
    }

    #[test]
    fn a_hinged_pendulum_swings_with_the_compound_period_and_locks_hold() {
        // centre of mass 0.5 m below the hinge, I_c = 0.9 (about z): small swings have
        // the period 2π √(I_h/(m g d)), I_h = I_c + m d²
        let mut b = body::<2>(
            "mass = 2.0\nhinge = [1.0, 2.5]\nangular_velocity = [0.01]",
            Vector::<2>::new(0.0, -9.81),
        );
        let i_h: f64 = 0.9 + 2.0 * 0.25;
        let period = std::f64::consts::TAU * (i_h / (2.0 * 9.81 * 0.5)).sqrt();
        let dt = period / 2000.0;
        rk4(&mut b, dt, 2000);
        // after one period the small swing is back where it started, moving as it did
        assert!(b.state.angle.abs() < 1e-6, "{}", b.state.angle);
        assert!((b.state.omega.z - 0.01).abs() < 1e-6, "{}", b.state.omega.z);
        assert_eq!(b.state.position, V3::new(1.0, 2.5, 0.0));
        // heave only: the sway and the rotation stay exactly where they were
        let mut b = body::<2>(
            "mass = 2.0\nlocked = [\"x\", \"rz\"]",
            Vector::<2>::new(0.0, -9.81),
        );
        let mut load = Load::<2>::default();
        load.add_pair(
            Vector::<2>::new(3.0, 10.0),
            Vector::<2>::zeros(),
            &Vector::<2>::new(0.4, 0.0),
        );
        b.take_load(&load);
        assert_eq!(b.rate.acceleration.x, 0.0);
        assert_eq!(b.rate.alpha, V3::zeros());
        assert!((b.rate.acceleration.y - (10.0 / 2.0 - 9.81)).abs() < 1e-14);
    }

    #[test]
    fn a_spring_holds_a_body_with_its_period() {
        let mut b = body::<2>(
            "mass = 2.0\nlocked = [\"x\", \"rz\"]\nvelocity = [0.0, 0.1]\n\
             [[springs]]\npoint = [1.0, 2.0]\nanchor = [1.0, 1.0]\nstiffness = 50.0",
            Vector::<2>::zeros(),
        );
        let period = std::f64::consts::TAU * (2.0 / 50.0_f64).sqrt();
        assert!((b.max_dt() - period / 20.0).abs() < 1e-15);
        rk4(&mut b, period / 1000.0, 1000);
        assert!((b.state.position.y - 2.0).abs() < 1e-9 && (b.state.velocity.y - 0.1).abs() < 1e-9);
    }
}
