"""Speed of vehdyn's rigid-body layer, with errors against an independent evaluation.

Run: ``python benchmarks/bench_rigid_body.py``. Prints, from one run on this machine:

1. ``newton_euler`` on 10,000 states at once against a per-sample Python loop of
   ``np.linalg.solve`` and ``np.cross`` (the naive baseline): time, ratio and max difference;
2. ``RigidBody6DOF.rhs`` per batch member for batches of 1, 100 and 10,000 variants against 100
   single calls in a loop: time per variant and speed-up;
3. the Jacobians (A, B, C, D) from ``RigidBody6DOF.jacobian`` (analytic) against the core's
   fourth-order central differences (one batched call of rhs and output on 72 points): time,
   ratio and their max difference relative to each matrix's largest entry.
"""

from __future__ import annotations

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
import platform
import time

import numpy as np



def main():
    import vehdyn
    from vehdyn.mechanics import InertiaTensor, RigidBody6DOF, newton_euler

    rng = np.random.default_rng(0)
    inertia = InertiaTensor(540.0, 2400.0, 2600.0, ixy=12.0, ixz=-60.0, iyz=8.0)
    mass = 1500.0
    print(f"vehdyn {vehdyn.__version__}, numpy {np.__version__}, Python {platform.python_version()}")

    # 1. newton_euler batched against a per-sample loop
    n = 10_000
    velocity, omega, force, moment = (rng.normal(size=(3, n)) * s for s in (10.0, 0.5, 3000.0, 2000.0))

    def naive():
        out = np.empty((2, 3, n))
        matrix = inertia.matrix
        for k in range(n):
            out[0, :, k] = force[:, k] / mass - np.cross(omega[:, k], velocity[:, k])
            out[1, :, k] = np.linalg.solve(matrix, moment[:, k] - np.cross(omega[:, k], matrix @ omega[:, k]))
        return out

    t_batch, (v_dot, w_dot) = best_time(lambda: newton_euler(mass, inertia, velocity, omega, force, moment))
    t_loop, reference = best_time(naive, repeats=2)
    err = max(np.max(np.abs(v_dot - reference[0])) / np.max(np.abs(reference[0])),
              np.max(np.abs(w_dot - reference[1])) / np.max(np.abs(reference[1])))
    print(f"\n1. newton_euler on {n} states")
    print(f"{'method':<28}{'time [ms]':>12}{'ratio':>10}{'max rel diff':>15}")
    print(f"{'vehdyn batched':<28}{t_batch * 1e3:>12.3f}{1.0:>10.1f}{'-':>15}")
    print(f"{'per-sample loop (naive)':<28}{t_loop * 1e3:>12.3f}{t_loop / t_batch:>10.1f}{err:>15.2e}")

    # 2. rhs per variant
    body = RigidBody6DOF(mass=mass, inertia=inertia, gravity=9.81)
    print("\n2. RigidBody6DOF.rhs, time per variant")
    print(f"{'batch size':<28}{'time [us]':>12}{'speed-up':>10}")
    x1 = np.zeros(12)
    x1[0] = 20.0
    u1 = np.zeros(6)
    t_single, _ = best_time(lambda: [body.rhs(0.0, x1, u1) for _ in range(100)])
    t_single /= 100
    print(f"{'1 (loop of 100 calls)':<28}{t_single * 1e6:>12.2f}{1.0:>10.1f}")
    for size in (100, 10_000):
        X = rng.normal(size=(12, size)) * 0.2
        X[0] += 20.0
        U = rng.normal(size=(6, size)) * 500.0
        t_b, F = best_time(lambda: body.rhs(0.0, X, U))
        per = t_b / size
        print(f"{size:<28}{per * 1e6:>12.3f}{t_single / per:>10.1f}")
        assert np.all(np.isfinite(F))

    # 3. linearization: analytic against finite differences
    x0 = {"longitudinal_velocity": 25.0, "yaw_rate": 0.2, "roll_angle": 0.03}
    u0 = {"vertical_force": -mass * 9.81}
    x0v, u0v = body.state_vector(x0), body.input_vector(u0)
    t_exact, exact = best_time(lambda: body.jacobian(0.0, x0v, u0v))
    t_fd, fd = best_time(lambda: body._finite_difference_jacobian(0.0, x0v, u0v))
    diff = max(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300) for a, b in zip(exact, fd))
    print("\n3. Jacobians about a steady turn")
    print(f"{'method':<28}{'time [ms]':>12}{'ratio':>10}{'max rel diff':>15}")
    print(f"{'analytic jacobian':<28}{t_exact * 1e3:>12.3f}{1.0:>10.1f}{'-':>15}")
    print(f"{'central differences':<28}{t_fd * 1e3:>12.3f}{t_fd / t_exact:>10.1f}{diff:>15.2e}")


if __name__ == "__main__":
    main()
