"""Driving a simulation from a study script: steps to each sampling time, the work
counted, and the loads read."""
import time

import numpy as np


class Sampler:
    """Iterating steps `sim` to each multiple of `every` up to `end` and yields that time;
    `wall` is then the wall time so far [s] and `rate` the particle-steps per second.
    `after_step(t_before)`, when given, is called after every step."""

    def __init__(self, sim, end, every, after_step=None):
        self.sim, self.end, self.every = sim, end, every
        self.after_step = after_step
        self.wall, self.particle_steps = 0.0, 0.0

    def __iter__(self):
        start = time.perf_counter()
        for k in range(1, round(self.end / self.every) + 1):
            t = self.every * k
            while self.sim.time < t * (1 - 1e-12):
                before = self.sim.time
                self.sim.step()
                self.particle_steps += self.sim.n_particles
                if self.after_step is not None:
                    self.after_step(before)
            self.wall = time.perf_counter() - start
            yield t

    @property
    def rate(self):
        return self.particle_steps / self.wall


def body_force(sim, name):
    """The fluid's force on the body `name`, pressure and viscous."""
    load = sim.loads()[name]
    return np.asarray(load["pressure"]) + np.asarray(load["viscous"])


def running_mean(t, f, width):
    """Mean of the samples of f within width/2 of each time t (sorted)."""
    lo = np.searchsorted(t, t - 0.5 * width, side="left")
    hi = np.searchsorted(t, t + 0.5 * width, side="right")
    sums = np.concatenate([[0.0], np.cumsum(f)])
    return (sums[hi] - sums[lo]) / (hi - lo)
