#!/usr/bin/env python3
"""Writes assets/rock.obj, the rock that the rock-drop sample scene drops into sand.

Usage: scripts/make-rock-asset.py [OUTPUT]   (default: assets/rock.obj beside this script)

An icosphere subdivided twice (320 triangles, 162 vertices), its vertices pushed in or out along
their own direction by a seeded random amount (smoothed over the neighbours, so that the surface
undulates instead of bristling), cut by a few random planes that flatten it where a rock has
broken faces, and squashed into an ellipsoid about 1 unit long. Every change moves a vertex along
the ray from the centre and keeps it off the centre, so the surface stays star-shaped about the
centre: it cannot fold over itself, it stays closed, and the icosphere's outward winding stays
outward. Python's random.Random(seed).random() gives the same sequence on every platform and
version, so the same seed writes the same file.
"""

import math
import random
import sys
from pathlib import Path

SEED = 20240611
SUBDIVISIONS = 2
# Semi-axes of the ellipsoid before the bumps: 1.0 x 0.62 x 0.78 units, a flattish pebble.
SEMI_AXES = (0.5, 0.31, 0.39)
# Largest radial bump, as a fraction of the radius, before smoothing.
BUMP = 0.16
# Planes that flatten the rock: a random unit normal each, cutting at this fraction of the
# radius in that direction.
CUTS = 5
CUT_DEPTH = (0.78, 0.9)


def icosphere(subdivisions):
    """Unit icosphere: vertices and counter-clockwise (seen from outside) triangles."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
                (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
                (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    vertices = [normalised(v) for v in vertices]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
                 (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
                 (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
                 (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        midpoints = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoints:
                pa, pb = vertices[a], vertices[b]
                vertices.append(normalised(tuple((pa[k] + pb[k]) / 2 for k in range(3))))
                midpoints[key] = len(vertices) - 1
            return midpoints[key]

        split = []
        for a, b, c in triangles:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        triangles = split
    return vertices, triangles


def normalised(v):
    length = math.sqrt(sum(x * x for x in v))
    return tuple(x / length for x in v)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def rock(seed):
    rng = random.Random(seed)
    directions, triangles = icosphere(SUBDIVISIONS)
    neighbours = [set() for _ in directions]
    for tri in triangles:
        for i in range(3):
            neighbours[tri[i]].update((tri[(i + 1) % 3], tri[(i + 2) % 3]))

    bumps = [rng.uniform(-BUMP, BUMP) for _ in directions]
    # One pass of neighbour averaging: lumps a few vertices wide rather than single spikes.
    smooth = [(bumps[i] + sum(bumps[j] for j in neighbours[i]) / len(neighbours[i])) / 2
              for i in range(len(directions))]
    radii = [1.0 + s for s in smooth]

    for _ in range(CUTS):
        normal = normalised(tuple(rng.gauss(0.0, 1.0) for _ in range(3)))
        depth = rng.uniform(*CUT_DEPTH)
        for i, direction in enumerate(directions):
            along = dot(direction, normal)
            # Pull the vertex back along its own ray onto the plane dot(p, normal) = depth.
            if along > 0.0 and radii[i] * along > depth:
                radii[i] = depth / along

    return [tuple(r * d[k] * SEMI_AXES[k] for k in range(3))
            for r, d in zip(radii, directions)], triangles


def main():
    here = Path(__file__).resolve().parent
    output = Path(sys.argv[1]) if len(sys.argv) > 1 else here.parent / "assets" / "rock.obj"
    vertices, triangles = rock(SEED)
    lo = [min(v[k] for v in vertices) for k in range(3)]
    hi = [max(v[k] for v in vertices) for k in range(3)]
    lines = [
        "# rock.obj: a rock for the rock-drop sample scene, made by scripts/make-rock-asset.py",
        f"# (seed {SEED}); edit and rerun the script rather than this file.",
        "# A closed, watertight triangle mesh wound counter-clockwise seen from outside.",
        "# Units: none of its own; about 1 unit across (bounding box "
        + " x ".join(f"{hi[k] - lo[k]:.3f}" for k in range(3)) + ", centred near the origin).",
        "# The scene decides the metres: its `scale` parameter (--scale) multiplies these",
        "# coordinates, 1 unit = `scale` m.",
        f"# {len(vertices)} vertices, {len(triangles)} triangles.",
    ]
    lines += [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in vertices]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in triangles]
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text("\n".join(lines) + "\n", encoding="ascii")
    print(f"{output}: {len(vertices)} vertices, {len(triangles)} triangles")


if __name__ == "__main__":
    main()
