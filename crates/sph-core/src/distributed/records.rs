//! Particles as bytes, for the messages between processes: whole particles (when they
//! move to another process, or join one's halo) and their state `(x, u, ρ)` (the halo
//! refreshed before an evaluation). Native byte order: the processes of a run share a
//! machine type.

use crate::particles::{Kind, Particles, Value, Vector};

/// Appends values to a message.
#[derive(Default)]
pub(super) struct Writer(pub(super) Vec<u8>);

impl Writer {
    /// Particle `i` of `p` whole, every column ([`Particles::write_particle`]).
    pub(super) fn particle<const D: usize>(&mut self, p: &Particles<D>, i: usize) {
        p.write_particle(i, &mut self.0);
    }

    /// The position and kind of particle `i` (for a new bisection).
    pub(super) fn position<const D: usize>(&mut self, p: &Particles<D>, i: usize) {
        p.x[i].put(&mut self.0);
        p.kind[i].put(&mut self.0);
    }
}

/// Reads values off a message, in the order they were written.
pub(super) struct Reader<'a> {
    bytes: &'a [u8],
}

impl<'a> Reader<'a> {
    pub(super) fn new(bytes: &'a [u8]) -> Self {
        Self { bytes }
    }

    pub(super) fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    /// Appends the next whole particle to `p` (which has the writer's columns).
    pub(super) fn particle<const D: usize>(&mut self, p: &mut Particles<D>) {
        p.read_particle(&mut self.bytes);
    }

    /// Appends the next position and kind.
    pub(super) fn position<const D: usize>(
        &mut self,
        x: &mut Vec<Vector<D>>,
        kind: &mut Vec<Kind>,
    ) {
        x.push(Value::get(&mut self.bytes));
        kind.push(Value::get(&mut self.bytes));
    }
}

/// Bytes of a state record `(x, u, ρ)` in D dimensions: a fixed size, so that the
/// records of a message are written and read in parallel.
pub(super) const fn state_len<const D: usize>() -> usize {
    (2 * D + 1) * 8
}

/// Writes the state `(x, u, ρ)` of particle `i` into `out`, [`state_len`] bytes.
pub(super) fn put_state<const D: usize>(out: &mut [u8], p: &Particles<D>, i: usize) {
    let values = (p.x[i].iter().chain(p.u[i].iter())).chain(std::iter::once(&p.rho[i]));
    for (bytes, v) in out.chunks_exact_mut(8).zip(values) {
        bytes.copy_from_slice(&v.to_ne_bytes());
    }
}

/// The state `(x, u, ρ)` in a record written by [`put_state`].
pub(super) fn get_state<const D: usize>(record: &[u8]) -> (Vector<D>, Vector<D>, f64) {
    let value = |k: usize| f64::from_ne_bytes(record[8 * k..8 * k + 8].try_into().expect("8"));
    let x = Vector::from_fn(|d, _| value(d));
    let u = Vector::from_fn(|d, _| value(D + d));
    (x, u, value(2 * D))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_state_reads_back_as_written() {
        let mut p = Particles::<2>::default();
        let (x, u) = (Vector::<2>::new(0.5, -1.25), Vector::<2>::new(3.0, 1e-300));
        p.push(Kind::Fluid, x, u, 1000.125, 1.0);
        let mut record = vec![0u8; state_len::<2>()];
        put_state(&mut record, &p, 0);
        assert_eq!(get_state::<2>(&record), (x, u, 1000.125));
    }

    #[test]
    fn a_particle_reads_back_as_written() {
        let mut p = Particles::<3>::default();
        let v = |a: f64| Vector::<3>::new(a, -2.0 * a, 0.1 + a);
        p.push(Kind::Fluid, v(1.0), v(2.0), 1000.5, 0.25);
        p.push(Kind::Wall, v(3.0), v(4.0), 999.0, 0.5);
        (p.p[1], p.u_wall_visc[1], p.id[1]) = (12.5, v(7.0), 4_000_000_000);
        p.shift_velocity = Some(vec![v(5.0), v(6.0)]);
        let mut w = Writer::default();
        w.particle(&p, 1);
        w.particle(&p, 0);
        let mut q = p.empty_like();
        let mut r = Reader::new(&w.0);
        while !r.is_empty() {
            r.particle(&mut q);
        }
        assert_eq!(
            (q.x.clone(), q.u.clone(), q.rho.clone()),
            (
                vec![p.x[1], p.x[0]],
                vec![p.u[1], p.u[0]],
                vec![999.0, 1000.5]
            )
        );
        assert_eq!(
            (q.p[0], q.mass.clone(), q.kind.clone()),
            (12.5, vec![0.5, 0.25], vec![Kind::Wall, Kind::Fluid])
        );
        assert_eq!(
            (q.id.clone(), q.u_wall_visc[0], q.shift_velocity.unwrap()),
            (vec![4_000_000_000, 0], v(7.0), vec![v(6.0), v(5.0)])
        );
    }
}
