#!/usr/bin/env python3
"""Expected lag-1 autocorrelation of the diagnosis's whitened residual when the noise model is wrong.

usage: whitened_lag1_expectation.py LOG [LOG ...]

Reads the "target ...: noise sigma true T, used U (model scatter S, lag-1 RHO, N runs: whitened)"
lines a Hertz twin test prints (test_hertz_hidden_cohesion.cpp) and, per seed and target, computes
what the diagnosis's whitening leaves when the residual's true covariance is

    C_true(k) = T^2 I + k S^2 R(RHO),   R(rho)_ij = rho^|i-j|

against the noise model the diagnosis whitens with (diagnose/src/model_scatter.cpp)

    C_model = (U^2 - S^2) I + S^2 R(RHO).

k = 1: the residual carries one run's scatter (the model's); k = 2: two independent realisations,
the model run's and the data's own (the twin's data are one DEM run plus white noise). For each k
it prints the expected lag-1 autocorrelation of L^-1 r (L the Cholesky factor of C_model),
sum_i S_i,i-1 / trace S with S = L^-1 C_true L^-T, and the whitened variance trace S / n: the values
the residual tests see for a model that is right. The lag-1 test assumes 0 (Bartlett: N(-1/n, 1/n)).
Points per target: 41 (the twin's image surface).
"""
import re, sys
import numpy as np

POINTS = 41
LINE = re.compile(r'seed (\d+)\].*|target (\S+): noise sigma true ([0-9.]+), used ([0-9.]+) '
                  r'\(model scatter ([0-9.]+), lag-1 ([0-9.]+)')


def ar1(n, rho):
    i = np.arange(n)
    return rho ** np.abs(i[:, None] - i[None, :])


def whitened(c_true, c_model):
    l_inv = np.linalg.inv(np.linalg.cholesky(c_model))
    s = l_inv @ c_true @ l_inv.T
    n = s.shape[0]
    return sum(s[i, i - 1] for i in range(1, n)) / np.trace(s), np.trace(s) / n


def main():
    seed = None
    print('| seed | target | white sigma (true) | white sigma (model) | scatter | lag-1 | k = 1: lag-1, variance | k = 2: lag-1, variance |')
    print('|---|---|---|---|---|---|---|---|')
    for path in sys.argv[1:]:
        for line in open(path):
            m = re.search(r'twin at 15 and 45 rpm, hidden cohesion, seed (\d+)\]', line)
            if m:
                seed = m.group(1)
                continue
            m = re.search(r'target (\S+): noise sigma true ([0-9.]+), used ([0-9.]+) \(model scatter ([0-9.]+), '
                          r'lag-1 ([0-9.]+)', line)
            if not m or seed is None:
                continue
            name = m.group(1)
            true_white, used, scatter, rho = (float(m.group(i)) for i in range(2, 6))
            model_white = (used ** 2 - scatter ** 2) ** 0.5
            c_model = model_white ** 2 * np.eye(POINTS) + scatter ** 2 * ar1(POINTS, rho)
            cells = []
            for k in (1, 2):
                c_true = true_white ** 2 * np.eye(POINTS) + k * scatter ** 2 * ar1(POINTS, rho)
                lag, var = whitened(c_true, c_model)
                cells.append('%.3f, %.2f' % (lag, var))
            print('| %s | %s | %.3f | %.3f | %.3f | %.3f | %s | %s |' % (seed, name, true_white, model_white, scatter, rho,
                                                                 cells[0], cells[1]))


if __name__ == '__main__':
    main()
