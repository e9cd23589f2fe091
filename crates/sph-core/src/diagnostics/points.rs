//! The fluid read at points (probes, gauges, sections, the measure tool): kernel sums
//! over the particles within the kernel support of a point.
//!
//! - Shepard-normalised fields, `f(x) = Σ_f f_f W(x - x_f) V_f / Σ_f W(x - x_f) V_f`,
//!   `V_f = m_f/ρ_f`, over the fluid; none where no fluid is in reach (a dry point has
//!   no SPH value, which is not the same as zero).
//! - The fluid's kernel sum `Γ(x) = Σ_f W(x - x_f) V_f` (the gauges' indicator).
//! - Flow densities through a section (see [`PointReader::flow_density`]).

use crate::domain::Domain;
use crate::neighbours::NeighbourList;
use crate::particles::{Kind, Particles, Vector};
use crate::physics::kernel::Smoothing;

/// What reading at points needs: the kernel, the particles, their neighbour list's
/// cells and the domain (whose periodic axes wrap distances).
pub struct PointReader<'a, const D: usize, K: Smoothing + ?Sized> {
    pub kernel: &'a K,
    pub particles: &'a Particles<D>,
    pub list: &'a NeighbourList<D>,
    pub domain: &'a Domain<D>,
}

impl<const D: usize, K: Smoothing + ?Sized> PointReader<'_, D, K> {
    /// Calls `f(j, W(x - x_j) V_j)` for every particle `j` (fluid and wall) within the
    /// kernel support of `point`.
    fn for_near(&self, point: &Vector<D>, mut f: impl FnMut(usize, f64)) {
        let (p, r_max) = (self.particles, self.kernel.support_radius());
        self.list.for_candidates(point, |j| {
            let r = self.domain.separation(point, &p.x[j]).norm();
            if r < r_max {
                f(j, self.kernel.w(r) * p.mass[j] / p.rho[j]);
            }
        });
    }

    /// [`Self::for_near`] over the fluid particles only.
    fn for_fluid_near(&self, point: &Vector<D>, mut f: impl FnMut(usize, f64)) {
        self.for_near(point, |j, wv| {
            if self.particles.kind[j] == Kind::Fluid {
                f(j, wv)
            }
        });
    }

    /// `Σ_j f_j W_ij V_j / Σ_j W_ij V_j` over the fluid within the kernel support of
    /// `point`; `None` where none is.
    fn shepard<const N: usize>(
        &self,
        point: &Vector<D>,
        f: impl Fn(usize) -> [f64; N],
    ) -> Option<[f64; N]> {
        let (mut num, mut den) = ([0.0; N], 0.0);
        self.for_fluid_near(point, |j, wv| {
            for (n, v) in num.iter_mut().zip(f(j)) {
                *n += v * wv;
            }
            den += wv;
        });
        (den > 0.0).then(|| num.map(|n| n / den))
    }

    /// Shepard-interpolated fluid pressure at `point`.
    pub fn pressure(&self, point: &Vector<D>) -> Option<f64> {
        let p = self.particles;
        self.shepard(point, |j| [p.p[j]]).map(|[v]| v)
    }

    /// Shepard-interpolated fluid velocity at `point`.
    pub fn velocity(&self, point: &Vector<D>) -> Option<Vector<D>> {
        let p = self.particles;
        let u = self.shepard(point, |j| std::array::from_fn(|d| p.u[j][d]));
        u.map(|u: [f64; D]| Vector::from(u))
    }

    /// Shepard-interpolated fluid density at `point`.
    pub fn density(&self, point: &Vector<D>) -> Option<f64> {
        let p = self.particles;
        self.shepard(point, |j| [p.rho[j]]).map(|[v]| v)
    }

    /// The fluid's kernel sum Γ at `point` (0 where no fluid is in reach).
    pub fn fluid_fraction(&self, point: &Vector<D>) -> f64 {
        let mut sum = 0.0;
        self.for_fluid_near(point, |_, wv| sum += wv);
        sum
    }

    /// The walls' kernel sum `Γ_w = Σ_w W V_w` at `point` (½ on a flat wall's surface).
    pub fn wall_fraction(&self, point: &Vector<D>) -> f64 {
        let mut sum = 0.0;
        self.for_near(point, |j, wv| {
            if self.particles.kind[j] == Kind::Wall {
                sum += wv
            }
        });
        sum
    }

    /// The volume and mass flow densities through a section at `point` along the unit
    /// `normal`: `[Σ_f (u_f·n) W_f V_f, Σ_f (u_f·n) W_f m_f] / (1 - Γ_w)`, with
    /// `Γ_w = Σ_w W_w V_w` the walls' kernel sum; zero inside a wall (`Γ_w >= ½`).
    ///
    /// Dividing by `1 - Γ_w` restores the kernel's share that the walls take next to
    /// them (where `Γ_f + Γ_w ≈ 1` the fluid's share counts fully), while at a free
    /// surface the fluid's taper `Γ_f` from 1 to 0 stays: integrated across a flat
    /// surface it gives the depth to the surface plane, as the gauges read it.
    pub fn flow_density(&self, point: &Vector<D>, normal: &Vector<D>) -> [f64; 2] {
        let p = self.particles;
        let (mut volume, mut mass, mut walls) = (0.0, 0.0, 0.0);
        self.for_near(point, |j, wv| match p.kind[j] {
            Kind::Fluid => {
                let un = p.u[j].dot(normal) * wv;
                volume += un;
                mass += un * p.rho[j];
            }
            Kind::Wall => walls += wv,
        });
        if walls >= 0.5 {
            return [0.0; 2];
        }
        [volume / (1.0 - walls), mass / (1.0 - walls)]
    }
}
