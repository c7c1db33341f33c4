# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # A wheel on a rail on sleepers: the steady response over a bay and the parametric resonance
#
# A UIC60 rail rests on sleepers every $l = 0.6$ m (`examples/sleepers.toml`, per rail). A wheel moving at
# $v$ passes them at the sleeper-passing frequency $\Omega_0 = 2\pi v / l$: the rail under the wheel is
# stiffer over a sleeper than between two, and the contact force and the deflection under the wheel vary
# over each bay (docs/sleepers.md, Eqs. (S16)-(S18)). A wheel can also resonate parametrically: its free
# vibration is a Floquet root $\Omega$ (time dependence $e^{i\Omega t}$, growing when
# $\mathrm{Im}\,\Omega < 0$), and the principal parametric zone lies where $\Omega_0$ is twice the wheel's
# natural frequency on the track, the root on $\mathrm{Re}\,\Omega = \Omega_0 / 2$ (Eq. (S14)).
#
# The comparison throughout is the continuous track with the same smeared supports: $k_f = k_{sup} / l$,
# $c_f = c_{sup} / l + c_f$, the limit $l \to 0$ of docs/sleepers.md (S2).

# %%
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import moving_bogie as mb

QUICK = os.environ.get("MOVING_BOGIE_QUICK", "").lower() in ("1", "true", "yes", "on")
EXAMPLES = Path.cwd().parent / "examples"
if not EXAMPLES.exists():  # run from the repository root
    EXAMPLES = Path("examples")
_, SLEEPERS = mb.load_parameters(EXAMPLES / "sleepers.toml")  # a model of the catalogue, eb/sleepers/mass
print(SLEEPERS.model.name, {name: float(value) for name, value in SLEEPERS.values().items()})


def with_si(physical, **changes):
    """The same SI parameters with some changed (as --set NAME=VALUE does)."""
    return mb.PhysicalParams(model=physical.model, **(physical.values() | changes))


# %% [markdown]
# ## 1. The steady contact force over a bay, against the speed
#
# `moving-bogie timeseries --file examples/sleepers.toml --plot F.png` draws one speed; here several. The
# mean force over a bay is the static load $P$ at every speed (the harmonic $n = 0$ of (S17) carries no
# inertia); the variation around it grows with the speed, as the sleeper-passing frequency approaches the
# wheel's natural frequency on the track.

# %%
speeds = [20.0, 40.0, 80.0] if QUICK else [10.0, 20.0, 40.0, 60.0, 80.0, 100.0]
fig, (ax_f, ax_w) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
for v in speeds:
    s = mb.sleeper_series(with_si(SLEEPERS, v=v), points=201, free=False).bay  # what the bays add
    print(
        f"v = {v:5.1f} m/s: Omega_0 = {s.Omega0:7.1f} rad/s, F mean {s.force_mean[0]:.1f} N, "
        f"F peak-to-peak {s.force_peak_to_peak[0]:7.1f} N, "
        f"w peak-to-peak {s.deflection_peak_to_peak[0]:.3e} m, "
        f"harmonics -{s.harmonics}..{s.harmonics} ({'converged' if s.converged else 'NOT converged'})"
    )
    ax_f.plot(s.position, s.contact_force[0] / 1e3, label=f"v = {v:g} m/s")
    ax_w.plot(s.position, s.deflection[0] * 1e3)
ax_f.axhline(s.static_force[0] / 1e3, color="k", ls="--", lw=0.8, label="static load P")
ax_w.axhline(s.continuous_deflection[0] * 1e3, color="k", ls="--", lw=0.8)
ax_f.set_ylabel("contact force [kN]")
ax_w.set_ylabel("deflection under the wheel [mm]")
ax_w.set_xlabel("wheel's position from a sleeper [m]")
ax_w.set_title(
    f"dashed: {s.continuous_model} with the smeared supports at v = {speeds[-1]:g} m/s", fontsize=9
)
ax_f.legend(fontsize=8)
plt.show()

# %% [markdown]
# ## 2. A wheel on a Hertz spring: its natural frequency on the smeared track
#
# The wheel of `examples/hertz_mass.toml` ($M$ on the linearised Hertz spring $k_H$) on the rail and sleepers
# of `examples/sleepers.toml`. On the continuous track with the smeared supports its induced frequency $q$
# (the paper's Eq. (48), every root counted) is the wheel's natural frequency at each speed; the principal
# parametric zone is expected where $\Omega_0(v) = 2\,\mathrm{Re}\,\Omega(v)$.

# %%
_, HERTZ_EXAMPLE = mb.load_parameters(EXAMPLES / "hertz_mass.toml")
physical = {name: float(value) for name, value in SLEEPERS.values().items()}
physical |= {"k_H": float(HERTZ_EXAMPLE.k_H), "M": float(HERTZ_EXAMPLE.M)}
HERTZ = mb.PhysicalParams(beam="eb", track="sleepers", vehicle="hertz_mass", **physical)


def continuous(v):
    """The continuous track with the smeared supports: natural frequency [rad/s], verdict, speed regime."""
    smeared = mb.smeared_track(with_si(HERTZ, v=v))
    result = mb.induced_frequencies(smeared, dps=15)
    t_scale = smeared.scales().t_scale
    Omega = [complex(r.q) / t_scale for r in result.roots]
    return Omega, result.verdict.state, mb.speed_regime(smeared.to_dimensionless(), smeared)


scan = [20.0, 80.0, 140.0] if QUICK else list(np.arange(20.0, 201.0, 20.0))
natural = []
for v in scan:
    Omega, verdict, regime = continuous(v)
    natural.append(min(Omega, key=lambda z: z.real))
    print(
        f"v = {v:5.1f} m/s: Omega_0 / 2 = {np.pi * v / physical['l']:7.1f} rad/s; continuous track: "
        f"{len(Omega)} root(s) "
        + ", ".join(f"{z.real:.1f}{z.imag:+.1f}i" for z in Omega)
        + f" rad/s, {verdict}"
    )
print("continuous track at the last speed:", regime.line())
half = np.pi * np.array(scan) / physical["l"]
re = np.array([z.real for z in natural])
crossing = np.flatnonzero(np.diff(np.sign(half - re)))
v_star = None
if crossing.size:
    i = crossing[0]
    slope = (half[i + 1] - half[i]) - (re[i + 1] - re[i])
    v_star = scan[i] + (scan[i + 1] - scan[i]) * (re[i] - half[i]) / slope
    print(f"Omega_0 / 2 meets the lowest natural frequency at v* = {v_star:.1f} m/s (linear interpolation)")
else:
    print("Omega_0 / 2 does not meet the lowest natural frequency in the scanned speeds")

# %%
fig, ax = plt.subplots(figsize=(7, 3.5))
ax.plot(scan, re, "o-", label=r"Re $\Omega$ of the Hertz wheel, continuous track")
ax.plot(scan, half, "s--", label=r"$\Omega_0 / 2 = \pi v / l$ (principal parametric zone)")
ax.plot(scan, 2 * half, "^:", label=r"$\Omega_0 = 2 \pi v / l$ (forced resonance)")
ax.set_ylim(0, 1.6 * re.max())
if v_star is not None:
    ax.axvline(v_star, color="0.5", ls=":", lw=1)
ax.set_xlabel("v [m/s]")
ax.set_ylabel("[rad/s]")
ax.legend(fontsize=8)
plt.show()

# %% [markdown]
# The line $\Omega_0 = 2\pi v / l$ meets the natural frequency at half $v^*$: there the sleepers force the
# wheel at resonance, which is where the peak-to-peak contact force of section 1 is largest among the speeds
# shown (40 m/s against 20 and 80 m/s).
#
# ## 3. The Floquet roots on sleepers around the principal zone
#
# `induced_frequencies`, on a model on sleepers, counts the roots in one strip of width $\Omega_0$ by the
# argument principle (no starting guesses) and converges them in the harmonics: a root with
# $\mathrm{Im}\,\Omega < 0$ is a growing vibration, none means the wheel is stable at that speed. The
# speeds are a modest set around $v^*$.

# %%
centre = v_star if v_star is not None else 100.0
around = [1.0, 1.2] if QUICK else [0.6, 0.8, 0.9, 1.0, 1.1, 1.2, 1.4]
rows = []
for factor in around:
    v = round(centre * factor, 1)
    at = with_si(HERTZ, v=v)
    result = mb.induced_frequencies(at)  # one strip of width Omega_0, as on every track: the same result
    _, verdict, _ = continuous(v)
    t_scale = at.scales().t_scale
    roots = [complex(r.q) / t_scale for r in result.roots]
    rows.append((v, result.count, result.verdict.state, verdict))
    harmonics = result.region.harmonics
    reasons = "; ".join(note.text for note in result.verdict.reasons)
    print(
        f"v = {v:6.1f} m/s: sleepers: {result.count} root(s) "
        f"{[f'{z.real:.1f}{z.imag:+.2f}i' for z in roots]}, "
        f"harmonics {harmonics[0]}..{harmonics[-1]}, "
        f"verdict {result.verdict.state.upper()}"
        f"{f' ({reasons})' if reasons else ''}; "
        f"continuous track: {verdict}"
    )
growing = [v for v, _, state, _ in rows if state == "unstable"]
print("growing roots on sleepers at v =", growing or "none of the speeds scanned")
print("continuous track unstable at v =", [v for v, *_, c in rows if c == "unstable"] or "none of them")

# %% [markdown]
# At the example's support damping ($c_{sup} = 3 \cdot 10^4$ N s/m per sleeper) the lines above say whether a
# growing root exists near $v^*$ on sleepers, and what the continuous track with the same smeared stiffness
# says at the same speeds: the continuous track has no parametric excitation, so any instability on sleepers
# that it does not share is parametric. The critical velocity of the continuous track (the speed regime
# printed in section 2) bounds the speeds at which the smeared comparison is subcritical.

# %% [markdown]
# ## 4. The parametric zones in (v, M)
#
# The zones open where the supports are lightly damped. `examples/sleepers_zones.toml` holds the same rail
# on supports every 1 m with the same smeared stiffness ($k_{sup} / l = 10^8$ N/m$^2$) and a tenth of the
# support damping. At each speed, the D-decomposition in the wheel mass
# (docs/sleepers.md, (S20)-(S22)) finds every mass at which a root crosses the real axis of the strip.
# The sign of each crossing then counts the unstable roots: none at M -> 0, plus the signed crossings
# below M. The same command draws the full map: `moving-bogie stability-map --file
# examples/sleepers_zones.toml --range v=20:400 --range M=0:3000 --plot map.png`.
# Beside it is the continuous track with the same smeared support, on the same grid.

# %%
from IPython.display import display  # noqa: E402

_, ZONES = mb.load_parameters(EXAMPLES / "sleepers_zones.toml")
vs = np.linspace(80.0, 140.0, 3) if QUICK else np.linspace(40.0, 250.0, 43)
ms = np.linspace(100.0, 3000.0, 30 if QUICK else 120)
smap = mb.sleeper_map(ZONES, vs, ms, verify=0 if QUICK else 2, workers=1 if QUICK else None)
smeared = mb.smeared_track(ZONES)
continuous_map = mb.stability_map(
    smeared,
    parameter="eta_M",
    alphas=(vs / smeared.si_factor("alpha")).tolist(),
    thetas=(ms / smeared.si_factor("eta_M")).tolist(),
)
unstable = int((smap.count > 0).sum())
print(f"sleepers: {unstable} unstable cells of {smap.count.size}; notes: {list(smap.notes)}")
print(f"continuous track, same smeared support: {int((continuous_map.count > 0).sum())} unstable cells")
for check in smap.checks:
    print(
        f"check at v = {check.v:g} m/s, M = {check.M:g} kg: "
        f"map {check.map_count}, search {check.search_count}"
    )
for line in smap.lines()[:8]:
    print(
        f"v = {line['v']:6.1f} m/s: crossing at M = {line['M']:7.1f} kg, "
        f"Omega = {line['Omega_rad_s']:.1f} rad/s, change {line['change']:+d}"
    )
display(mb.sleeper_map_figure(smap, continuous_map, operating=(float(ZONES.v), float(ZONES.M))))

# %% [markdown]
# Each band is a parametric zone: a narrow interval of wheel masses, at each speed, in which the wheel's
# free vibration grows. Along the band, twice the wheel's natural frequency on the track equals the
# sleeper-passing frequency, so heavier wheels resonate at lower speeds. The continuous track with the
# same smeared support shows none of it on this grid: its smeared stiffness is that of section 2, whose
# critical velocity (printed there) lies far above these speeds.

# %% [markdown]
# ## 5. A bogie and a car on the same rail
#
# The same D-decomposition runs for any vehicle on the rail: the Hill matrix stays linear in the wheel
# mass $M$ when the frame and the body are held fixed (S19). The bogie of `examples/uic60-bogie.toml` and
# the car of `examples/car.toml` go on the rail of `examples/sleepers_zones.toml`, and each is compared with
# the single wheel at the same speeds. The lines below count the crossings at each edge of a zone: one per
# root that crosses the real axis there. Beside each is the verdict of the continuous track
# with the same smeared support, at the middle of the wheel's zone. Quick mode draws the wheel and the bogie
# at one speed; the full notebook adds the car and more speeds. A car column costs about ten times a bogie
# column.

# %%
RAIL_KEYS = {"EI", "m", "k_f", "c_f", "k_s"}


def on_the_rail(example: str, vehicle: str):
    """The rail of sleepers_zones.toml under the vehicle of a continuous example (its wheel, frame, body)."""
    _, parts = mb.load_parameters(EXAMPLES / example)
    physical = ZONES.values() | {k: v for k, v in parts.values().items() if k not in RAIL_KEYS}
    return mb.PhysicalParams(beam="eb", track="sleepers", vehicle=vehicle, **physical)


vehicles = {"wheel": ZONES, "bogie": on_the_rail("uic60-bogie.toml", "bogie")}
if not QUICK:
    vehicles["car"] = on_the_rail("car.toml", "car")
zone_speeds = [88.0] if QUICK else [80.0, 84.0, 88.0, 92.0, 96.0]
wheel_masses = np.linspace(100.0, 3000.0, 59 if QUICK else 291)
zones_by_vehicle = {}
for name, on_rail in vehicles.items():
    vmap = mb.sleeper_map(on_rail, zone_speeds, wheel_masses, verify=0, workers=1)
    zones_by_vehicle[name] = vmap
    for v in zone_speeds:
        crossings = sorted((p for p in vmap.lines() if p["v"] == v), key=lambda p: p["M"])
        ups = [p["M"] for p in crossings if p["change"] > 0]
        downs = [p["M"] for p in crossings if p["change"] < 0]
        if not crossings:
            print(f"{name:5s} v = {v:5.1f} m/s: no crossing for 100 <= M <= 3000 kg")
            continue
        low, high = min(ups), max(downs)
        middle = mb.smeared_track(with_si(on_rail, v=v, M=(low + high) / 2))
        state = mb.induced_frequencies(middle, dps=15).verdict.state
        print(
            f"{name:5s} v = {v:5.1f} m/s: {len(ups)} crossing(s) up, {len(downs)} down; unstable for "
            f"{low:7.1f} < M < {high:7.1f} kg; continuous track at the zone's middle: {state}"
        )

# %% [markdown]
# Every vehicle resonates in a narrow band of wheel masses at the same speeds as the single wheel. Its
# primary suspension couples the wheels through the frame, which moves and narrows the band. In the band,
# the vehicle is unstable on sleepers and stable on the continuous track with the same smeared stiffness.
