#!/usr/bin/python3
"""A worked stereo check: triangulate the stereo plate from the rig's calibration files and compare
with the ground truth P.

scenes/stereo_plate.lua (frame 0) is rendered twice, identically: by the CLI for the calibration
files (rig.yml, rig.left.yml: OpenCV's FileStorage format), and through the Python module for the
arrays `disparity` (where each left pixel's point appears in the right image) and `P` (that point in
the world). Each left pixel whose point the right camera sees is undistorted with OpenCV
(cv2.undistortPointsIter), triangulated (cv2.triangulatePoints with P1 = [I|0], P2 = [R|T] of
rig.yml) and taken to the world frame with rig.left.yml's pose; the distance to P is what a stereo
code would make of perfect correspondences: it tests the calibration files, the disparity and P
against each other.

  PYTHONPATH=build /usr/bin/python3 examples/stereo_triangulation.py
"""
import argparse
import os
import subprocess
import tempfile

import cv2
import numpy as np

import dicsynth

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "scenes", "stereo_plate.lua")
BINARY = os.path.join(ROOT, "build", "dicsynth")


def matrix(storage, name):
    return storage.getNode(name).mat()


def main():
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    downscale = 4
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([BINARY, "render", SCENE, "-o", folder, "--downscale", str(downscale), "--layers", "image"],
                       check=True, capture_output=True)
        rig = cv2.FileStorage(os.path.join(folder, "rig.yml"), cv2.FILE_STORAGE_READ)
        left = cv2.FileStorage(os.path.join(folder, "rig.left.yml"), cv2.FILE_STORAGE_READ)
        K1, D1 = matrix(rig, "camera_matrix_left"), matrix(rig, "distortion_coefficients_left")
        K2, D2 = matrix(rig, "camera_matrix_right"), matrix(rig, "distortion_coefficients_right")
        R, T = matrix(rig, "R"), matrix(rig, "T")
        R_left, t_left = matrix(left, "R"), matrix(left, "t")

    out = dicsynth.Renderer(downscale=downscale).render(dicsynth.Scene(SCENE), layers=["P", "disparity"])
    arrays = out["rig.left", 0]
    disparity, seen, P = arrays["disparity"], arrays["disparity.mask"] > 0, arrays["P"]
    ys, xs = np.nonzero(seen)
    pl = np.stack([xs, ys], axis=1).astype(np.float64)
    pr = pl + disparity[ys, xs].astype(np.float64)
    criteria = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 100, 1e-14)
    nl = cv2.undistortPointsIter(pl.reshape(-1, 1, 2), K1, D1, None, None, criteria).reshape(-1, 2)
    nr = cv2.undistortPointsIter(pr.reshape(-1, 1, 2), K2, D2, None, None, criteria).reshape(-1, 2)
    P1 = np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = np.hstack([R, T.reshape(3, 1)])
    X = cv2.triangulatePoints(P1, P2, nl.T, nr.T)
    X_left = (X[:3] / X[3]).T
    X_world = (R_left.T @ (X_left.T - t_left.reshape(3, 1))).T
    error = np.linalg.norm(X_world - P[ys, xs].astype(np.float64), axis=1)
    print("%d points seen by both cameras (downscale %d)" % (len(error), downscale))
    print("triangulated minus P: median %.3g m, 99th percentile %.3g m, max %.3g m"
          % (np.median(error), np.percentile(error, 99), error.max()))
    print("(P is float32: half an ulp at 0.5 m is 3e-8 m; disparity is float32 too: ~3e-5 px)")


if __name__ == "__main__":
    main()
