#!/usr/bin/env python3
"""Draws the validation plots and writes docs/validation/README.md from the results JSON of
sandphys-validation. Every number in the report comes from that file; the paper's values are
the reference the program wrote beside its own. Needs python3-matplotlib. The plots are
report_plots.py, the summary table and its verdicts report_tables.py.

Usage: scripts/validation/make_report.py RESULTS.json OUT_DIR [BESIDE.json]

BESIDE.json, a second run under the other contact law (sandphys-validation --contact-law), puts
its angle-of-repose sweeps beside the main run's.
"""
import json
import math
import sys
from pathlib import Path

from report_plots import (plot_beverloo, plot_dunes, plot_flow_friction, plot_forces, plot_repose,
                          plot_stress_strain, plot_structure)
from report_tables import (EXPONENT_TOLERANCE, MIN_LAW_R2, MIN_STEADY_R2, compression_runs,
                           fit_text, fmt, rows_compression, rows_dunes, rows_flow_friction,
                           rows_flow_outlet, rows_repose)


def cost_text(r):
    """A run's largest overlap and substeps per frame in a sentence (empty in results written
    before sandphys-validation recorded them)."""
    if r.get('max_overlap_d') is None:
        return ""
    return (f" Largest overlap {fmt(r['max_overlap_d'], 2)} d, "
            f"{fmt(r.get('substeps_per_frame'), 3)} substeps per frame.")


def cost(r):
    """Two table cells of a run: its largest overlap (d) and substeps per frame (n/a in results
    written before sandphys-validation recorded them)."""
    return f"{fmt(r.get('max_overlap_d'), 2)} | {fmt(r.get('substeps_per_frame'), 3)}"


# The library's default density, kg/m³, for results written before they carried granule_mass_kg.
DEFAULT_DENSITY = 2600.0


def at_rest(section, r):
    """Whether the run ended at rest: its rms speed from the final kinetic energy under the sweep's
    settle speed (results before these were recorded: the scene's own `settled`)."""
    if "kinetic_energy_j" not in r or "settle_speed_m_s" not in section:
        return r.get("settled") != 0
    d = section["particle_diameter_m"]
    mass = section.get("granule_mass_kg", 4 * DEFAULT_DENSITY * math.pi * d ** 3 / 6)
    moving = section["granules"] - r.get("granules_not_born", 0)
    return math.sqrt(2 * r["kinetic_energy_j"] / (max(moving, 1) * mass)) <= section["settle_speed_m_s"]


def angle_header(*extra):
    """The two header lines of an angle table (angle_lines' rows), with `extra` columns after."""
    columns = ["μ", "angle (°)", "R²", "flank cells", "height (d)", "simulated (s)",
               "largest overlap (d)", "substeps per frame", "wall (s)", *extra]
    return ["| " + " | ".join(columns) + " |", "|" + " --- |" * len(columns)]


def angle_lines(section):
    """Table rows of an angle sweep: μ, angle, R², flank cells, height, simulated and wall time."""
    lines = []
    for r in section["runs"]:
        # A heap with no flank to fit (at μ = 0 the sand may spread flat): its error, which
        # names the peak and the cells, is in results.json.
        angle = f"{r['angle_deg']:.2f}" if "angle_deg" in r else "no flank to fit"
        r2 = fmt(r.get("angle_fit_r2"), 3)
        height = (f"{r['peak_height_m'] / section['particle_diameter_m']:.1f}"
                  if "peak_height_m" in r else "n/a")
        cells = len(r.get("flank_radius_m", []))
        # A run that stopped at its time limit with the sand still moving says so.
        creeping = "" if at_rest(section, r) else " (not at rest)"
        lines.append(f"| {r['friction']:g} | {angle}{creeping} | {r2} | {cells} | {height} | "
                     f"{r['simulated_seconds']:.2f} | {cost(r)} | {r['wall_seconds']:.0f} |")
    return lines


# What each value of sandphys-validation's --contact-law is called in the report.
LAW_NAMES = {"hertz-mindlin": "Hertz–Mindlin", "paper": "the paper's law"}


def law_of(results):
    return results.get("contact_law", "hertz-mindlin")


def beside_text(section, beside, law):
    """The other law's sweep of the same experiment, as a paragraph and table, or nothing."""
    if not beside:
        return []
    return [
        "",
        f"The same sweep under {LAW_NAMES[law]} (`--contact-law {law}`):",
        "",
        *angle_header(),
        *angle_lines(beside),
        "",
        power_law_text(beside),
    ]


def power_law_text(section):
    law = section.get("power_law")
    if not law:
        return section.get("power_law_error", "")
    zero = (" μ = 0, measured above, has no place on a power law and is left out of the fit."
            if any(r["friction"] == 0 for r in section["runs"]) else "")
    return (f"Power law (`analysis::fitPowerLaw`): angle = {law['coefficient']:.3g}° · "
            f"μ^{law['exponent']:.3f}, R² = {law['r2']:.3f}; the paper's exponent: "
            f"{section['paper']['exponent']:g}.{zero}")


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    results = json.loads(Path(sys.argv[1]).read_text())
    out = Path(sys.argv[2])
    other = json.loads(Path(sys.argv[3]).read_text()) if len(sys.argv) == 4 else {}
    main_law, other_law = law_of(results), law_of(other) if other else None
    # The summary names the law of each angle row once a second law is beside.
    main_name = f", {LAW_NAMES[main_law]}" if other else ""
    other_name = f", {LAW_NAMES[other_law]}" if other else ""
    out.mkdir(parents=True, exist_ok=True)

    rows = []
    sections = []
    if "flow-friction" in results:
        s = results["flow-friction"]
        plot_flow_friction(s, out)
        rows += rows_flow_friction(s)
        lines = [f"| {r['friction']:g} | {r['granules_at_release']} | {r['flow_rate']:.1f} | "
                 f"{fmt(r['flow_rate_r2'], 5)} | {r['steady_start_s']:.2f}–{r['steady_end_s']:.2f} | "
                 f"{cost(r)} | {r['wall_seconds']:.0f} |" for r in s["runs"]]
        sections.append("\n".join([
            "## Flow rate against friction",
            "",
            f"The `hourglass` scene: {s['granules']} granules settle in the funnel (45° full "
            f"aperture) over an outlet of {s['outlet_d']:g} d, then drain"
            + (f"; the funnel wall's friction is held at {s['wall_friction']:g} while the grains' "
               "μ changes" if "wall_friction" in s else "")
            + ". The flow rate is the "
            "slope of a least-squares line through the granules remaining while 10% to 80% of "
            "them have left.",
            "",
            "| μ | granules at release | flow rate (granules/s) | R² | steady window (s) | "
            "largest overlap (d) | substeps per frame | wall (s) |",
            "| --- | --- | --- | --- | --- | --- | --- | --- |",
            *lines,
            "",
            "![flow against friction](flow_friction.png)",
        ]))
    if "flow-outlet" in results:
        s = results["flow-outlet"]
        plot_beverloo(s, out)
        rows += rows_flow_outlet(s)
        lines = [f"| {r['outlet_d']:g} | {r['granules_at_release']} | {r['flow_rate']:.1f} | "
                 f"{fmt(r['flow_rate_r2'], 5)} | {cost(r)} | {r['wall_seconds']:.0f} |"
                 for r in s["runs"]]
        fit = s.get("beverloo")
        beverloo_text = (f"Fitted (`analysis::fitBeverloo`): C = {fit['c']:.4g}, k = {fit['k']:.4g} d, "
                    f"R² = {fit['r2']:.4f}; the paper: C = {s['paper']['c']:g}, "
                    f"k = {s['paper']['k']:g} d." if fit else s.get("beverloo_error", ""))
        sections.append("\n".join([
            "## Flow rate against outlet diameter (Beverloo's law)",
            "",
            f"The same funnel and fill size at μ = {s['friction']:g}, for each outlet diameter D. "
            "A run whose outlet jammed has no steady part (rate 0) and is left out of the fit.",
            "",
            "| D (d) | granules at release | flow rate (granules/s) | R² | largest overlap (d) | "
            "substeps per frame | wall (s) |",
            "| --- | --- | --- | --- | --- | --- | --- |",
            *lines,
            "",
            beverloo_text,
            "",
            "C carries the grains' bulk density, gravity and size, so it is only comparable "
            "between equal grains: sandphys's granule weighs 4 · 2600 kg/m³ · π d³/6 = 0.044 kg "
            "at d = 2 cm, the paper's 0.0143 kg. k, the empty annulus at the outlet's rim in "
            "grain diameters, is the comparable constant.",
            "",
            "![Beverloo](beverloo.png)",
        ]))
    if "repose" in results:
        s = results["repose"]
        b = other.get("repose")
        plot_repose(s, out, beside=b, labels=(LAW_NAMES[main_law], other_law and LAW_NAMES[other_law]))
        rows += rows_repose(s, law_name=main_name)
        if b:
            rows += rows_repose(b, law_name=other_name)
        lines = angle_lines(s)
        law_text = power_law_text(s)
        sections.append("\n".join([
            "## Angle of repose against friction",
            "",
            f"The `repose-heap` scene under {LAW_NAMES[main_law]}: {s['granules']} granules poured "
            "from a narrow emitter onto a rough floor"
            + (f" {s['floor_radius_d']:.1f} d in radius (wide enough for a heap of them at "
               "10°, so that only a heap flatter than that reaches the edge)"
               if "floor_radius_d" in s else "")
            + (f", until the rms speed is below {s['settle_speed_m_s']:g} m/s"
               if "settle_speed_m_s" in s else "")
            + ". Once the heap has settled, the surface is the highest granule centre "
            "in every square cell one granule wide; the flank is the part between 15% and 85% of "
            "the peak height (chosen by radius, see `analysis::angleOfRepose`), and the angle is "
            "that of a bisquare-weighted line through it.",
            "",
            *angle_header(),
            *lines,
            "",
            law_text,
            *beside_text(s, b, other_law),
            "",
            "![angle of repose](repose.png)",
        ]))
    if "repose-scupper" in results:
        s = results["repose-scupper"]
        g = s["geometry_d"]
        b = other.get("repose-scupper")
        plot_repose(s, out, "repose_scupper.png", "sump piles", "the ledge's face", beside=b,
                    labels=(LAW_NAMES[main_law], other_law and LAW_NAMES[other_law]))
        rows += rows_repose(s, "sump of the reservoir and scupper", "Figs. 15 and 22", main_name)
        if b:
            rows += rows_repose(b, "sump of the reservoir and scupper", "Figs. 15 and 22",
                                other_name)
        lines = [line + f" {r.get('granules_in_sump', 0):.0f} |"
                 for line, r in zip(angle_lines(s), s["runs"])]
        sections.append("\n".join([
            "## Angle of repose in the sump (the paper's setup)",
            "",
            f"The `repose-scupper` scene (the paper's Fig. 15): {s['granules']} granules settle in "
            f"a reservoir {g['reservoir_width']:g} d wide on a ledge {g['ledge']:g} d above the "
            f"sump's rough floor, in a container {g['depth']:g} d deep. The gate at the foot of the "
            f"reservoir's wall rises by {g['outlet']:g} d: sand runs through that slot, across the "
            "whole depth, and piles up in the sump against the ledge until the pile buries the "
            "slot. The angle is that of the pile's flank, away from the ledge, read as for the "
            "heaps but against the distance from the ledge's face (`HeapShape::ridge`), leaving "
            "out the cells within 3 d of the side walls. The paper's container is 100 d deep and "
            "holds 64 K granules; ours has walls close on either side, whose friction "
            + (f"(fixed at {s['wall_friction']:g}, as for the paper's Fig. 22)"
               if "wall_friction" in s else "(the grains' μ)")
            + " holds the pile up a little.",
            "",
            *angle_header("granules in the sump"),
            *lines,
            "",
            power_law_text(s),
            *beside_text(s, b, other_law),
            "",
            "![angle of repose in the sump](repose_scupper.png)",
        ]))

    if "dunes" in results:
        s = results["dunes"]
        plot_dunes(s, out)
        rows += rows_dunes(s)
        sections.append("\n".join([
            "## Dunes",
            "",
            f"The `dunes` scene: two emitters {s['separation_d']:g} d apart each pour "
            f"{s['granules_per_column']} granules onto a rough floor. The profile is the highest "
            "granule centre in each strip one granule wide along the axis through both columns; "
            "a dune with two crests has a saddle at least 1 d below the lower crest between them. "
            f"Settled after {s['simulated_seconds']:.2f} s simulated ({s['wall_seconds']:.0f} s wall)."
            + cost_text(s),
            "",
            "![dune profile](dunes.png)",
        ]))

    if "compression" in results:
        s = results["compression"]
        plot_forces(s, out)
        plot_structure(s, out)
        plot_stress_strain(s, out)
        rows += rows_compression(s)
        rough, smooth = compression_runs(s)
        lines = []
        for run in (rough, smooth):
            for snap in ("rest", "peak"):
                if snap not in run:
                    continue
                for level in ("particles", "granules"):
                    for kind in ("normal", "tangential"):
                        dist = run[snap][level][kind]
                        lines.append(f"| {run['friction']:g} | {snap} | {level} | {kind} | {dist['count']} | "
                                     f"{fmt(dist.get('mean_n'))} | {fit_text(dist, 'exponential')} | "
                                     f"{fit_text(dist, 'gaussian')} | {fit_text(dist, 'gamma')} |")
        sections.append("\n".join([
            "## Contact forces, contact network, stress and strain",
            "",
            f"The `compression` scene: a lattice of {rough['granules']} granules ({s['layers']} layers) "
            f"drops into a smooth cylinder of radius {s['radius_d']:g} d on a rough floor and settles; "
            "every contact is read (\"rest\"). A flat plunger then presses the top flat (to half the peak "
            "stress, see `Compression::Config::preloadFraction`), eases back up to the lowest height "
            "without compression (the paper's protocol), and comes down from there at 5 cm/s until the mean "
            f"axial stress reaches {s['max_stress_pa'] / 1000:g} kPa, where every contact is read again "
            "(\"peak\"), and goes back up until the sand no longer pushes on it. The same pile at μ = 0 "
            "gives the frictionless distributions.",
            "",
            "Forces are normalised by their mean. Particle level: every contact between particles of two "
            "different granules. Granule level: the contacts of each pair of granules summed into one "
            "force, whose normal part lies along the line between the two centres. Densities: "
            "Kaplan–Meier CDF, Freedman–Diaconis bins. Tail fits over f ≥ 1: exponential P = a e^(−b f), "
            "Gaussian P = β e^(−α f²); gamma by maximum likelihood over all forces. The paper does not "
            "say how its exponential is written; if its b is a decay length, compare it with our 1/b.",
            "",
            "| μ | when | level | force | contacts | mean (N) | exponential | Gaussian | gamma |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- |",
            *lines,
            "",
            "![force distributions](forces.png)",
            "",
            "![contact network](structure.png)",
            "",
            f"Stress–strain: the strain is the plunger's travel from that eased height over the pile's "
            f"height there; {100 * rough['max_strain']:.2f}% at the peak, "
            f"{100 * rough['residual_strain']:.2f}% when the stress was back at zero "
            f"({rough['recovered_fraction']:.0%} recovered). Run: {rough['simulated_seconds']:.2f} s "
            f"simulated, {rough['wall_seconds']:.0f} s wall." + cost_text(rough),
            "",
            "![stress-strain](stress_strain.png)",
        ]))

    table = ["| feature | expected (paper) | measured | verdict |", "| --- | --- | --- | --- |"]
    table += [f"| {a} | {b} | {c} | {d} |" for a, b, c, d in rows]
    wall = results.get("wall_seconds", 0.0)
    report = "\n".join([
        "# Validation report",
        "",
        "The experiments of Longmore, Marais & Kuttel 2013, section 6, run by sandphys. "
        "Generated by `scripts/validation-report.sh` (which runs `sandphys-validation` and then "
        "`scripts/validation/make_report.py`); every number below comes from that run.",
        "",
        f"- Run started {results['started']}, {wall / 60:.1f} min wall, on {results['gpu']}, "
        f"under {LAW_NAMES[main_law]}.",
        f"- Command: `{results['command']}`",
        *([f"- Beside it, the angle-of-repose sweeps under {LAW_NAMES[other_law]}: run started "
           f"{other['started']}, {other.get('wall_seconds', 0.0) / 60:.1f} min wall, command "
           f"`{other['command']}` ([{Path(sys.argv[3]).name}]({Path(sys.argv[3]).name}))."]
          if other else []),
        "- The measurements: [results.json](results.json); "
        "`scripts/validation/make_report.py docs/validation/results.json docs/validation"
        + (f" docs/validation/{Path(sys.argv[3]).name}" if other else "")
        + "` redraws this report from them.",
        "",
        "## Summary",
        "",
        *table,
        "",
        f"Verdicts: a steady part agrees at R² ≥ {MIN_STEADY_R2}; a law (Beverloo, power law) "
        f"at R² ≥ {MIN_LAW_R2}; the power law's exponent within ±{EXPONENT_TOLERANCE} of the "
        "paper's.",
        "",
        *[s + "\n" for s in sections],
    ])
    (out / "README.md").write_text(report)
    print(f"make_report: wrote {out / 'README.md'} and {len(list(out.glob('*.png')))} plots")


if __name__ == "__main__":
    main()
