"""Checks of the plotting tools on synthetic outputs with known answers.

usage: check_plot_tools.py CASE WORK_DIR [MPM_LIG]   (CASE: a function named in CASES;\nreal_footing also needs the mpm_lig executable)

Each case writes a run directory in the writers' formats (synthetic.py), runs the tool as a
user would and checks its exit code, its printed numbers against the closed-form values the
data were built from, and that the picture is a real plot (size, ink, colours).
"""
import math
import os
import re
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOLS = os.path.join(HERE, "..", "..", "tools")
import synthetic


def run_tool(tool, *args, dpi=100):
    """Run a tool; pictures at a screen resolution by default to keep the tests quick."""
    extra = ["--dpi", str(dpi)] if dpi else []
    result = subprocess.run([sys.executable, os.path.join(TOOLS, tool), *map(str, args), *extra],
                            capture_output=True, text=True)
    sys.stdout.write(result.stdout)
    sys.stderr.write(result.stderr)
    return result


def expect(condition, message):
    if not condition:
        raise SystemExit(f"FAILED: {message}")


def check_picture(path, min_colours=20):
    """The PNG exists, is large, has ink and more than a few colours."""
    import matplotlib.image as mpimg
    expect(os.path.isfile(path), f"{path} not written")
    image = mpimg.imread(path)[:, :, :3]
    expect(image.shape[0] >= 300 and image.shape[1] >= 500, f"{path}: small {image.shape}")
    ink = np.mean(image.min(axis=2) < 0.9)
    colours = len(np.unique((image * 255).astype(np.uint8).reshape(-1, 3), axis=0))
    print(f"{path}: {image.shape[1]}x{image.shape[0]}, ink {100 * ink:.1f} %, {colours} colours")
    expect(ink > 0.03, f"{path}: nearly blank ({100 * ink:.2f} % ink)")
    expect(colours >= min_colours, f"{path}: only {colours} colours")


def expect_bad_input(result, *words):
    expect(result.returncode == 2, f"exit code {result.returncode}, expected 2")
    for w in words:
        expect(w in result.stderr, f"'{w}' not named in the message: {result.stderr!r}")


def numbers_after(text, label):
    return [float(v) for v in re.findall(re.escape(label) + r"\s*=?\s*([-+0-9.eE]+)", text)]


# ---- cyclic simple shear ------------------------------------------------------------------
GAMMA_A, P0, CYCLES = 0.01, 100e3, 4
MODULI = [8e6 * 0.7 ** k for k in range(CYCLES)]  # secant modulus of cycle k + 1
P_RATIO = 0.6  # mean stress falls by this factor per cycle


def shear_path(per_quarter=10):
    """gamma 0 -> +a -> -a -> 0 per cycle; tau on an ellipse loop around G_k gamma (so
    tau(+-a) = +-G_k a exactly); p = P0 * P_RATIO^(cycles travelled)."""
    gamma, tau, p, cycle = [0.0], [0.0], [P0], [1]
    steps = 4 * per_quarter
    for k in range(CYCLES):
        for i in range(1, steps + 1):
            phase = i / steps  # fraction of this cycle
            g = GAMMA_A * math.sin(2 * math.pi * phase)
            # zero where gamma = +-a (cos = 0), so there tau = +-G_k a
            loop = 0.3 * MODULI[k] * GAMMA_A * math.cos(2 * math.pi * phase)
            loop = loop if abs(math.cos(2 * math.pi * phase)) > 1e-12 else 0.0
            gamma.append(g)
            tau.append(MODULI[k] * g - loop)
            p.append(P0 * P_RATIO ** (k + phase))
            cycle.append(k + 1)
    return [np.array(v) for v in (gamma, tau, p, cycle)]


def check_shear_table(stdout):
    rows = [line.split() for line in stdout.splitlines() if re.match(r"\s*\d+\s", line)]
    expect(len(rows) == CYCLES, f"{len(rows)} cycle rows, expected {CYCLES}")
    for k, row in enumerate(rows):
        modulus, ratio = float(row[3]) * 1e6, float(row[6])
        expect(abs(modulus / MODULI[k] - 1) < 2e-3, f"cycle {k + 1}: G_sec {modulus} vs {MODULI[k]}")
        expect(abs(ratio - P_RATIO ** (k + 1)) < 2e-3, f"cycle {k + 1}: p ratio {ratio}")
        expect(abs(float(row[1]) - 100 * GAMMA_A) < 1e-6, f"cycle {k + 1}: amplitude {row[1]}")


def shear_element(work):
    """Element-test layout (gamma_xy, s_xy, p; no cycle column: cycles counted from strain)."""
    gamma, tau, p, _ = shear_path()
    n = len(gamma)
    columns = ["increment", "time", "e_xy", "s_xy", "p", "q", "gamma_xy"]
    rows = np.column_stack([np.arange(n), np.arange(n) * 1e-3, gamma / 2, tau, p, np.abs(tau), gamma])
    synthetic.write_history(work, columns, rows)
    result = run_tool("plot_shear.py", work, "-o", os.path.join(work, "shear.png"))
    expect(result.returncode == 0, "plot_shear failed")
    check_shear_table(result.stdout)
    check_picture(os.path.join(work, "shear.png"))
    # p = P0 0.6^c with c the cycles of time: below 0.1 P0 only after 4.51 cycles (this path
    # has 4); below 0.3 P0 after c = ln 0.3 / ln 0.6 = 2.357, which on the sine strain path is
    # 2 + (1 + 1 - sin(2π 0.357)) / 4 cycles of path (the first row past it: 1/40 cycle later).
    expect("p' < 0.1 p'0: not reached" in result.stdout, "liquefaction line")
    from mpm_lig_post.shear import cycles_to_liquefaction
    at = cycles_to_liquefaction(np.array(gamma), np.array(p), fraction=0.3)
    c = math.log(0.3) / math.log(P_RATIO)
    phase = c - math.floor(c)
    quarter = math.floor(4 * phase)
    expected = math.floor(c) + (quarter + abs(math.sin(2 * math.pi * phase)
                                              - math.sin(math.pi * quarter / 2))) / 4
    expect(at is not None and expected <= at < expected + 1 / 40,
           f"p < 0.3 p0 after {at} cycles of path, expected {expected}")


def shear_mpm(work):
    """MPM layout (cycle, shear_strain, shear_stress, mean_stress), mean stress tension positive."""
    gamma, tau, p, cycle = shear_path()
    synthetic.write_history(work, ["step", "time", "cycle", "shear_strain", "shear_stress", "mean_stress"],
                            np.column_stack([np.arange(len(gamma)), np.arange(len(gamma)) * 1e-3,
                                             cycle, gamma, tau, -p]))
    result = run_tool("plot_shear.py", work)
    expect(result.returncode == 0, "plot_shear failed")
    check_shear_table(result.stdout)
    check_picture(os.path.join(work, "shear.png"))


def shear_points(work):
    """--points: per-point p' from results.h5; three points at heights 0.3, 0.1, 0.2 whose p'
    falls to 80 %, 0 and 50 % of p0 while their log shear strain e_xy peaks at 0.4, 1.5 and
    0.6 %."""
    gamma, tau, p, cycle = shear_path()
    synthetic.write_history(work, ["step", "time", "cycle", "shear_strain", "shear_stress", "mean_stress"],
                            np.column_stack([np.arange(len(gamma)), np.arange(len(gamma)) * 1e-3,
                                             cycle, gamma, tau, -p]))
    heights, final, peak = np.array([0.3, 0.1, 0.2]), np.array([0.8, 0.0, 0.5]), np.array([0.4, 1.5, 0.6])
    steps = []
    for k, f in enumerate(np.linspace(0, 1, 6)):
        ratio = 1 - f * (1 - final)
        stress = np.zeros((3, 6))
        stress[:, 0] = stress[:, 1] = -P0 * ratio
        strain = np.zeros((3, 6))
        strain[:, 3] = peak / 100 * math.sin(math.pi * f / 2) * (-1) ** k
        positions = np.column_stack([np.full(3, 0.025), heights, np.zeros(3)])
        steps.append((k * 10, k * 0.01, {"positions": positions, "stress": stress, "strain": strain}))
    synthetic.write_fields(work, steps)
    result = run_tool("plot_shear.py", work, "--points")
    expect(result.returncode == 0, "plot_shear --points failed: " + result.stderr)
    cycles, _, points = result.stdout.partition("point  y0")
    check_shear_table(cycles)
    rows = [line.split() for line in points.splitlines()[1:] if re.match(r"\s*\d+\s", line)]
    expect([int(r[0]) for r in rows] == [1, 2, 0], f"points not in height order: {rows}")
    for r in rows:
        k = int(r[0])
        expect(abs(float(r[2]) - final[k]) < 1e-3, f"point {k}: p_end/p0 {r[2]}, expected {final[k]}")
        expect(abs(float(r[3]) - 2 * peak[k]) < 1e-2, f"point {k}: max gamma {r[3]} %, expected {2 * peak[k]}")
    check_picture(os.path.join(work, "shear.png"))


def shear_bad(work):
    synthetic.write_history(work, ["cycle", "shear_strain", "mean_stress"], [[1, 0, 1e5], [1, 0.01, 1e5]])
    expect_bad_input(run_tool("plot_shear.py", work), "shear_stress", "history.csv")
    expect_bad_input(run_tool("plot_shear.py", os.path.join(work, "nowhere")), "nowhere")


# ---- force chains -------------------------------------------------------------------------
def packing(seed, compress):
    """A square lattice of discs, compressed vertically by `compress`, with contacts to the
    right and upper neighbours; vertical forces grow with `compress`."""
    rng = np.random.default_rng(seed)
    n, d = 10, 0.01
    centres, radii, contacts, forces = [], [], [], []
    for j in range(n):
        for i in range(n):
            centres.append([(i + 0.5) * d, (j + 0.5) * d * (1 - compress), 0.0])
            radii.append(0.5 * d * rng.uniform(0.8, 1.0))
    for j in range(n):
        for i in range(n):
            k = j * n + i
            if i + 1 < n:
                contacts.append((k, k + 1))
                forces.append(rng.uniform(1, 3))
            if j + 1 < n:
                contacts.append((k, k + n))
                forces.append(rng.uniform(1, 3) * (1 + 20 * compress) * (1 + (i % 3 == 0) * 2))
    box = [[n * d, 0, 0], [0, n * d * (1 - compress), 0], [0, 0, d]]
    return centres, radii, contacts, forces, box


def force_chains(work):
    snaps = os.path.join(work, "snapshots")
    os.makedirs(snaps, exist_ok=True)
    for step, compress in ((0, 0.0), (300, 0.1)):
        synthetic.write_snapshot(os.path.join(snaps, "rve_%06d" % step), *packing(step, compress))
    from mpm_lig_post.vtk_legacy import read_polydata
    contacts = read_polydata(os.path.join(snaps, "rve_000300_contacts.vtk"))
    expect(contacts.lines().shape == (180, 2, 3), f"contact lines {contacts.lines().shape}")
    expected = packing(300, 0.1)[3]
    expect(np.allclose(contacts.field("force", "cell"), expected, rtol=1e-8), "forces read back")
    grains = read_polydata(os.path.join(snaps, "rve_000300_grains.vtk"))
    expect(grains.points.shape == (100, 3) and grains.field("velocity").shape == (100, 3), "grains")
    result = run_tool("plot_force_chains.py", work, "--steps", 0, 300)
    expect(result.returncode == 0, "plot_force_chains failed")
    check_picture(os.path.join(work, "force_chains.png"), min_colours=8)


def force_chains_bad(work):
    snaps = os.path.join(work, "snapshots")
    os.makedirs(snaps, exist_ok=True)
    synthetic.write_snapshot(os.path.join(snaps, "rve_000000"), *packing(0, 0.0))
    expect_bad_input(run_tool("plot_force_chains.py", work, "--steps", 0, 7), "increment 7")
    # a contacts file without its force data
    path = os.path.join(snaps, "rve_000000_contacts.vtk")
    text = open(path).read()
    open(path, "w").write(text[: text.index("CELL_DATA")])
    expect_bad_input(run_tool("plot_force_chains.py", work, "--steps", 0, 0), "'force'", path)


# ---- footing ------------------------------------------------------------------------------
PHI, SURCHARGE, WIDTH = 28.1, 10e3, 2.0


def footing_history(work, plateau):
    s = np.linspace(0, 0.3, 301)  # settlement [m]
    q = plateau * SURCHARGE * (1 - np.exp(-s / 0.02)) * (1 + 0.05 * np.exp(-((s - 0.1) / 0.02) ** 2))
    synthetic.write_history(work, ["step", "time", "kinetic_energy", "settlement", "load", "q"],
                            np.column_stack([np.arange(len(s)), s, 0 * s, s, q * WIDTH / 2, q]))
    return q.max()


def footing(work):
    nq = math.tan(math.pi / 4 + math.radians(PHI) / 2) ** 2 * math.exp(math.pi * math.tan(math.radians(PHI)))
    peak = footing_history(work, nq)
    case = os.path.join(work, "case.json")
    # q_s is the first traction with a vertical component: the shear traction after it is not.
    open(case, "w").write('{"rigid_bodies": [{"type": "footing", "width": [%g]}], '
                          '"boundary_conditions": [{"type": "traction", "traction": [0, %g]}, '
                          '{"type": "traction", "traction": [%g, 0]}]}'
                          % (WIDTH, -SURCHARGE, 0.3 * SURCHARGE))
    result = run_tool("plot_footing.py", work, "--case", case, "--phi", PHI)
    expect(result.returncode == 0, "plot_footing failed")
    expect(abs(numbers_after(result.stdout, "N_q(28.1 deg) =")[0] - 14.88) < 0.01, "N_q(28.1)")
    expect(abs(numbers_after(result.stdout, "peak / N_q =")[0] - peak / SURCHARGE / nq) < 2e-3, "peak / N_q")
    expect(abs(numbers_after(result.stdout, "B =")[0] - WIDTH) < 1e-12, "B from the case")
    check_picture(os.path.join(work, "footing.png"), min_colours=8)
    # A second run at half the plateau, compared; the window mean of the plateau region.
    other = os.path.join(work, "other")
    footing_history(other, nq / 2)
    result = run_tool("plot_footing.py", work, "--case", case, "--phi", PHI, "--label", "run A",
                      "--compare", other, "run B", "--window", 0.1, 0.15)
    expect(result.returncode == 0, "plot_footing --compare failed: " + result.stderr)
    mean_a = numbers_after(result.stdout, "run A: mean over s/B in [0.1, 0.15] =")[0]
    mean_b = numbers_after(result.stdout, "run B: mean over s/B in [0.1, 0.15] =")[0]
    expect(abs(mean_a / nq - 1) < 0.01, f"run A window mean {mean_a}, expected about {nq}")
    expect(abs(mean_b / mean_a - 0.5) < 1e-3, f"run B / run A window means {mean_b / mean_a}")
    expect(abs(numbers_after(result.stdout, "run B: peak")[0] - peak / SURCHARGE / 2) < 1e-3,
           "run B peak")
    check_picture(os.path.join(work, "footing.png"), min_colours=8)


def footing_bad(work):
    synthetic.write_history(work, ["step", "time", "settlement", "load"], [[0, 0, 0, 0], [1, 1, 0.1, 5]])
    expect_bad_input(run_tool("plot_footing.py", work, "--width", 1), "'q'", "history.csv")
    footing_history(work, 10)
    expect_bad_input(run_tool("plot_footing.py", work), "--width")
    expect_bad_input(run_tool("plot_footing.py", work, "--width", 1, "--phi", 30), "--surcharge")


def footing_intrusion(work):
    """Points placed inside a descending footing (centre 0, B = 0.2 m, base 0.6 m at s = 0):
    0, 2, then 1 point inside at three output steps; the count is read from the table. q_s comes
    from the vertical traction, not the shear traction after it."""
    t = np.linspace(0, 0.2, 21)
    s = 0.5 * t  # settlement: base 0.6 - s
    synthetic.write_history(work, ["step", "time", "settlement", "q"],
                            np.column_stack([np.arange(len(t)), t, s, 1e6 + 0 * t]))
    grid = np.array([[x, y, 0.0] for x in (0.05, 0.15, 0.25) for y in (0.05, 0.15, 0.25)])
    inside = {0: [], 10: [[0.05, 0.56, 0.0], [0.09, 0.7, 0.0]], 20: [[0.02, 0.51, 0.0]]}
    # Near misses: beside the footprint (x = 0.11) and just under the base at step 20.
    near = [[0.11, 0.58, 0.0], [0.02, 0.49, 0.0]]
    steps = [(k, t[k], {"positions": np.array(grid.tolist() + inside[k] + near)}) for k in inside]
    synthetic.write_fields(work, steps)
    case = os.path.join(work, "case.json")
    open(case, "w").write('{"rigid_bodies": [{"type": "footing", "center": [0], "width": [0.2], '
                          '"base": 0.6}], "boundary_conditions": [{"type": "traction", '
                          '"traction": [0, -1e5]}, {"type": "traction", "traction": [3e4, 0]}]}')
    result = run_tool("footing_intrusion.py", work, "--case", case)
    expect(result.returncode == 0, "footing_intrusion failed: " + result.stderr)
    rows = [line.split() for line in result.stdout.splitlines() if re.match(r"\s*[0-9.]+\s+\d+\s", line)]
    expect([int(r[1]) for r in rows] == [0, 2, 1], f"counts per changed step: {rows}")
    expect([float(r[0]) for r in rows] == [0.0, 0.25, 0.5], f"s/B of the rows: {rows}")
    expect(abs(float(rows[0][2]) - 10.0) < 1e-9, "q/q_s from the case's traction")
    expect(numbers_after(result.stdout, "at once:")[0] == 2, "largest count")
    check_picture(os.path.join(work, "intrusion.png"), min_colours=8)
    expect_bad_input(run_tool("footing_intrusion.py", work, "--case", os.path.join(work, "none.json")),
                     "none.json")
    words = os.path.join(work, "words.json")
    open(words, "w").write('{"rigid_bodies": [{"type": "footing", "center": [0], "width": [0.2], '
                           '"base": 0.6}], "boundary_conditions": [{"type": "traction", '
                           '"traction": [0, "heavy"]}]}')
    expect_bad_input(run_tool("footing_intrusion.py", work, "--case", words),
                     "words.json", "boundary_conditions[0].traction")
    # A case that is not a JSON object, or whose boundary_conditions is not a list: exit 2.
    listed = os.path.join(work, "listed.json")
    open(listed, "w").write('[{"rigid_bodies": []}]')
    expect_bad_input(run_tool("plot_footing.py", work, "--case", listed), "listed.json", "JSON object")
    mapped = os.path.join(work, "mapped.json")
    open(mapped, "w").write('{"rigid_bodies": [{"type": "footing", "center": [0], "width": [0.2], '
                            '"base": 0.6}], "boundary_conditions": {"type": "traction"}}')
    expect_bad_input(run_tool("footing_intrusion.py", work, "--case", mapped),
                     "mapped.json", "boundary_conditions is not a list")


def footing_noise(work):
    """A footing at 0.5 m/s (B = 0.2 m, q_s = 100 kPa) with three field outputs: one before
    s/B = 0.2 whose 50 m/s points must be left out, then speeds 0.01 ... 1 m/s and twice that
    (95th percentiles 0.9505 and 1.901), 7 and 12 of 100 points below 1 kPa in-plane mean
    stress; the load 20 q_s to s/B 0.1 (outside every window but the peak's), 12 to 0.4 with one
    13, 8 to 1.0 with one 6, 9 beyond with one 11."""
    s_over_b = 0.025 + 0.05 * np.arange(25)  # never on a window's edge
    q = np.where(s_over_b < 0.1, 20.0, np.where(s_over_b < 0.4, 12.0, np.where(s_over_b < 1.0, 8.0, 9.0)))
    q[5], q[12], q[22] = 13.0, 6.0, 11.0  # s/B = 0.275, 0.625, 1.125
    settlement = 0.2 * s_over_b
    time = settlement / 0.5
    synthetic.write_history(work, ["step", "time", "settlement", "q"],
                            np.column_stack([np.arange(25), time, settlement, 1e5 * q]))
    rng = np.random.default_rng(3)
    directions = rng.normal(size=(100, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    speeds = 0.01 * np.arange(1, 101)

    def output(k, scale, free):
        stress = np.zeros((100, 6))
        stress[:, :2] = -1e5  # a 2D packing: szz = 0
        chosen = rng.permutation(100)
        stress[chosen[:free], :2] = -900.0  # below 1 kPa
        stress[chosen[free:free + 10], :2] = -1400.0  # above 1 kPa in plane, below as tr/3
        return (k, time[k], {"positions": rng.random((100, 3)),
                             "velocity": rng.permutation(speeds)[:, None] * scale * directions,
                             "stress": stress})

    synthetic.write_fields(work, [output(1, 50.0, 40), output(10, 1.0, 7), output(20, 2.0, 12)])
    case = os.path.join(work, "case.json")
    open(case, "w").write('{"dimension": 2, "rigid_bodies": [{"type": "footing", "width": [0.2]}], '
                          '"boundary_conditions": [{"type": "traction", "traction": [0, -1e5]}]}')
    result = run_tool("footing_noise.py", work, "--case", case, dpi=0)
    expect(result.returncode == 0, "footing_noise failed: " + result.stderr)
    row = [line.split() for line in result.stdout.splitlines() if line.rstrip().endswith(work)]
    expect(len(row) == 1, f"one row per run: {result.stdout!r}")
    values = [float(v) for v in row[0][:10]]
    expected = [1.225, 0.9505, 1.901, 2.0, 4.0, 12.0, 20.0, (5 * 12 + 13) / 6, (11 * 8 + 6) / 12,
                (4 * 9 + 11) / 5]
    for name, got, want in zip(["s/B", "p95 lo", "p95 hi", "fastest", "/ v_f", "free %", "peak",
                                "0.1-0.4", "0.4-1.0", "1.0-1.5"], values, expected):
        expect(abs(got - want) <= 0.0051, f"{name}: {got}, expected {want} (printed to 0.01)")
    # --from past every output or not a number, --free-below not positive, a case without a
    # surcharge, a run without fields: exit 2.
    expect_bad_input(run_tool("footing_noise.py", work, "--case", case, "--from", 2, dpi=0),
                     "no field output")
    expect_bad_input(run_tool("footing_noise.py", work, "--case", case, "--from", "nan", dpi=0),
                     "--from")
    expect_bad_input(run_tool("footing_noise.py", work, "--case", case, "--free-below", 0, dpi=0),
                     "--free-below")
    bare = os.path.join(work, "bare.json")
    open(bare, "w").write('{"rigid_bodies": [{"type": "footing", "width": [0.2]}]}')
    expect_bad_input(run_tool("footing_noise.py", work, "--case", bare, dpi=0), "traction")
    os.remove(os.path.join(work, "results.h5"))
    expect_bad_input(run_tool("footing_noise.py", work, "--case", case, dpi=0), "results.h5")


# ---- fields -------------------------------------------------------------------------------
def lattice(dimension, n=(24, 12, 6), h=0.1):
    axes = [(np.arange(k) + 0.5) * h for k in n[:dimension]]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, dimension)
    positions = np.zeros((len(grid), 3))
    positions[:, :dimension] = grid
    return positions, np.full(len(grid), h ** dimension)


def field_step(positions, volume, amplitude):
    """A shear band along x = y (eps_q peak = amplitude) and a displacement bowl."""
    x, y = positions[:, 0], positions[:, 1]
    eq = amplitude * np.exp(-(((x - y) / 0.15) ** 2))
    u = np.zeros_like(positions)
    u[:, 1] = -0.05 * amplitude * np.exp(-((x / 0.8) ** 2))
    return {"positions": positions + u, "displacement": u, "velocity": 0 * u,
            "stress": np.zeros((len(x), 6)), "strain": np.zeros((len(x), 6)),
            "deviatoric_strain": eq, "volume": volume, "material": np.zeros(len(x), dtype=np.int32)}


def fields_2d(work):
    positions, volume = lattice(2)
    synthetic.write_fields(work, [(0, 0.0, field_step(positions, volume, 0.0)),
                                  (100, 0.5, field_step(positions, volume, 0.2)),
                                  (200, 1.0, field_step(positions, volume, 0.4))])
    result = run_tool("plot_fields.py", work, "--step", 100)
    expect(result.returncode == 0, "plot_fields failed")
    expect("step 100" in result.stdout, "--step 100 chosen")
    eq_max = numbers_after(result.stdout, "eps_q max")[0]
    expected = field_step(positions, volume, 0.2)["deviatoric_strain"].max()
    expect(abs(eq_max - expected) < 1e-9, f"eps_q max {eq_max} vs {expected}")
    check_picture(os.path.join(work, "fields.png"))


def fields_3d(work):
    positions, volume = lattice(3)
    synthetic.write_fields(work, [(50, 0.2, field_step(positions, volume, 0.3))])
    result = run_tool("plot_fields.py", work, "--slice", "z=0.25")
    expect(result.returncode == 0, "plot_fields 3D failed")
    expect(re.search(r"\b288 points", result.stdout) is not None, "a slice holds one layer (24 x 12)")
    check_picture(os.path.join(work, "fields.png"))


def fields_bad(work):
    positions, volume = lattice(2)
    data = field_step(positions, volume, 0.1)
    del data["deviatoric_strain"]
    synthetic.write_fields(work, [(10, 0.1, data)])
    expect_bad_input(run_tool("plot_fields.py", work), "deviatoric_strain", "results.h5")
    expect_bad_input(run_tool("plot_fields.py", work, "--step", 11), "no output step 11")


# ---- a real solver run ------------------------------------------------------------------
def real_footing(work, mpm_lig):
    """footing_tiny.json through mpm_lig, then plot_footing and plot_fields on its output:
    the readers agree with the writers, and the numbers with summary.json / results.h5."""
    import h5py
    import json
    out = os.path.join(work, "run")
    run = subprocess.run([mpm_lig, os.path.join(HERE, "footing_tiny.json"), "--output", out],
                         capture_output=True, text=True)
    expect(run.returncode == 0, f"mpm_lig failed: {run.stderr}")
    summary = json.load(open(os.path.join(out, "summary.json")))
    result = run_tool("plot_footing.py", out, "--case", os.path.join(HERE, "footing_tiny.json"),
                      "--prandtl")
    expect(result.returncode == 0, "plot_footing failed")
    expect(abs(numbers_after(result.stdout, "B =")[0] - 0.4) < 1e-12, "B from the case")
    peak = numbers_after(result.stdout, "peak q =")[0]
    # history every 5 steps: its peak is at most the exact one, and close to it
    expect(0.97 * summary["peak_q"] <= peak <= summary["peak_q"] * (1 + 1e-9),
           f"history peak {peak} vs summary peak_q {summary['peak_q']}")
    check_picture(os.path.join(out, "footing.png"), min_colours=8)
    result = run_tool("plot_fields.py", out)
    expect(result.returncode == 0, "plot_fields failed")
    expect(f"step {summary['mpm_steps']}," in result.stdout, "default is the last step")
    with h5py.File(os.path.join(out, "results.h5"), "r") as f:
        eq = f["step_%06d/deviatoric_strain" % summary["mpm_steps"]][()]
    expect(abs(numbers_after(result.stdout, "eps_q max")[0] / eq.max() - 1) < 1e-3, "eps_q max")
    check_picture(os.path.join(out, "fields.png"))


CASES = {f.__name__: f for f in (real_footing, shear_element, shear_mpm, shear_points, shear_bad, force_chains, force_chains_bad,
                                 footing, footing_bad, footing_intrusion, footing_noise, fields_2d, fields_3d, fields_bad)}

if __name__ == "__main__":
    if len(sys.argv) not in (3, 4) or sys.argv[1] not in CASES:
        raise SystemExit(f"usage: check_plot_tools.py {{{'|'.join(CASES)}}} WORK_DIR [MPM_LIG]")
    work = os.path.join(sys.argv[2], sys.argv[1])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    CASES[sys.argv[1]](work, *sys.argv[3:])
    print("passed")
