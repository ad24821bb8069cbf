#!/usr/bin/env python3
"""Plots the relaxed toy star and polytrope against their analytic profiles (docs/validation.md).

Usage: RTSPH_GAS_CSV_DIR=DIR build/release/physics_gas_test --gtest_filter='*Profile*:*LaneEmden*'
       scripts/plot_gas_profiles.py DIR docs/validation
The CSVs hold every particle's radius from the centre of mass and its SPH density."""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [float(r["r"]) for r in rows], [float(r["rho"]) for r in rows]


def main(src, out):
    # Toy star, 2D, gamma = 2: rho = lambda/(4K) (R^2 - r^2); scene K = 0.25, lambda = 1,
    # m = rho0 s^2 = 0.5 * 0.04^2 per particle.
    r, rho = read(f"{src}/toy_star_2d.csv")
    K, lam = 0.25, 1.0
    M = 0.5 * 0.04 ** 2 * len(r)
    R = (8 * K * M / (math.pi * lam)) ** 0.25
    xs = [R * i / 200 for i in range(201)]
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].plot(r, rho, ".", ms=2, alpha=0.4, label=f"SPH, {len(r)} particles")
    ax[0].plot(xs, [lam / (4 * K) * (R * R - x * x) for x in xs], "k-", label="ρ = λ(R² − r²)/4K")
    ax[0].set(xlabel="r", ylabel="ρ", title="toy star 2D (γ = 2, code units)")
    ax[0].legend()
    # Polytrope n = 1, G = 1: rho = rho_c sin(xi)/xi, xi = pi r/R, R = sqrt(pi K/2G),
    # rho_c = pi M/(4 R^3); scene K = 2/pi (R = 1), m = rho0 s^3.
    r, rho = read(f"{src}/polytrope_star_3d.csv")
    rho0, s = 0.238732414637843, 2.0 / 22
    M = rho0 * s ** 3 * len(r)
    R = 1.0
    rc = math.pi * M / (4 * R ** 3)
    xs = [R * i / 200 for i in range(1, 201)]
    ax[1].plot(r, rho, ".", ms=2, alpha=0.3, label=f"SPH, {len(r)} particles")
    ax[1].plot(xs, [rc * math.sin(math.pi * x / R) / (math.pi * x / R) for x in xs], "k-",
               label="Lane–Emden n = 1")
    ax[1].set(xlabel="r", ylabel="ρ", title="polytrope n = 1 under self-gravity (G = 1)")
    ax[1].legend()
    fig.tight_layout()
    fig.savefig(f"{out}/gas_profiles.png", dpi=90)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
