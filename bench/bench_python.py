#!/usr/bin/python3
"""A Python-driven loop against processes (issue 17): N points of bench/tiny_sweep.lua (a 32x24
plate whose offset is the parameter) rendered
  (a) by N `dicsynth render` processes (each pays start-up, scene, device and file writing),
  (b) by one `dicsynth sweep` of N points (one process, files written),
  (c) by one Python process: dicsynth.Renderer kept warm, N render() calls returning arrays.
Each the median of --repeat runs, interleaved; ratios printed for bench/RESULTS.md.

  PYTHONPATH=build /usr/bin/python3 bench/bench_python.py [--points 20] [--repeat 3] [--backend gpu]
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import dicsynth

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "bench", "tiny_sweep.lua")
# The CLI of the build whose module was imported (PYTHONPATH=build2 times build2 against build2:
# it always took build/, the bench audit of 2026-11-28).
BINARY = os.path.join(os.path.dirname(os.path.abspath(dicsynth.__file__)), "dicsynth")
if not os.access(BINARY, os.X_OK):
    sys.exit("no dicsynth binary beside the module %s (PYTHONPATH must name a build folder)" % dicsynth.__file__)


def processes(n, backend):
    with tempfile.TemporaryDirectory() as folder:
        for i in range(n):
            subprocess.run([BINARY, "render", SCENE, "-o", os.path.join(folder, str(i)), "--backend", backend,
                            "-D", "shift=%r" % (0.01 * i / max(1, n - 1))], check=True, capture_output=True)


def sweep(n, backend):
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([BINARY, "sweep", SCENE, "-o", folder, "--backend", backend, "--sweep", "shift=0:0.01:%d" % n],
                       check=True, capture_output=True)


def python_loop(n, backend, renderer):
    for i in range(n):
        renderer.render(dicsynth.Scene(SCENE, defines={"shift": 0.01 * i / max(1, n - 1)}))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--points", type=int, default=20)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--backend", default="gpu")
    args = parser.parse_args()
    times = {"processes": [], "sweep": [], "python": []}
    for _ in range(args.repeat):
        for name in times:
            start = time.perf_counter()
            if name == "processes":
                processes(args.points, args.backend)
            elif name == "sweep":
                sweep(args.points, args.backend)
            else:
                # The renderer is made inside the timing: the Python process pays its start-up once.
                python_loop(args.points, args.backend, dicsynth.Renderer(backend=args.backend))
            times[name].append(time.perf_counter() - start)
    median = {k: statistics.median(v) for k, v in times.items()}
    print("| %d points of tiny_sweep.lua, %s | median of %d | per point | vs processes |" % (args.points, args.backend, args.repeat))
    print("|---|---|---|---|")
    for name, label in (("processes", "N `dicsynth render` processes"), ("sweep", "`dicsynth sweep` (one process, files)"),
                        ("python", "Python: one Renderer, N render() (arrays)")):
        print("| %s | %.2f s | %.3f s | %.2fx |" % (label, median[name], median[name] / args.points,
                                                    median["processes"] / median[name]))


if __name__ == "__main__":
    main()
