#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets (tests/fuzz/corpus/<target>/, kept in the tree).

Seeds: the meshes of ../shared/meshes cut down to their first facets (small files: libFuzzer
mutates short inputs best), each in the formats its targets read, and meshes built here: a
tetrahedron, a cube, a cube with the defects of a careless STL export (facets turned, repeated,
repeated reversed, zero-area), an OBJ with polygons, negative indices and texture/normal
references, an OFF with comments and colours. The inputs of fuzzing's findings, added to the
folders by hand (slow_*, crash_*), are left as they are. Run again after changing it:
    /usr/bin/python3 scripts/make_fuzz_corpus.py
"""
import pathlib
import struct
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared" / "meshes"
CORPUS = ROOT / "tests" / "fuzz" / "corpus"
CUT = 48  # facets kept of each shared mesh


def read_shared(path):
    """(points, triangles) of a shared mesh, read simply (these files are well formed)."""
    data = path.read_bytes()
    if path.suffix == ".stl":
        if len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]:
            n = struct.unpack_from("<I", data, 80)[0]
            rec = np.frombuffer(data[84:], dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]), count=n)
            pts = rec["v"].reshape(-1, 3).astype(float)
        else:
            pts = np.array([[float(x) for x in line.split()[1:4]] for line in data.decode().splitlines()
                            if line.strip().startswith("vertex")])
        return pts, np.arange(len(pts)).reshape(-1, 3)
    lines = data.decode().splitlines()
    if path.suffix == ".off":
        nv, nf = (int(x) for x in lines[1].split()[:2])
        pts = np.array([[float(x) for x in l.split()[:3]] for l in lines[2:2 + nv]])
        tris = np.array([[int(x) for x in l.split()[1:4]] for l in lines[2 + nv:2 + nv + nf]])
        return pts, tris
    pts = np.array([[float(x) for x in l.split()[1:4]] for l in lines if l.startswith("v ")])
    tris = np.array([[int(x.split("/")[0]) - 1 for x in l.split()[1:4]] for l in lines if l.startswith("f ")])
    return pts, tris


def cut(points, triangles, count=CUT):
    tris = triangles[:count]
    used, inverse = np.unique(tris, return_inverse=True)
    return points[used], inverse.reshape(-1, 3)


def stl_ascii(points, triangles):
    out = ["solid seed"]
    for t in triangles:
        out.append("  facet normal 0 0 0\n    outer loop")
        out += ["      vertex %.9g %.9g %.9g" % tuple(points[i]) for i in t]
        out.append("    endloop\n  endfacet")
    return ("\n".join(out) + "\nendsolid seed\n").encode()


def stl_facets(points, triangles):
    """The facets of a binary STL without its 84-byte header (the stl_binary and remesh targets add it)."""
    body = b""
    for t in triangles:
        body += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *points[i]) for i in t) + b"\0\0"
    return body


def obj(points, triangles):
    return ("".join("v %.9g %.9g %.9g\n" % tuple(p) for p in points) +
            "".join("f %d %d %d\n" % tuple(t + 1) for t in triangles)).encode()


def off(points, triangles):
    return ("OFF\n%d %d 0\n" % (len(points), len(triangles)) + "".join("%.9g %.9g %.9g\n" % tuple(p) for p in points) +
            "".join("3 %d %d %d\n" % tuple(t) for t in triangles)).encode()


def cube(n):
    """[-1, 1]^3, each face an n x n grid in two triangles a square, outward oriented."""
    pts, tris, index = [], [], {}

    def vid(p):
        key = tuple(np.round(p, 9))
        if key not in index:
            index[key] = len(pts)
            pts.append(p)
        return index[key]

    for axis in range(3):
        for side in (-1.0, 1.0):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            for i in range(n):
                for j in range(n):
                    quad = []
                    for a, b in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)):
                        p = np.zeros(3)
                        p[axis], p[u], p[v] = side, -1 + 2 * a / n, -1 + 2 * b / n
                        quad.append(vid(p))
                    if side < 0:
                        quad.reverse()
                    tris += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    return np.array(pts), np.array(tris)


def careless(points, triangles, seed=7):
    """The defects of a careless export: every third facet turned, some repeated (some of those
    reversed), three zero-area facets along the first facets' sides."""
    rng = np.random.default_rng(seed)
    tris = [t[::-1] if k % 3 == 0 else t for k, t in enumerate(triangles.tolist())]
    for k in rng.choice(len(tris), size=min(10, len(tris)), replace=False):
        tris.append(tris[k][::-1] if k % 2 else tris[k])
    pts = list(points)
    for t in triangles[:3]:
        pts.append((points[t[0]] + points[t[1]]) / 2)
        tris.append([t[0], t[1], len(pts) - 1])
    return np.array(pts), np.array(tris)


def main():
    tetra = (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]]), np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    seeds = {"tetrahedron": tetra, "cube2": cube(2), "careless_cube2": careless(*cube(2))}
    for path in sorted(SHARED.glob("*")):
        if path.suffix in (".stl", ".off", ".obj"):
            seeds[path.stem] = cut(*read_shared(path))
    files = {t: {} for t in ("stl_ascii", "stl_binary", "obj", "off", "remesh")}
    for name, (p, t) in seeds.items():
        files["stl_ascii"][name + ".stl"] = stl_ascii(p, t)[len(b"solid "):]  # the target adds "solid "
        files["stl_binary"][name + ".bin"] = stl_facets(p, t)
        files["obj"][name + ".obj"] = obj(p, t)
        files["off"][name + ".off"] = off(p, t)
        files["remesh"][name + ".bin"] = stl_facets(p, t)
    files["obj"]["polygons.obj"] = (b"# quads, negative indices, v/t/n\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
                                    b"vt 0 0\nvn 0 0 1\nf 1/1/1 4/1/1 3/1/1 2/1/1\nf -5//1 -4//1 -1//1\no part\ng side\n"
                                    b"f 2 3 5\nf 3 4 5\nf 4 1 5\n")
    files["off"]["coff_comments.off"] = (b"COFF # coloured\n# a comment line\n4 4 6\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n"
                                         b"0 1 0 0 0 255 255\n0 0 1 9 9 9 255\n3 0 2 1\n3 0 1 3 255 0 0\n3 0 3 2\n3 1 2 3\n")
    files["remesh"]["careless_cube3.bin"] = stl_facets(*careless(*cube(3)))
    total = 0
    for target, named in files.items():
        folder = CORPUS / target
        folder.mkdir(parents=True, exist_ok=True)
        for name, data in named.items():
            (folder / name).write_bytes(data)
            total += len(data)
    print("wrote %d files, %d bytes, in %s" % (sum(len(v) for v in files.values()), total, CORPUS), file=sys.stderr)


if __name__ == "__main__":
    main()
