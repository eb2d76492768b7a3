"""Nonlinear handling diagram and limit behaviour of the shipped vehicles.

The nonlinear single-track model (vehdyn.handling.SingleTrack) of the sedan, the compact car and
the van, each with the Magic Formula tire of its own .tir file, is put in steady turns of growing
lateral acceleration until no equilibrium exists (vehdyn.handling.nonlinear_handling_diagram):
on a 100 m circle (ISO 4138 constant radius) and at a constant 25 m/s. The diagram shows the front
steer angle and the sideslip at the centre of gravity against lateral acceleration; the linear
bicycle model's straight line (delta = L/R + K a_y) is drawn for comparison. The limit lateral
acceleration is where the steady-state branch ends. A table gives, per vehicle, the linear
understeer gradient, the gradient near the limit and the limit itself.
"""

import numpy as np

import vehdyn
from vehdyn.handling import SingleTrack, nonlinear_handling_diagram, understeer_gradient
from vehdyn.plotting import new_figure
from vehdyn.report import Study

G = vehdyn.units.GRAVITY


def run(study: Study) -> None:
    import pandas as pd

    vehicles = vehdyn.shipped_vehicles("passenger_car")
    radius, speed = 100.0, 25.0
    step = 0.6 if study.quick else 0.25
    fig, axes = new_figure(1, 2, height_per_row=3.6, width=11.0)
    axes = axes[0]
    rows = []
    for name in vehicles:
        vehicle = vehdyn.load_vehicle(name)
        model = SingleTrack(vehicle, tire_lag=False)  # steady state: tire lag plays no part
        circle = nonlinear_handling_diagram(model, radius=radius, step=step, tolerance=0.05)
        constant_speed = nonlinear_handling_diagram(model, speed=speed, step=step, tolerance=0.05)
        line = axes[0].plot(circle.lateral_acceleration / G, np.degrees(circle.steer_angle), label=f"{name}")[0]
        k_linear = understeer_gradient(vehicle)
        ay = np.linspace(0, circle.limit_lateral_acceleration, 20)
        axes[0].plot(ay / G, np.degrees(vehicle.wheelbase / radius + k_linear * ay), ls=":", color=line.get_color())
        axes[1].plot(circle.lateral_acceleration / G, np.degrees(circle.sideslip_angle), color=line.get_color(),
                     label=name)
        slope = np.gradient(circle.steer_angle, circle.lateral_acceleration)
        rows.append({"vehicle": name, "linear_understeer_gradient": np.degrees(k_linear) * G,
                     "understeer_gradient_at_0.5_limit": np.degrees(np.interp(0.5 * circle.limit_lateral_acceleration,
                                                                              circle.lateral_acceleration, slope)) * G,
                     "limit_on_100m_circle": circle.limit_lateral_acceleration / G,
                     "limit_at_25ms": constant_speed.limit_lateral_acceleration / G,
                     "tire_friction_mu": vehicle.tires.friction_coefficient})
    axes[0].set_xlabel("lateral acceleration [g]")
    axes[0].set_ylabel("front steer angle [deg]")
    axes[0].set_title(f"constant radius {radius:g} m (dotted: linear bicycle)")
    axes[0].legend()
    axes[1].set_xlabel("lateral acceleration [g]")
    axes[1].set_ylabel("sideslip angle at CG [deg]")
    axes[1].set_title("sideslip (SAE: negative = nose into the turn)")
    study.figure(fig, "handling_diagram", caption="Nonlinear handling diagram up to the limit, Magic Formula tires")
    frame = pd.DataFrame(rows).set_index("vehicle")
    frame.attrs["units"] = {"linear_understeer_gradient": "deg/g", "understeer_gradient_at_0.5_limit": "deg/g",
                            "limit_on_100m_circle": "g", "limit_at_25ms": "g", "tire_friction_mu": "-"}
    study.table(frame, "limits", caption="Understeer gradients and limit lateral acceleration")
    study.text("The steer angle leaves the linear line as the front tires approach their peak force; the branch "
               "ends at the limit lateral acceleration, which stays below mu g because the Magic Formula "
               "friction falls with load (PDY2 < 0) and the driven rear axle spends part of its grip on the "
               "drive force that holds the speed.")


if __name__ == "__main__":
    Study.main(run, __file__)
