"""The summary table of the validation report: one row per feature, "feature | expected
(paper) | measured | verdict", from a section of sandphys-validation's results; the verdicts'
thresholds; the paper's Table 4 and the texts of the force fits. No plotting here (make_report.py
writes the report, report_plots.py draws)."""
import math

# Verdict thresholds, stated in the report.
MIN_STEADY_R2 = 0.98
MIN_LAW_R2 = 0.95
EXPONENT_TOLERANCE = 0.15


def fmt(value, digits=3):
    if value is None:
        return "n/a"
    if isinstance(value, float) and not math.isfinite(value):
        return "n/a"
    return f"{value:.{digits}g}"


def compression_runs(section):
    rough = next(r for r in section["runs"] if r["friction"] > 0)
    smooth = next(r for r in section["runs"] if r["friction"] == 0)
    return rough, smooth


def rows_dunes(section):
    left, right, saddle = section["left_crest"], section["right_crest"], section["saddle"]
    depth = min(left["height_d"], right["height_d"]) - saddle["height_d"]
    two = depth >= 1.0 and left["x_d"] < saddle["x_d"] < right["x_d"]
    return [("Dune from two columns (Fig. 25)", "two crests with a saddle between them",
             f"crests {left['height_d']:.1f} d and {right['height_d']:.1f} d high, "
             f"{right['x_d'] - left['x_d']:.1f} d apart; saddle {saddle['height_d']:.1f} d high, "
             f"{depth:.1f} d below the lower crest",
             "agrees" if two else "disagrees")]


def rows_flow_friction(section):
    runs = section["runs"]
    flowing = [r for r in runs if r["flow_rate"] > 0]
    r2 = min((r["flow_rate_r2"] for r in flowing), default=None)
    steady = bool(flowing) and r2 >= MIN_STEADY_R2
    rates = [r["flow_rate"] for r in runs]
    falling = all(b < a for a, b in zip(rates, rates[1:]))
    listing = ", ".join(f"μ {r['friction']:g}: {r['flow_rate']:.0f}/s" for r in runs)
    return [
        ("Constant mean flow rate through the outlet (Fig. 23)",
         "granules remaining fall linearly with time",
         f"lowest R² of the steady part {fmt(r2, 4)} over {len(flowing)} runs",
         "agrees" if steady else "disagrees"),
        ("Slower flow with more friction (Fig. 23)",
         "flow rate falls as μ rises",
         listing,
         "agrees" if falling else "disagrees"),
    ]


def rows_flow_outlet(section):
    fit = section.get("beverloo")
    paper = section["paper"]
    if not fit:
        return [("Beverloo's law (Fig. 24)", f"W = {paper['c']:g} (D − {paper['k']:g})^5/2",
                 section.get("beverloo_error", "no fit"), "disagrees")]
    obeys = fit["r2"] >= MIN_LAW_R2
    # k is the empty annulus at the outlet's rim: a negative one is no annulus, and no Beverloo.
    if not obeys:
        verdict = "disagrees"
    elif fit["k"] < 0:
        verdict = "disagrees (the curve fits, but k < 0 has no meaning as an empty annulus)"
    else:
        verdict = "agrees (law obeyed; constants differ, see below)"
    return [("Beverloo's law W = C (D − k)^5/2 (Fig. 24)",
             f"obeyed; C = {paper['c']:g}, k = {paper['k']:g} d",
             f"C = {fit['c']:.3g}, k = {fit['k']:.3g} d, R² {fit['r2']:.4f}", verdict)]


# Dry sand's angle of repose (natural sands, about 30° to 35°), to compare the heaps' with.
REAL_SAND_DEGREES = (30.0, 35.0)
# The grain-on-grain friction of quartz sand, about 0.5: the runs compared with real sand.
REAL_SAND_FRICTIONS = (0.4, 0.6)


def rows_repose(section, setup="poured heap", figures="Fig. 22", law_name=""):
    """Rows of an angle sweep; `law_name` (", paper's law") tells a second contact law's apart."""
    law = section.get("power_law")
    runs = [r for r in section["runs"] if "angle_deg" in r]
    angles = [r["angle_deg"] for r in runs]
    rising = all(b > a for a, b in zip(angles, angles[1:]))
    expected = section["paper"]["exponent"]
    if not law:
        return [(f"Angle of repose against friction, {setup}{law_name} ({figures})",
                 f"power law, exponent {expected:g}", section.get("power_law_error", "no fit"),
                 "disagrees")]
    close = abs(law["exponent"] - expected) <= EXPONENT_TOLERANCE and law["r2"] >= MIN_LAW_R2
    listing = ", ".join(f"μ {r['friction']:g}: {r['angle_deg']:.1f}°" for r in runs)
    lo, hi = REAL_SAND_FRICTIONS
    sandlike = [r for r in runs if lo <= r["friction"] <= hi]
    real = []
    if sandlike:
        inside = all(REAL_SAND_DEGREES[0] <= r["angle_deg"] <= REAL_SAND_DEGREES[1]
                     for r in sandlike)
        real = [(f"Angle of repose at sand's friction (μ {lo:g} to {hi:g}), {setup}{law_name}",
                 f"real dry sand: {REAL_SAND_DEGREES[0]:g}° to {REAL_SAND_DEGREES[1]:g}°",
                 ", ".join(f"μ {r['friction']:g}: {r['angle_deg']:.1f}°" for r in sandlike),
                 "agrees" if inside else "disagrees")]
    return [
        (f"Angle of repose rises with friction, {setup}{law_name} ({figures})",
         "steeper with more friction", listing, "agrees" if rising else "disagrees"),
        (f"Power law of the angle in μ, {setup}{law_name} ({figures})", f"exponent {expected:g}",
         f"exponent {law['exponent']:.2f}, coefficient {law['coefficient']:.3g}°, R² {law['r2']:.3f}",
         "agrees" if close else "disagrees"),
        *real,
    ]


# The paper's Table 4, as printed: exponential (a, b), Gaussian (beta, alpha), gamma (a, b).
TABLE4 = {
    ("particles", "friction"): {"exponential": (2.10, 0.61), "gaussian": (1.29, 1.51)},
    ("particles", "no friction"): {"exponential": (2.78, 0.72), "gaussian": (1.46, None)},
    ("particles", "compression"): {"gamma": (3.36, 0.30)},
    ("granules", "friction"): {"exponential": (2.14, 0.66), "gaussian": (1.24, 2.45)},
    ("granules", "no friction"): {"exponential": (10.05, 1.01), "gaussian": (2.13, None)},
    ("granules", "compression"): {"gamma": (6.14, 0.16)},
}


def fit_text(dist, kind):
    fit = dist.get(kind) or {}
    if "error" in fit or not fit:
        return "n/a"
    if kind == "exponential":
        return f"a {fit['a']:.2f}, b {fit['b']:.2f} (1/b {1 / fit['b']:.2f}), R² {fit['r2']:.2f}"
    if kind == "gaussian":
        return f"β {fit['beta']:.2f}, α {fit['alpha']:.2f}, R² {fit['r2']:.2f}"
    return f"a {fit['shape']:.2f}, b {fit['scale']:.2f}"


def paper_text(level, case, kind):
    values = TABLE4.get((level, case), {}).get(kind)
    if not values:
        return "—"
    return ", ".join("—" if v is None else f"{v:g}" for v in values)


def rows_compression(section):
    rough, smooth = compression_runs(section)
    rows = []
    for level in ("particles", "granules"):
        for case, run, snap in (("friction", rough, "rest"), ("no friction", smooth, "rest")):
            dist = run.get(snap, {}).get(level, {}).get("normal", {})
            measured = f"exponential {fit_text(dist, 'exponential')}; Gaussian {fit_text(dist, 'gaussian')}"
            expected = (f"exponential {paper_text(level, case, 'exponential')}; "
                        f"Gaussian {paper_text(level, case, 'gaussian')}")
            e, g = dist.get("exponential", {}), dist.get("gaussian", {})
            better = "r2" in e and "r2" in g and g["r2"] >= e["r2"]
            rows.append((f"P(f_n), {level}, at rest, {case} (Fig. 17a, b; Table 4)", expected, measured,
                         "Gaussian tail fits at least as well as the exponential (as the paper finds)"
                         if better else "exponential tail fits better (the paper finds the Gaussian better)"))
        dist = rough.get("peak", {}).get(level, {}).get("normal", {})
        g = dist.get("gamma", {})
        peak_near_one = False
        if "density" in dist:
            top = max(range(len(dist["density"])), key=lambda i: dist["density"][i])
            peak_near_one = 0.5 <= dist["centres"][top] <= 1.5
        rows.append((f"P(f_n), {level}, under compression (Fig. 17c; Table 4)",
                     f"gamma {paper_text(level, 'compression', 'gamma')}, peak near f = 1",
                     f"gamma {fit_text(dist, 'gamma')}",
                     "peak near f = 1" if peak_near_one else "no peak near f = 1"))
    rest = rough.get("rest", {})
    c = rest.get("correlation", {})
    if "correlation" in c:
        far = [y for x, y, n in zip(c["distance_d"], c["correlation"], c["pairs"]) if x >= 4 and n]
        near = [y for x, y, n in zip(c["distance_d"], c["correlation"], c["pairs"]) if x < 2 and n]
        spread = max(abs(y - 1) for y in far) if far else float("nan")
        rows.append(("Force–force spatial correlation (Fig. 18)", "only local, within a few d",
                     f"g(r) up to {max(near):.2f} below 2 d; within {spread:.2f} of 1 beyond 4 d",
                     "agrees" if spread <= 0.15 else "disagrees"))
    angles = [r.get("rest", {}).get("contact_angles", {}) for r in (rough, smooth)]
    if all("density" in a for a in angles):
        diff = max(abs(a - b) for a, b in zip(angles[0]["density"], angles[1]["density"]))
        peak = max(angles[0]["density"])
        rows.append(("Contact angle distribution, μ = 0 and 0.5 (Fig. 19)",
                     "friction has a weak influence",
                     f"largest difference between the two densities {diff / peak:.0%} of the peak",
                     "agrees" if diff / peak <= 0.25 else "disagrees"))
    n = rest.get("networks", {})
    if "threshold" in n:
        i = n["threshold"].index(min(n["threshold"], key=lambda t: abs(t - 1.0)))
        rows.append(("Weak and strong networks (Fig. 20)", "a weak distinction",
                     f"{n['contacts'][i]:.0%} of the contacts carry f > 1, with {n['force'][i]:.0%} of the force",
                     "measured (no single number in the paper to compare)"))
    frac = rough["recovered_fraction"]
    rows.append(("Stress–strain, loading and unloading (Fig. 21)",
                 "hysteresis; about two thirds of the strain recovered",
                 f"strain {100 * rough['max_strain']:.2f}% at {section['max_stress_pa'] / 1000:g} kPa, "
                 f"{100 * rough['residual_strain']:.2f}% left: {frac:.0%} recovered",
                 "agrees" if 0.5 <= frac <= 0.8 else "disagrees"))
    return rows
