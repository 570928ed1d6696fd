"""The direct DEM's boundary value problem: the periodic cell opened into the half block (side
planes, frozen base, footing grains, regrown cut grains), the surcharge that follows the heave,
the settling under it and the footing's push with its history rows, fields and snapshots."""
import math
import os
import time

import numpy as np

from mpm_lig_post.coarse_grain import mesh_points, point_fields
from mpm_lig_post.direct_dem.preparation import AT_REST

SETTLE_UPDATES = 400   # surcharge updates at most to settle the opened block
BALANCE = 0.01         # ... at rest once the base carries the applied load within 1 %
HISTORY = ("step", "time", "settlement", "s_over_B", "footing_force", "q", "q_over_qs",
           "base_force", "surcharge_force", "wall_force", "kinetic_energy", "top_grains")



def loading_steps(pb, speed_factor, settlement):
    """DEM steps of the loading to s/B = `settlement`."""
    return int(math.ceil(settlement * pb["B"] / (pb["speed"] * speed_factor * pb["dt"])))

class Block:
    """The block and loading stages of Run (run.py), which owns the engine session and state."""

    def open_block(self):
        """Periodic cell -> half model: walls, base, footing, surcharge; cut grains regrown."""
        pb = self.pb
        lx, ly = self.prepared["cell"]
        self.lx, self.ly = lx, ly
        rmax = pb["rmax"]
        # The servo scaled the cell about its centre: move it back to the origin first.
        self.send(f"change_box all x final 0.0 {lx!r} y final 0.0 {ly!r} remap units box\n"
                  "change_box all boundary f m p")
        ids, xy, r = self.grains_now()
        base = ids[xy[:, 1] < 2 * 2 * rmax]
        foot = ids[(xy[:, 0] < 0.5 * pb["B"]) & (xy[:, 1] > ly - 2 * rmax)]
        self.send("group base id " + " ".join(map(str, base)) + "\n"
                  "group footing id " + " ".join(map(str, foot)) + "\n"
                  "group frozen union base footing\ngroup soil subtract all frozen\n"
                  "velocity frozen set 0 0 0")
        self.base_ids, self.footing_ids = base.tolist(), foot.tolist()
        soil = np.isin(ids, np.concatenate([base, foot]), invert=True)
        cut = soil & ((xy[:, 0] - r < 0) | (xy[:, 0] + r > lx))
        cut_radii = {int(i): float(rr) for i, rr in zip(ids[cut], r[cut])}
        # A cut grain shrinks to fit between its centre and the plane, but to no less than half
        # its radius: then its centre moves in to that half radius (no new overlap: the move
        # is at most what the radius lost).
        gap, moves = {}, []
        for i, x, rr in zip(ids[cut], xy[cut, 0], r[cut]):
            room = min(x, lx - x)
            gap[int(i)] = max(0.98 * room, 0.49 * rr)
            if 0.98 * room < 0.49 * rr:
                target = 0.5 * rr if x < 0.5 * lx else lx - 0.5 * rr
                moves.append(f"set atom {int(i)} x {target!r}")
        rho = float(pb["rve"]["density"])
        self.send("\n".join([f"set atom {i} diameter {2 * g!r} density {rho!r}"
                             for i, g in gap.items()] + moves))
        self.dynamics()
        self.cut_radii = cut_radii
        self.regrow(gap)
        self.progress(f"opened the block: {len(base)} base, {len(foot)} footing, "
                      f"{len(cut_radii)} cut grains regrown", force=True)

    def add_footing_column(self, height):
        """--footing-column H: the footing block extended up by a column H footing widths above
        the soil's surface over 0 <= x < B/2, of touching discs on a square grid that fills the
        half width (radius at most r_max), frozen and moved with the footing. The one-grain block
        alone sinks below the heaving surface and the soil flows onto it; a footing on its
        column (and the multiscale footing, which keeps its whole column clear) holds that soil
        beside it. Sites where a disc would overlap a grain stay empty. The discs' ids."""
        pb = self.pb
        half = 0.5 * pb["B"]
        per_row = int(math.ceil(half / (2.0 * pb["rmax"]) - 1e-9))
        r = half / (2.0 * per_row)
        ids, xy, radii = self.grains_now()
        foot = np.isin(ids, self.footing_ids)
        bottom = float(np.max(xy[foot, 1] + radii[foot])) + r
        top = self.ly + height * pb["B"]
        rows = max(1, int(math.floor((top - bottom) / (2.0 * r))) + 1)
        sites = [(r * (2 * i + 1), bottom + 2.0 * r * j)
                 for j in range(rows) for i in range(per_row)]
        free = [(x, y) for x, y in sites
                if np.all(np.hypot(xy[:, 0] - x, xy[:, 1] - y) >= radii + r)]
        rho = float(pb["rve"]["density"])
        first = int(ids.max()) + 1
        lines = [f"change_box all y final 0.0 {bottom + 2.0 * r * rows!r} units box"]
        for k, (x, y) in enumerate(free):
            lines += [f"create_atoms 1 single {x!r} {y!r} 0.0 units box",
                      f"set atom {first + k} diameter {2 * r!r} density {rho!r}"]
        column = list(range(first, first + len(free)))
        lines += ["group footing id " + " ".join(map(str, column)),
                  "group frozen union base footing", "velocity frozen set 0 0 0"]
        self.send("\n".join(lines))
        self.footing_ids = self.footing_ids + column
        self.grains += len(column)
        got = self.grains_now()[0]
        if len(got) != self.grains or not np.all(np.isin(column, got)):
            raise RuntimeError(f"the footing's column: {len(column)} discs asked, the engine "
                               f"holds {len(got)} grains where {self.grains} were expected")
        self.progress(f"the footing's column: {len(column)} discs of radius {r:.4g} m, "
                      f"{rows} rows to {height:g} B above the surface "
                      f"({len(sites) - len(free)} sites left empty)", force=True)
        return column

    def dynamics(self):
        """Integration of the soil, walls, exclusions, force sums (also after --resume)."""
        lx = self.lx
        self.send("unfix integrate\nunfix plane\nfix integrate soil nve/sphere\n"
                  "fix plane soil enforce2d\n"
                  f"fix wall_l soil wall/gran model hertz tangential history primitive type 2 "
                  f"xplane 0.0\nfix wall_r soil wall/gran model hertz tangential history primitive "
                  f"type 2 xplane {lx!r}\n"
                  "neigh_modify exclude group frozen frozen\n"
                  "compute f_foot footing reduce sum fy\ncompute f_base base reduce sum fy\n"
                  "compute f_soil_x soil reduce sum fx\ncompute ke_soil soil ke\n"
                  "thermo_style custom step atoms c_stress[1] c_stress[2] c_ke c_ov c_f_foot "
                  "c_f_base c_ke_soil c_f_soil_x\nthermo_modify norm no lost ignore\nthermo 0")

    def regrow(self, gap):
        """Cut grains from their fitted radius back to their own in 50 increments of 100 steps
        (an overlap growth of 1 % of the radius per increment), the surcharge re-found every 5."""
        rho = float(self.pb["rve"]["density"])
        for k in range(51):
            f = k / 50.0
            cmds = [f"set atom {i} diameter {2 * ((1 - f) * gap[i] + f * r)!r} density {rho!r}"
                    for i, r in self.cut_radii.items()]
            if cmds:
                self.send("\n".join(cmds))
            if k % 5 == 0:
                self.surcharge_update()
            self.run(100)

    def grains_now(self, group="all", velocities=False):
        """(ids, centres n x 2, radii[, velocities n x 3: vx, vy, omega_z]) from a dump of the
        engine now."""
        path = os.path.join(self.out, "grains.tmp")
        extra = " vx vy omegaz" if velocities else ""
        self.send(f'write_dump {group} custom "{path}" id x y radius{extra} modify sort id',
                  self.grains * 10)
        data = np.loadtxt(path, skiprows=9, ndmin=2)
        os.remove(path)
        got = (data[:, 0].astype(int), data[:, 1:3], data[:, 3])
        return got + (data[:, 4:7],) if velocities else got

    def grains_moving(self):
        """(ids, centres n x 2, radii, {"mass": n, "velocity": n x 2}) sorted by id."""
        path = os.path.join(self.out, "grains.tmp")
        self.send(f'write_dump all custom "{path}" id x y radius mass vx vy modify sort id',
                  self.grains * 10)
        data = np.loadtxt(path, skiprows=9, ndmin=2)
        os.remove(path)
        return (data[:, 0].astype(int), data[:, 1:3], data[:, 3],
                {"mass": data[:, 4], "velocity": data[:, 5:7]})

    def contacts_now(self):
        """(first ids, second ids, forces n x 2 on the first grain from the second) of the
        grain-grain contacts now (the engine's pair/gran/local list of the last step)."""
        path = os.path.join(self.out, "contacts.tmp")
        self.send(f'write_dump all local "{path}" c_pl[1] c_pl[2] c_pl[4] c_pl[5]',
                  self.grains * 10)
        loc = np.loadtxt(path, skiprows=9, ndmin=2)
        os.remove(path)
        if loc.size == 0:
            return np.zeros(0, int), np.zeros(0, int), np.zeros((0, 2))
        return loc[:, 0].astype(int), loc[:, 1].astype(int), loc[:, 2:4]

    def surcharge_update(self):
        """Forces q_s t w on the top soil grain of each w-wide column over [B/2, lx]."""
        pb = self.pb
        ids, xy, r = self.grains_now("soil")
        x0, x1 = 0.5 * pb["B"], self.lx
        columns = max(1, int(round((x1 - x0) / (0.5 * pb["d"]))))
        w = (x1 - x0) / columns
        top = {}
        reach = xy[:, 1] + r
        for c in range(columns):
            a, b = x0 + c * w, x0 + (c + 1) * w
            inside = np.flatnonzero((xy[:, 0] + r > a) & (xy[:, 0] - r < b))
            if len(inside):
                k = inside[np.argmax(reach[inside])]
                top[int(ids[k])] = top.get(int(ids[k]), 0) + 1
        force = pb["qs"] * pb["thickness"] * w
        cmds = []
        for m in self.top_fixes:
            cmds += [f"unfix sur{m}", f"group top{m} delete"]
        self.top_fixes = sorted(set(top.values()))
        for m in self.top_fixes:
            members = [i for i, n in top.items() if n == m]
            cmds += [f"group top{m} id " + " ".join(map(str, members)),
                     f"fix sur{m} top{m} addforce 0.0 {-m * force!r} 0.0"]
        self.send("\n".join(cmds))
        self.top_count = len(top)
        self.top_force = force * columns
        self.top_y = float(np.mean([xy[ids == i, 1][0] for i in top])) if top else float("nan")

    # ------------------------------------------------------------------- loading
    def settle(self):
        """Under the surcharge, the footing held, until the soil is at rest: the kinetic energy
        below AT_REST of the elastic, or (the kinetic floor of a large block) the base carrying
        the surcharge and the footing's load within BALANCE; three updates in a row, at most
        SETTLE_UPDATES (the 3709-disc block at e0 = 0.187 ran all 200 under the kinetic
        criterion alone and started loading 5 % out of balance). Its state (self.settle_state)
        is kept in the checkpoints."""
        if self.settle_state is None:
            self.settle_state = {"updates": 0, "settled": 0, "balance": None}
        st = self.settle_state
        st.setdefault("last_kinetic", 0.0)
        st.setdefault("quenches", 0)
        while st["updates"] < SETTLE_UPDATES:
            self.surcharge_update()
            self.run(self.args.surcharge_every)
            o = self.observe()
            kr = self.kinetic_ratio(o, self.lx * self.ly, self.pb["p0"])
            row = self.history_row(0.0)
            self.damp_kinetic(st, row["kinetic_energy"])
            st["balance"] = row["base_force"] / (row["surcharge_force"] + row["footing_force"]) - 1.0
            st["settled"] = st["settled"] + 1 if kr < AT_REST or abs(st["balance"]) < BALANCE else 0
            st["updates"] += 1
            self.progress(f"settling under q_s: update {st['updates']}, base / applied - 1 = "
                          f"{st['balance']:+.4f}, kinetic/elastic {kr:.2g}, "
                          f"{st['quenches']} quenches")
            if st["settled"] >= 3 and st["updates"] > 5:
                break
            self.safe_point("settle")
        self.surcharge_update()
        self.send("run 0")
        row = self.history_row(0.0)
        self.settled = {"steps": self.steps, "base_force_over_qs_L": row["base_force"] /
                        (self.pb["qs"] * self.pb["thickness"] * self.lx),
                        "balance": st["balance"], "updates": st["updates"],
                        "q_over_qs": row["q_over_qs"], "top_grains": self.top_count,
                        "damping": self.args.settle_damping, "quenches": st["quenches"]}
        self.progress(f"settled under q_s after {st['updates']} updates: base / applied - 1 = "
                      f"{st['balance']:+.4f}, footing q/q_s = {row['q_over_qs']:.3f}, "
                      f"{st['quenches']} quenches", force=True)

    def damp_kinetic(self, st, kinetic):
        """--settle-damping kinetic: the soil's velocities set to zero whenever its kinetic
        energy (`kinetic`, this chunk's) has passed a maximum (dynamic relaxation; their spins
        are left to the contacts: this LIGGGHTS has no per-grain `set ... omega`). A block
        opened from its periodic cell rings in its lowest vertical mode, which the contacts'
        damping hardly touches (the B/d = 80 block still swung +-20 % of its load after 400
        updates): each quench takes out the energy of one swing, and what is left is the
        block's static state."""
        if self.args.settle_damping != "kinetic":
            return
        if kinetic < st["last_kinetic"]:
            self.send("velocity soil set 0.0 0.0 0.0")
            st["quenches"] += 1
            kinetic = 0.0
        st["last_kinetic"] = kinetic

    def history_row(self, s):
        pb = self.pb
        ff, fb, ke, fx = self.session.values("H", ["c_f_foot", "c_f_base", "c_ke_soil",
                                                   "c_f_soil_x"])
        q = ff / (pb["thickness"] * 0.5 * pb["B"])
        return {"step": self.steps, "time": self.load_steps * pb["dt"] * 1.0,
                "settlement": s, "s_over_B": s / pb["B"], "footing_force": ff, "q": q,
                "q_over_qs": q / pb["qs"], "base_force": -fb, "surcharge_force": self.top_force,
                "wall_force": fx, "kinetic_energy": ke, "top_grains": self.top_count}

    def push(self):
        """The footing moved down at its constant speed (after a reload too)."""
        v = self.pb["speed"] * self.args.speed_factor
        self.send(f"fix push footing move linear 0.0 {-v!r} 0.0")

    def load(self):
        """The footing pushed to --settlement; a history row every --surcharge-every steps.
        True when it got there."""
        pb, a = self.pb, self.args
        ds = pb["speed"] * a.speed_factor * pb["dt"]
        total = loading_steps(pb, a.speed_factor, a.settlement)
        hist = os.path.join(self.out, "history.csv")
        if self.stage != "load":
            self.stage = "load"
            self.push()
            self.surcharge_update()
            self.send("run 0")  # the force sums current before the first history row
            with open(hist, "w") as f:
                f.write(",".join(HISTORY) + "\n")
            self.load_steps = self.next_field = self.next_snap = self.next_probe = 0
            self.write_row(hist, self.history_row(0.0))
            if self.probes:
                self.probes.header(os.path.join(self.out, "probes.csv"))
        outs = [k * a.fields_every for k in range(int(a.settlement / a.fields_every + 1e-9) + 1)]
        snaps = sorted(a.snapshots)
        self.probe(self.load_steps * ds / pb["B"])
        started, first_step = time.time(), self.load_steps  # the ETA from this sitting's rate
        while self.load_steps < total:
            n = min(a.surcharge_every, total - self.load_steps)
            self.surcharge_update()
            self.run(n)
            self.load_steps += n
            s = self.load_steps * ds
            row = self.history_row(s)
            self.write_row(hist, row)
            sB = s / pb["B"]
            while self.next_field < len(outs) and sB >= outs[self.next_field] - 1e-9:
                self.fields(s)
                self.next_field += 1
            while self.next_snap < len(snaps) and sB >= snaps[self.next_snap] - 1e-9:
                self.snapshot()
                self.next_snap += 1
            self.probe(sB)
            done = self.load_steps - first_step
            left = (total - self.load_steps) / max(done, 1) * (time.time() - started)
            self.progress(f"s/B = {sB:.3f}, q/q_s = {row['q_over_qs']:.2f}, "
                          f"{self.load_steps}/{total} steps, ETA {left / 60:.1f} min")
            self.safe_point("load")
        return True

    def probe(self, sB):
        """The probes' rows when one is due (every --probes-every s/B, from s = 0)."""
        if not self.probes:
            return
        every = self.args.probes_every
        if sB >= self.next_probe * every - 1e-9:
            self.send("run 0")  # the contact list of this state
            self.probes.record(sB * self.pb["B"])
            while self.next_probe * every <= sB + 1e-9:
                self.next_probe += 1

    def write_row(self, path, row):
        with open(path, "a") as f:
            f.write(",".join("%.10g" % row[k] for k in HISTORY) + "\n")

    def fields(self, s):
        pb = self.pb
        ids, xy, _ = self.grains_now()
        keep = np.isin(ids, self.ref_ids)
        cur = xy[keep][np.argsort(ids[keep])]
        mesh = pb["mesh"]
        sx, sy = self.lx / pb["box"][0], self.ly / pb["box"][1]
        pts, h = mesh_points(mesh["origin"], mesh["size"], mesh["cells"], [0, 0], pb["box"])
        pts = pts * [sx, sy]
        h = h * [sx, sy]
        pos, data = point_fields(self.ref_xy, cur, pts, 0.5 * float(np.mean(h)), float(np.prod(h)))
        step = int(round(s / pb["B"] * 1000))
        self.field_out.add(step, self.load_steps * pb["dt"], pos, data)

    def snapshot(self):
        """Grains and contacts as legacy VTK (the layout of src/rve/snapshot.cpp)."""
        folder = os.path.join(self.out, "snapshots")
        os.makedirs(folder, exist_ok=True)
        prefix = os.path.join(folder, f"grains_{self.load_steps:09d}")
        self.send("run 0")  # forces and the contact list of one state
        ids, xy, r = self.grains_now()
        id1, id2, force = self.contacts_now()
        where = {int(i): k for k, i in enumerate(ids)}
        first = xy[[where[int(i)] for i in id1]].reshape(-1, 2)
        second = xy[[where[int(i)] for i in id2]].reshape(-1, 2)
        np.savez(prefix + "_contacts.npz", id1=id1, id2=id2, fx=force[:, 0], fy=force[:, 1],
                 footing_force=self.history_row(0.0)["footing_force"])
        loc = np.column_stack([first, second, force])
        with open(prefix + "_grains.vtk", "w") as f:
            f.write("# vtk DataFile Version 3.0\ngrains\nASCII\nDATASET POLYDATA\n"
                    f"POINTS {len(xy)} double\n")
            np.savetxt(f, np.column_stack([xy, np.zeros(len(xy))]), fmt="%.9g")
            f.write(f"POINT_DATA {len(xy)}\nSCALARS radius double 1\nLOOKUP_TABLE default\n")
            np.savetxt(f, r, fmt="%.9g")
        with open(prefix + "_contacts.vtk", "w") as f:
            n = len(loc)
            f.write("# vtk DataFile Version 3.0\ncontacts\nASCII\nDATASET POLYDATA\n"
                    f"POINTS {2 * n} double\n")
            pts = np.zeros((2 * n, 3))
            pts[0::2, :2], pts[1::2, :2] = loc[:, 0:2], loc[:, 2:4]
            np.savetxt(f, pts, fmt="%.9g")
            f.write(f"LINES {n} {3 * n}\n")
            np.savetxt(f, np.column_stack([np.full(n, 2), 2 * np.arange(n), 2 * np.arange(n) + 1]),
                       fmt="%d")
            f.write(f"CELL_DATA {n}\nSCALARS force double 1\nLOOKUP_TABLE default\n")
            np.savetxt(f, np.hypot(loc[:, 4], loc[:, 5]), fmt="%.9g")

