#!/usr/bin/env python3
"""Tutorial step 2: writes a small deconvolution problem in Matrix Market form (standard library only).

A is the Gaussian average R_eta of the seed paper (2.7)-(2.8) on a column of n = 64 points across a channel of
width 1, eta = 1/16, normalised so that each row sums to one (a square, symmetric, coarse-coarse operator);
x_true is the Poiseuille profile 4 y (1 - y) (zero at the walls); b = A x_true + noise, the noise Gaussian with
seed 1 and standard deviation 1e-4 per entry. Writes A.mtx, x_true.mtx, b.mtx and prints ||noise||_2, the value
to give `--noise-level` for the discrepancy principle.

Usage: python3 docs/tutorials/step-2/make_system.py OUT_DIR
"""
import math
import random
import sys


def write_array(path, rows, cols, entry):
    with open(path, "w") as f:
        f.write("%%MatrixMarket matrix array real general\n")
        f.write(f"{rows} {cols}\n")
        for j in range(cols):  # array format: column-major
            for i in range(rows):
                f.write(f"{entry(i, j):.17g}\n")


def main(out):
    n, eta = 64, 1.0 / 16
    y = [(i + 0.5) / n for i in range(n)]
    a = [[math.exp(-((y[i] - y[j]) / eta) ** 2) for j in range(n)] for i in range(n)]
    a = [[v / sum(row) for v in row] for row in a]
    x = [4 * t * (1 - t) for t in y]
    rng = random.Random(1)
    noise = [rng.gauss(0.0, 1e-4) for _ in range(n)]
    b = [sum(a[i][j] * x[j] for j in range(n)) + noise[i] for i in range(n)]
    write_array(f"{out}/A.mtx", n, n, lambda i, j: a[i][j])
    write_array(f"{out}/x_true.mtx", n, 1, lambda i, j: x[i])
    write_array(f"{out}/b.mtx", n, 1, lambda i, j: b[i])
    print(f"{math.sqrt(sum(e * e for e in noise)):.6g}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    main(sys.argv[1])
