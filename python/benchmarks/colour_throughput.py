"""Throughput of rimu's XYZ -> CIELAB and CIEDE2000 against plain numpy implementations of the same formulas
(CIE 15:2018 §8.2.1; Sharma, Wu & Dalal 2005), on one core: run it under `taskset -c 1` so oneTBB sees one CPU.

    PYTHONPATH=build/python taskset -c 1 python3 python/benchmarks/colour_throughput.py [count] [rounds]

For instruction counts (undisturbed by the machine's load), one function alone under callgrind, minus "none":

    PYTHONPATH=build/python valgrind --tool=callgrind --callgrind-out-file=/dev/null \
        python3 python/benchmarks/colour_throughput.py --only lab_rimu 200000 2

Prints, per round (rimu and numpy alternate, so a change in the machine's load touches both), millions of colours
(or pairs) per second, then the medians. The numpy versions are checked against rimu first (1e-9).
"""
import statistics
import sys
import time

import numpy as np

import rimu

EPSILON, KAPPA = 216 / 24389, 24389 / 27


def numpy_lab(xyz, white):
    t = xyz / white
    f = np.where(t > EPSILON, np.cbrt(t), (KAPPA * t + 16) / 116)
    return np.stack([116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]), 200 * (f[..., 1] - f[..., 2])], axis=-1)


def numpy_ciede2000(lab1, lab2):
    l1, a1, b1 = np.moveaxis(lab1, -1, 0)
    l2, a2, b2 = np.moveaxis(lab2, -1, 0)
    c_bar = (np.hypot(a1, b1) + np.hypot(a2, b2)) / 2
    g = 0.5 * (1 - np.sqrt(c_bar ** 7 / (c_bar ** 7 + 25.0 ** 7)))
    a1p, a2p = (1 + g) * a1, (1 + g) * a2
    c1p, c2p = np.hypot(a1p, b1), np.hypot(a2p, b2)
    h1p = np.degrees(np.arctan2(b1, a1p)) % 360
    h2p = np.degrees(np.arctan2(b2, a2p)) % 360
    dlp, dcp = l2 - l1, c2p - c1p
    dh = h2p - h1p
    dh = np.where(c1p * c2p == 0, 0, np.where(dh > 180, dh - 360, np.where(dh < -180, dh + 360, dh)))
    dhp = 2 * np.sqrt(c1p * c2p) * np.sin(np.radians(dh / 2))
    lbp, cbp = (l1 + l2) / 2, (c1p + c2p) / 2
    hsum = h1p + h2p
    hbp = np.where(c1p * c2p == 0, hsum,
                   np.where(np.abs(h1p - h2p) <= 180, hsum / 2, np.where(hsum < 360, (hsum + 360) / 2, (hsum - 360) / 2)))
    t = (1 - 0.17 * np.cos(np.radians(hbp - 30)) + 0.24 * np.cos(np.radians(2 * hbp))
         + 0.32 * np.cos(np.radians(3 * hbp + 6)) - 0.20 * np.cos(np.radians(4 * hbp - 63)))
    d_theta = 30 * np.exp(-(((hbp - 275) / 25) ** 2))
    rc = 2 * np.sqrt(cbp ** 7 / (cbp ** 7 + 25.0 ** 7))
    sl = 1 + 0.015 * (lbp - 50) ** 2 / np.sqrt(20 + (lbp - 50) ** 2)
    sc, sh = 1 + 0.045 * cbp, 1 + 0.015 * cbp * t
    rt = -np.sin(np.radians(2 * d_theta)) * rc
    return np.sqrt((dlp / sl) ** 2 + (dcp / sc) ** 2 + (dhp / sh) ** 2 + rt * (dcp / sc) * (dhp / sh))


def rate(f, count):
    start = time.perf_counter()
    f()
    return count / (time.perf_counter() - start) / 1e6


def main():
    args = sys.argv[1:]
    only = None
    if args[:1] == ["--only"]:
        only, args = args[1], args[2:]
    count = int(args[0]) if args else 1_000_000
    rounds = int(args[1]) if len(args) > 1 else 5
    rng = np.random.default_rng(1)
    xyz = rng.uniform(0.0, 100.0, size=(count, 3))
    white = np.array([95.047, 100.0, 108.883])
    lab1 = rng.uniform([0, -100, -100], [100, 100, 100], size=(count, 3))
    lab2 = rng.uniform([0, -100, -100], [100, 100, 100], size=(count, 3))
    if only:
        f = {"none": lambda: None, "lab_rimu": lambda: rimu.lab(xyz, white), "lab_numpy": lambda: numpy_lab(xyz, white),
             "de_rimu": lambda: rimu.delta_e_2000(lab1, lab2),
             "de_numpy": lambda: numpy_ciede2000(lab1, lab2)}[only]
        for _ in range(rounds):
            f()
        return
    np.testing.assert_allclose(numpy_lab(xyz[:1000], white), rimu.lab(xyz[:1000], white), atol=1e-9)
    np.testing.assert_allclose(numpy_ciede2000(lab1[:1000], lab2[:1000]), rimu.delta_e_2000(lab1[:1000], lab2[:1000]),
                               atol=1e-9)
    results = {k: [] for k in ("lab rimu", "lab numpy", "de2000 rimu", "de2000 numpy")}
    for r in range(rounds):
        results["lab rimu"].append(rate(lambda: rimu.lab(xyz, white), count))
        results["lab numpy"].append(rate(lambda: numpy_lab(xyz, white), count))
        results["de2000 rimu"].append(rate(lambda: rimu.delta_e_2000(lab1, lab2), count))
        results["de2000 numpy"].append(rate(lambda: numpy_ciede2000(lab1, lab2), count))
        print(f"round {r + 1}: " + ", ".join(f"{k} {v[-1]:.2f}" for k, v in results.items()) + " M/s")
    print("median:  " + ", ".join(f"{k} {statistics.median(v):.2f}" for k, v in results.items()) + " M/s")


if __name__ == "__main__":
    main()
