#!/usr/bin/env python3
"""The 2D dam break's surge front against Martin & Moyce (1952), plotted with matplotlib.

A water column of width a = 1 m and height 2a collapses; the front x (from the back wall) is
recorded in the dimensionless units of the experiment, T = t·sqrt(2g/a) and Z = x/a, and
plotted over their measurements (their 2.25 in column, n² = 2). docs/python.md walks through it.

    python examples/dam_break_front.py                      # 5,000 particles, about a minute
    python examples/dam_break_front.py --method pbf --out front_pbf.png
"""
import argparse
import math

import rtsph

# Martin & Moyce 1952, surge front of the n² = 2 column: (T, Z).
MARTIN_MOYCE = [(0.41, 1.11), (0.84, 1.22), (1.19, 1.44), (1.43, 1.67), (1.63, 1.89),
                (1.83, 2.11), (1.98, 2.33), (2.20, 2.56), (2.32, 2.78), (2.51, 3.00)]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--method", default="wcsph", choices=rtsph.solver_methods())
    ap.add_argument("--spacing", type=float, default=0.02, help="particle spacing (m)")
    ap.add_argument("--until", type=float, default=2.55, help="end, in the experiment's T units")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--out", default="dam_break_front.png")
    args = ap.parse_args()

    a, g = 1.0, 9.81
    scale = math.sqrt(2 * g / a)  # t -> T
    scene = rtsph.scene("dam_break_2d", {"fluid.spacing": args.spacing, "solver.method": args.method})
    sim = rtsph.Simulation(scene, threads=args.threads)
    T, Z = [], []

    def record(s: rtsph.Simulation) -> None:
        # A particle stands for a cell one spacing wide, so the front is half a spacing further.
        T.append(s.time * scale)
        Z.append((float(s.positions[:, 0].max()) + 0.5 * args.spacing) / a)

    sim.run(until=args.until / scale, every=0.01 / scale, callback=record, progress=True)

    def z_at(t: float) -> float:
        for k in range(1, len(T)):
            if T[k] >= t:
                w = (t - T[k - 1]) / (T[k] - T[k - 1])
                return Z[k - 1] + w * (Z[k] - Z[k - 1])
        return Z[-1]

    print(f"{args.method}, {sim.particle_count} particles, {sim.stats['steps']} steps in {sim.stats['wall_s']:.1f} s")
    print("    T   Z_exp   Z_sph    error")
    for t, z in MARTIN_MOYCE:
        if t <= T[-1]:
            print(f"{t:5.2f}  {z:5.2f}  {z_at(t):6.3f}  {100 * (z_at(t) / z - 1):+6.1f}%")

    import matplotlib
    matplotlib.use("Agg")  # files only: no display needed
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(T, Z, label=f"rtsph {args.method}, spacing {args.spacing} m")
    ax.plot(*zip(*MARTIN_MOYCE), "o", label="Martin & Moyce 1952")
    ax.set_xlabel(r"$T = t\sqrt{2g/a}$")
    ax.set_ylabel(r"$Z = x/a$")
    ax.set_title("Dam break: surge front")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
