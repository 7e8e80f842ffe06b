"""The Python module as a notebook or a script uses it (the module audit of 2026-11-28 and its
follow-up): Ctrl-C stops a render, what a render says reaches sys.stderr, a Scene survives os.chdir
and pickling, and arguments out of range are ValueErrors naming the argument, not pybind11's
signature dump. Run by ctest with the other tests in tests/python (PYTHONPATH=build)."""
import os
import pickle
import re
import signal
import threading
import time
import warnings

import numpy as np
import pytest

import dicsynth

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "scenes")

# A plane filling a 320 x 240 view with the analytic speckle: cheap per sample, the same work in
# every pixel, so that a render's time is samples x frames.
PLANE = """camera = Camera.Pinhole { resolution = {320, 240}; focalLength = 0.016; pixelSize = {1e-5, 1e-5} }
o = Object.Simple { shape = Shape.Plane {}; shader = Shader.Constant { color = 0.5 };
                    texture = Texture.Speckle { radius = 0.001 }; transform = translate(0, 0, 1) }
"""


def write(folder, name, text):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def image(out, camera="camera", frame=0):
    return out[camera, frame]["image"]


@pytest.mark.parametrize("backend", ["cpu", "gpu"])
def test_ctrl_c_stops_a_render_and_the_renderer_renders_again(backend, tmp_path):
    # Before, render ran to its end with the GIL released and Python raised KeyboardInterrupt only
    # once it returned: a long render could not be stopped from a notebook. The render now stops at
    # its next CPU row, GPU tile or frame.
    scene = dicsynth.Scene(write(tmp_path, "plane.lua", PLANE))
    renderer = dicsynth.Renderer(backend=backend, precision="fp32" if backend == "gpu" else "auto")
    spp, frames = 16, 400
    renderer.render(scene, spp=spp, layers="image")  # the device started, the pipeline made
    start = time.perf_counter()
    before = renderer.render(scene, spp=spp, layers="image")
    one_frame = time.perf_counter() - start
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        renderer.render(scene, frames=range(frames), spp=spp, layers="image")
    stopped_after = time.perf_counter() - start
    timer.join()
    # Not a speed bound: uninterrupted, the call takes `frames` frames (400 x one_frame, over a
    # minute on lavapipe); stopped, it ends within the frame or tile under way when the signal came
    # (plus the 0.1 s poll). A quarter of the whole separates the two by a wide margin.
    assert stopped_after < frames * one_frame / 4, (stopped_after, one_frame)
    # The Renderer is intact: the next render equals the one before, pixel for pixel.
    np.testing.assert_array_equal(image(renderer.render(scene, spp=spp, layers="image")), image(before))


def test_a_signal_handler_that_raises_stops_a_render_too(tmp_path):
    # Any exception a Python signal handler raises ends the render with it (a SIGALRM timeout).
    scene = dicsynth.Scene(write(tmp_path, "plane.lua", PLANE))
    renderer = dicsynth.Renderer(backend="cpu")

    def timeout(signum, frame):
        raise TimeoutError("render took too long")

    previous = signal.signal(signal.SIGALRM, timeout)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.3)
        with pytest.raises(TimeoutError, match="render took too long"):
            renderer.render(scene, frames=range(400), spp=16, layers="image")
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def test_what_a_render_says_reaches_sys_stderr(capsys, tmp_path):
    # A scene's print and a Nurbs.deform fit's report were written to the process's stderr (fd 2),
    # which a notebook does not show; they are now lines on sys.stderr, in the order said.
    path = write(tmp_path, "talk.lua", PLANE + 'print("frame", frame, "says hello")\n'
                 "local s = Nurbs.plate { size = {0.02, 0.02}; location = {0, 0, 0.9} }\n"
                 "bent = Object.Simple { shape = Nurbs.deform { surface = s; tolerance = 1e-9;\n"
                 "  displacement = function(x, y, z) return 0, 0, 1e-4 * x end } }\n")
    renderer = dicsynth.Renderer(backend="cpu", downscale=8)
    scene = dicsynth.Scene(path)
    capsys.readouterr()
    renderer.render(scene, frames=[0, 1], spp=1, layers="image")
    said = capsys.readouterr().err.splitlines()
    assert len(said) == 4, said
    for frame in [0, 1]:
        assert said[2 * frame] == path + ":4: frame\t%d\tsays hello" % frame, said
        assert re.match(re.escape(path) + r":6: note: Nurbs\.deform: fit error \S+ m \(tolerance 1e-09 m\)", said[2 * frame + 1]), said
    # capsys sees sys.stderr only: a line written to fd 2, as before, is not in `said`.


def test_a_relative_scene_path_survives_os_chdir(tmp_path, monkeypatch):
    # The path was read relative to the working directory of each call: an os.chdir between Scene()
    # and render() made it name another file, or none (the module audit).
    write(tmp_path, "plane.lua", PLANE)
    monkeypatch.chdir(tmp_path)
    scene = dicsynth.Scene("plane.lua")
    renderer = dicsynth.Renderer(backend="cpu", downscale=4)
    here = renderer.render(scene, spp=1, layers="image")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    write(elsewhere, "plane.lua", "error('the wrong file was read')\n")  # what the relative path now names
    monkeypatch.chdir(elsewhere)
    np.testing.assert_array_equal(image(renderer.render(scene, spp=1, layers="image")), image(here))
    assert renderer.objects(scene) == ["o"]
    assert scene.path == "plane.lua"  # as given: messages name it so while the folder is the same


def test_a_scene_pickles_for_worker_processes(tmp_path):
    # ProcessPoolExecutor hands its arguments over by pickle: a Scene could not be pickled.
    scene = dicsynth.Scene(write(tmp_path, "plane.lua", PLANE.replace("color = 0.5", "color = grey")),
                           defines={"grey": 0.25})
    copy = pickle.loads(pickle.dumps(scene))
    assert copy.path == scene.path and copy.defines == scene.defines == {"grey": "0.25"}
    renderer = dicsynth.Renderer(backend="cpu", downscale=4)
    np.testing.assert_array_equal(image(renderer.render(copy, spp=1, layers="image")),
                                  image(renderer.render(scene, spp=1, layers="image")))
    with pytest.raises(ValueError, match="not a pickled Scene"):
        dicsynth.Scene.__new__(dicsynth.Scene).__setstate__(("only", "two"))


def test_arguments_out_of_range_name_the_argument(tmp_path):
    # pybind11's int conversion answered a number beyond 32 bits with a TypeError quoting the whole
    # signature; frames had no limits (the CLI's: frame numbers up to 999,999,999, a million frames).
    scene = dicsynth.Scene(write(tmp_path, "plane.lua", PLANE))
    renderer = dicsynth.Renderer(backend="cpu", downscale=8)
    for kwargs, message in [({"frames": [2**31]}, "frames: frame number 2147483648: must be in 0..999999999"),
                            ({"frames": 10**9}, "frames: frame number 1000000000: must be in 0..999999999"),
                            ({"frames": [-1]}, "frames: frame number -1: must be in 0..999999999"),
                            ({"frames": range(10**12)}, "frames: 1000000000000 frames, over the limit of 1000000 per call"),
                            ({"frames": []}, "frames: at least one frame"),
                            ({"spp": 2**40}, "spp 1099511627776: must be in 1..65536"),
                            ({"spp": 0}, "spp 0: must be in 1..65536"),
                            ({"reference_frame": 2**64}, "reference_frame 18446744073709551616: must be in 0..999999999"),
                            ({"layers": []}, "layers: at least one layer")]:
        with pytest.raises(dicsynth.InputError) as error:
            renderer.render(scene, **kwargs)
        assert str(error.value).startswith(message), str(error.value)
    for make, message in [(lambda: dicsynth.Renderer(backend="cpu", downscale=2**40), "downscale 1099511627776: must be in 1..2147483647"),
                          (lambda: renderer.calibration(scene, frame=2**63), "frame 9223372036854775808: must be in 0..999999999"),
                          (lambda: renderer.objects(scene, frame=-2), "frame -2: must be in 0..999999999")]:
        with pytest.raises(dicsynth.InputError) as error:
            make()
        assert str(error.value).startswith(message), str(error.value)
    for kwargs in [{"frames": "0"}, {"frames": 1.5}, {"frames": [0.0]}, {"spp": 4.0}, {"frames": True},
                   {"frames": np.array(2.0)}]:
        with pytest.raises(TypeError, match="frames|spp"):
            renderer.render(scene, **kwargs)
    # What is accepted: one int, any iterable of ints, numpy's ints.
    assert sorted(renderer.render(scene, frames=1, spp=1, layers="image")) == [("camera", 1)]
    assert sorted(renderer.render(scene, frames=np.arange(2), spp=np.int64(1), layers="image")) == [("camera", 0), ("camera", 1)]
    assert sorted(renderer.render(scene, frames=(f for f in [2, 0]), spp=1, layers="image")) == [("camera", 0), ("camera", 2)]
    # A 0-d array is one frame (it raised "len() of unsized object", naming no argument).
    assert sorted(renderer.render(scene, frames=np.array(2), spp=1, layers="image")) == [("camera", 2)]


def test_each_call_may_warn_again(tmp_path):
    # Warnings said once per process in the CLI (a lit object without lights, a target seen from its
    # back; the empty image at most 10 times) were said in a Python session's first call only.
    scene = dicsynth.Scene(write(tmp_path, "unlit.lua", PLANE.replace("Shader.Constant { color = 0.5 }", "Shader.Lambert {}")))
    renderer = dicsynth.Renderer(backend="cpu", downscale=8)
    for _ in range(2):
        with pytest.warns(dicsynth.DicsynthWarning, match="which needs a light, and frame 0 has none"):
            renderer.render(scene, spp=1, layers="image")


def test_messages_name_python_arguments_not_cli_options(tmp_path):
    # A pose list's error named `--frames 0:N`; a device given to the CPU backend was ignored unsaid.
    path = write(tmp_path, "poses.lua", PLANE + "local spec = { squares = {10, 7}; squareSize = 0.002 }\n"
                 "local poses = Target.poses { target = Target.Checkerboard(spec); cameras = {camera}; count = 3;\n"
                 "  distance = {0.2, 0.3} }\n"
                 "spec.transform = poses[frame + 1]\nboard = Target.Checkerboard(spec)\n")
    renderer = dicsynth.Renderer(backend="cpu", downscale=8)
    with pytest.raises(dicsynth.InputError, match=re.escape("(with frames=range(3), use poses[frame + 1])")):
        renderer.objects(dicsynth.Scene(path), frame=3)
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        dicsynth.Renderer(backend="cpu", device="0")
    assert [str(w.message) for w in said] == ['device 0 is not used: the CPU backend (backend="cpu") renders on the CPU, '
                                              'with no Vulkan device']


def test_defines_arrive_as_cli_and_sweep_values_do(tmp_path):
    """Python's defines follow -D's and the sweep's rule (scene/define_value.h): 3.0 is the Lua
    integer 3 (as the sweep gives it; "tex_" .. size named another file before), a float beyond
    2^53 stays a float, an int keeps its exact value, -0.0 its sign."""
    scene = write(str(tmp_path), "types.lua",
                  "camera = Camera.Pinhole { resolution = {8, 6}; focalLength = 0.01; pixelSize = {1e-4, 1e-4} }\n"
                  "assert(math.type(n) == kind, tostring(n) .. ' is ' .. tostring(math.type(n)))\n"
                  "assert('v' .. tostring(n) == want, tostring(n))\n")
    for value, kind, want in [(3.0, "integer", "3"), (np.float32(2.0), "integer", "2"), (0.5, "float", "0.5"),
                              (1e16, "float", "1e+16"), (2**53 + 1, "integer", "9007199254740993"),
                              (-0.0, "float", "-0.0")]:
        dicsynth.Scene(scene, defines={"n": value, "kind": kind, "want": "v" + want})
