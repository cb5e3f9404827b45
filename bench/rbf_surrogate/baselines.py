#!/usr/bin/env python3
"""Baselines for bench_rbf_surrogate: scipy differential evolution, scipy Nelder-Mead and a
scikit-learn Gaussian-process expected-improvement loop, on the same problems, targets and budgets
as the C++ bench. Prints one line per run:  RESULT <method> <problem> <seed> <evaluations|-1>
(-1: target not reached within the budget).
Usage: baselines.py [seeds] [method,method,...] [problem,problem,...]. Needs python3-scipy and python3-sklearn
(scripts/setup --bench); prints "SKIPPED <reason>" and exits 0 when they are missing."""
import math
import sys

try:
    import numpy as np
    from scipy.optimize import differential_evolution, minimize
    from scipy.stats import norm, qmc
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import ConstantKernel, Matern, WhiteKernel
except ImportError as exc:  # pragma: no cover
    print("SKIPPED", exc)
    sys.exit(0)

import warnings
warnings.filterwarnings("ignore")


def branin(x):
    b, c, t = 5.1 / (4 * math.pi ** 2), 5 / math.pi, 1 / (8 * math.pi)
    return (x[1] - b * x[0] ** 2 + c * x[0] - 6) ** 2 + 10 * (1 - t) * math.cos(x[0]) + 10


ALPHA = [1.0, 1.2, 3.0, 3.2]
A = [[10, 3, 17, 3.5, 1.7, 8], [0.05, 10, 17, 0.1, 8, 14], [3, 3.5, 1.7, 10, 17, 8], [17, 8, 0.05, 10, 0.1, 14]]
P = [[1312, 1696, 5569, 124, 8283, 5886], [2329, 4135, 8307, 3736, 1004, 9991],
     [2348, 1451, 3522, 2883, 3047, 6650], [4047, 8828, 8732, 5743, 1091, 381]]


def hartmann6(x):
    return -sum(ALPHA[i] * math.exp(-sum(A[i][j] * (x[j] - 1e-4 * P[i][j]) ** 2 for j in range(6)))
                for i in range(4))


def rosenbrock(x):
    return sum(100 * (x[i + 1] - x[i] ** 2) ** 2 + (1 - x[i]) ** 2 for i in range(len(x) - 1))


# name: (function, bounds, target on the TRUE value of the incumbent, budget, noisy)
PROBLEMS = {
    "branin": (branin, [(-5, 10), (0, 15)], 0.397887357729739 + 1e-3, 100, False),
    "hartmann6": (hartmann6, [(0, 1)] * 6, 0.99 * -3.32236801141551, 300, False),
    "rosenbrock4": (rosenbrock, [(-2, 2)] * 4, 0.1, 300, False),
    "branin_noisy": (branin, [(-5, 10), (0, 15)], 0.397887357729739 + 1e-2, 100, True),
}


class Budget(Exception):
    pass


class Counter:
    """Counts evaluations, adds 1 % multiplicative noise for noisy problems, and records the first
    evaluation at which the incumbent (best OBSERVED value) has a true value meeting the target."""

    def __init__(self, f, target, budget, noisy, seed):
        self.f, self.target, self.budget, self.noisy = f, target, budget, noisy
        self.rng = np.random.default_rng(seed)
        self.n, self.best_obs, self.hit = 0, math.inf, -1

    def __call__(self, x):
        if self.n >= self.budget or self.hit > 0:
            raise Budget()
        true = self.f(list(x))
        obs = true * (1 + 0.01 * self.rng.standard_normal()) if self.noisy else true
        self.n += 1
        if obs < self.best_obs:
            self.best_obs = obs
            if true <= self.target:
                self.hit = self.n
        return obs


def run_de(c, bounds, seed):
    differential_evolution(c, bounds, seed=seed, maxiter=100000, tol=0, polish=True)


def run_nm(c, bounds, seed):
    rng = np.random.default_rng(seed)
    lo, hi = np.array(bounds, float).T
    while True:  # restarts from random points until the budget is used
        x0 = lo + rng.random(len(bounds)) * (hi - lo)
        minimize(c, x0, method="Nelder-Mead", bounds=bounds, options={"xatol": 1e-8, "fatol": 1e-10})


def run_gp_ei(c, bounds, seed, initial=None):
    d = len(bounds)
    lo, hi = np.array(bounds, float).T
    rng = np.random.default_rng(seed)
    u = qmc.LatinHypercube(d=d, seed=seed).random(initial or 2 * (d + 1))
    xs = [list(lo + ui * (hi - lo)) for ui in u]
    ys = [c(x) for x in xs]
    kernel = ConstantKernel(1.0) * Matern(length_scale=[0.2] * d, nu=2.5) + WhiteKernel(1e-6, (1e-10, 1e-1))
    fitted = None
    while True:
        xu = (np.array(xs) - lo) / (hi - lo)
        # Hyperparameters re-optimised every 5 points (the cost of the baseline, not of its quality).
        if fitted is None or len(xs) % 5 == 0:
            gp = GaussianProcessRegressor(kernel, normalize_y=True, n_restarts_optimizer=1, random_state=seed)
        else:
            gp = GaussianProcessRegressor(fitted, normalize_y=True, optimizer=None)
        gp.fit(xu, np.array(ys))
        fitted = gp.kernel_
        best = min(ys)

        def neg_ei(z):
            m, s = gp.predict(np.atleast_2d(z), return_std=True)
            s = np.maximum(s, 1e-12)
            g = (best - m) / s
            return -((best - m) * norm.cdf(g) + s * norm.pdf(g))

        cand = rng.random((2000, d))
        ei = neg_ei(cand)
        starts = cand[np.argsort(ei)[:3]]
        z_best, f_best = starts[0], ei.min()
        for z0 in starts:
            r = minimize(lambda z: float(neg_ei(z)[0]), z0, method="L-BFGS-B", bounds=[(0, 1)] * d)
            if r.fun < f_best:
                z_best, f_best = r.x, r.fun
        x = list(lo + np.clip(z_best, 0, 1) * (hi - lo))
        xs.append(x)
        ys.append(c(x))


def run_gp_ei_small_design(c, bounds, seed):
    """The same GP-EI loop started from d+1 points (demfit_ei's default design size), to check that
    demfit_ei's lead is not only its smaller initial design."""
    run_gp_ei(c, bounds, seed, initial=len(bounds) + 1)


METHODS = {"scipy_de": run_de, "scipy_nelder_mead": run_nm, "sklearn_gp_ei": run_gp_ei,
           "sklearn_gp_ei_d1": run_gp_ei_small_design}
DEFAULT_METHODS = ["scipy_de", "scipy_nelder_mead", "sklearn_gp_ei"]


def main():
    seeds = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    methods = sys.argv[2].split(",") if len(sys.argv) > 2 else DEFAULT_METHODS
    problems = sys.argv[3].split(",") if len(sys.argv) > 3 else list(PROBLEMS)
    for method in methods:
        for name, (f, bounds, target, budget, noisy) in PROBLEMS.items():
            if name not in problems:
                continue
            for seed in range(1, seeds + 1):
                # Cheap direct-search baselines get 20x the budget so that the evaluations they need
                # can be measured at all; the GP loop gets the surrogate methods' budget.
                limit = budget if method.startswith("sklearn_gp_ei") else 20 * budget
                c = Counter(f, target, limit, noisy, 1000 + seed)
                try:
                    METHODS[method](c, bounds, seed)
                except Budget:
                    pass
                print("RESULT", method, name, seed, c.hit, flush=True)


if __name__ == "__main__":
    main()
