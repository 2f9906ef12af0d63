"""The example study (python/examples/speed_accuracy.py) at a small size:
it writes its plot, its self-contained report and its results, and the
error it measures falls as samples grow, as it must for an unbiased
estimator against a converged reference."""
import json
import subprocess
import sys


def test_speed_accuracy_study(source_dir, tmp_path):
    out = tmp_path / "study"
    subprocess.run([sys.executable, str(source_dir / "python" / "examples" / "speed_accuracy.py"),
                    str(source_dir / "scenes" / "cornell-box.pbrt"), "--out", str(out), "--integrators", "path",
                    "bdpt", "--spp", "1", "16", "--maxdepth", "5", "--resolution", "32", "32",
                    "--reference-spp", "256"], check=True)
    png = (out / "error-vs-time.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10000
    page = (out / "report.html").read_text()
    assert page.count("data:image/png;base64,") == 2 + 4  # plot, reference, one per render
    assert "http:" not in page and "https:" not in page  # self-contained
    results = json.loads((out / "results.json").read_text())["results"]
    assert len(results) == 4
    for integrator in ("path", "bdpt"):
        err = {r["spp"]: r["relmse"] for r in results if r["integrator"] == integrator}
        # 16 times the samples: about a sixteenth of the variance; a third
        # leaves room for the reference's own noise.
        assert err[16] < err[1] / 3, err
