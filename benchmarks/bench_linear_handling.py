"""Speed against error of a 10-s step steer of the linear bicycle model (sedan, 25 m/s, 1 kHz output).

Reference: the closed-form step response x(t) = A^-1 (e^(A t) - I) B delta, evaluated by eigen-
decomposition (independent of vehdyn.simulate). Methods: vehdyn's exact discretization, RK4 and
solve_ivp integrators, scipy.signal.lsim and python-control's forced_response. Times are the median
of repeated runs measured in this process; ratios are against vehdyn "exact".

Run: ``PYTHONPATH=. python benchmarks/bench_linear_handling.py``
"""

from _timing import best_time  # first: pins BLAS to one thread before numpy loads
import time

import numpy as np

import vehdyn
from vehdyn.handling import LinearBicycle


DELTA = np.deg2rad(1.0)


def reference(car, t):
    lam, V = np.linalg.eig(car.A)
    b = np.linalg.solve(V, car.B[:, 0] * DELTA)
    # x(t) = V diag((e^(lam t) - 1) / lam) V^-1 B delta
    x = (V @ (((np.exp(np.outer(lam, t)) - 1.0) / lam[:, None]) * b[:, None])).real
    return car.C @ x + car.D[:, :1] * DELTA


def main(repeats: int = 5) -> None:
    import control as ct
    from scipy import signal

    car = LinearBicycle(vehdyn.load_vehicle("sedan"), 25.0)
    t = np.linspace(0.0, 10.0, 10001)
    u = np.zeros((2, t.size))
    u[0] = DELTA
    ref = reference(car, t)
    yaw = car.index("yaw_rate", "outputs")
    scale = np.max(np.abs(ref[yaw]))
    sys_ct = car.to_control()
    sys_sp = car.to_scipy()
    runs = {
        "vehdyn exact (foh)": lambda: vehdyn.simulate(car, t, u, method="exact")["yaw_rate"],
        "vehdyn exact (zoh)": lambda: vehdyn.simulate(car, t, u, method="exact", hold="zoh")["yaw_rate"],
        "vehdyn rk4": lambda: vehdyn.simulate(car, t, u, method="rk4")["yaw_rate"],
        "vehdyn RK45 rtol 1e-6": lambda: vehdyn.simulate(car, t, u, method="RK45", rtol=1e-6, atol=1e-9)["yaw_rate"],
        "vehdyn DOP853 rtol 1e-10": lambda: vehdyn.simulate(car, t, u, method="DOP853", rtol=1e-10,
                                                            atol=1e-13)["yaw_rate"],
        "scipy.signal.lsim": lambda: signal.lsim(sys_sp, u.T, t)[1][:, yaw],
        "control.forced_response": lambda: ct.forced_response(sys_ct, t, u).outputs[yaw],
    }
    rows = []
    for name, fun in runs.items():
        seconds, y = best_time(fun, repeats)
        rows.append((name, seconds, float(np.max(np.abs(y - ref[yaw])) / scale)))
    base = rows[0][1]
    print(f"10-s step steer, sedan at 25 m/s, {t.size} samples; yaw-rate error relative to its peak")
    print(f"{'method':28s} {'time [ms]':>10s} {'ratio':>8s} {'max rel. error':>15s}")
    for name, seconds, err in rows:
        print(f"{name:28s} {seconds * 1e3:10.3f} {seconds / base:8.2f} {err:15.2e}")


if __name__ == "__main__":
    main()
