"""`rapidgen secure DEPLOYMENT -k KEYSTORE`: the DDS Security keystore of a deployment
(docs/secure.md). `--check` reports expired and soon-expiring certificates and grants out
of date instead of writing. Exit 0, 1 (input errors, or --check found an error), 2 usage."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from rapidgen.diagnostics import DiagnosticSink, FileLineCache, escaped, render


def add_parser(sub) -> None:
    p = sub.add_parser("secure", help="DDS Security keystore (certificates, signed governance and permissions) "
                       "from asset descriptors and a deployment file",
                       description="Create or bring up to date a DDS Security keystore (SROS2-like layout): "
                       "an identity CA and a permissions CA, a key and certificate per asset and ground tool, "
                       "governance.xml and one permissions.xml per participant, both S/MIME-signed.")
    p.add_argument("deployment", help="deployment YAML: assets (descriptor paths) and ground tools")
    p.add_argument("-k", "--keystore", required=True, help="keystore folder (created when missing)")
    p.add_argument("--rotate", action="store_true", help="issue a new key and certificate to every participant")
    p.add_argument("--check", action="store_true",
                   help="write nothing: report expired or soon-expiring certificates and stale grants")
    p.add_argument("--warn-days", type=int, default=30, metavar="N",
                   help="with --check: warn about certificates expiring within N days (default 30)")


def _report(sink: DiagnosticSink) -> None:
    lines = FileLineCache()
    for d in sink.sorted():
        print(render(d, lines), file=sys.stderr)


def run(args: argparse.Namespace) -> int:
    try:
        from rapidgen.secure import keystore
    except ImportError as exc:  # cryptography missing
        print(f"rapidgen secure: needs the 'cryptography' package ({escaped(str(exc))}); "
              "pip install 'rapidgen[secure]'", file=sys.stderr)
        return 1
    from rapidgen.asset.load import load_asset
    from rapidgen.secure.deploy import load_deployment

    sink = DiagnosticSink()
    dep = load_deployment(args.deployment, sink, load_asset)
    _report(sink)
    if dep is None:
        return 1
    root = Path(args.keystore)
    if args.check:
        if not root.is_dir():
            print(f"{escaped(str(root))}: error: no keystore here (run rapidgen secure without --check)",
                  file=sys.stderr)
            return 1
        findings = keystore.check(root, dep, args.warn_days)
        for f in findings:
            print(f"{escaped(str(root / f.file))}: {f.severity}: {escaped(f.message)}", file=sys.stderr)
        errors = sum(f.severity == "error" for f in findings)
        print(f"keystore {escaped(str(root))}: {errors} error(s), {len(findings) - errors} warning(s)")
        return 1 if errors else 0
    try:
        out = keystore.build(dep, root, rotate=args.rotate)
    except keystore.KeystoreError as exc:
        print(f"{escaped(str(root))}: error: {escaped(str(exc))}", file=sys.stderr)
        return 1
    except OSError as exc:
        print(f"{escaped(str(exc.filename or root))}: error: {escaped(exc.strerror or str(exc))}", file=sys.stderr)
        return 1
    for what, items in (("created", out.created), ("updated", out.updated)):
        for item in items:
            print(f"{what}: {escaped(item)}")
    for name in out.strangers:
        print(f"left alone: enclaves/{escaped(name)} (not in the deployment)")
    for what in out.withdrawn:
        print(f"withdrawn: {escaped(what)}")
    if out.new_cas:
        why = "--rotate" if args.rotate else "grants withdrawn"
        print(f"new {' and '.join(out.new_cas)} ({why}): every enclave handed out before now fails against the new "
              "ones; hand out every participant's enclave folder again (docs/secure.md, \"Rotation and withdrawn "
              "grants\")")
    print(f"keystore {escaped(str(root))}: {len(dep.assets)} asset(s), {len(dep.tools)} ground tool(s); "
          f"{len(out.created)} created, {len(out.updated)} updated, {len(out.kept)} kept")
    return 0
