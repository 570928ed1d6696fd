#!/usr/bin/python3
"""Reads and edits the DEM point bundles of a checkpoint step folder (format 5: every rank
group's points in m<id>/rank_<r>.bundle, indexed in mpm.h5 by m<id>_bundle_index: per point
and member rank, offset, length and the SHA-256 as eight 32-bit words; docs/hpc.md §3).

usage: bundle_checkpoint.py check STEP_DIR BUNDLES
         the step folder holds mpm.h5, case.json, build, MANIFEST.sha256 and exactly BUNDLES
         bundles; every member's bytes match the index's SHA-256, the members tile each bundle,
         and the manifest's checksums match every file
       bundle_checkpoint.py corrupt STEP_DIR POINT
         flip one byte in the middle of POINT's engine restart (index and manifest untouched);
         prints the bundle's name
       bundle_checkpoint.py replace STEP_DIR POINT FILE
         POINT's engine restart becomes the bytes of FILE, the index made to match (its
         bundle rewritten, later members moved; the manifest is left to the caller)
       bundle_checkpoint.py to_format4 STEP_DIR
         rewrite as a checkpoint of format 4 (point_<i>.restart and .placement files, no
         bundles, no index; the manifest made to match)"""
import hashlib
import os
import re
import sys

import h5py
import numpy as np

WIDTH = 11  # doubles per member
MEMBERS = 2  # engine restart, grain placement


def index_names(f):
    return sorted(n for n in f if re.fullmatch(r"m\d+_bundle_index", n))


def members(row):
    out = []
    for m in range(MEMBERS):
        v = row[m * WIDTH:(m + 1) * WIDTH]
        digest = "".join("%08x" % int(w) for w in v[3:])
        out.append((int(v[0]), int(v[1]), int(v[2]), digest))
    return out


def pack(rank, offset, length, digest):
    return [rank, offset, length] + [int(digest[8 * w:8 * w + 8], 16) for w in range(8)]


def load(step):
    with h5py.File(os.path.join(step, "mpm.h5"), "r") as f:
        names = index_names(f)
        if len(names) != 1:
            sys.exit("%s: expected one m<id>_bundle_index, found %s" % (step, names))
        index = f[names[0]][()].reshape(-1, MEMBERS * WIDTH)
    return names[0], os.path.join(step, names[0].split("_")[0]), index


def write_manifest(step):
    lines = []
    for root, _, files in os.walk(step):
        for name in files:
            path = os.path.join(root, name)
            rel = os.path.relpath(path, step)
            if rel != "MANIFEST.sha256":
                lines.append("%s  %s\n" % (hashlib.sha256(open(path, "rb").read()).hexdigest(), rel))
    open(os.path.join(step, "MANIFEST.sha256"), "w").write("".join(sorted(lines, key=lambda l: l[66:])))


def check(step, bundles):
    name, folder, index = load(step)
    found = sorted(os.listdir(folder))
    expected = sorted("rank_%d.bundle" % r for r in {m[0] for row in index for m in members(row)})
    problems = []
    if found != expected or len(found) != bundles:
        problems.append("%s holds %s, expected %d bundles %s" % (folder, found, bundles, expected))
    top = sorted(os.listdir(step))
    if top != sorted(["MANIFEST.sha256", "build", "case.json", "mpm.h5", os.path.basename(folder)]):
        problems.append("%s holds %s" % (step, top))
    ends = {}
    for p, row in enumerate(index):
        for m, (rank, offset, length, digest) in enumerate(members(row)):
            data = open(os.path.join(folder, "rank_%d.bundle" % rank), "rb").read()[offset:offset + length]
            if len(data) != length or hashlib.sha256(data).hexdigest() != digest:
                problems.append("point %d member %d: bytes do not match the index" % (p, m))
            ends.setdefault(rank, []).append((offset, length))
    for rank, ranges in ends.items():
        ranges.sort()
        end = 0
        for offset, length in ranges:
            if offset != end:
                problems.append("rank_%d.bundle: gap or overlap at %d" % (rank, end))
            end = offset + length
        if os.path.getsize(os.path.join(folder, "rank_%d.bundle" % rank)) != end:
            problems.append("rank_%d.bundle: size is not its members' end %d" % (rank, end))
    for line in open(os.path.join(step, "MANIFEST.sha256")):
        digest, rel = line.rstrip("\n").split("  ", 1)
        if hashlib.sha256(open(os.path.join(step, rel), "rb").read()).hexdigest() != digest:
            problems.append("MANIFEST.sha256: %s does not match" % rel)
    if problems:
        sys.exit("\n".join(problems))
    print("%s: %d points in %d bundles, every member and the manifest match" % (step, len(index), len(found)))


def corrupt(step, point):
    _, folder, index = load(step)
    rank, offset, length, _ = members(index[point])[0]
    bundle = os.path.join(folder, "rank_%d.bundle" % rank)
    with open(bundle, "r+b") as out:
        out.seek(offset + length // 2)
        byte = out.read(1)
        out.seek(offset + length // 2)
        out.write(bytes([byte[0] ^ 0xFF]))
    print("rank_%d.bundle" % rank)


def replace(step, point, file):
    name, folder, index = load(step)
    new = open(file, "rb").read()
    rank = members(index[point])[0][0]
    bundle = os.path.join(folder, "rank_%d.bundle" % rank)
    data = open(bundle, "rb").read()
    pieces = []
    for p, row in enumerate(index):
        for m, (r, offset, length, _) in enumerate(members(row)):
            if r == rank:
                pieces.append((offset, p, m, new if (p, m) == (point, 0) else data[offset:offset + length]))
    out = b""
    for _, p, m, piece in sorted(pieces):
        index[p, m * WIDTH:(m + 1) * WIDTH] = pack(rank, len(out), len(piece), hashlib.sha256(piece).hexdigest())
        out += piece
    open(bundle, "wb").write(out)
    with h5py.File(os.path.join(step, "mpm.h5"), "r+") as f:
        f[name][...] = index.reshape(-1)


def to_format4(step):
    name, folder, index = load(step)
    for p, row in enumerate(index):
        for m, (rank, offset, length, _) in enumerate(members(row)):
            data = open(os.path.join(folder, "rank_%d.bundle" % rank), "rb").read()[offset:offset + length]
            suffix = ".restart" if m == 0 else ".restart.placement"
            open(os.path.join(folder, "point_%d%s" % (p, suffix)), "wb").write(data)
    for bundle in [b for b in os.listdir(folder) if b.endswith(".bundle")]:
        os.remove(os.path.join(folder, bundle))
    with h5py.File(os.path.join(step, "mpm.h5"), "r+") as f:
        del f[name]
        del f.attrs[name.split("_")[0] + "_bundle_members_per_point"]
        f.attrs["format"] = np.float64(4)
    write_manifest(step)


def main():
    a = sys.argv[1:]
    if len(a) == 3 and a[0] == "check":
        check(a[1], int(a[2]))
    elif len(a) == 3 and a[0] == "corrupt":
        corrupt(a[1], int(a[2]))
    elif len(a) == 4 and a[0] == "replace":
        replace(a[1], int(a[2]), a[3])
    elif len(a) == 2 and a[0] == "to_format4":
        to_format4(a[1])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
