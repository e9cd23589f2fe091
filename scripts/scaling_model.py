#!/usr/bin/env python3
"""The scaling model of docs/scaling.md: time per step of a 3D δ-SPH run (RK4) on P
nodes, one process per node with its threads, split by recursive coordinate bisection.

Measured here (2-core machine; see docs/scaling.md for the commands):
  RATE_PER_CORE  3D particle-steps/s per core (README scaling table: 0.26-0.33 M on
                 2 threads at 10^5-10^6 particles)
  BYTES          resident bytes per particle in 3D (README: 2 240 at 10^6)
  halo formula   H = 6 n² w + 3π n w² + (4/3)π w³ for a box of n³ particles and a halo
                 w spacings deep, within 0.7% of `sph-cli check --ranks` on a periodic
                 cube of 10^6 particles (w = 4: 68 080 and 19 180 per box at P = 8, 64)
Assumed (stated in docs/scaling.md): the node, the network and the skin.
"""
import math

N = 1e8                      # particles of the 3D case
RATE_PER_CORE = 0.15e6       # particle-steps/s per core (measured, 3D)
THREAD_EFFICIENCY = 0.6      # assumed at 64 threads (memory bandwidth)
CORES = 64                   # assumed node: 2 × 32 cores, 256 GB
BYTES = 2240                 # bytes per particle (measured, 3D)
W = 5                        # halo depth in spacings: support 4Δx plus a skin of 1Δx
HALO_BYTES = (2 * 3 + 2) * 8 + 9   # x, u, ρ, m, id, kind (decomposition::halo_bytes)
EXCHANGES = 5                # per RK4 step: 4 stage states + the δ-SPH gradient
NEIGHBOURS = 26              # messages per exchange and process (3D)
BANDWIDTH = 12e9             # bytes/s per node, assumed (InfiniBand HDR100)
LATENCY = 2e-6               # s per message, assumed
REDUCTIONS = 2               # allreduce per step: Δt and the stability guard


def halo(particles_per_rank, w=W):
    n = particles_per_rank ** (1.0 / 3.0)
    return 6 * n * n * w + 3 * math.pi * n * w * w + 4.0 / 3.0 * math.pi * w ** 3


def step(nodes, per_node=None):
    """(compute, communication, halo fraction, memory per node [GB]) of one step."""
    owned = per_node if per_node else N / nodes
    compute = owned / (RATE_PER_CORE * CORES * THREAD_EFFICIENCY)
    if nodes == 1:
        return compute, 0.0, 0.0, owned * BYTES / 1e9
    h = halo(owned)
    volume = EXCHANGES * h * HALO_BYTES / BANDWIDTH
    latency = EXCHANGES * NEIGHBOURS * LATENCY + REDUCTIONS * math.log2(nodes) * LATENCY
    return compute, volume + latency, h / owned, (owned + h) * BYTES / 1e9


def table(title, rows):
    print(f"\n{title}\n")
    print("| nodes | particles per node | halo / owned | memory per node [GB] | "
          "compute [s] | communication [s] | efficiency |")
    print("|---|---|---|---|---|---|---|")
    base = None
    for nodes, per_node in rows:
        c, m, f, mem = step(nodes, per_node)
        t = c + m
        if per_node:
            eff = (step(1, per_node)[0]) / t
        else:
            base = base or t
            eff = base / (nodes * t)
        owned = per_node or N / nodes
        print(f"| {nodes} | {owned:.3g} | {100 * f:.0f}% | {mem:.1f} | {c:.3g} | {m:.2g} | "
              f"{100 * eff:.0f}% |")


table("Strong scaling, 10⁸ particles", [(p, None) for p in (1, 2, 4, 8, 16, 32, 64)])
table("Weak scaling, 1.5·10⁶ particles per node",
      [(p, 1.5e6) for p in (1, 2, 4, 8, 16, 32, 64)])
