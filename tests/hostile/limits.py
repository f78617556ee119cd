"""Run rapidgen (or a snippet of Python) in a child process under hard resource limits.

The limits are set with `resource.setrlimit` in the child before it starts: a case that
blows past them is killed by the kernel (SIGKILL/SIGXCPU, MemoryError), and the test sees
that as a failure. Tests never assert on wall time; the CPU limit is only a fence.
"""
from __future__ import annotations

import os
import resource
import subprocess
import sys
from dataclasses import dataclass

MiB = 1024 * 1024


@dataclass
class Limited:
    code: int  # negative: killed by that signal
    out: str
    err: str

    @property
    def killed(self) -> bool:
        return self.code < 0


def _limits(mem_mib: int, cpu_s: int):
    def apply() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (mem_mib * MiB, mem_mib * MiB))
        resource.setrlimit(resource.RLIMIT_CPU, (cpu_s, cpu_s + 1))
    return apply


def run_rapidgen(*args: str, cwd: str | os.PathLike | None = None, mem_mib: int = 1024,
                 cpu_s: int = 30) -> Limited:
    """`rapidgen ARGS` in a child bounded to mem_mib of address space and cpu_s CPU seconds."""
    return _run([sys.executable, "-m", "rapidgen", *args], cwd, mem_mib, cpu_s)


def run_python(code: str, cwd: str | os.PathLike | None = None, mem_mib: int = 1024,
               cpu_s: int = 30) -> Limited:
    """`python -c CODE` in a bounded child (for library calls such as Codec.decode)."""
    return _run([sys.executable, "-c", code], cwd, mem_mib, cpu_s)


def _run(argv: list[str], cwd, mem_mib: int, cpu_s: int) -> Limited:
    env = dict(os.environ, PYTHONHASHSEED="0")
    proc = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True, errors="replace",
                          preexec_fn=_limits(mem_mib, cpu_s), timeout=cpu_s * 4 + 30)
    return Limited(proc.returncode, proc.stdout, proc.stderr)
