//! Rigid-body kinematics: where a point fixed to a moving body is, how fast it moves
//! and how it accelerates.
//!
//! A body turns by the rotation `R(t)` about its pivot `P(t)`. A point at `r0` from the
//! pivot at t = 0 is at `x = P + r`, `r = R r0`, and moves with
//!
//! `u = V + Ω × r`,   `a = A + α × r + Ω × (Ω × r)`,
//!
//! `V`, `A` the pivot's velocity and acceleration, `Ω`, `α` the angular velocity and
//! acceleration (spatial frame). Vectors in 2D are embedded in 3D with z = 0; a 2D body
//! turns about z only.

use crate::particles::Vector;
use nalgebra::{Matrix3, Rotation3, Vector3};

/// The state of a rigid motion at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose<const D: usize> {
    /// Where the pivot is.
    pub pivot: Vector<D>,
    /// The rotation vector φ as the motion gives it (2D: (0, 0, θ), θ not wrapped).
    pub phi: Vector3<f64>,
    /// `R = exp([φ]×)`.
    pub rotation: Rotation3<f64>,
    /// `V`, `A`: the pivot's velocity and acceleration.
    pub velocity: Vector<D>,
    pub acceleration: Vector<D>,
    /// `Ω`, `α`: angular velocity and acceleration.
    pub omega: Vector3<f64>,
    pub alpha: Vector3<f64>,
}

impl<const D: usize> Pose<D> {
    /// Position, velocity and acceleration of the point at `r0` from the pivot at t = 0.
    pub fn point(&self, r0: &Vector<D>) -> (Vector<D>, Vector<D>, Vector<D>) {
        let r = self.rotation * embed(r0);
        let u = self.omega.cross(&r);
        let a = self.alpha.cross(&r) + self.omega.cross(&u);
        (
            self.pivot + project::<D>(&r),
            self.velocity + project::<D>(&u),
            self.acceleration + project::<D>(&a),
        )
    }
}

/// A vector of `D ≤ 3` components as a 3-vector (missing components zero).
pub fn embed<const D: usize>(v: &Vector<D>) -> Vector3<f64> {
    Vector3::from_fn(|d, _| if d < D { v[d] } else { 0.0 })
}

/// The first `D` components of a 3-vector.
pub fn project<const D: usize>(v: &Vector3<f64>) -> Vector<D> {
    Vector::from_fn(|d, _| v[d])
}

/// The left Jacobian of the rotation vector φ (angle θ = |φ|, Φ = `[φ]×`):
/// `J(φ) = I + (1 - cos θ)/θ² Φ + (θ - sin θ)/θ³ Φ²`, so that the angular velocity of
/// `R = exp(Φ)` is `Ω = J(φ) dφ/dt` (spatial frame; Ω = dφ/dt for a fixed axis).
pub fn left_jacobian(phi: &Vector3<f64>) -> Matrix3<f64> {
    let theta2 = phi.norm_squared();
    let (a, b) = if theta2 < 1e-8 {
        // the series: errors below θ⁴/720 ≈ 1e-19
        (0.5 - theta2 / 24.0, 1.0 / 6.0 - theta2 / 120.0)
    } else {
        let theta = theta2.sqrt();
        (
            (1.0 - theta.cos()) / theta2,
            (theta - theta.sin()) / (theta2 * theta),
        )
    };
    let skew = phi.cross_matrix();
    Matrix3::identity() + skew * a + skew * skew * b
}

/// Ω and α of the rotation vector φ(t) from φ, dφ/dt and d²φ/dt²:
/// `Ω = J(φ) φ'`, `α = J(φ) φ'' + (dJ/dt) φ'`, the last term by a central difference of
/// J along φ' (zero for a fixed axis, as in every 2D motion).
pub fn angular_rates(
    phi: &Vector3<f64>,
    rate: &Vector3<f64>,
    rate2: &Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let j = left_jacobian(phi);
    let eps = 1e-6;
    let dj =
        (left_jacobian(&(phi + rate * eps)) - left_jacobian(&(phi - rate * eps))) / (2.0 * eps);
    (j * rate, j * rate2 + dj * rate)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ω from a central difference of R(t): `[Ω]× = dR/dt Rᵀ`.
    fn omega_of(phi: impl Fn(f64) -> Vector3<f64>, t: f64) -> Vector3<f64> {
        let r = |t: f64| Rotation3::from_scaled_axis(phi(t)).into_inner();
        let e = 1e-6;
        let w = (r(t + e) - r(t - e)) / (2.0 * e) * r(t).transpose();
        Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)])
    }

    #[test]
    fn angular_velocity_and_acceleration_match_the_rotation_they_come_from() {
        // a tumbling rotation vector, its derivatives exact
        let phi = |t: f64| Vector3::new(0.7 * t.sin(), 0.3 * t * t, 1.1 - 0.5 * t);
        let rate = |t: f64| Vector3::new(0.7 * t.cos(), 0.6 * t, -0.5);
        let rate2 = |t: f64| Vector3::new(-0.7 * t.sin(), 0.6, 0.0);
        for t in [0.0, 0.4, 1.3] {
            let (omega, alpha) = angular_rates(&phi(t), &rate(t), &rate2(t));
            assert!((omega - omega_of(phi, t)).norm() < 1e-8, "{omega} at {t}");
            let e = 1e-4;
            let d_omega = (omega_of(phi, t + e) - omega_of(phi, t - e)) / (2.0 * e);
            assert!(
                (alpha - d_omega).norm() < 1e-5,
                "{alpha} vs {d_omega} at {t}"
            );
        }
    }

    #[test]
    fn a_point_on_a_spinning_disc_accelerates_towards_the_centre() {
        let pose = Pose::<2> {
            pivot: Vector::<2>::new(1.0, 2.0),
            phi: Vector3::new(0.0, 0.0, 0.5),
            rotation: Rotation3::from_scaled_axis(Vector3::new(0.0, 0.0, 0.5)),
            velocity: Vector::<2>::zeros(),
            acceleration: Vector::<2>::zeros(),
            omega: Vector3::new(0.0, 0.0, 3.0),
            alpha: Vector3::zeros(),
        };
        let (x, u, a) = pose.point(&Vector::<2>::new(2.0, 0.0));
        let r = x - pose.pivot;
        assert!((r.norm() - 2.0).abs() < 1e-15 && (r[1] / r[0] - 0.5f64.tan()).abs() < 1e-14);
        assert!((u.norm() - 6.0).abs() < 1e-14 && u.dot(&r).abs() < 1e-13);
        assert!((a + r * 9.0).norm() < 1e-13);
    }
}
