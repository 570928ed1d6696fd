"""The direct DEM's packing: grains placed in a periodic cell and consolidated by the RVE
procedure (src/rve/consolidation.cpp) as phases a checkpoint can stop, optionally repeated
into a larger cell and settled again (--tiles)."""
import math
import os

import numpy as np

from mpm_lig_post.direct_dem.case import contact_friction
from mpm_lig_post.direct_dem.packing import draw_radii, fabric, place, tile
from mpm_lig_post.liggghts import render
from mpm_lig_post.love_weber import window_stress

CHUNK = 100            # servo steps per update (src/rve/consolidation.cpp kChunk)
AT_REST = 2e-3         # kinetic / elastic energy of a relaxed packing (kAtRest)
FRICTION_STEP = 0.7    # friction factor per compaction stage (kFrictionStep)
NEAR_TARGET = 0.05     # a compaction stage stops at its void ratio this close to p (kNearTarget)
STILL_CHUNKS = 20      # ... or on target with the void ratio within STILL_VOID_RATIO this long
STILL_VOID_RATIO = 2e-5


class Preparation:
    """The preparation stage of Run (run.py), which owns the engine session and the state."""

    def prepare(self):
        """Grains placed at random in the periodic cell (of 1/T of the block with --tiles T),
        the engine set up; the consolidation follows (consolidate)."""
        pb, rve = self.pb, self.pb["rve"]
        prep, tiles = pb["prep"], self.args.tiles
        rng = np.random.default_rng(self.args.seed)
        box = pb["box"] / tiles
        # as many grains as the drawn sample needs to fill the cell at the target void ratio
        # (counted on the cell itself: the same seed gives the same cell for every --tiles)
        mean_r2 = (pb["rmin"] ** 2 + pb["rmin"] * pb["rmax"] + pb["rmax"] ** 2) / 3.0
        expected = float(np.prod(box)) / ((1.0 + pb["e0"]) * math.pi * mean_r2)
        pool = draw_radii(rve["radius"], int(1.2 * expected) + 50, rng)
        area = float(np.prod(box)) / (1.0 + pb["e0"])
        count = int(np.searchsorted(np.cumsum(math.pi * pool ** 2), area)) + 1
        radii = pool[:count]
        self.solid = float(np.sum(math.pi * radii ** 2))
        phi0 = float(prep.get("initial_solid_fraction", 0.6 * 0.8))
        aspect = box[0] / box[1]
        ly = math.sqrt(self.solid / phi0 / aspect)
        lx = aspect * ly
        centres, radii = place(radii, lx, ly, rng)
        self.grains = len(radii)
        self.open()
        self.send(self.periodic_cell(lx, ly, radii.max()))
        lines = []
        for i, (c, r) in enumerate(zip(centres, radii)):
            lines.append(f"create_atoms 1 single {c[0]!r} {c[1]!r} 0.0 units box")
            lines.append(f"set atom {i + 1} diameter {2 * r!r} density {float(rve['density'])!r}")
            if len(lines) >= 2000:
                self.send("\n".join(lines))
                lines = []
        if lines:
            self.send("\n".join(lines))
        friction = math.tan(math.radians(prep["consolidation_friction_deg"])) \
            if "consolidation_friction_deg" in prep else contact_friction(rve)
        self.materials(friction)
        self.observers()
        self.send("run 0")
        self.prep_state = {"phase": "first", "friction": friction, "compacted": None,
                           "void_ratio": None, "budget": int(prep.get("max_steps", 5_000_000))
                           * max(1, int(round(self.grains / 400)))}

    def periodic_cell(self, lx, ly, rmax):
        """The engine's set-up of an orthogonal periodic cell with two atom types (grains and
        the frictionless side planes). The executable lacks the library path's triclinic
        correction (docs/DESIGN.md §3.2, tools/native_twin.py): a prism cell loses its
        periodic images here, an orthogonal block keeps them."""
        setup = render("setup.in", {"dimension": "2", "lx": repr(lx), "ly": repr(ly),
                                    "zlo": repr(-rmax), "zhi": repr(rmax),
                                    "skin": repr(0.4 * 0.5 * self.pb["d"])}, {"two_d"})
        setup = setup.replace("create_box      1 cell", "create_box      2 cell")
        setup = setup.replace("region          cell prism", "region          cell block")
        return setup.replace(f" {rmax!r} 0 0 0 units box", f" {rmax!r} units box")

    def consolidate(self):
        """src/rve/consolidation.cpp consolidate(), as phases that a checkpoint can stop and a
        resume continue (self.prep_state: the phase and the friction in use): the first servo,
        friction lowered and the servo again until the void ratio is reached, the contact
        friction restored and the final servo; with --tiles the cell repeated and settled."""
        pb, prep = self.pb, self.pb["prep"]
        mu = contact_friction(pb["rve"])
        tol = float(prep.get("tolerance", 0.005))
        target = pb["e0"]
        stop = target + 0.25 * self.args.void_ratio_tolerance
        st = self.prep_state
        while st["phase"] != "done":
            phase = st["phase"]
            if phase in ("first", "stage", "final", "tiled"):
                friction = st["friction"]
                o = self.servo(tol, stop if phase == "stage" and friction <= mu else 0.0)
                st["void_ratio"] = self.void_ratio(o)
                st["phase"] = {"first": "lower", "stage": "lower", "final": "tile",
                               "tiled": "done"}[phase]
                if phase == "final":
                    self.prepared = self.preparation(o, st["friction"])
                if st["phase"] == "tile" and self.args.tiles == 1:
                    st["phase"] = "done"
            elif phase == "lower":
                friction = st["friction"]
                if st["void_ratio"] > stop and friction > 0.0:
                    lowered = FRICTION_STEP * friction if friction > 1e-3 else 0.0
                    st["friction"] = mu if friction > mu > lowered else lowered
                    st["phase"] = "stage"
                else:
                    st["compacted"] = st["void_ratio"]
                    st["phase"] = "final" if friction != mu else "tile"
                    if friction == mu:  # compacted at the contact friction: no final servo
                        self.prepared = self.preparation(self.observe(), friction)
                    if st["phase"] == "tile" and self.args.tiles == 1:
                        st["phase"] = "done"
                    st["friction"] = mu
                if friction != st["friction"]:
                    self.materials(st["friction"])
                    self.send("run 0")
            elif phase == "tile":
                self.check_void_ratio(st["void_ratio"])  # before the larger cell costs anything
                self.repeat_cell(self.args.tiles)
                st["phase"] = "tiled"
        e = st["void_ratio"]
        o = self.observe()
        if self.args.tiles > 1:  # what the repeated cell became after settling again
            self.prepared["before_tiling"] = {k: self.prepared[k] for k in
                                              ("void_ratio", "sxx", "syy", "steps", "cell",
                                               "grains", "fabric")}
            self.prepared["fabric"] = self.fabric_now(o)
        self.prepared.update(void_ratio=e, sxx=o["sxx"], syy=o["syy"], steps=self.steps,
                             cell=[o["lx"], o["ly"]], grains=self.grains,
                             love_weber=self.love_weber_now(o))
        self.check_void_ratio(e)
        self.progress(f"prepared: e = {e:.4f} (target {target}), sigma = "
                      f"{-o['sxx'] / 1e3:.1f} / {-o['syy'] / 1e3:.1f} kPa, {self.steps} steps",
                      force=True)

    def check_void_ratio(self, e):
        target = self.pb["e0"]
        if abs(e - target) > self.args.void_ratio_tolerance:
            raise RuntimeError(f"preparation reached void ratio {e:.4f}, "
                               f"preparation.target_void_ratio asks {target} +- "
                               f"{self.args.void_ratio_tolerance} (another --seed may reach it)")

    def preparation(self, o, friction):
        """What the RVE procedure reached (before any tiling): summary.json's preparation."""
        return {"void_ratio": self.void_ratio(o), "compacted_void_ratio":
                self.prep_state["compacted"], "friction_used": friction, "sxx": o["sxx"],
                "syy": o["syy"], "steps": self.steps, "cell": [o["lx"], o["ly"]],
                "grains": self.grains, "tiles": self.args.tiles,
                "fabric": self.fabric_now(o)}

    def fabric_now(self, o):
        """The contact fabric of the periodic cell now (from a dump: the run is not
        disturbed)."""
        _, xy, r = self.grains_now()
        origin = self.session.values("BOX", ["xlo", "ylo"])
        return fabric(xy, r, (o["lx"], o["ly"]), origin)

    def love_weber_now(self, o):
        """The whole periodic cell's stress from its contacts (love_weber.py, what the probes
        use) beside the engine's virial: the two must agree (tests/tools/check_direct_dem.py)."""
        self.send("run 0")  # the contact list of this state
        ids, xy, r = self.grains_now()
        index = {int(i): k for k, i in enumerate(ids)}
        first, second, force = self.contacts_now()
        contacts = ([index[int(i)] for i in first], [index[int(i)] for i in second], force)
        sigma = window_stress(np.ones(len(ids), bool), xy, r, contacts, o["lx"] * o["ly"],
                              self.pb["thickness"], period=(o["lx"], o["ly"]))
        return {"sxx": float(sigma[0, 0]), "syy": float(sigma[1, 1]), "sxy": float(sigma[0, 1]),
                "engine_sxx": o["sxx"], "engine_syy": o["syy"]}

    def repeat_cell(self, tiles):
        """The prepared periodic cell repeated tiles x tiles times in a new engine (a data
        file: contact history starts anew, so the larger cell is settled again)."""
        ids, xy, r, vel = self.grains_now(velocities=True)
        o = self.observe()
        big_xy, big_r, big_v, (lx, ly), n = tile(xy, r, vel, (o["lx"], o["ly"]), tiles)
        origin = self.session.values("BOX", ["xlo", "ylo"])
        self.close()
        path = os.path.join(self.out, "tiles.data")
        rho = float(self.pb["rve"]["density"])
        rmax = float(r.max())
        with open(path, "w") as f:
            f.write(f"direct DEM: {tiles} x {tiles} tiles\n\n{n} atoms\n2 atom types\n"
                    f"{origin[0]!r} {origin[0] + lx!r} xlo xhi\n{origin[1]!r} {origin[1] + ly!r} "
                    f"ylo yhi\n{-rmax!r} {rmax!r} zlo zhi\n\nAtoms\n\n")
            for k in range(n):
                f.write(f"{k + 1} 1 {2 * big_r[k]!r} {rho!r} {big_xy[k, 0]!r} {big_xy[k, 1]!r} "
                        "0.0\n")
            f.write("\nVelocities\n\n")
            for k in range(n):
                f.write(f"{k + 1} {big_v[k, 0]!r} {big_v[k, 1]!r} 0.0 0.0 0.0 {big_v[k, 2]!r}\n")
        self.grains = n
        self.solid *= tiles * tiles
        self.open()
        setup = self.periodic_cell(lx, ly, rmax).splitlines()
        keep = [ln for ln in setup if not ln.startswith(("region", "create_box"))]
        at = next(i for i, ln in enumerate(keep) if ln.startswith("neighbor"))
        keep.insert(at, f'read_data "{path}"')
        self.send("\n".join(keep), work=n * 10)
        self.materials(contact_friction(self.pb["rve"]))
        self.observers()
        self.send("run 0")
        os.remove(path)
        self.progress(f"repeated the cell {tiles} x {tiles}: {n} grains", force=True)

    def void_ratio(self, o):
        return o["lx"] * o["ly"] / self.solid - 1.0

    def servo(self, tol, stop_void_ratio=0.0):
        """src/rve/consolidation.cpp servo_isotropic on the periodic cell; its own state
        (self.servo_state) is kept in the checkpoints, so a resumed servo goes on as it was."""
        pb = self.pb
        p_t = pb["p0"]
        rate = 5e-3 / (pb["d"] * math.sqrt(pb["rve"]["density"] / p_t))
        max_step = float(pb["prep"].get("max_strain_rate", rate)) * CHUNK * pb["dt"]
        if self.servo_state is None:
            self.servo_state = {"history": [], "settled": 0}
        st = self.servo_state
        o = self.observe()
        budget = self.prep_state["budget"]
        while self.steps < budget:
            p = -0.5 * (o["sxx"] + o["syy"])
            strains = []
            for s in (o["sxx"], o["syy"]):
                strain = -max_step
                if p > 0.2 * p_t and o["ov"] > 0:
                    stiffness = 1.5 * p / o["ov"]
                    strain = min(max(-0.5 * (p_t + s) / stiffness, -max_step), max_step)
                strains.append(1.0 + strain)
            self.send(f"fix servo all deform 1 x scale {strains[0]!r} y scale {strains[1]!r} "
                      "remap x")
            self.run(CHUNK)
            self.send("unfix servo")
            o = self.observe()
            p_new = -0.5 * (o["sxx"] + o["syy"])
            e = self.void_ratio(o)
            kr = self.kinetic_ratio(o, o["lx"] * o["ly"], p_new)
            self.progress(f"preparing: e = {e:.4f}, p = {p_new / 1e3:.1f} kPa, kinetic/elastic "
                          f"{kr:.2g}")
            if stop_void_ratio > 0 and e <= stop_void_ratio and abs(p_new - p_t) <= NEAR_TARGET * p_t:
                self.servo_state = None
                return o
            on = abs(p_new - p_t) <= tol * p_t
            # At rest as an RVE (kinetic energy below AT_REST of the elastic), or, as a block of
            # thousands of discs keeps a kinetic floor (rattlers: 0.5 % of its estimated
            # elastic energy for 3666 discs), on target with its void ratio still for
            # STILL_CHUNKS servo chunks.
            st["history"] = (st["history"] + [e])[-STILL_CHUNKS - 1:]
            history = st["history"]
            still = len(history) > STILL_CHUNKS and max(history[-STILL_CHUNKS:]) - \
                min(history[-STILL_CHUNKS:]) < STILL_VOID_RATIO
            st["settled"] = st["settled"] + 1 if on and (kr < AT_REST or still) else 0
            if st["settled"] >= 3:
                self.servo_state = None
                return o
            if self.safe_point("prepare"):
                o = self.observe()
        raise RuntimeError(f"the isotropic servo to {p_t} Pa did not settle within "
                           f"{budget} steps (preparation.max_steps per 400 grains)")
