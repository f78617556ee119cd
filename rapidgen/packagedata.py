"""Files shipped inside rapidgen's packages (the IDL grammar, the schemas, the QoS library)."""
from __future__ import annotations

import os
import sys


def read_text(package: str, name: str) -> str:
    """The text of `name` in `package` (already imported): read from the folder beside the
    package's modules, which imports nothing; through importlib.resources (~5 ms of imports,
    zipfile among them) only for a package not on the file system."""
    where = getattr(sys.modules.get(package), "__file__", None)
    if where:
        try:
            with open(os.path.join(os.path.dirname(where), name), encoding="utf-8") as f:
                return f.read()
        except OSError:
            pass
    from importlib import resources
    return resources.files(package).joinpath(name).read_text(encoding="utf-8")
