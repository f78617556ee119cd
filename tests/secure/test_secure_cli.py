"""`rapidgen secure` (issue 24): the keystore's layout and modes, signatures that verify
with OpenSSL, grants that agree with the descriptors' access_control by construction,
reuse and --check, and located deployment errors."""
from __future__ import annotations

import itertools
import os
import shutil
import stat
import subprocess
from pathlib import Path

import pytest

from cryptography import x509

from rapidgen.secure import pki, xmldocs
from tests.secure.conftest import DEPLOYMENT, DOMAIN, ROOT, secure, secure_process, write_deployment

SEEDS = ["k10", "chariot", "athlete", "xarm2", "robonaut2", "eva-suit"]
ENCLAVE_FILES = {"cert.pem", "key.pem", "identity_ca.cert.pem", "permissions_ca.cert.pem", "governance.p7s",
                 "permissions.xml", "permissions.p7s", "cyclonedds-security.xml"}


def test_layout_is_sroslike_and_owner_only(keystores):
    ks = keystores["main"]
    assert {p.name for p in (ks / "public").iterdir()} == {"identity_ca.cert.pem", "permissions_ca.cert.pem"}
    assert {p.name for p in (ks / "private").iterdir()} == {"identity_ca.key.pem", "permissions_ca.key.pem"}
    names = {"K10Red", "Chariot", "RapidWorkbench", "ChariotCrewDisplay", "ScienceBackroom", "Outsider", "Conformance"}
    assert {p.name for p in (ks / "enclaves").iterdir() if p.is_dir()} == names
    for name in names:  # an asset's enclave also lists the ground tools' identities (cmdSrc's binding)
        extra = {"identities.txt"} if name in ("K10Red", "Chariot") else set()
        assert {p.name for p in (ks / "enclaves" / name).iterdir()} == ENCLAVE_FILES | extra
    for path in [ks, *ks.rglob("*")]:
        mode = stat.S_IMODE(path.stat().st_mode)
        assert mode == (0o700 if path.is_dir() else 0o600), (path, oct(mode))


@pytest.mark.parametrize("name", ["K10Red", "RapidWorkbench"])
def test_signed_files_verify_with_openssl_against_the_permissions_ca(keystores, name):
    enclave = keystores["main"] / "enclaves" / name
    for signed, xml in (("permissions.p7s", "permissions.xml"), ("governance.p7s", "../governance.xml")):
        res = subprocess.run(["openssl", "smime", "-verify", "-in", str(enclave / signed), "-CAfile",
                              str(enclave / "permissions_ca.cert.pem"), "-text"], capture_output=True)
        assert res.returncode == 0, res.stderr
        assert res.stdout.replace(b"\r\n", b"\n") == (enclave / xml).read_bytes()
        res = subprocess.run(["openssl", "smime", "-verify", "-in", str(enclave / signed), "-CAfile",
                              str(enclave / "identity_ca.cert.pem")], capture_output=True)
        assert res.returncode != 0  # the identity CA did not sign it
    res = subprocess.run(["openssl", "verify", "-CAfile", str(enclave / "identity_ca.cert.pem"),
                          str(enclave / "cert.pem")], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr


def test_grants_by_topic_and_partition(keystores):
    enclaves = keystores["main"] / "enclaves"
    d = str(DOMAIN)

    def grants(name):
        return xmldocs.read_grants((enclaves / name / "permissions.xml").read_bytes())
    k10 = grants("K10Red")
    assert k10["subscribe"] == {(d, "rapid_command", "K10Red")}
    assert (d, "rapid_ack", "K10Red") in k10["publish"] and (d, "rapid_command", "K10Red") not in k10["publish"]
    assert {p for _, _, p in k10["publish"]} == {"K10Red"}
    wb = grants("RapidWorkbench")
    assert {(t, p) for _, t, p in wb["publish"]} == {("rapid_command", "K10Red")}
    assert (d, "rapid_ack", "Chariot") in wb["subscribe"]  # watches every asset
    assert grants("Outsider")["publish"] == set()
    assert (d, "rapid_command", "K10Red") in wb["subscribe"]  # it audits K10: reads every commander's
    assert (d, "rapid_command", "K10Red") not in grants("ScienceBackroom")["subscribe"]  # others' commands: auditors
    assert (d, "rapid_command", "K10Red") in grants("Conformance")["subscribe"]
    # ScienceBackroom asked for every asset: K10's list admits it, Chariot's does not
    assert {(t, p) for _, t, p in grants("ScienceBackroom")["publish"]} == {("rapid_command", "K10Red")}


def _runtime_allows(loaded, source: str) -> bool:
    """The Python runtime's own allow-list (runtime/rapid_runtime/access.py) asked about every
    command of the asset but the always-allowed stopAllMotion: does it let `source` run any?"""
    from rapid_runtime.access import allowed, always_allowed
    from rapid_runtime.tables import AccessRule, AccessSpec
    acc = loaded.access
    spec = None if acc is None else AccessSpec(acc.default, tuple(AccessRule(r.source, r.allow) for r in acc.rules))
    return any(allowed(spec, source, s.name, c.name) for s in loaded.subsystems
               for c in loaded.types[s.type].commands if not always_allowed(s.type, c.name))


def test_command_grants_agree_with_every_seeds_access_control(tmp_path):
    """Every source any seed names (and one none does), each asking to command every asset:
    the keystore grants rapid_command in an asset's partition exactly when the runtime's
    allow-list would run one of its commands from that source."""
    from rapidgen.asset.load import load_asset
    from rapidgen.diagnostics import DiagnosticSink
    assets = {s: load_asset(str(ROOT / "specs" / "assets" / f"{s}.yaml"), DiagnosticSink()) for s in SEEDS}
    sources = sorted({r.source for a in assets.values() if a.access for r in a.access.rules} | {"Nobody"})
    dep = tmp_path / "deploy.yaml"
    dep.write_text("version: 1\nassets: [" + ", ".join(str(ROOT / "specs" / "assets" / f"{s}.yaml") for s in SEEDS) +
                   "]\nground:\n" + "".join(f'  - {{source: {s}, command: ["*"]}}\n' for s in sources))
    res = secure(str(dep), "-k", str(tmp_path / "ks"))
    assert res.returncode == 0, res.stderr
    checked = 0
    for source, (seed, loaded) in itertools.product(sources, assets.items()):
        granted = xmldocs.read_grants((tmp_path / "ks" / "enclaves" / source / "permissions.xml").read_bytes())
        partition = loaded.spec.partition or loaded.spec.name
        has = any(t == "rapid_command" and p == partition for _, t, p in granted["publish"])
        assert has == (bool(loaded.command_topic) and _runtime_allows(loaded, source)), (source, seed)
        checked += has
    assert checked >= 8  # the seeds do grant (RapidWorkbench on most; each seed's own tools)


def test_second_run_keeps_everything_and_check_passes(tmp_path):
    dep = write_deployment(tmp_path)
    ks = tmp_path / "ks"
    first = secure_process(str(dep), "-k", str(ks))  # the real command, once
    assert first.returncode == 0 and "created: identity_ca" in first.stdout
    before = {p: p.read_bytes() for p in ks.rglob("*") if p.is_file()}
    again = secure(str(dep), "-k", str(ks))
    assert again.returncode == 0 and "0 created, 0 updated" in again.stdout
    assert {p: p.read_bytes() for p in ks.rglob("*") if p.is_file()} == before
    check = secure(str(dep), "-k", str(ks), "--check")
    assert check.returncode == 0 and "0 error(s), 0 warning(s)" in check.stdout
    for out in (first, again, check):  # keys are never printed
        assert "PRIVATE KEY" not in out.stdout + out.stderr
    # rotation: a new trust generation: new CAs, keys and certificates, everything re-signed
    rot = secure(str(dep), "-k", str(ks), "--rotate")
    assert rot.returncode == 0 and "updated: RapidWorkbench/cert.pem" in rot.stdout
    assert "new identity_ca and permissions_ca (--rotate): every enclave handed out before now fails" in rot.stdout
    assert (ks / "enclaves" / "K10Red" / "key.pem").read_bytes() != before[ks / "enclaves" / "K10Red" / "key.pem"]
    for ca in ("identity_ca", "permissions_ca"):
        assert (ks / "private" / f"{ca}.key.pem").read_bytes() != before[ks / "private" / f"{ca}.key.pem"]
    new_ca = pki.load_pair(ks / "public" / "identity_ca.cert.pem", ks / "private" / "identity_ca.key.pem").cert
    old_cert = x509.load_pem_x509_certificate(before[ks / "enclaves" / "RapidWorkbench" / "cert.pem"])
    assert not pki.issued_by(old_cert, new_ca)  # the old enclave no longer authenticates
    perm_ca = pki.load_pair(ks / "public" / "permissions_ca.cert.pem", ks / "private" / "permissions_ca.key.pem").cert
    assert pki.smime_content(before[ks / "enclaves" / "RapidWorkbench" / "permissions.p7s"], perm_ca) is None
    check = secure(str(dep), "-k", str(ks), "--check")
    assert check.returncode == 0 and "0 error(s), 0 warning(s)" in check.stdout, check.stderr
    assert "0 created, 0 updated" in secure(str(dep), "-k", str(ks)).stdout  # and it stays


def test_check_warns_before_expiry_and_fails_when_stale(tmp_path):
    dep = write_deployment(tmp_path, DEPLOYMENT.replace("version: 1\n", "version: 1\nvalidity_days: 20\n"))
    ks = tmp_path / "ks"
    assert secure(str(dep), "-k", str(ks)).returncode == 0
    soon = secure(str(dep), "-k", str(ks), "--check")  # 20 days < the 30-day warning
    assert soon.returncode == 0, soon.stderr
    assert "enclaves/K10Red/cert.pem: warning: expires on" in soon.stderr
    assert "0 error(s), 7 warning(s)" in soon.stdout
    assert "warning" not in secure(str(dep), "-k", str(ks), "--check", "--warn-days", "5").stderr
    # the deployment grows: the grants on disk no longer say what it says
    write_deployment(tmp_path, DEPLOYMENT.replace("{source: Outsider, watch: [K10Red]}",
                                                  "{source: Outsider, watch: [K10Red, Chariot]}"))
    stale = secure(str(dep), "-k", str(ks), "--check", "--warn-days", "5")
    assert stale.returncode == 1
    assert "enclaves/Outsider/permissions.xml: error: not what the deployment and descriptors grant" in stale.stderr


def test_check_reports_an_expired_certificate(keystores, tmp_path):
    ks = tmp_path / "ks"
    shutil.copytree(keystores["main"], ks)
    shutil.copy(keystores["variants"] / "expired" / "cert.pem", ks / "enclaves" / "RapidWorkbench" / "cert.pem")
    shutil.copy(keystores["variants"] / "expired" / "key.pem", ks / "enclaves" / "RapidWorkbench" / "key.pem")
    res = secure(str(keystores["deployment"]), "-k", str(ks), "--check")
    assert res.returncode == 1
    assert "enclaves/RapidWorkbench/cert.pem: error: expired on" in res.stderr
    # the next run replaces it
    assert "updated: RapidWorkbench/cert.pem" in secure(str(keystores["deployment"]), "-k", str(ks)).stdout


@pytest.mark.parametrize("edit, at, message", [
    (("version: 1", "version: 2"), ("version: 2", 9), "version must be 1"),
    (("command: [K10Red]", "command: [K10Reed]"), "K10Reed", "no asset 'K10Reed' in this deployment"),
    (("{source: Outsider, watch: [K10Red]}", "{source: Outsider, command: [K10Red]}"), ("Outsider, command: [", 20),
     "K10Red's access_control does not admit source 'Outsider'"),
    (("{source: Outsider, watch: [K10Red]}", "{source: Outsider, wach: [K10Red]}"), "wach", "unknown key 'wach'"),
    (("{source: Outsider,", "{source: RapidWorkbench,"), "RapidWorkbench, watch",
     "'RapidWorkbench' names two participants"),
    (("{source: Outsider,", "{source: ../evil,"), "../evil", "a ground tool needs a source"),
    (("{source: Outsider,", "{source: '..',"), "'..'", "a ground tool needs a source"),
    (("{source: Outsider,", "{source: .,"), "., watch", "a ground tool needs a source"),
    (("{source: Outsider,", "{source: '...',"), "'...'", "a ground tool needs a source"),
    (("{source: Outsider,", "{source: 'a/b',"), "'a/b'", "a ground tool needs a source"),
    (("{source: Outsider,", "{source: '',"), "'',", "a ground tool needs a source"),
    (("domains: [124]", "domains: [999]"), "[999]", "domains must be a non-empty list"),
])
def test_deployment_errors_are_located(tmp_path, edit, at, message):
    """Each error at the line and column of what is wrong (`at`: the text there, or the text
    before it and how far)."""
    text = DEPLOYMENT.replace("domains: [{domain}]", f"domains: [{DOMAIN}]").replace(*edit)
    assert text != DEPLOYMENT
    dep = write_deployment(tmp_path, text)
    text = dep.read_text()
    needle, offset = at if isinstance(at, tuple) else (at, 0)
    where = text.index(needle) + offset
    line, col = text.count("\n", 0, where) + 1, where - text.rfind("\n", 0, where)
    res = secure(str(dep), "-k", str(tmp_path / "ks"))
    assert res.returncode == 1
    assert f"deploy.yaml:{line}:{col}: error[RG2001]: {message}" in res.stderr, res.stderr
    assert "Traceback" not in res.stderr
    assert "^" in res.stderr  # the line shown, the place marked
    assert not (tmp_path / "ks").exists()  # nothing written


def test_hint_says_how_to_admit_a_source(tmp_path):
    dep = write_deployment(tmp_path, DEPLOYMENT.replace("{source: Outsider, watch: [K10Red]}",
                                                        "{source: Outsider, command: [K10Red]}"))
    res = secure(str(dep), "-k", str(tmp_path / "ks"))
    assert "add {source: Outsider, allow: [...]} to" in res.stderr and "k10.yaml's access_control" in res.stderr


def test_descriptor_errors_are_reported_at_the_descriptor(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("version: 1\nasset: {name: X, kind: rover}\nsubsystems: [{name: Nope}]\n")
    dep = tmp_path / "deploy.yaml"
    dep.write_text(f"version: 1\nassets: [{bad}]\n")
    res = secure(str(dep), "-k", str(tmp_path / "ks"))
    assert res.returncode == 1 and "bad.yaml:3:" in res.stderr and "deploy.yaml:2:10: error[RG2001]" in res.stderr


def test_an_unusable_ca_is_an_error_not_a_traceback(tmp_path):
    dep = write_deployment(tmp_path)
    ks = tmp_path / "ks"
    assert secure(str(dep), "-k", str(ks)).returncode == 0
    other = tmp_path / "other"
    assert secure(str(dep), "-k", str(other)).returncode == 0
    shutil.copy(other / "private" / "identity_ca.key.pem", ks / "private" / "identity_ca.key.pem")
    os.chmod(ks / "private" / "identity_ca.key.pem", 0o600)
    res = secure(str(dep), "-k", str(ks))
    assert res.returncode == 1 and "identity_ca: identity_ca.key.pem is not the key of identity_ca.cert.pem" in res.stderr
    assert "Traceback" not in res.stderr


def test_the_teams_own_ca_is_used(tmp_path):
    """A team that has its own CAs puts them in public/ and private/ first: they are kept."""
    dep = write_deployment(tmp_path)
    theirs = tmp_path / "theirs"
    assert secure(str(dep), "-k", str(theirs)).returncode == 0
    ks = tmp_path / "ks"
    for sub in ("public", "private"):
        shutil.copytree(theirs / sub, ks / sub)
    res = secure(str(dep), "-k", str(ks))
    assert res.returncode == 0 and "created: identity_ca" not in res.stdout
    assert (ks / "public" / "identity_ca.cert.pem").read_bytes() == (theirs / "public" / "identity_ca.cert.pem").read_bytes()
    assert Path(ks / "enclaves" / "K10Red" / "identity_ca.cert.pem").read_bytes() == \
        (theirs / "public" / "identity_ca.cert.pem").read_bytes()



@pytest.mark.parametrize("escape", ["\\t", "\\x01", "\\n", "\\x7f"])
def test_a_source_with_a_control_character_is_refused_where_it_is(tmp_path, escape):
    dep = write_deployment(tmp_path, DEPLOYMENT.replace("{source: Outsider,", f'{{source: "Out{escape}sider",'))
    res = secure(str(dep), "-k", str(tmp_path / "ks"))
    assert res.returncode == 1 and "deploy.yaml:8:14: error[" in res.stderr, res.stderr
    assert "Traceback" not in res.stderr and not (tmp_path / "ks").exists()


def _variant(tmp_path: Path, name: str, **dds) -> Path:
    """K10's descriptor under another asset name, its dds section changed."""
    import yaml
    k10 = ROOT / "specs" / "assets" / "k10.yaml"
    data = yaml.safe_load(k10.read_text(encoding="utf-8"))
    data["idl"] = {"rapid": str(k10.parent / data["idl"]["rapid"]), "files": [str(k10.parent / f) for f in data["idl"]["files"]]}
    data["asset"]["name"] = name
    data["dds"].update(dds)
    path = tmp_path / f"{name.lower()}.yaml"
    path.write_text(yaml.safe_dump(data), encoding="utf-8")
    return path


def test_two_assets_sharing_a_partition_on_a_domain_are_refused(tmp_path):
    """Issue 35 item 2: Evil's descriptor says partition K10Red; a grant to command Evil
    would be one to command K10 (and Evil's enclave would read K10's commands)."""
    evil = _variant(tmp_path, "Evil", partition="K10Red")
    k10 = ROOT / "specs" / "assets" / "k10.yaml"
    dep = tmp_path / "deploy.yaml"
    dep.write_text(f"version: 1\nassets: [{k10}, {evil}]\ndomains: [{DOMAIN}]\n"
                   "ground:\n  - {source: Mallory, command: [Evil]}\n")
    res = secure(str(dep), "-k", str(tmp_path / "ks"))
    assert res.returncode == 1
    col = dep.read_text().index(str(evil)) - dep.read_text().index("assets") + 1
    assert f"deploy.yaml:2:{col}: error[RG2002]: Evil uses partition 'K10Red', which is K10Red's, on domain " \
        f"{DOMAIN}" in res.stderr, res.stderr
    assert "^ a grant in that partition would cover K10Red's commands" in res.stderr
    assert "Traceback" not in res.stderr and not (tmp_path / "ks").exists()
    # each on its own domain (no domains: each asset's dds.domain): they never meet
    k10_domain = yaml_domain(k10)
    other = _variant(tmp_path, "Evil", partition="K10Red", domain=k10_domain + 1)
    dep.write_text(f"version: 1\nassets: [{k10}, {other}]\n")
    res = secure(str(dep), "-k", str(tmp_path / "ks"))
    assert res.returncode == 0, res.stderr


def yaml_domain(descriptor: Path) -> int:
    import yaml
    return int(yaml.safe_load(descriptor.read_text(encoding="utf-8"))["dds"]["domain"])


def test_a_partition_that_is_a_pattern_is_refused(tmp_path):
    """DDS Security matches permission partitions as patterns: 'K*' would grant K10Red's too."""
    import yaml
    k10 = ROOT / "specs" / "assets" / "k10.yaml"
    data = yaml.safe_load(k10.read_text(encoding="utf-8"))
    data["idl"] = {"rapid": str(k10.parent / data["idl"]["rapid"]), "files": [str(k10.parent / f) for f in data["idl"]["files"]]}
    data["asset"]["name"] = "Wild"
    data["dds"]["partition"] = "K*"
    bad = tmp_path / "wild.yaml"
    bad.write_text(yaml.safe_dump(data), encoding="utf-8")
    dep = tmp_path / "deploy.yaml"
    dep.write_text(f"version: 1\nassets: [{bad}]\n")
    res = secure(str(dep), "-k", str(tmp_path / "ks"))
    assert res.returncode == 1 and "deploy.yaml:2:10: error[RG2001]: Wild's partition 'K*' holds a DDS wildcard" \
        in res.stderr, res.stderr


def test_streams_are_granted_as_the_descriptors_declare(tmp_path):
    """Issue 35 item 5, seed 001: X-Arm-2 writes handPose (an output stream, its own
    partition), Robonaut 2 reads it (an input stream from XArm2's partition); nobody else."""
    dep = tmp_path / "deploy.yaml"
    dep.write_text(f"version: 1\nassets: [{ROOT / 'specs/assets/xarm2.yaml'}, {ROOT / 'specs/assets/robonaut2.yaml'}]\n"
                   f"domains: [{DOMAIN}]\nground:\n  - {{source: XArm2Span, command: [XArm2], watch: ['*'], "
                   "audit: ['*']}\n")
    res = secure(str(dep), "-k", str(tmp_path / "ks"))
    assert res.returncode == 0, res.stderr

    def grants(name):
        return xmldocs.read_grants((tmp_path / "ks" / "enclaves" / name / "permissions.xml").read_bytes())
    hand = (str(DOMAIN), "rapid_position_sample-handPose", "XArm2")
    xarm, r2, tool = grants("XArm2"), grants("Robonaut2"), grants("XArm2Span")
    assert hand in xarm["publish"] and hand not in xarm["subscribe"]
    assert hand in r2["subscribe"] and hand not in r2["publish"]
    assert hand not in tool["publish"] and hand not in tool["subscribe"]  # a stream is not a publication
    # and nothing else moved: Robonaut 2 still publishes only in its own partition
    assert {p for _, _, p in r2["publish"]} == {"Robonaut2"}
    assert {(t, p) for _, t, p in r2["subscribe"]} == {("rapid_command", "Robonaut2"),
                                                       ("rapid_position_sample-handPose", "XArm2")}


def test_smime_content_verifies_as_openssl_does(keystores, tmp_path):
    """pki.smime_content (what --check and every run use) against OpenSSL's own verdict:
    the keystore's files, another CA's, and one edited after signing."""
    ks, other = keystores["main"], keystores["other"]
    ca_file = ks / "public" / "permissions_ca.cert.pem"
    ca = x509.load_pem_x509_certificate(ca_file.read_bytes())
    edited = tmp_path / "edited.p7s"
    edited.write_bytes((ks / "enclaves" / "Outsider" / "permissions.p7s").read_bytes()
                       .replace(b"<partition>K10Red</partition>", b"<partition>Chariot</partition>"))
    cases = [ks / "enclaves" / "Outsider" / "permissions.p7s", ks / "enclaves" / "governance.p7s",
             other / "enclaves" / "Outsider" / "permissions.p7s", edited]
    verdicts = []
    for f in cases:
        res = subprocess.run(["openssl", "smime", "-verify", "-in", str(f), "-CAfile", str(ca_file), "-text"],
                             capture_output=True)
        ours = pki.smime_content(f.read_bytes(), ca)
        assert (ours is not None) == (res.returncode == 0), f
        if ours is not None:
            assert ours == res.stdout.replace(b"\r\n", b"\n")
        verdicts.append(ours is not None)
    assert verdicts == [True, True, False, False]


def test_withdrawn_grant_replaces_the_permissions_ca_and_check_reports_the_old_file(tmp_path):
    """Issue 35 item 3: ScienceBackroom's command grant withdrawn. The run makes a new
    permissions CA (Fast DDS 2.9 takes any permissions the CA it has signed while their
    validity lasts), so the old, validly signed permissions.p7s is refused everywhere;
    put back into the keystore, --check reports it and the next run replaces it."""
    dep = write_deployment(tmp_path)
    ks = tmp_path / "ks"
    assert secure(str(dep), "-k", str(ks)).returncode == 0
    sb = ks / "enclaves" / "ScienceBackroom"
    old_p7s, old_xml = (sb / "permissions.p7s").read_bytes(), (sb / "permissions.xml").read_bytes()
    old_ca = (ks / "public" / "permissions_ca.cert.pem").read_bytes()
    old_identity = (ks / "public" / "identity_ca.cert.pem").read_bytes()
    old_cert = (sb / "cert.pem").read_bytes()
    # a change that only adds grants keeps the CA
    write_deployment(tmp_path, DEPLOYMENT.replace("{source: Outsider, watch: [K10Red]}",
                                                  "{source: Outsider, watch: [K10Red, Chariot]}"))
    grown = secure(str(dep), "-k", str(ks))
    assert grown.returncode == 0 and "withdrawn:" not in grown.stdout and "new permissions_ca" not in grown.stdout
    assert (ks / "public" / "permissions_ca.cert.pem").read_bytes() == old_ca
    # the withdrawal
    write_deployment(tmp_path, DEPLOYMENT.replace("{source: ScienceBackroom, command: [\"*\"]}",
                                                  "{source: ScienceBackroom, watch: [\"*\"]}"))
    res = secure(str(dep), "-k", str(ks))
    assert res.returncode == 0, res.stderr
    assert "withdrawn: ScienceBackroom (publish rapid_command in K10Red on domain" in res.stdout
    assert "withdrawn: Outsider" in res.stdout  # Chariot again taken from it
    assert "new permissions_ca (grants withdrawn)" in res.stdout
    assert (ks / "public" / "permissions_ca.cert.pem").read_bytes() != old_ca
    assert (ks / "public" / "identity_ca.cert.pem").read_bytes() == old_identity  # certificates kept
    assert (sb / "cert.pem").read_bytes() == old_cert
    new_ca = x509.load_pem_x509_certificate((ks / "public" / "permissions_ca.cert.pem").read_bytes())
    assert pki.smime_content(old_p7s, new_ca) is None  # the old grant: another CA's now
    assert secure(str(dep), "-k", str(ks), "--check").returncode == 0
    # the old, validly signed file put back (with its XML, or without)
    for xml in (old_xml, None):
        (sb / "permissions.p7s").write_bytes(old_p7s)
        if xml is not None:
            (sb / "permissions.xml").write_bytes(xml)
        check = secure(str(dep), "-k", str(ks), "--check")
        assert check.returncode == 1
        assert "enclaves/ScienceBackroom/permissions.p7s: error: not signed by public/permissions_ca.cert.pem" \
            in check.stderr, check.stderr
        again = secure(str(dep), "-k", str(ks))
        assert again.returncode == 0 and "updated: ScienceBackroom/permissions" in again.stdout
        assert "withdrawn:" not in again.stdout  # no second new CA: the old file was another CA's
        assert pki.smime_content((sb / "permissions.p7s").read_bytes(), new_ca) == (sb / "permissions.xml").read_bytes()
        assert secure(str(dep), "-k", str(ks), "--check").returncode == 0


def test_check_reports_a_stale_signed_file_of_the_same_ca(tmp_path):
    """A permissions.p7s the current CA signed, but for other XML (an older grant put back
    before any withdrawal), and a governance.p7s that is not the governance: both reported,
    both replaced by the next run."""
    dep = write_deployment(tmp_path)
    ks = tmp_path / "ks"
    assert secure(str(dep), "-k", str(ks)).returncode == 0
    outsider, k10 = ks / "enclaves" / "Outsider", ks / "enclaves" / "K10Red"
    (outsider / "permissions.p7s").write_bytes((ks / "enclaves" / "Conformance" / "permissions.p7s").read_bytes())
    (k10 / "governance.p7s").write_bytes((k10 / "permissions.p7s").read_bytes())
    check = secure(str(dep), "-k", str(ks), "--check")
    assert check.returncode == 1
    assert "enclaves/Outsider/permissions.p7s: error: signed by the CA but not what enclaves/Outsider/permissions.xml " \
        "says" in check.stderr, check.stderr
    assert "enclaves/K10Red/governance.p7s: error: signed by the CA but not what enclaves/governance.xml says" \
        in check.stderr
    again = secure(str(dep), "-k", str(ks))
    assert "updated: Outsider/permissions" in again.stdout
    assert secure(str(dep), "-k", str(ks), "--check").returncode == 0
