"""The Python module `dicsynth` (host/python/dicsynth_module.cpp), run by ctest with Debian's
python3-pytest (PYTHONPATH=build, DICSYNTH_BINARY=the CLI). Its arrays are checked against the files
the CLI writes for the same scene, read back with OpenImageIO's own Python binding (an independent
reader), value for value."""
import os
import re
import pathlib
import subprocess
import tempfile
import time

import numpy as np
import OpenImageIO as oiio
import pytest

import dicsynth

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "scenes")
BINARY = os.environ["DICSYNTH_BINARY"]


def write_scene(folder, name, text):
    """Writes a scene file of the test's own into `folder`; returns its path."""
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def read_channels(path):
    """Every channel of an image file as float32 (H, W) arrays by name (objectId, defects as uint32)."""
    image = oiio.ImageInput.open(path)
    assert image, oiio.geterror()
    spec = image.spec()
    out = {}
    for c, name in enumerate(spec.channelnames):
        kind = oiio.UINT if name in ("objectId", "defects") else oiio.FLOAT
        out[name] = image.read_image(0, 0, c, c + 1, kind)[:, :, 0]
    image.close()
    return out


def read_tiff(path):
    image = oiio.ImageInput.open(path)
    assert image, oiio.geterror()
    pixels = image.read_image(0, 0, 0, 1, oiio.UINT16)[:, :, 0]
    image.close()
    return pixels


@pytest.mark.parametrize("backend", ["cpu", "gpu"])
def test_arrays_equal_the_cli_files(backend):
    scene_path = os.path.join(SCENES, "stereo_plate.lua")
    renderer = dicsynth.Renderer(backend=backend, precision="fp64", downscale=16)
    scene = dicsynth.Scene(scene_path, defines={"strain": 0.003})
    out = renderer.render(scene, frames=[0, 1], spp=2)
    assert set(out.keys()) == {("rig.left", 0), ("rig.right", 0), ("rig.left", 1), ("rig.right", 1)}
    with tempfile.TemporaryDirectory() as folder:
        subprocess.run([BINARY, "render", scene_path, "-o", folder, "--backend", backend, "--precision", "fp64",
                        "--downscale", "16", "--spp", "2", "--frames", "0:1", "-D", "strain=0.003"],
                       check=True, capture_output=True)
        for (camera, frame), arrays in out.items():
            stem = os.path.join(folder, "%s_%04d" % (camera, frame))
            files = read_channels(stem + ".exr")
            assert len(files) >= 20  # Y Z P N uv objectId mask disp flow disparity distortion
            np.testing.assert_array_equal(arrays["image"], read_tiff(stem + ".tif"))
            assert arrays["image"].dtype == np.uint16
            h, w = arrays["image"].shape
            groups = {"P": "XYZ", "N": "XYZ", "disp": "XYZ", "uv": "UV", "flow": "XY", "disparity": "XY",
                      "distortion": "XY"}
            for name, values in files.items():
                group, _, component = name.partition(".")
                if group in groups and component in groups[group]:
                    array = arrays[group][:, :, groups[group].index(component)]
                else:
                    array = arrays[name]
                assert array.shape == (h, w), name
                # Bit for bit, NaN where the file has NaN.
                np.testing.assert_array_equal(array, values, err_msg="%s %d %s" % (camera, frame, name))
            assert arrays["disp"].shape == (h, w, 3) and arrays["disp"].dtype == np.float32
            assert np.isfinite(arrays["disp"]).any()
            assert arrays["objectId"].dtype == np.uint32
            # objectId k names objects()[k - 1], as the EXR header's dicsynth:objects does.
            spec = oiio.ImageInput.open(stem + ".exr")
            header = spec.spec().get_string_attribute("dicsynth:objects")
            spec.close()
            assert renderer.objects(scene, frame=frame) == header.split(",")
            assert int(arrays["objectId"].max()) <= len(header.split(","))


def test_layers_errors_and_a_warm_loop():
    renderer = dicsynth.Renderer(backend="cpu", downscale=16)
    scene = dicsynth.Scene(os.path.join(SCENES, "rectangle.lua"))
    out = renderer.render(scene, layers=["image", "P"])
    arrays = next(iter(out.values()))
    assert sorted(arrays.keys()) == ["P", "image"]
    # One layer as a str, as the CLI's --layers image (the docs walk of 2026-11-28 got a TypeError).
    assert sorted(next(iter(renderer.render(scene, layers="image").values())).keys()) == ["image"]
    assert sorted(next(iter(renderer.render(scene, layers="image,P").values())).keys()) == ["P", "image"]
    with pytest.raises(dicsynth.InputError, match="frame 0 is listed twice"):
        renderer.render(scene, frames=[0, 0])
    with pytest.raises(dicsynth.InputError, match="unknown layer 'bogus'"):
        renderer.render(scene, layers=["bogus"])
    with pytest.raises(dicsynth.InputError, match="no such file|cannot read the scene file"):
        dicsynth.Scene(os.path.join(SCENES, "missing.lua"))
    with tempfile.NamedTemporaryFile("w", suffix=".lua", delete=False) as bad:
        bad.write("cam = Camera.Pinhole { resolution = {16, 12}; focalLength = 0.012; pixelSize = {2e-4, 2e-4} }\n"
                  "x = Shape.Sphere { radius = -1 }\n")
    try:
        with pytest.raises(dicsynth.InputError, match=":2: Shape.Sphere"):
            dicsynth.Scene(bad.name)
    finally:
        os.unlink(bad.name)
    with pytest.raises(ValueError):  # InputError is a ValueError
        dicsynth.Renderer(backend="vulkan")
    with pytest.raises(TypeError):
        renderer.render("not a scene")
    with pytest.raises(TypeError, match="a number, a bool or a str"):
        dicsynth.Scene(os.path.join(SCENES, "rectangle.lua"), defines={"x": [1, 2]})
    # The module audit of 2026-11-28: numpy numbers and ints of any size are numbers; a NaN is said
    # as such; bytes paths are paths; a seed beyond 64 bits is a ValueError like any out of range.
    rectangle = os.path.join(SCENES, "rectangle.lua")
    for value, text in [(np.int64(3), "3"), (np.float32(0.5), "0.5"), (2**70, str(2**70)), (np.bool_(True), "true")]:
        assert dicsynth.Scene(rectangle, defines={"x": value}).defines["x"] == text
    for bad in [None, 1 + 2j, [1, [2]]]:
        with pytest.raises(TypeError):
            dicsynth.Scene(rectangle, defines={"x": bad})
    with pytest.raises(dicsynth.InputError, match=re.escape("defines['x']: nan is not a finite number")):
        dicsynth.Scene(rectangle, defines={"x": float("nan")})
    assert dicsynth.Scene(os.fsencode(rectangle)).path == rectangle
    for seed in [2**63, 2**64, -2**70]:
        with pytest.raises(dicsynth.InputError, match="seed %d: must be in 0..4294967295" % seed):
            dicsynth.Renderer(backend="cpu", seed=seed)
    # The audit of 2026-11-27: a define that only later frames read was refused at construction;
    # now render refuses one that none of the rendered frames reads. Paths may be path-like.
    with tempfile.NamedTemporaryFile("w", suffix=".lua", delete=False) as later:
        later.write("cam = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.012; pixelSize = {2e-5, 2e-5} }\n"
                    "local r = 0.1\nif frame >= 1 then r = r * (1 + growth) end\n"
                    "ball = Object.Simple { shape = Shape.Sphere { radius = r; location = {0, 0, 1} } }\n")
    try:
        grown = dicsynth.Scene(pathlib.Path(later.name), defines={"growth": 0.5})
        assert sorted(renderer.render(grown, frames=[0, 1], layers=["mask"]).keys()) == [("cam", 0), ("cam", 1)]
        with pytest.raises(dicsynth.InputError, match=re.escape("defines['growth']: the scene never reads 'growth'")):
            renderer.render(grown, frames=[0], layers=["mask"])
    finally:
        os.unlink(later.name)
    # A scene whose frames start at 1 (a pose list read as poses[frame], Lua's lists counting from
    # 1): Scene checks the frame it is given. It checked frame 0 only, an error the CLI's
    # --frames 1:2 never meets (the motion audit of 2026-11-28).
    with tempfile.NamedTemporaryFile("w", suffix=".lua", delete=False) as onebased:
        onebased.write("local z = ({1.0, 1.2})[frame]\n"
                       "cam = Camera.Pinhole { resolution = {160, 120}; focalLength = 0.012; pixelSize = {2e-5, 2e-5} }\n"
                       "ball = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, z} } }\n")
    try:
        with pytest.raises(dicsynth.InputError, match=":3: Shape.Sphere: 'location'"):
            dicsynth.Scene(onebased.name)
        poses = dicsynth.Scene(onebased.name, frame=1)
        assert sorted(renderer.render(poses, frames=[1, 2], layers=["mask"]).keys()) == [("cam", 1), ("cam", 2)]
        with pytest.raises(dicsynth.InputError, match="frame -1: must be in 0.."):
            dicsynth.Scene(onebased.name, frame=-1)
    finally:
        os.unlink(onebased.name)
    # Messages name the arguments as Python spells them, not as the CLI's options (the audit of
    # 2026-11-27 found "--downscale must be >= 1" and "-D growth" in Python's errors).
    for make, message in [(lambda: dicsynth.Renderer(backend="cpu", downscale=0), "downscale 0: must be in 1..2147483647"),
                          (lambda: dicsynth.Renderer(backend="cpu", max_error_px=0), "max_error_px 0: must be"),
                          (lambda: dicsynth.Renderer(backend="cpu", seed=-1), "seed -1: must be in 0..4294967295"),
                          (lambda: dicsynth.Renderer(backend="cpu", seed=2**32), "seed 4294967296: must be"),
                          (lambda: renderer.render(scene, layers=["disparity"]), "layers: layer 'disparity' cannot be produced"),
                          (lambda: dicsynth.Renderer(device="no such device").render(scene), "device 'no such device': no such Vulkan device"),
                          (lambda: dicsynth.Scene(os.path.join(SCENES, "rectangle.lua"), defines={"frame": 1}),
                           "defines['frame']: 'frame' is reserved: the frame number is set by render's frames")]:
        with pytest.raises(dicsynth.InputError) as error:
            make()
        assert str(error.value).startswith(message), str(error.value)
        assert "--" not in str(error.value) and "-D " not in str(error.value), str(error.value)
    assert dicsynth.Renderer(backend="cpu", seed=2**32 - 1).backend == "cpu"
    assert renderer.backend == "cpu" and dicsynth.Renderer(backend="cpu").backend == "cpu"
    # A loop of renders pays the start-up once: later renders reuse the session (a figure, not a
    # bound: the benchmark compares with processes, bench/RESULTS.md).
    start = time.perf_counter()
    for _ in range(3):
        renderer.render(scene, layers=["image"])
    assert time.perf_counter() - start < 60


def read_yaml(path):
    """Every node of an OpenCV FileStorage file (cv2: an independent reader) as numbers, arrays or text."""
    import cv2
    storage = cv2.FileStorage(path, cv2.FILE_STORAGE_READ)
    assert storage.isOpened(), path
    out = {}
    for key in storage.root().keys():
        node = storage.getNode(key)
        out[key] = node.mat() if node.isMap() else node.string() if node.isString() else node.real()
    storage.release()
    return out


def assert_calibration_equals_file(calibration, path, side=""):
    """The module's calibration of one camera equals the file's, double for double (the files print 17
    significant digits, so a double reads back exactly)."""
    stored = read_yaml(path)
    for key, value in calibration.items():
        if key in ("R", "t") and side:
            continue  # a rig file states the stereo R, T instead of each camera's pose
        expected = stored[key + side]
        if isinstance(value, np.ndarray):
            assert value.dtype == np.float64, key
            np.testing.assert_array_equal(value, expected.reshape(value.shape), err_msg="%s %s" % (path, key))
        else:
            assert value == expected, (path, key, value, expected)
    own = {key + side for key in calibration if not (side and key in ("R", "t"))}
    assert own >= {key for key in stored if key.endswith(side) and key not in ("R", "T", "rig_name")}, path


def test_calibration_equals_the_cli_files():
    # A camera that moves between frames (numbered calibration files, one per frame), a stereo rig
    # with Brown distortion at downscale 4, and a telecentric camera (not OpenCV's model: its
    # camera_model and magnification keys).
    with tempfile.TemporaryDirectory() as folder:
        moving = write_scene(folder, "moving.lua",
            "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.012; pixelSize = {4e-5, 4e-5};\n"
            "  position = {0.01 * frame, 0, 0}; principalPoint = {30.25, 25.5};\n"
            "  distortion = Distortion.Rational { radial = {0.01, 0.001, 0, 0.002, 0, 0}; thinPrism = {0, 1e-4, 0, 0} } }\n"
            "ball = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, 1} } }\n")
        cases = [(moving, [], 1, [0, 1]),
                 (os.path.join(SCENES, "stereo_plate.lua"), ["-D", "strain=0.003"], 4, [0, 1]),
                 (os.path.join(SCENES, "telecentric.lua"), [], 8, [0])]
        for path, defines, downscale, frames in cases:
            out = os.path.join(folder, os.path.basename(path) + ".out")
            subprocess.run([BINARY, "render", path, "-o", out, "--backend", "cpu", "--downscale", str(downscale),
                            "--spp", "1", "--layers", "image", "--frames", "%d:%d" % (frames[0], frames[-1])] + defines,
                           check=True, capture_output=True)
            renderer = dicsynth.Renderer(backend="cpu", downscale=downscale)
            scene = dicsynth.Scene(path, defines={"strain": 0.003} if defines else {})
            for frame in frames:
                calibration = renderer.calibration(scene, frame=frame)
                numbered = os.path.exists(os.path.join(out, "cam_0000.yml"))
                suffix = "_%04d" % frame if numbered else ""
                for name, camera in calibration["cameras"].items():
                    assert camera["camera_name"] == name
                    assert_calibration_equals_file(camera, os.path.join(out, name + suffix + ".yml"))
                for name, rig in calibration["rigs"].items():
                    rig_file = os.path.join(out, name + suffix + ".yml")
                    for side in ("left", "right"):
                        assert_calibration_equals_file(calibration["cameras"][rig[side]], rig_file, "_" + side)
                    stored = read_yaml(rig_file)
                    assert rig["rig_name"] == stored["rig_name"] == name
                    np.testing.assert_array_equal(rig["R"], stored["R"])
                    np.testing.assert_array_equal(rig["T"], stored["T"].reshape(3))
            if path == moving:
                assert numbered
                first, second = (renderer.calibration(scene, frame=f)["cameras"]["cam"] for f in (0, 1))
                assert second["t"][0] == first["t"][0] - 0.01  # x_cam = R x_world + t, the camera moved +1 cm in x
                assert len(first["distortion_coefficients"]) == 12
            if path.endswith("telecentric.lua"):
                camera = calibration["cameras"]["camera"]
                assert camera["camera_model"] == "orthographic" and camera["magnification"] == 0.5
            if "stereo_plate" in path:
                assert calibration["cameras"]["rig.left"]["image_width"] == 1600 // 4


def test_calibration_checks_as_a_render_does():
    renderer = dicsynth.Renderer(backend="cpu")
    with tempfile.TemporaryDirectory() as folder:
        folded = write_scene(folder, "folded.lua",
            "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.012; pixelSize = {4e-4, 4e-4};\n"
            "  distortion = Distortion.Brown { radial = {-3} } }\n"
            "ball = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, 1} } }\n")
        scene = dicsynth.Scene(folded)
        with pytest.raises(dicsynth.InputError, match=r"folded\.lua:1: Distortion\.Brown of camera 'cam' cannot be inverted"):
            renderer.calibration(scene)
    with pytest.raises(dicsynth.InputError, match=re.escape("frame -1: must be in 0..999999999")):
        renderer.calibration(dicsynth.Scene(os.path.join(SCENES, "rectangle.lua")), frame=-1)


def test_features_equal_the_cli_files():
    # Renderer.features against the CLI's feature JSON of the same frames (a stereo calibration set
    # with Brown distortion at downscale 4), value for value (the files print 17 digits; NaN as null);
    # and the pixels against OpenCV's projection of the world points through the calibration.
    import json
    import cv2
    path = os.path.join(SCENES, "stereo_calibration.lua")
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "out")
        subprocess.run([BINARY, "render", path, "-o", out, "--backend", "cpu", "--downscale", "4", "--spp", "1",
                        "--layers", "image", "--frames", "0:1"], check=True, capture_output=True)
        renderer = dicsynth.Renderer(backend="cpu", downscale=4)
        scene = dicsynth.Scene(path)
        for frame in (0, 1):
            features = renderer.features(scene, frame=frame)
            calibration = renderer.calibration(scene, frame=frame)
            assert sorted(features) == ["rig.left", "rig.right"]
            for camera, targets in features.items():
                with open(os.path.join(out, "%s_%04d.features.json" % (camera, frame))) as f:
                    stored = json.load(f)
                assert len(targets) == len(stored["targets"]) == 1
                for got, want in zip(targets, stored["targets"]):
                    for key in ("name", "kind", "asymmetric", "spacing_m"):
                        assert got[key] == want[key], key
                    assert list(got["pattern_size"]) == want["pattern_size"]
                    np.testing.assert_array_equal(got["R_camera_from_target"].reshape(9), want["R_camera_from_target"])
                    np.testing.assert_array_equal(got["t_camera_from_target_m"], want["t_camera_from_target_m"])
                    rows = want["features"]
                    assert got["pixel"].shape == (len(rows), 2) and got["index"].dtype == np.int32
                    for key in ("index", "row", "col", "in_front", "in_image", "unoccluded", "visible"):
                        assert got[key].tolist() == [r[key] for r in rows], key
                    for key, json_key in (("target_m", "target_m"), ("world_m", "world_m"), ("pixel", "pixel")):
                        want_rows = np.array([[np.nan if v is None else v for v in r[json_key]] for r in rows])
                        np.testing.assert_array_equal(got[key], want_rows, err_msg=key)
                    np.testing.assert_array_equal(got["depth_m"], [r["depth_m"] for r in rows])
                    assert got["visible"].all()  # the poses keep every corner in both images
                    cam = calibration["cameras"][camera]
                    projected, _ = cv2.projectPoints(got["world_m"], cv2.Rodrigues(cam["R"])[0], cam["t"],
                                                     cam["camera_matrix"], cam["distortion_coefficients"])
                    # OpenCV's projection in double against dicsynth's: rounding only (measured 3.4e-13 px; 1e-9 px
                    # leaves room for another libm and is far below a detector's 0.02 px)
                    assert np.abs(projected.reshape(-1, 2) - got["pixel"]).max() < 1e-9


def test_features_warn_of_a_target_seen_from_its_back():
    # The warning the CLI says when it writes the feature files (docs/calibration.md) reaches Python
    # through features(), which writes none (the calibration trial of 2026-11-28: render,
    # calibration and Scene said nothing in Python).
    renderer = dicsynth.Renderer(backend="cpu")
    with tempfile.TemporaryDirectory() as folder:
        back = write_scene(folder, "back.lua",
            "cam = Camera.Pinhole { resolution = {64, 48}; focalLength = 0.012; pixelSize = {4e-5, 4e-5} }\n"
            "board = Target.Checkerboard { squares = {5, 4}; squareSize = 0.02; location = {0.04, -0.03, 1};\n"
            "  transform = rotate_y(math.pi) }\n")
        scene = dicsynth.Scene(back)
        with pytest.warns(dicsynth.DicsynthWarning, match="target 'board' is seen from its back"):
            features = renderer.features(scene)
        assert features["cam"][0]["visible"].any()


def test_warnings_are_python_warnings(capfd):
    # What the CLI says on stderr without stopping reaches Python's warnings (a notebook shows them,
    # filters act on them): here a camera that sees nothing.
    renderer = dicsynth.Renderer(backend="cpu")
    with tempfile.TemporaryDirectory() as folder:
        empty = write_scene(folder, "empty.lua",
            "cam = Camera.Pinhole { resolution = {16, 12}; focalLength = 0.012; pixelSize = {4e-5, 4e-5} }\n"
            "ball = Object.Simple { shape = Shape.Sphere { radius = 0.1; location = {0, 0, -1} } }\n")
        scene = dicsynth.Scene(empty)
        capfd.readouterr()
        with pytest.warns(dicsynth.DicsynthWarning, match="camera cam, frame 0: no pixel centre sees an object"):
            renderer.render(scene, layers=["image"])
        assert capfd.readouterr().err == ""  # not on stderr as well
        assert issubclass(dicsynth.DicsynthWarning, UserWarning)
        import warnings
        with warnings.catch_warnings():
            warnings.simplefilter("error", dicsynth.DicsynthWarning)
            with pytest.raises(dicsynth.DicsynthWarning, match="no pixel centre sees an object"):
                renderer.render(scene, layers=["image"])


def test_one_gpu_renderer_shared_by_threads_renders_one_at_a_time():
    # Two threads rendering with one GPU Renderer crashed in the driver (the module audit of
    # 2026-11-28): render now takes the Renderer for itself. Each result equals the serial one.
    import threading
    # A fresh Renderer: the threads' renders are its first (the crash needed no render before), and
    # the module's first arrays (pybind11's numpy lookup, which deadlocked two first callers).
    renderer = dicsynth.Renderer(backend="gpu", precision="fp64", downscale=16)
    scene = dicsynth.Scene(os.path.join(SCENES, "rectangle.lua"))
    results, errors = [], []

    def work():
        try:
            results.append(next(iter(renderer.render(scene, spp=1, layers="image").values()))["image"])
        except Exception as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=work) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert len(results) == 3
    serial = next(iter(renderer.render(scene, spp=1, layers="image").values()))["image"]
    for image in results:
        np.testing.assert_array_equal(image, serial)


def test_a_reference_frame_outside_the_frames_is_traced_not_returned():
    """Chunks of a sequence measured from one frame (the DIC-developer trial of 2026-11-29: frames=[2, 3]
    measured frame 3 from frame 2, frames=[1] alone gave a flow of 0, without a word)."""
    renderer = dicsynth.Renderer(backend="cpu")
    with tempfile.TemporaryDirectory() as folder:
        # fx = 0.016 / 2e-4 = 80 px; 1 mm per frame at Z = 0.4 m: 0.2 px per frame.
        moving = write_scene(folder, "moving.lua",
            "cam = Camera.Pinhole { resolution = {40, 30}; focalLength = 0.016; pixelSize = {2e-4, 2e-4} }\n"
            "obj = Object.Simple { shape = Shape.Rectangle { size = {1, 1}; location = {frame * 1e-3, 0, 0.4} } }\n")
        scene = dicsynth.Scene(moving)
        chunk = renderer.render(scene, frames=[2, 3], spp=1, layers=["image", "flow"], reference_frame=0)
        assert sorted(chunk.keys()) == [("cam", 2), ("cam", 3)]
        whole = renderer.render(scene, frames=[0, 1, 2, 3], spp=1, layers=["image", "flow"])
        for frame in (2, 3):
            assert np.array_equal(chunk["cam", frame]["flow"], whole["cam", frame]["flow"])
            assert np.array_equal(chunk["cam", frame]["image"], whole["cam", frame]["image"])
            assert np.abs(chunk["cam", frame]["flow"][:, :, 0] - 0.2 * frame).max() < 1e-6
        with pytest.warns(dicsynth.DicsynthWarning, match="frame 1 is rendered alone and is its own reference frame: "
                                                          r"its flow is 0 everywhere \(reference_frame R"):
            renderer.render(scene, frames=[1], spp=1, layers="flow")


def test_a_seed_per_render_call():
    """render(seed=...) replaces the Renderer's seed for one call (the DIC-developer trial of 2026-11-29:
    a Monte-Carlo loop needed a new Renderer per seed, ~1 s each). The same seed is the same image."""
    renderer = dicsynth.Renderer(backend="cpu", downscale=8, seed=1)
    scene = dicsynth.Scene(os.path.join(SCENES, "noisy_speckle.lua"))
    default = renderer.render(scene, layers="image")
    one = renderer.render(scene, layers="image", seed=1)
    two = renderer.render(scene, layers="image", seed=2)
    again = renderer.render(scene, layers="image")
    key = next(iter(default))
    assert np.array_equal(default[key]["image"], one[key]["image"])
    assert np.array_equal(default[key]["image"], again[key]["image"])  # the Renderer's own seed is kept
    assert not np.array_equal(default[key]["image"], two[key]["image"])
    assert np.array_equal(two[key]["image"], dicsynth.Renderer(backend="cpu", downscale=8, seed=2).render(scene, layers="image")[key]["image"])
    with pytest.raises(dicsynth.InputError, match=r"seed 4294967296: must be in 0\.\.4294967295"):
        renderer.render(scene, layers="image", seed=2**32)
