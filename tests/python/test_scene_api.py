"""kasumi.Scene against the CLI: the same pixels, plan, probes and errors; arrays that view the
film, outlive the scene and are writable; Ctrl-C keeps the partial image."""
import _thread
import gc
import json
import os
import pathlib
import subprocess
import threading

import numpy as np
import pytest

import kasumi

ROOT = pathlib.Path(__file__).resolve().parents[2]
FOG = str(ROOT / "data" / "scenes" / "fog_height.json")
CLI = os.environ.get("KASUMI_CLI", str(ROOT / "build" / "ci" / "apps" / "kasumi"))
# fog_height at a small size: surfaces, a height fog, shadow rays and every AOV.
RES = {"/film/width": 48, "/film/height": 27}


def cli(*args, check=True):
    return subprocess.run([CLI, *args], capture_output=True, text=True, check=check)


def small_fog():
    scene = kasumi.Scene.load(FOG)
    for pointer, value in RES.items():
        scene.set(pointer, value)
    return scene


def bits(a):
    return np.ascontiguousarray(a, dtype=np.float32).view(np.uint32)


def fog_dict():
    return {
        "camera": {"position": [0, 1, 5], "look_at": [0, 0.5, 0], "fov_deg": 50},
        "film": {"width": 16, "height": 12, "spp": 2},
        "materials": {"grey": {"type": "phong", "kd": 0.5, "ks": 0.0}},
        "shapes": [{"type": "quad", "material": "grey",
                    "vertices": [[-3, 0, 3], [3, 0, 3], [3, 0, -3], [-3, 0, -3]]}],
        "lights": [{"type": "directional", "direction": [0.3, -1, 0.2],
                    "illuminance_lux": 1000}],
        "render": {"seed": 7},
    }


def test_render_equals_the_cli_exr_bit_for_bit(tmp_path):
    out = tmp_path / "cli.exr"
    cli("render", FOG, "--res", "48x27", "--spp", "3", "--seed", "11", "-o", str(out),
        "--no-preview", "-q")
    channels, metadata = kasumi.read_exr(str(out))
    result = small_fog().render(spp=3, seed=11)
    arrays = {"R": result.beauty[..., 0], "G": result.beauty[..., 1],
              "B": result.beauty[..., 2], "A": result.alpha[..., 0],
              "depth.Z": result.depth[..., 0]}
    for aov in ("albedo", "surface", "volume", "transmittance"):
        for c, name in enumerate("RGB"):
            arrays[f"{aov}.{name}"] = getattr(result, aov)[..., c]
    assert sorted(arrays) == sorted(channels)
    for name, array in arrays.items():
        assert np.array_equal(bits(array), bits(channels[name])), name
    assert float(result.volume.sum()) > 0.0  # the fog is in the picture
    assert metadata["spp"] == "3" and metadata["seed"] == "11"

    # The module's own EXR: the same pixels and the same metadata keys as the CLI's.
    ours = tmp_path / "ours.exr"
    result.write_exr(str(ours))
    our_channels, our_metadata = kasumi.read_exr(str(ours))
    assert sorted(our_metadata) == sorted(metadata)
    for key in ("scene", "spp", "seed", "frame", "units", "interrupted", "plan/ran",
                "stats/camera_rays", "stats/volume_steps"):
        assert our_metadata[key] == metadata[key], key
    for name in channels:
        assert np.array_equal(bits(our_channels[name]), bits(channels[name])), name


def test_stats_and_times():
    result = small_fog().render(spp=2, seed=1)
    assert result.beauty.shape == (27, 48, 3) and result.beauty.dtype == np.float32
    assert result.depth.shape == (27, 48, 1)
    assert result.aovs == ["beauty", "alpha", "albedo", "depth", "surface", "volume",
                           "transmittance"]
    assert result.stats["camera_rays"] == 48 * 27 * 2
    assert result.stats["volume_rays"] > 0  # the fog ran the volume stage
    assert {"load", "build", "render"} <= set(result.times)
    assert not result.interrupted


def test_arrays_view_the_film_without_copies():
    result = small_fog().render(spp=1)
    a, b = result.beauty, result.beauty
    assert not a.flags.owndata and np.shares_memory(a, b)
    a[3, 4, 1] = 12345.0
    assert result.beauty[3, 4, 1] == 12345.0  # writable, and every view sees the write


def test_arrays_outlive_the_scene_and_the_result():
    scene = small_fog()
    result = scene.render(spp=1)
    beauty, depth = result.beauty, result.depth
    expected = beauty.copy(), depth.copy()
    del scene, result
    gc.collect()
    assert np.array_equal(beauty, expected[0]) and np.array_equal(depth, expected[1])
    beauty += 1.0  # still our memory to write
    assert float(beauty.sum()) > 0.0


def test_threads_do_not_change_the_image():
    scene = small_fog()
    one = scene.render(spp=2, threads=1)
    two = scene.render(spp=2, threads=2)
    for aov in one.aovs:
        assert np.array_equal(bits(getattr(one, aov)), bits(getattr(two, aov))), aov


def test_set_creates_missing_parents_and_the_render_uses_them():
    scene = kasumi.Scene.from_dict(fog_dict())
    clear = scene.render()
    assert np.all(clear.transmittance == 1.0)
    # No "media" key at all: "/media/-" creates the array and appends, as --set does.
    scene.set("/media/-", {"type": "homogeneous", "bounds": [[-4, -1, -4], [4, 3, 4]],
                           "sigma_a": 0.05, "sigma_s": 0.2})
    assert len(scene.document()["media"]) == 1
    stages = {s["name"]: s for s in scene.plan()["stages"]}
    assert any(s["enabled"] for name, s in stages.items() if "volume" in name)
    foggy = scene.render()
    assert float(foggy.transmittance.max()) < 1.0
    assert float(foggy.volume.sum()) > 0.0


def test_plan_is_the_cli_plan():
    plan = json.loads(cli("plan", FOG, "--json").stdout)
    assert kasumi.Scene.load(FOG).plan() == plan


def test_a_bad_value_raises_scene_error_naming_file_and_pointer():
    scene = small_fog()
    scene.set("/media/0/phase/g", 1.2)
    with pytest.raises(kasumi.SceneError) as error:
        scene.render()
    message = str(error.value)
    assert isinstance(error.value, ValueError)
    assert FOG in message and "/media/0/phase/g" in message
    # The CLI's message, word for word.
    run = cli("check", FOG, "--set", "/media/0/phase/g=1.2", check=False)
    assert run.returncode == 3
    assert message in run.stderr


def test_set_refuses_what_set_refuses_and_keeps_the_scene():
    scene = small_fog()
    with pytest.raises(kasumi.SceneError, match="/shapes/99"):
        scene.set("/shapes/99/name", "x")  # an index past the end
    with pytest.raises(ValueError):
        scene.set("/film/spp", float("nan"))  # JSON has no NaN
    assert scene.document()["film"]["width"] == 48


def test_missing_and_unwritable_files_raise_os_errors(tmp_path):
    with pytest.raises(FileNotFoundError):
        kasumi.Scene.load(str(tmp_path / "no_such_scene.json"))
    result = kasumi.Scene.from_dict(fog_dict()).render()
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(OSError):
        result.write_exr(str(blocker / "out.exr"))  # a directory that is a file
    with pytest.raises(OSError):
        result.write_png(str(blocker / "out.png"))


def test_write_png(tmp_path):
    result = kasumi.Scene.from_dict(fog_dict()).render()
    png = tmp_path / "out.png"
    result.write_png(str(png))
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_probes_report_what_the_cli_reports():
    scene = small_fog()
    at = ["--set", "/film/width=48", "--set", "/film/height=27"]
    cases = [
        (scene.probe_radiance([0, 45, 120], [0, -0.1, -1], 16),
         ["radiance", FOG, "--origin", "0,45,120", "--direction", "0,-0.1,-1", "--spp", "16"]),
        (scene.probe_transmittance([0, 5, 0], [0, 5, -100], "ratio", 64),
         ["transmittance", FOG, "--from", "0,5,0", "--to", "0,5,-100", "--estimator",
          "ratio", "--samples", "64"]),
        (scene.probe_illuminance([0, 0.01, 0], [0, 1, 0]),
         ["illuminance", FOG, "--at", "0,0.01,0", "--normal", "0,1,0"]),
    ]
    for ours, args in cases:
        assert ours == json.loads(cli("probe", *args, *at).stdout), args[0]
    with pytest.raises(ValueError):
        scene.probe_radiance([0, 0, 0], [0, 0, 0])


def test_ctrl_c_raises_keyboard_interrupt_with_the_partial_image():
    scene = small_fog()
    # Hours of samples: only the interrupt can end this render.
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt) as interrupt:
            scene.render(spp=1 << 20)
    finally:
        timer.cancel()
    partial = interrupt.value.result
    assert partial.interrupted
    assert partial.beauty.shape == (27, 48, 3)
