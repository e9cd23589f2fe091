#!/usr/bin/env python3
"""The scaling model of docs/scaling.md: time per step of a 3D δ-SPH run (RK4) on P
nodes, one process per node with its threads, split by recursive coordinate bisection.

Measured here (2-core machine; docs/scaling.md gives the commands):
  RATE_PER_CORE  3D particle-steps/s per core (docs/scaling.md: 0.26-0.33 M on
                 2 threads at 10^5-10^6 particles, h = 2Δx)
  BYTES          resident bytes per particle in 3D (docs/testing.md: 957 measured at
                 10^6 and h = 1.33Δx, 305 of them in the neighbour rows; the rows
                 grow as (R + s)^3, about 3x at h = 2Δx: 1 600)
  SKIN           the list skin over the support: the dam breaks' halos are 7.0
                 spacings deep at R = 2.66Δx with two passes, 2 (R + s) = 7.0Δx
  REFRESHES      halo refreshes per RK4 step (244 in 61 steps, 3D dam break)
  REBUILD_EVERY  steps per list rebuild, when the halo is gathered whole (61 / 10)
  PACK_S, SCAN_S seconds of a refresh on one thread per halo particle (packing and
                 unpacking its record) and per particle held (the unpacking pass):
                 0.25 ms for 2 233 of 107 000 (2D), 0.56-0.68 ms for 13 594 of
                 131 000 (3D); both parallel over the threads
  halo formula   H = 6 n² w + 3π n w² + (4/3)π w³ for a box of n³ particles and a halo
                 w spacings deep, within 0.7% of `sph-cli check --ranks` on a periodic
                 cube of 10^6 particles
Assumed (stated in docs/scaling.md): the node, the network.
"""
import math

N = 1e8                      # particles of the 3D case
RATE_PER_CORE = 0.15e6       # particle-steps/s per core (measured, 3D)
THREAD_EFFICIENCY = 0.6      # assumed at 64 threads (memory bandwidth)
CORES = 64                   # assumed node: 2 × 32 cores, 256 GB
BYTES = 1600                 # bytes per particle, 3D, h = 2Δx (estimated, below)
SUPPORT = 4.0                # kernel support in spacings (Wendland C2, h = 2Δx, default)
SKIN = 0.33                  # list skin over the support (measured)
PASSES = 2                   # pair passes per evaluation (δ-SPH: gradient, pair loop)
REFRESHES = 4                # halo refreshes per step (measured)
STATE_BYTES = 7 * 8          # x, u, ρ in 3D
GRADIENT_BYTES = 3 * 8       # the renormalised density gradient, in 3D
REBUILD_EVERY = 6            # steps per list rebuild (measured)
RECORD_BYTES = 13 * 8 + 5    # a whole particle: x, u, ρ, p, m, wall velocity, id, kind
PACK_S = 23e-9               # s per halo particle and refresh on one thread (measured)
SCAN_S = 2.35e-9             # s per particle held and refresh on one thread (measured)
BANDWIDTH = 12e9             # bytes/s per node, assumed (InfiniBand HDR100)
LATENCY = 2e-6               # s per message, assumed
COLLECTIVES = 2              # per exchange: the counts (all-to-all), then the data
REDUCTIONS = 4               # allreduce per step: acceleration, speed, list, guard


def depth(passes=PASSES):
    """Halo depth w in spacings: passes × (R + s)."""
    return passes * SUPPORT * (1.0 + SKIN)


def halo(particles_per_rank, w):
    n = particles_per_rank ** (1.0 / 3.0)
    return 6 * n * n * w + 3 * math.pi * n * w * w + 4.0 / 3.0 * math.pi * w ** 3


def communication(nodes, owned, h, between_passes):
    """Seconds per step of halo traffic, message latency and reductions."""
    refresh_bytes = REFRESHES * h * (STATE_BYTES + (GRADIENT_BYTES if between_passes else 0))
    rebuild_bytes = h * RECORD_BYTES / REBUILD_EVERY
    exchanges = REFRESHES * (2 if between_passes else 1)
    pack = exchanges * (h * PACK_S + (owned + h) * SCAN_S) / (CORES * THREAD_EFFICIENCY)
    messages = (exchanges + 1.0 / REBUILD_EVERY) * COLLECTIVES
    latency = messages * (nodes - 1) * LATENCY
    latency += REDUCTIONS * math.log2(nodes) * LATENCY
    return (refresh_bytes + rebuild_bytes) / BANDWIDTH + pack + latency


def step(nodes, per_node=None, between_passes=False):
    """(compute, communication, halo fraction, memory per node [GB]) of one step.

    As built, the halo is `PASSES` deep and its inner `PASSES - 1` layers are evaluated
    with the own particles (their fluid rows add their share to every pair pass); with
    an exchange between the passes it is one pass deep, not evaluated, and the δ-SPH
    gradient is exchanged as well."""
    owned = per_node if per_node else N / nodes
    compute = owned / (RATE_PER_CORE * CORES * THREAD_EFFICIENCY)
    if nodes == 1:
        return compute, 0.0, 0.0, owned * BYTES / 1e9
    h = halo(owned, depth(1 if between_passes else PASSES))
    if not between_passes:
        compute *= 1.0 + halo(owned, depth(PASSES - 1)) / owned
    return (compute, communication(nodes, owned, h, between_passes), h / owned,
            (owned + h) * BYTES / 1e9)


def table(title, rows, **kind):
    print(f"\n{title}\n")
    print("| nodes | particles per node | halo / owned | memory per node [GB] | "
          "compute [s] | communication [s] | efficiency |")
    print("|---|---|---|---|---|---|---|")
    base = None
    for nodes, per_node in rows:
        c, m, f, mem = step(nodes, per_node, **kind)
        t = c + m
        if per_node:
            eff = step(1, per_node)[0] / t
        else:
            base = base or t
            eff = base / (nodes * t)
        owned = per_node or N / nodes
        print(f"| {nodes} | {owned:.3g} | {100 * f:.0f}% | {mem:.1f} | {c:.3g} | {m:.2g} | "
              f"{100 * eff:.0f}% |")


NODES = (1, 2, 4, 8, 16, 32, 64)
print(f"halo depth: {depth():.1f} spacings (δ-SPH), {depth(3):.1f} (with shifting), "
      f"{depth(1):.1f} (an exchange between passes)")
table("Strong scaling, 10⁸ particles, δ-SPH (as built: one exchange per evaluation)",
      [(p, None) for p in NODES])
table("Strong scaling, 10⁸ particles, δ-SPH with an exchange between the two passes",
      [(p, None) for p in NODES], between_passes=True)
table("Weak scaling, 1.5·10⁶ particles per node, δ-SPH (as built)",
      [(p, 1.5e6) for p in NODES])
table("Weak scaling, 1.5·10⁶ particles per node, an exchange between the passes",
      [(p, 1.5e6) for p in NODES], between_passes=True)
