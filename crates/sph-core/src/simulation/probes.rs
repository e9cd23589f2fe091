//! Reading the fluid at points: Shepard-interpolated pressure and velocity, the kernel
//! sum Γ and the wave gauges' elevations built on it; in a split run each point is read
//! by the process whose region holds it.

use super::Simulation;
use crate::diagnostics::gauges::Gauge;
use crate::diagnostics::PointReader;
use crate::error::Result;
use crate::geometry;
use crate::particles::Vector;
use crate::scheme::model::Model;

impl<const D: usize> Simulation<D> {
    /// Shepard-interpolated pressures at `points` (see [`Self::probe_pressure`]): in a
    /// split run each point's from the process whose region holds it, which holds all
    /// the fluid in reach of it (collective).
    pub fn probe_pressures(&self, points: &[Vector<D>]) -> Vec<Option<f64>> {
        let values = self.at_owners(points, |x| self.probe_pressure(x).map(|p| [p]));
        values.into_iter().map(|v| v.map(|[p]| p)).collect()
    }

    /// Shepard-interpolated fluid velocities at `points` (see [`PointReader::velocity`]),
    /// in a split run each from its owner (collective).
    pub fn probe_velocities(&self, points: &[Vector<D>]) -> Vec<Option<Vector<D>>> {
        let reader = self.reader();
        let velocity = |x: &Vector<D>| reader.velocity(x).map(|u| std::array::from_fn(|d| u[d]));
        let values = self.at_owners(points, velocity);
        values.into_iter().map(|v| v.map(Vector::from)).collect()
    }

    /// The volume and mass flow densities through a section along `normal` at `points`
    /// (see [`PointReader::flow_density`]), in a split run each from its owner
    /// (collective).
    pub fn flow_densities(&self, points: &[Vector<D>], normal: &Vector<D>) -> Vec<[f64; 2]> {
        let reader = self.reader();
        let density = |x: &Vector<D>| Some(reader.flow_density(x, normal));
        let values = self.at_owners(points, density);
        values.into_iter().map(|v| v.unwrap_or([0.0; 2])).collect()
    }

    /// `f` at each of `points`; in a split run from the process whose region holds the
    /// point, which holds all the fluid in reach of it (collective).
    fn at_owners<const N: usize>(
        &self,
        points: &[Vector<D>],
        f: impl Fn(&Vector<D>) -> Option<[f64; N]>,
    ) -> Vec<Option<[f64; N]>> {
        let Some(ranks) = self.ranks() else {
            return points.iter().map(f).collect();
        };
        let mine = |x: &Vector<D>| ranks.decomposition().owner(x) == ranks.rank();
        let mut sums: Vec<f64> = (points.iter())
            .flat_map(|x| {
                let value = mine(x).then(|| f(x)).flatten();
                let found = [value.is_some() as u8 as f64];
                value.unwrap_or([0.0; N]).into_iter().chain(found)
            })
            .collect();
        ranks.sum(&mut sums);
        (sums.chunks(N + 1))
            .map(|c| (c[N] > 0.0).then(|| std::array::from_fn(|k| c[k])))
            .collect()
    }

    /// The fluid's kernel sum Γ at `points` (see [`PointReader::fluid_fraction`]); in a
    /// split run each point's owner sums it (collective).
    pub fn fluid_fractions(&self, points: &[Vector<D>]) -> Vec<f64> {
        let reader = self.reader();
        let gamma = |x: &Vector<D>| reader.fluid_fraction(x);
        let Some(ranks) = self.ranks() else {
            return points.iter().map(gamma).collect();
        };
        let mine = |x: &Vector<D>| ranks.decomposition().owner(x) == ranks.rank();
        let mut sums: Vec<f64> = (points.iter())
            .map(|x| if mine(x) { gamma(x) } else { 0.0 })
            .collect();
        ranks.sum(&mut sums);
        sums
    }

    /// The free surface's elevation above `diagnostics.still_level` on the vertical
    /// lines at `positions` (x in 2D, (x, y) in 3D), as gauges read it
    /// ([`crate::diagnostics::gauges`]); refused where the case gives no vertical extent
    /// for the lines (no `[domain]` or `[[tank]]`). Collective in a split run.
    pub fn wave_elevations(&self, positions: &[Vec<f64>]) -> Result<Vec<f64>> {
        let mut out = Vec::with_capacity(positions.len());
        for (k, position) in positions.iter().enumerate() {
            let gauge = Gauge::<D>::at(self.case(), position, &format!("positions[{k}]"))?;
            out.push(gauge.elevation(&self.fluid_fractions(&gauge.points)));
        }
        Ok(out)
    }

    /// Shepard-interpolated pressure at `point` (call [`Self::sync_pressure`] first);
    /// `None` where no fluid is within the kernel support.
    pub fn probe_pressure(&self, point: &Vector<D>) -> Option<f64> {
        self.reader().pressure(point)
    }

    /// The run read at points with its own kernel (one process's particles in a split
    /// run).
    fn reader(&self) -> PointReader<'_, D, dyn Model<D>> {
        let s = &self.stepper;
        PointReader {
            kernel: s.model.as_ref(),
            particles: self.particles(),
            list: &s.list,
            domain: &s.domain,
        }
    }

    /// Why no fluid can ever reach `point` (what a probe point is expected to be; see
    /// [`geometry::probe_refusal`]), or `None` where fluid can.
    pub fn probe_refusal(&self, point: &Vector<D>) -> Option<String> {
        geometry::probe_refusal(&self.case, &self.stepper.domain, &self.wall_solids, point)
    }
}
