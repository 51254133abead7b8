#!/usr/bin/env python3
"""Ground truth for tests/t_brlcad_nirt.c: BRL-CAD's own answers along the rays of a small orthographic image.

    tests/data/brlcad/nirt_rays.py BRLCAD_BIN IACSG SIZE MODEL.asc [OBJECT ...] > nirt/MODEL.txt

For the view iacsg takes by default for a model (orthographic, -az 35 -el 25, centred on rt's model box
that `iacsg regions` prints, as high as its diagonal), each pixel's ray of a SIZE x SIZE image (the camera formula
of `iacsg --help`) is shot by nirt (asc2g makes the .g): every partition it crosses, with its region path and the
in and out distances from the ray's origin. Output: the model and objects, the camera (eye, at, ortho height,
size; up is +z), then per pixel
    ray I J N  PATH_1 IN_1 OUT_1  ...  PATH_N IN_N OUT_N
(N = 0 where nirt hits nothing). Air regions are left out, as nirt does by default.
"""
import math
import os
import subprocess
import sys
import tempfile


def main():
    bindir, iacsg, size, model, objects = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5:]
    header = subprocess.run([iacsg, "regions", model] + objects, check=True, capture_output=True, text=True).stdout
    bounds = [float(v) for v in header.split("# bounds (rt's model box): ")[1].split("\n")[0].split(",")]
    tops = objects or subprocess.run([iacsg, "objects", model], check=True, capture_output=True,
                                     text=True).stdout.split()
    at = [(bounds[k] + bounds[k + 3]) / 2 for k in range(3)]
    diag = math.sqrt(sum((bounds[k + 3] - bounds[k]) ** 2 for k in range(3)))
    az, el = math.radians(35), math.radians(25)
    toward = [math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)]
    eye = [at[k] + diag * toward[k] for k in range(3)]
    f = [-t for t in toward]
    up = [0.0, 0.0, 1.0]
    r = [f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]]
    rn = math.sqrt(sum(v * v for v in r))
    r = [v / rn for v in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    print("# nirt (BRL-CAD 7.32.6) along the rays of a %dx%d image of %s %s" % (size, size, os.path.basename(model),
                                                                              " ".join(objects)))
    print("model %s %s" % (os.path.basename(model), " ".join(objects)))
    print("camera %.17g %.17g %.17g  %.17g %.17g %.17g  %.17g  %d" % (*eye, *at, diag, size))
    origins = []
    for j in range(size):
        for i in range(size):
            s = (2 * (i + 0.5) / size - 1) * diag / 2
            v = (1 - 2 * (j + 0.5) / size) * diag / 2
            origins.append((i, j, [eye[k] + s * r[k] + v * u[k] for k in range(3)]))
    with tempfile.TemporaryDirectory() as tmp:
        g = os.path.join(tmp, "model.g")
        subprocess.run([os.path.join(bindir, "asc2g"), model, g], check=True, capture_output=True)
        # nirt reads and writes points in the database's units (truck's are inches, havoc's cm): ours are mm
        cmds = ['units mm', 'fmt r "R\\n"', 'fmt h ""',
                'fmt p "P %s %.17g %.17g %.17g %.17g %.17g %.17g\\n" path_name x_in y_in '
                'z_in x_out y_out z_out', 'fmt f "E\\n"', 'fmt m "M\\n"', 'fmt g ""', 'fmt o ""',
                "dir %.17g %.17g %.17g" % tuple(f)]
        for _, _, o in origins:
            cmds += ["xyz %.17g %.17g %.17g" % tuple(o), "s"]
        out = subprocess.run([os.path.join(bindir, "nirt"), "-s", g] + tops, input="\n".join(cmds) + "\n",
                             check=True, capture_output=True, text=True).stdout
    shots, cur = [], None
    for line in out.splitlines():
        w = line.split()
        if not w:
            continue
        if w[0] == "R":
            cur = []
        elif w[0] == "P":
            cur.append((w[1], [float(x) for x in w[2:8]]))
        elif w[0] == "E":
            shots.append(cur)
            cur = None
        elif w[0] == "M":
            shots.append([])
            cur = None
    assert len(shots) == len(origins), "nirt answered %d of %d rays" % (len(shots), len(origins))
    for (i, j, o), parts in zip(origins, shots):
        fields = ["ray", str(i), str(j), str(len(parts))]
        for name, p in parts:
            d_in = sum((p[k] - o[k]) * f[k] for k in range(3))
            d_out = sum((p[3 + k] - o[k]) * f[k] for k in range(3))
            if not all(math.isfinite(x) for x in p[3:6]):  # a half-space's: its out point is at infinity
                d_out = math.inf
            fields += [name, "%.9g" % d_in, "%.9g" % d_out]
        print(" ".join(fields))


main()
