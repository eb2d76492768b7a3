"""A quarter car built with LinearModel.from_second_order (part A's QuarterCar lives in another branch)."""

import numpy as np

import vehdyn


def quarter_car(ms, mu, ks, cs, kt, ct=0.0):
    """Quarter car: states sprung/unsprung displacement and velocity; inputs road displacement and velocity.

    ms zs'' = -ks (zs - zu) - cs (zs' - zu'); mu zu'' = ks (zs - zu) + cs (zs' - zu') - kt (zu - zr) - ct (zu' - zr').
    Outputs: sprung acceleration, suspension travel zs - zu, tire deflection zu - zr, dynamic tire load kt (zr - zu)
    + ct (zr' - zu').
    """
    M = np.diag([ms, mu])
    C = np.array([[cs, -cs], [-cs, cs + ct]])
    K = np.array([[ks, -ks], [-ks, ks + kt]])
    F = np.array([[0.0, 0.0], [kt, ct]])
    acc = -np.linalg.solve(M, np.hstack([K, C]))[0]
    acc_in = np.linalg.solve(M, F)[0]
    Cout = np.array([acc, [1.0, -1.0, 0, 0], [0, 1.0, 0, 0], [0, -kt, 0, -ct]])
    Dout = np.array([acc_in, [0, 0], [-1.0, 0], [kt, ct]])
    return vehdyn.LinearModel.from_second_order(
        M, C, K, F, dof=["sprung_displacement", "unsprung_displacement"],
        inputs=["road_displacement", "road_velocity"],
        outputs=["sprung_acceleration", "suspension_travel", "tire_deflection", "dynamic_tire_load"],
        output_matrix=Cout, feedthrough=Dout, name="quarter car")
