#!/usr/bin/env python3
"""Random but ordinary wing configs for `mixmesh generate` (the robustness suite, issue #13).

    scripts/random-wings.py N SEED OUTDIR [--layers L1,L2,...] [--space ordinary|wide]

writes OUTDIR/wing_SEED_0001.toml ... wing_SEED_NNNN.toml. Wing i depends only on SEED
and i, so a larger N keeps the first wings. The first line of each config lists its
drawn parameters. --layers draws the layer count from the given list instead of 24, 28,
32 (everything else is drawn as without it).

Design space: NACA 4- and 5-digit sections of 8-18 % thickness; aspect ratio 4-12;
taper 0.2-1; leading-edge sweep 0-45 deg; dihedral -3..8 deg; twist -6..+4 deg (tip
against root); root chord 0.3-9 m; Re 3e6-6e7 on the mean chord (the reference length);
y+ 0.5-2; 24-32 layers. About a quarter of the wings are cranked three-station
(transport-like) planforms, a quarter have rounded tips, a fifth blunt bases (open
NACA trailing edge kept as a base face) and a fifth no wake. Surfaces are as coarse as
the shipped cases (120-200 x 24-48 wing faces), so a wing takes seconds.

--space wide draws from streams of their own over what a designer might also try: the
ONERA D section file besides NACA 4- and 5-digit sections of 6-21 %; aspect ratio 3-20
(log-uniform), sweep 0-60 deg below aspect ratio 6 and 0-40 deg above; taper 0.1-1;
dihedral -8..12 deg; twist -8..+4 deg; root chord 0.1-15 m; Re 1e6-1e8; y+ 0.3-5; 16-48
layers; 120-320 x 20-100 wing faces with leading-, trailing-edge, root and tip spacings
of 0.5-3, 1-5, 5-30 and 2-10 thousandths; wakes of 3-20 root chords growing 1.1-1.3.
About 30 % cranked, 30 % rounded tips, 20 % bases, 15 % no wake.
"""
import math
import os
import random
import shutil
import sys


def naca_section(rng, thickness):
    family = rng.random()
    if family < 0.35:
        return f"00{thickness:02d}"
    if family < 0.7:
        camber = rng.choice([1, 2, 4])
        position = rng.choice([3, 4])
        return f"{camber}{position}{thickness:02d}"
    # Five-digit: design lift 0.3 (2) or 0.45 (3), camber positions 0.1-0.25, normal lines.
    lift = rng.choice([2, 3])
    position = rng.choice([2, 3, 4, 5])
    return f"{lift}{position}0{thickness:02d}"


def half_area(stations):
    return sum((b["y"] - a["y"]) * (a["chord"] + b["chord"]) / 2 for a, b in zip(stations, stations[1:]))


def cranked_stations(root_chord, taper, semi_span, kink_fraction, kink_chord_share, sweep, inboard_extra_sweep,
                     dihedral, root_twist, tip_twist):
    """Root, kink and tip stations: inboard the chord falls fast (a transport's unswept or
    little-swept inboard trailing edge), outboard it tapers to the tip."""
    tip_chord = taper * root_chord
    y_kink = kink_fraction * semi_span
    linear_chord = root_chord + (tip_chord - root_chord) * kink_fraction
    kink_chord = tip_chord + (linear_chord - tip_chord) * kink_chord_share
    x_kink = y_kink * math.tan(math.radians(sweep + inboard_extra_sweep))
    x_tip = x_kink + (semi_span - y_kink) * math.tan(math.radians(sweep))
    rise = math.tan(math.radians(dihedral))
    kink_twist = root_twist + (tip_twist - root_twist) * kink_fraction
    return [
        dict(y=0.0, chord=root_chord, leading_edge_x=0.0, leading_edge_z=0.0, twist=root_twist),
        dict(y=y_kink, chord=kink_chord, leading_edge_x=x_kink, leading_edge_z=y_kink * rise, twist=kink_twist),
        dict(y=semi_span, chord=tip_chord, leading_edge_x=x_tip, leading_edge_z=semi_span * rise, twist=tip_twist),
    ]


def draw_wing(seed, index, layer_counts=(24, 28, 32)):
    rng = random.Random(f"mixmesh-robustness-{seed}-{index}")
    p = {}
    p["thickness"] = rng.randint(8, 18)
    p["naca"] = naca_section(rng, p["thickness"])
    p["aspect_ratio"] = rng.uniform(4.0, 12.0)
    p["root_chord"] = math.exp(rng.uniform(math.log(0.3), math.log(9.0)))
    p["sweep"] = rng.uniform(0.0, 45.0)
    p["dihedral"] = rng.uniform(-3.0, 8.0)
    p["root_twist"] = rng.uniform(-1.0, 3.0)
    p["twist"] = rng.uniform(-6.0, 4.0)  # tip minus root
    p["cranked"] = rng.random() < 0.25
    p["taper"] = rng.uniform(0.2, 0.5) if p["cranked"] else rng.uniform(0.2, 1.0)
    p["rounded_tip"] = rng.random() < 0.25
    p["base"] = rng.random() < 0.2
    p["wake"] = rng.random() >= 0.2
    p["reynolds"] = math.exp(rng.uniform(math.log(3e6), math.log(6e7)))
    p["y_plus"] = rng.uniform(0.5, 2.0)
    p["layers"] = rng.choice([24, 28, 32])
    if tuple(layer_counts) != (24, 28, 32):  # from a stream of its own: the other draws stay
        p["layers"] = random.Random(f"mixmesh-robustness-{seed}-{index}-layers").choice(layer_counts)
    p["chordwise_cells"] = 2 * rng.randint(60, 100)
    p["spanwise_cells"] = rng.randint(24, 48)
    # Cranked-only draws are made for every wing so the stream stays aligned.
    kink_fraction = rng.uniform(0.3, 0.45)
    kink_chord_share = rng.uniform(0.5, 0.9)
    inboard_extra_sweep = rng.uniform(0.0, 5.0)
    stations = planform(p, kink_fraction, kink_chord_share, inboard_extra_sweep)
    return p, stations


def log_uniform(rng, low, high):
    return math.exp(rng.uniform(math.log(low), math.log(high)))


def draw_wide_wing(seed, index):
    """The wide design space (module docstring); same keys as draw_wing, plus the surface
    spacings and the wake, so config_text writes both."""
    rng = random.Random(f"mixmesh-robustness-wide-{seed}-{index}")
    p = {}
    p["thickness"] = rng.randint(6, 21)
    p["naca"] = naca_section(rng, p["thickness"])
    p["airfoil_file"] = rng.random() < 0.15
    p["aspect_ratio"] = log_uniform(rng, 3.0, 20.0)
    p["root_chord"] = log_uniform(rng, 0.1, 15.0)
    p["sweep"] = rng.uniform(0.0, 60.0 if p["aspect_ratio"] < 6.0 else 40.0)
    p["dihedral"] = rng.uniform(-8.0, 12.0)
    p["root_twist"] = rng.uniform(-2.0, 4.0)
    p["twist"] = rng.uniform(-8.0, 4.0)
    p["cranked"] = rng.random() < 0.3
    p["taper"] = rng.uniform(0.1, 0.5) if p["cranked"] else rng.uniform(0.1, 1.0)
    p["rounded_tip"] = rng.random() < 0.3
    p["base"] = rng.random() < 0.2 and not p["airfoil_file"]
    p["wake"] = rng.random() >= 0.15
    p["reynolds"] = log_uniform(rng, 1e6, 1e8)
    p["y_plus"] = log_uniform(rng, 0.3, 5.0)
    p["layers"] = rng.randint(16, 48)
    p["chordwise_cells"] = 2 * rng.randint(60, 160)
    p["spanwise_cells"] = rng.randint(20, 100)
    p["spacings"] = dict(leading_edge_spacing=rng.uniform(0.0005, 0.003),
                         trailing_edge_spacing=rng.uniform(0.001, 0.005),
                         root_spacing=rng.uniform(0.005, 0.03), tip_spacing=rng.uniform(0.002, 0.01))
    p["wake_length"] = rng.uniform(3.0, 20.0)
    p["wake_growth"] = rng.uniform(1.1, 1.3)
    kink_fraction = rng.uniform(0.25, 0.5)
    kink_chord_share = rng.uniform(0.4, 0.9)
    inboard_extra_sweep = rng.uniform(0.0, 8.0)
    if p["cranked"]:
        p["sweep"] = min(p["sweep"], 52.0)  # the inboard panel is swept further
    stations = planform(p, kink_fraction, kink_chord_share, inboard_extra_sweep)
    return p, stations


def planform(p, kink_fraction, kink_chord_share, inboard_extra_sweep):
    """Stations for the drawn planform; sets semi_span, mean_chord and, when cranked,
    kink, kink_chord and inboard_sweep in p."""
    tip_twist = p["root_twist"] + p["twist"]
    if p["cranked"]:
        p["kink"] = kink_fraction
        # Semi-span for the target aspect ratio: AR = (2b)^2 / (2 S_half(b)), fixed point.
        semi_span = p["aspect_ratio"] * p["root_chord"] * (1 + p["taper"]) / 4
        for _ in range(50):
            stations = cranked_stations(p["root_chord"], p["taper"], semi_span, kink_fraction, kink_chord_share,
                                        p["sweep"], inboard_extra_sweep, p["dihedral"], p["root_twist"], tip_twist)
            semi_span = math.sqrt(p["aspect_ratio"] * 2 * half_area(stations)) / 2
        stations = cranked_stations(p["root_chord"], p["taper"], semi_span, kink_fraction, kink_chord_share,
                                    p["sweep"], inboard_extra_sweep, p["dihedral"], p["root_twist"], tip_twist)
        p["kink_chord"] = stations[1]["chord"]
        p["inboard_sweep"] = p["sweep"] + inboard_extra_sweep
    else:
        semi_span = p["aspect_ratio"] * p["root_chord"] * (1 + p["taper"]) / 4
        stations = [dict(y=0.0, chord=p["root_chord"]), dict(y=semi_span, chord=p["taper"] * p["root_chord"])]
    p["semi_span"] = semi_span
    p["mean_chord"] = half_area(stations) / semi_span
    return stations


def number(value, digits=6):
    return f"{value:.{digits}g}"


def config_text(seed, index, p, stations):
    section = "onera_d.dat" if p.get("airfoil_file") else f"naca {p['naca']}"
    drawn = (f"{section}  AR {p['aspect_ratio']:.2f}  taper {p['taper']:.3f}  "
             f"sweep {p['sweep']:.1f}  dihedral {p['dihedral']:.1f}  twist {p['root_twist']:.1f}"
             f"..{p['root_twist'] + p['twist']:.1f} ({p['twist']:+.1f})  root_chord {p['root_chord']:.3f}  semi_span {p['semi_span']:.3f}  "
             f"mean_chord {p['mean_chord']:.4f}  Re {p['reynolds']:.3g}  y+ {p['y_plus']:.2f}  "
             f"layers {p['layers']}  cells {p['chordwise_cells']}x{p['spanwise_cells']}  "
             + (f"cranked(kink {p['kink']:.2f} chord {p['kink_chord']:.3f} inboard_sweep "
                f"{p['inboard_sweep']:.1f})" if p["cranked"] else "straight")
             + f"  tip {'rounded' if p['rounded_tip'] else 'flat'}  te {'base' if p['base'] else 'closed'}"
             f"  wake {'on' if p['wake'] else 'off'}")
    lines = [f"# {drawn}",
             f"# random-wings.py seed {seed} wing {index}: a random ordinary wing for the robustness suite (issue #13).",
             "", "[wing]"]
    lines += ['airfoil_file = "airfoils/onera_d.dat"'] if p.get("airfoil_file") else [f'naca = "{p["naca"]}"']
    if p["base"]:
        lines += ["naca_closed_trailing_edge = false", 'blunt_trailing_edge = "base"']
    if p["cranked"]:
        for station in stations:
            lines += ["", "[[wing.station]]"]
            lines += [f"{key} = {number(value)}" for key, value in station.items()]
    else:
        lines += [f"root_chord = {number(p['root_chord'])}", f"semi_span = {number(p['semi_span'])}",
                  f"leading_edge_sweep = {number(p['sweep'], 4)}", f"taper = {number(p['taper'], 4)}",
                  f"dihedral = {number(p['dihedral'], 4)}", f"root_twist = {number(p['root_twist'], 4)}",
                  f"tip_twist = {number(p['root_twist'] + p['twist'], 4)}"]
    lines += ["", "[surface]", f"chordwise_cells = {p['chordwise_cells']}",
              f"spanwise_cells = {p['spanwise_cells']}"]
    lines += [f"{key} = {number(value, 4)}" for key, value in p.get("spacings", {}).items()]
    if not p["wake"]:
        lines += ["", "[surface.wake]", "enabled = false"]
    elif "wake_length" in p:
        lines += ["", "[surface.wake]", f"length = {number(p['wake_length'], 4)}",
                  f"growth = {number(p['wake_growth'], 4)}"]
    if p["rounded_tip"]:
        lines += ["", "[surface.tip]", 'shape = "rounded"']
    lines += ["", "[march]", f"layers = {p['layers']}", f"y_plus = {p['y_plus']:.3f}",
              f"reynolds_number = {p['reynolds']:.4g}", f"reference_length = {number(p['mean_chord'])}",
              "", "[output]", 'formats = ["vtu"]', ""]
    return "\n".join(lines)


def layer_list(text):
    try:
        counts = tuple(int(value) for value in text.split(","))
    except ValueError:
        counts = ()
    if not counts or min(counts) < 1:
        raise ValueError(f"--layers: '{text}' is not a comma-separated list of positive layer counts")
    return counts


def main(argv):
    usage = "usage: random-wings.py N SEED OUTDIR [--layers L1,L2,...] [--space ordinary|wide]\n"
    layer_counts = (24, 28, 32)
    space = "ordinary"
    positional = [argv[0]]
    index = 1
    while index < len(argv):
        if argv[index] in ("--layers", "--space") and index + 1 < len(argv):
            option, value = argv[index], argv[index + 1]
            index += 2
            if option == "--space":
                if value not in ("ordinary", "wide"):
                    sys.stderr.write(f"random-wings.py: --space: '{value}' is neither ordinary nor wide\n")
                    return 2
                space = value
                continue
            try:
                layer_counts = layer_list(value)
            except ValueError as error:
                sys.stderr.write(f"random-wings.py: {error}\n")
                return 2
            continue
        positional.append(argv[index])
        index += 1
    argv = positional
    if space == "wide" and layer_counts != (24, 28, 32):
        sys.stderr.write("random-wings.py: --layers applies to the ordinary space only (wide draws 16-48)\n")
        return 2
    if len(argv) != 4:
        sys.stderr.write(usage)
        return 2
    try:
        count, seed = int(argv[1]), int(argv[2])
    except ValueError:
        sys.stderr.write("random-wings.py: N and SEED must be integers\n")
        return 2
    if count < 1:
        sys.stderr.write("random-wings.py: N must be at least 1\n")
        return 2
    os.makedirs(argv[3], exist_ok=True)
    if space == "wide":  # the section file the wide space may draw, beside the configs
        os.makedirs(os.path.join(argv[3], "airfoils"), exist_ok=True)
        source = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cases", "airfoils", "onera_d.dat")
        shutil.copyfile(source, os.path.join(argv[3], "airfoils", "onera_d.dat"))
    for index in range(1, count + 1):
        p, stations = draw_wide_wing(seed, index) if space == "wide" else draw_wing(seed, index, layer_counts)
        path = os.path.join(argv[3], f"wing_{seed}_{index:04d}.toml")
        with open(path, "w") as f:
            f.write(config_text(seed, index, p, stations))
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
