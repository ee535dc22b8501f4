"""The plots of the validation report, one PNG per figure of the paper, from a section of
sandphys-validation's results. Needs python3-matplotlib."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_tables import compression_runs  # noqa: E402


def plot_flow_friction(section, out):
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for run in section["runs"]:
        points = run["remaining"]
        if not points:
            continue
        left.plot([p[0] for p in points], [p[1] for p in points], label=f"μ = {run['friction']:g}")
    left.set_xlabel("time since the outlet opened (s)")
    left.set_ylabel("granules in the funnel")
    left.set_title(f"Granules remaining, outlet {section['outlet_d']:g} d (cf. Fig. 23)")
    left.legend()
    mus = [r["friction"] for r in section["runs"]]
    rates = [r["flow_rate"] for r in section["runs"]]
    right.plot(mus, rates, "o-")
    right.set_xlabel("friction coefficient μ")
    right.set_ylabel("flow rate (granules/s)")
    right.set_title("Steady flow rate against friction")
    right.set_ylim(bottom=0)
    fig.tight_layout()
    fig.savefig(out / "flow_friction.png", dpi=110)
    plt.close(fig)


def plot_beverloo(section, out):
    fig, ax = plt.subplots(figsize=(6, 4.2))
    runs = [r for r in section["runs"] if r["flow_rate"] > 0]
    ds = [r["outlet_d"] for r in runs]
    ax.plot(ds, [r["flow_rate"] for r in runs], "o", label="sandphys")
    jammed = [r["outlet_d"] for r in section["runs"] if r["flow_rate"] <= 0]
    if jammed:
        ax.plot(jammed, [0] * len(jammed), "x", color="red", label="jammed")
    lo, hi = min(r["outlet_d"] for r in section["runs"]), max(r["outlet_d"] for r in section["runs"])
    grid = [lo + (hi - lo) * i / 100 for i in range(101)]

    def curve(c, k):
        return [c * max(d - k, 0.0) ** 2.5 for d in grid]

    fit = section.get("beverloo")
    if fit:
        ax.plot(grid, curve(fit["c"], fit["k"]), "-",
                label=f"fit: {fit['c']:.3g} (D − {fit['k']:.3g})^5/2")
    paper = section["paper"]
    ax.plot(grid, curve(paper["c"], paper["k"]), "--",
            label=f"paper: {paper['c']:g} (D − {paper['k']:g})^5/2")
    ax.set_xlabel("outlet diameter D (d)")
    ax.set_ylabel("flow rate W (granules/s)")
    ax.set_title(f"Beverloo's law, μ = {section['friction']:g} (cf. Fig. 24)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "beverloo.png", dpi=110)
    plt.close(fig)


def plot_repose(section, out, name="repose.png", what="heaps", distance="the heap's axis",
                beside=None, labels=("sandphys", None)):
    """`beside`: the same sweep under another contact law, drawn on the left beside the first
    (whose flanks alone are drawn on the right); `labels`: the two laws' names."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    runs = [r for r in section["runs"] if "angle_deg" in r]
    mus = [r["friction"] for r in runs]
    left.plot(mus, [r["angle_deg"] for r in runs], "o", label=f"sandphys, {labels[0]}")
    if beside:
        other = [r for r in beside["runs"] if "angle_deg" in r]
        left.plot([r["friction"] for r in other], [r["angle_deg"] for r in other], "s",
                  fillstyle="none", label=f"sandphys, {labels[1]}")
    law = section.get("power_law")
    if law and mus:
        grid = [max(mus) * i / 100 for i in range(1, 101)]
        left.plot(grid, [law["coefficient"] * g ** law["exponent"] for g in grid], "-",
                  label=f"fit: {law['coefficient']:.3g} μ^{law['exponent']:.2f}")
        # The paper gives the exponent only: its law through our largest-μ point.
        top = max(runs, key=lambda r: r["friction"])
        scale = top["angle_deg"] / top["friction"] ** section["paper"]["exponent"]
        left.plot(grid, [scale * g ** section["paper"]["exponent"] for g in grid], "--",
                  label=f"paper's exponent {section['paper']['exponent']:g} (through μ = {top['friction']:g})")
    left.set_xlabel("friction coefficient μ")
    left.set_ylabel("angle of repose (degrees)")
    left.set_title(f"Angle of repose of {what} against friction (cf. Fig. 22)")
    left.set_ylim(bottom=0)
    left.legend()
    d = section["particle_diameter_m"]
    for r in runs:
        xs = [x / d for x in r["flank_radius_m"]]
        ys = [y / d for y in r["flank_height_m"]]
        line = right.plot(xs, ys, ".", markersize=3, alpha=0.6)[0]
        if xs:
            lo, hi = min(xs), max(xs)
            right.plot([lo, hi], [(r["fit_intercept_m"] + r["fit_slope"] * lo * d) / d,
                                  (r["fit_intercept_m"] + r["fit_slope"] * hi * d) / d],
                       "-", color=line.get_color(),
                       label=f"μ = {r['friction']:g}: {r['angle_deg']:.1f}°")
    right.set_xlabel(f"distance from {distance} (d)")
    right.set_ylabel("height above the floor (d)")
    right.set_title("Flank surface cells and their bisquare lines")
    right.set_aspect("equal", adjustable="datalim")
    right.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / name, dpi=110)
    plt.close(fig)


def plot_dunes(section, out):
    fig, ax = plt.subplots(figsize=(9, 3.4))
    xs = [p[0] for p in section["profile_d"]]
    ys = [p[1] for p in section["profile_d"]]
    ax.fill_between(xs, 0, ys, color="#d8b56a")
    ax.plot(xs, ys, color="#8a6a2a")
    for name in ("left_crest", "right_crest", "saddle"):
        p = section[name]
        ax.plot([p["x_d"]], [p["height_d"]], "o", color="black")
        ax.annotate(name.replace("_", " "), (p["x_d"], p["height_d"]), textcoords="offset points",
                    xytext=(0, 6), ha="center", fontsize=8)
    ax.set_xlabel("x (d)")
    ax.set_ylabel("height (d)")
    ax.set_title(f"Profile of the dune along its axis, columns {section['separation_d']:g} d apart (cf. Fig. 25)")
    ax.set_aspect("equal", adjustable="datalim")
    fig.tight_layout()
    fig.savefig(out / "dunes.png", dpi=110)
    plt.close(fig)


def plot_forces(section, out):
    rough, smooth = compression_runs(section)
    cases = [("(a) at rest, μ = %g" % rough["friction"], rough.get("rest"), "normal"),
             ("(b) at rest, μ = 0", smooth.get("rest"), "normal"),
             ("(c) at the peak of the compression, μ = %g" % rough["friction"], rough.get("peak"), "normal"),
             ("(d) tangential, at rest, μ = %g" % rough["friction"], rough.get("rest"), "tangential")]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    for ax, (title, snap, kind) in zip(axes.flat, cases):
        ax.set_title(title, fontsize=10)
        ax.set_yscale("log")
        ax.set_xlabel("normalised force f = F / ⟨F⟩")
        ax.set_ylabel("P(f)")
        if not snap:
            continue
        for level, marker in (("particles", "o"), ("granules", "s")):
            dist = snap[level][kind]
            if "density" not in dist:
                continue
            xs = [x for x, p in zip(dist["centres"], dist["density"]) if p > 0]
            ps = [p for p in dist["density"] if p > 0]
            line = ax.plot(xs, ps, marker, markersize=3, label=level)[0]
            grid = [i * max(xs) / 100 for i in range(101)]
            if title.startswith("(c)"):
                g = dist.get("gamma", {})
                if "shape" in g:
                    k, theta = g["shape"], g["scale"]
                    ys = [x ** (k - 1) * math.exp(-x / theta) / (math.gamma(k) * theta ** k) if x > 0 else None
                          for x in grid]
                    ax.plot(grid[1:], ys[1:], "-", color=line.get_color(), label=f"{level} gamma")
            elif kind == "normal":
                e, gs = dist.get("exponential", {}), dist.get("gaussian", {})
                tail = [x for x in grid if x >= 1.0]
                if "a" in e:
                    ax.plot(tail, [e["a"] * math.exp(-e["b"] * x) for x in tail], "--",
                            color=line.get_color(), label=f"{level} exponential")
                if "beta" in gs:
                    ax.plot(tail, [gs["beta"] * math.exp(-gs["alpha"] * x * x) for x in tail], ":",
                            color=line.get_color(), label=f"{level} Gaussian")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "forces.png", dpi=110)
    plt.close(fig)


def plot_structure(section, out):
    rough, smooth = compression_runs(section)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    rest = rough.get("rest", {})
    c = rest.get("correlation", {})
    if "distance_d" in c:
        pairs = c["pairs"]
        xs = [x for x, n in zip(c["distance_d"], pairs) if n]
        ys = [y for y, n in zip(c["correlation"], pairs) if n]
        axes[0].plot(xs, ys, "o-", markersize=3)
        axes[0].axhline(1.0, color="grey", linewidth=0.8)
    axes[0].set_xlabel("distance between contacts (d)")
    axes[0].set_ylabel("g(r) = ⟨f_i f_j⟩ / ⟨f⟩²")
    axes[0].set_title("Force–force correlation, particles at rest (cf. Fig. 18)", fontsize=10)
    for run, style in ((rough, "o-"), (smooth, "s-")):
        a = run.get("rest", {}).get("contact_angles", {})
        if "degrees" in a:
            axes[1].plot(a["degrees"], a["density"], style, markersize=3, label=f"μ = {run['friction']:g}")
            iso = a["isotropic"]
    if "degrees" in rest.get("contact_angles", {}):
        axes[1].plot(rest["contact_angles"]["degrees"], iso, "--", color="grey", label="random directions")
    axes[1].set_xlabel("elevation of the contact normal (degrees; 0 sideways, 90 vertical)")
    axes[1].set_ylabel("density (1/degree)")
    axes[1].set_title("Granule contact angles at rest (cf. Fig. 19)", fontsize=10)
    axes[1].legend(fontsize=8)
    n = rest.get("networks", {})
    if "threshold" in n:
        axes[2].plot(n["threshold"], n["contacts"], "-", label="fraction of contacts with f > f_cut")
        axes[2].plot(n["threshold"], n["force"], "--", label="fraction of the force they carry")
        axes[2].axvline(1.0, color="grey", linewidth=0.8)
    axes[2].set_xlabel("f_cut")
    axes[2].set_title("Weak and strong networks, granules at rest (cf. Fig. 20)", fontsize=10)
    axes[2].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "structure.png", dpi=110)
    plt.close(fig)


def plot_stress_strain(section, out):
    rough, _ = compression_runs(section)
    curve, turn = rough["stress_strain"], rough["turn_index"]
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.plot([-100 * p[0] for p in curve[:turn]], [-p[1] / 1000 for p in curve[:turn]], "-", label="loading")
    ax.plot([-100 * p[0] for p in curve[turn:]], [-p[1] / 1000 for p in curve[turn:]], "-", label="unloading")
    ax.set_xlabel("axial strain (%)")
    ax.set_ylabel("axial stress (kPa)")
    ax.set_title("Stress–strain, loading and unloading (cf. Fig. 21)", fontsize=10)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "stress_strain.png", dpi=110)
    plt.close(fig)
