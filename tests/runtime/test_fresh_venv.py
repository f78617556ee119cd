"""A robot's install: the generated K10 package and the runtime pip-installed into a fresh
venv (no system site-packages) that can import cyclonedds and nothing of the compiler
(lark, jinja2, jsonschema, yaml, rapidgen are shown not importable). Run from outside the
checkout with CYCLONEDDS_URI unset, the bridge finds its QoS files in the installed
package, stays on loopback (the package's "local" transport) and answers a command."""
import os
import subprocess
import sys
import venv
from pathlib import Path

ROOT = Path(__file__).parents[2]
DOMAIN = 125


def test_installed_package_and_runtime_run_the_bridge_without_the_compiler(tmp_path):
    env_dir = tmp_path / "venv"
    venv.EnvBuilder(system_site_packages=False, with_pip=False).create(env_dir)
    py = env_dir / "bin" / "python"
    site = next((env_dir / "lib").glob("python*")) / "site-packages"
    # cyclonedds alone, by path: a folder holding links to it and its bundled libraries only.
    import cyclonedds
    dds_dir = Path(cyclonedds.__file__).parent
    only = tmp_path / "cyclonedds-only"
    only.mkdir()
    for name in ("cyclonedds", "cyclonedds.libs"):
        if (dds_dir.parent / name).exists():
            (only / name).symlink_to(dds_dir.parent / name)
    (site / "cyclonedds_only.pth").write_text(str(only) + "\n")
    res = subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target", str(site),
                          str(ROOT / "runtime"), str(ROOT / "generated" / "k10" / "python")],
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr[-3000:]
    work = tmp_path / "robot"
    work.mkdir()
    env = {k: v for k, v in os.environ.items() if k not in ("CYCLONEDDS_URI", "PYTHONPATH")}
    env["PYTHONNOUSERSITE"] = "1"
    probe = subprocess.run([str(py), "-c", (
        "import importlib.util as u, rapid_runtime, rapid_k10red\n"
        "print([m for m in ('lark', 'jinja2', 'jsonschema', 'yaml', 'rapidgen') if u.find_spec(m)])\n"
        "print(rapid_runtime.__file__, rapid_k10red.__file__)\n")], cwd=work, env=env, capture_output=True,
        text=True, timeout=60)
    assert probe.returncode == 0, probe.stderr
    missing, where = probe.stdout.splitlines()[:2]
    assert missing == "[]" and str(ROOT) not in where and str(site) in where
    bridge = subprocess.Popen([str(py), "-m", "rapid_k10red.bridge", "--simulate", "--domain", str(DOMAIN)],
                              cwd=work, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert bridge.stdout.readline().startswith("bridge ready: asset K10Red")
        ground = subprocess.run([str(py), "-c", (
            "import os\n"
            "from rapid_k10red import rapid\n"
            "from rapid_k10red.qos import RapidQos\n"
            "from rapid_runtime.dds import use_transport\n"
            "from rapid_runtime.commander import Commander\n"
            "q = RapidQos(); use_transport(q, None); print(os.environ['CYCLONEDDS_URI'])\n"
            f"c = Commander(rapid, q, 'K10Red', 'RapidWorkbench', {DOMAIN})\n"
            "assert c.wait_for_asset(15)\n"
            "print(c.wait_final(c.send('AccessControl', 'requestControl'), 10)[-1])\n"
            "print(c.wait_final(c.send('Admin', 'echo', [('RAPID_STRING', 'from a robot')]), 10)[-1])\n")],
            cwd=work, env=env, capture_output=True, text=True, timeout=90)
    finally:
        bridge.terminate()
        err = bridge.communicate(timeout=20)[1]
    assert ground.returncode == 0, ground.stderr[-3000:] + err[-2000:]
    uri, control, echo = ground.stdout.splitlines()[:3]
    assert uri.endswith("rapid_k10red/qos_files/cyclonedds/local.xml") and str(site) in uri
    assert "ACK_COMPLETED_OK" in control and "'from a robot'" in echo and "ACK_COMPLETED_OK" in echo
