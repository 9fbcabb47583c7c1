"""A stepper coupled to a controller in Python: the paper's Table 4 beam with a tip force whose
factor an integral controller (with a feed-forward of the linear tip stiffness 3 EI / L³) sets
every 10 ms from the tip it reads, to bring the tip to y = 0.3 m. The same loop couples the beam
to a flight-dynamics model.

    python examples/python/stepper.py
"""

from __future__ import annotations

import time

import flexwing

beam = flexwing.Beam(length=1.0, elements=20, EI=50.0, mass_per_length=0.2)
model = flexwing.FullModel(beam)
force = {"type": "point-force", "span": 1.0, "direction": "follower", "normal": 1.0}  # N per unit factor, normal to the tip element
# A reduced model on 4 modes: cheap steps; hold="linear" ramps the factor over each interval.
# 5 % of critical damping in each mode.
damping = {"type": "modal", "ratios": [0.05] * 4}
stepper = model.reduced(4).stepper([force], scales=[0.0], rtol=1e-6, atol=1e-8, damping=damping)

target, ki = 0.3, 300.0  # m, N/(m s)
feed_forward = 3 * 50.0 / 1.0**3 * target  # N: the linear estimate
dt, integral = 0.01, 0.0  # s, m s
start = time.perf_counter()
for k in range(200):  # 2 s
    tip_y = stepper.tip[1]
    integral += (target - tip_y) * dt
    factor = feed_forward + ki * integral
    stepper.step(dt, [factor])
    if k % 25 == 0:
        print(f"  t = {stepper.t:5.2f} s: tip y = {tip_y:+.4f} m, force {factor:+8.2f} N")
wall = time.perf_counter() - start
stats = stepper.stats
print(f"final tip y = {stepper.tip[1]:.4f} m (target {target} m)")
print(
    f"{stats['calls']} calls in {1e3 * wall:.1f} ms: {1e3 * stats['rust_time_s']:.1f} ms in the "
    f"integrator, {1e6 * (wall - stats['rust_time_s']) / stats['calls']:.1f} us a call in Python "
    f"and the binding"
)
